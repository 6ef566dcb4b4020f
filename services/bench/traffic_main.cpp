// pena-traffic: a counting subscriber for the bandwidth table of docs/dds.md. Joins a DDS domain
// on the loopback profile, subscribes to every PeNa topic, and counts samples and serialised
// (CDR) payload bytes per topic and per entity until the traffic stops. Prints bytes per second
// of wall time and of mission time (--rate: the entities' time scale) per entity and topic.
// Payload only: RTPS adds about 60-80 bytes of headers per sample (more when fragmented).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "dds_endpoints.hpp"
#include "pena_dds/correctionPubSubTypes.h"
#include "pena_dds/entityPubSubTypes.h"
#include "pena_dds/global_mapPubSubTypes.h"
#include "pena_dds/line_mapPubSubTypes.h"
#include "pena_dds/operatorPubSubTypes.h"
#include "pena_dds/scanPubSubTypes.h"

namespace {

using namespace pena::services;

struct Count {
  long samples = 0;
  double bytes = 0.0;
  std::int64_t first_ns = 0, last_ns = 0;
};

class Counter {
 public:
  void Add(const std::string& topic, const std::string& key, std::uint32_t bytes,
           std::int64_t at_ns) {
    const std::lock_guard<std::mutex> lock(mutex_);
    Count& c = counts_[{topic, key}];
    if (c.samples++ == 0) c.first_ns = at_ns;
    c.last_ns = at_ns;
    c.bytes += bytes;
    last_ns_ = at_ns;
  }
  std::int64_t last_ns() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return last_ns_;
  }
  std::map<std::pair<std::string, std::string>, Count> counts() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
  }

 private:
  mutable std::mutex mutex_;
  std::map<std::pair<std::string, std::string>, Count> counts_;
  std::int64_t last_ns_ = 0;
};

// A reader on `spec` counting every sample under key(sample).
template <class PubSubType, class KeyOf>
std::shared_ptr<void> Counted(Participant& participant, const TopicSpec& spec, Counter& counter,
                            KeyOf key_of) {
  const std::string topic = spec.name;
  return std::make_shared<Reader<PubSubType>>(
      participant, spec, [&counter, topic, key_of](typename PubSubType::type&& sample,
                                                   const SampleMeta& meta) {
        PubSubType type;
        counter.Add(topic, key_of(sample), type.getSerializedSizeProvider(&sample)(),
                    meta.reception_time_ns);
      });
}

std::vector<std::shared_ptr<void>> Subscribe(Participant& p, Counter& c) {
  const auto entity = [](const auto& s) { return s.entity_id().to_string(); };
  const auto map = [](const auto& s) { return s.map_id().to_string(); };
  return {Counted<pena_dds::EntityPosePubSubType>(p, topics::kPose, c, entity),
          Counted<pena_dds::EntityStatusPubSubType>(p, topics::kStatus, c, entity),
          Counted<pena_dds::LineMapDeltaPubSubType>(p, topics::kLineMapDelta, c, entity),
          Counted<pena_dds::LineMapSnapshotPubSubType>(p, topics::kLineMapSnapshot, c, entity),
          Counted<pena_dds::ReferenceScanPubSubType>(p, topics::kReferenceScan, c, entity),
          Counted<pena_dds::CorrectionPubSubType>(p, topics::kCorrection, c, entity),
          Counted<pena_dds::GlobalMapDeltaPubSubType>(p, topics::kGlobalMapDelta, c, map),
          Counted<pena_dds::GlobalMapSnapshotPubSubType>(p, topics::kGlobalMapSnapshot, c, map),
          Counted<pena_dds::SyncRequestPubSubType>(
              p, topics::kSyncRequest, c, [](const auto& s) { return s.requester_id().to_string(); }),
          Counted<pena_dds::AnnotationPubSubType>(
              p, topics::kAnnotation, c, [](const auto& s) { return s.author_id().to_string(); })};
}

void Print(const std::map<std::pair<std::string, std::string>, Count>& counts, double rate) {
  // An entity's active span: its first to last pose (else its own samples' span).
  std::map<std::string, double> span_s;
  for (const auto& [key, c] : counts) {
    if (key.first == topics::kPose.name) span_s[key.second] = static_cast<double>(c.last_ns - c.first_ns) * 1e-9;
  }
  std::printf("%-32s %-8s %8s %12s %10s %12s %12s\n", "topic", "key", "samples", "bytes",
              "B/sample", "B/s wall", "B/s mission");
  for (const auto& [key, c] : counts) {
    double span = span_s.count(key.second) ? span_s[key.second]
                                           : static_cast<double>(c.last_ns - c.first_ns) * 1e-9;
    span = std::max(span, 1e-3);
    std::printf("%-32s %-8s %8ld %12.0f %10.1f %12.1f %12.1f\n", key.first.c_str(),
                key.second.c_str(), c.samples, c.bytes, c.bytes / static_cast<double>(c.samples),
                c.bytes / span, c.bytes / span / rate);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("pena-traffic: samples and payload bytes per PeNa topic and entity (loopback DDS)");
  int domain = 0;
  double rate = 1.0, idle_s = 5.0, max_s = 600.0;
  app.add_option("--domain", domain, "DDS domain id of the run to count")->required();
  app.add_option("--rate", rate, "The entities' time scale (pena-entity --rate), for B/s mission")
      ->capture_default_str();
  app.add_option("--idle", idle_s, "Stop this long after the last sample, s")->capture_default_str();
  app.add_option("--max", max_s, "Stop after this long in any case, s")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  if (rate <= 0.0) {
    std::fprintf(stderr, "pena-traffic: --rate must be > 0, got %g\n", rate);
    return 1;
  }
  const std::filesystem::path dir = std::filesystem::path(PENA_SOURCE_DIR) / "deploy" / "dds";
  setenv("FASTRTPS_DEFAULT_PROFILES_FILE", (dir / "pena-loopback.xml").c_str(), 1);
  DdsOptions dds;
  dds.profiles_files = {dir / "pena-loopback.xml", dir / "pena-qos.xml"};
  dds.domain_id = domain;
  Counter counter;
  try {
    Participant participant(dds, "pena-traffic");
    const std::vector<std::shared_ptr<void>> readers = Subscribe(participant, counter);
    std::fprintf(stderr, "pena-traffic: listening on domain %d\n", domain);
    const std::int64_t start_ns = NowNs();
    while (true) {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      const std::int64_t now_ns = NowNs(), last_ns = counter.last_ns();
      if (last_ns > 0 && now_ns - last_ns > static_cast<std::int64_t>(idle_s * 1e9)) break;
      if (now_ns - start_ns > static_cast<std::int64_t>(max_s * 1e9)) break;
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "pena-traffic: %s\n", error.what());
    return 2;
  }
  Print(counter.counts(), rate);
  return 0;
}
