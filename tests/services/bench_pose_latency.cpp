// bench_pose_latency: EntityPose latency from a publishing process to a subscribing process on
// loopback (deploy/dds/pena-loopback.xml + pena-qos.xml), measured as the subscriber's clock at
// take minus the writer's source timestamp (one machine, one system clock). Prints p50/p90/p99.
// Two sources: a synthetic publisher (default; poses at --rate for --count per entity) or the
// real pena-entity on a mission entity (--input DIR, run at --entity-rate x real time).
// --security DIR (deploy/security/make-identities.sh output) secures both ends: the subscriber
// as DIR/monitor, the synthetic publisher as DIR/gateway, pena-entity as DIR/<its id>. The
// publisher's CPU time over its wall time is printed too (pena-entity's CPU per entity).
// A benchmark: it reports, it does not judge.
#include <CLI/CLI.hpp>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <thread>
#include <vector>

#include "dds_endpoints.hpp"
#include "pena_dds/entityPubSubTypes.h"
#include "pena_dds/line_mapPubSubTypes.h"
#include "work_queue.hpp"

namespace {

using namespace pena::services;

DdsOptions Loopback(int domain, const std::filesystem::path& identity = {}) {
  const std::filesystem::path dir = std::filesystem::path(PENA_SOURCE_DIR) / "deploy" / "dds";
  setenv("FASTRTPS_DEFAULT_PROFILES_FILE", (dir / "pena-loopback.xml").c_str(), 1);
  DdsOptions options;
  options.profiles_files = {dir / "pena-loopback.xml", dir / "pena-qos.xml"};
  options.domain_id = domain;
  options.security_dir = identity;
  return options;
}

// The child: waits for the reader, then publishes `count` poses at `rate_hz`.
int Publisher(int domain, int count, double rate_hz, int entities,
              const std::filesystem::path& identity) {
  Participant participant(Loopback(domain, identity), "bench-publisher");
  Writer<pena_dds::EntityPosePubSubType> writer(participant, topics::kPose);
  for (int i = 0; i < 500 && writer.matched() == 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // let discovery settle
  const auto period = std::chrono::duration<double>(1.0 / rate_hz);
  auto next = std::chrono::steady_clock::now();
  for (int i = 0; i < count; ++i) {
    for (int e = 0; e < entities; ++e) {
      pena_dds::EntityPose pose;
      pose.entity_id("bench" + std::to_string(e));
      pose.schema_version(pena_dds::SCHEMA_VERSION);
      pose.seq(static_cast<std::uint64_t>(i + 1));
      writer.Write(pose);
    }
    next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(period);
    std::this_thread::sleep_until(next);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  return 0;
}

// The child when --input is given: pena-entity on that mission entity, on the same domain.
[[noreturn]] void ExecEntity(const std::string& input, double entity_rate, int domain,
                             const std::string& security) {
  const std::filesystem::path dir = std::filesystem::path(PENA_SOURCE_DIR) / "deploy" / "dds";
  const std::string rate = std::to_string(entity_rate), dom = std::to_string(domain);
  const std::string loopback = (dir / "pena-loopback.xml").string();
  const std::string qos = (dir / "pena-qos.xml").string();
  execl(PENA_ENTITY_BIN, PENA_ENTITY_BIN, "--input", input.c_str(), "--rate", rate.c_str(),
        "--domain", dom.c_str(), "--profiles-file", loopback.c_str(), "--profiles-file",
        qos.c_str(), "--wait-for-readers", "20", "--log-level", "warn",
        security.empty() ? nullptr : "--security", security.c_str(), nullptr);
  std::perror("bench_pose_latency: cannot start pena-entity");
  std::_Exit(127);
}

double Percentile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  const auto index = static_cast<std::size_t>(p * static_cast<double>(values.size() - 1) + 0.5);
  return values[index];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("bench_pose_latency: EntityPose latency between two processes on loopback");
  int count = 400, domain = 90, entities = 1;
  double rate_hz = 20.0;
  app.add_option("--count", count, "Poses per entity")->capture_default_str();
  app.add_option("--rate", rate_hz, "Poses per second per entity")->capture_default_str();
  app.add_option("--entities", entities, "Entity instances the publisher simulates")
      ->capture_default_str();
  app.add_option("--domain", domain, "DDS domain id")->capture_default_str();
  std::string input;
  double entity_rate = 1.0;
  app.add_option("--input", input, "Measure pena-entity on this mission entity instead");
  app.add_option("--entity-rate", entity_rate, "pena-entity's --rate")->capture_default_str();
  std::string security;
  app.add_option("--security", security,
                 "DDS Security: the identities directory of deploy/security/make-identities.sh");
  CLI11_PARSE(app, argc, argv);
  Loopback(domain);  // sets FASTRTPS_DEFAULT_PROFILES_FILE for the child too
  const std::filesystem::path ids = security;
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = fork();
  if (child == 0) {
    if (!input.empty()) {
      const std::filesystem::path entity = std::filesystem::path(input).lexically_normal();
      const std::string id = (entity.has_filename() ? entity : entity.parent_path()).filename();
      ExecEntity(input, entity_rate, domain, security.empty() ? "" : (ids / id).string());
    }
    std::_Exit(Publisher(domain, count, rate_hz, entities,
                         security.empty() ? std::filesystem::path() : ids / "gateway"));
  }
  std::vector<double> latencies_ms;
  {
    Participant participant(
        Loopback(domain, security.empty() ? std::filesystem::path() : ids / "monitor"),
        "bench-subscriber");
    WorkQueue<double> queue;
    Reader<pena_dds::EntityPosePubSubType> reader(
        participant, topics::kPose, [&](pena_dds::EntityPose&&, const SampleMeta& meta) {
          queue.Push(static_cast<double>(meta.reception_time_ns - meta.source_time_ns) * 1e-6);
        });
    // pena-entity starts when a line-map reader matched (--wait-for-readers).
    Reader<pena_dds::LineMapDeltaPubSubType> deltas(
        participant, topics::kLineMapDelta, [](pena_dds::LineMapDelta&&, const SampleMeta&) {});
    const int expected = input.empty() ? count * entities : std::numeric_limits<int>::max();
    while (static_cast<int>(latencies_ms.size()) < expected) {
      auto latency = queue.PopFor(std::chrono::seconds(5));
      if (!latency) break;
      latencies_ms.push_back(*latency);
    }
  }
  int status = 0;
  waitpid(child, &status, 0);
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  const double cpu_s = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                       static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-6;
  if (latencies_ms.empty()) {
    std::fprintf(stderr, "bench_pose_latency: no pose arrived\n");
    return 1;
  }
  if (input.empty()) {
    std::printf("poses received %zu of %d (%d entities x %d at %.1f Hz, synthetic publisher)\n",
                latencies_ms.size(), count * entities, entities, count, rate_hz);
  } else {
    std::printf("poses received %zu from pena-entity --input %s --rate %.1f\n",
                latencies_ms.size(), input.c_str(), entity_rate);
  }
  std::printf("DDS Security: %s\n", security.empty() ? "off" : "on");
  std::printf("publisher CPU %.2f s over %.1f s wall (%.1f %% of a core)\n", cpu_s, wall_s,
              100.0 * cpu_s / wall_s);
  std::printf("latency ms: p50 %.3f  p90 %.3f  p99 %.3f  max %.3f\n",
              Percentile(latencies_ms, 0.5), Percentile(latencies_ms, 0.9),
              Percentile(latencies_ms, 0.99), *std::max_element(latencies_ms.begin(), latencies_ms.end()));
  return 0;
}
