// dds_ping: one publisher or subscriber of EntityPose with a chosen participant profile, for the
// network-namespace test of the LAN and discovery-server profiles (netns_profiles_test.sh).
// pub: publishes a pose every 50 ms for --seconds. sub: exits 0 after --count poses, 1 if they
// do not arrive within --seconds.
#include <CLI/CLI.hpp>

#include <chrono>
#include <iostream>
#include <thread>

#include "dds_endpoints.hpp"
#include "pena_dds/entityPubSubTypes.h"
#include "work_queue.hpp"

namespace {

using namespace pena::services;

int Publish(Participant& participant, const std::string& id, double seconds) {
  Writer<pena_dds::EntityPosePubSubType> writer(participant, topics::kPose);
  const auto until = std::chrono::steady_clock::now() +
                     std::chrono::milliseconds(static_cast<long>(seconds * 1000));
  std::uint64_t seq = 0;
  while (std::chrono::steady_clock::now() < until) {
    pena_dds::EntityPose pose;
    pose.entity_id(id);
    pose.schema_version(pena_dds::SCHEMA_VERSION);
    pose.seq(++seq);
    writer.Write(pose);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::cout << "dds_ping pub: " << seq << " poses, " << writer.matched() << " readers matched\n";
  return 0;
}

int Subscribe(Participant& participant, int count, double seconds) {
  WorkQueue<pena_dds::EntityPose> queue;
  Reader<pena_dds::EntityPosePubSubType> reader(
      participant, topics::kPose,
      [&](pena_dds::EntityPose&& pose, const SampleMeta&) { queue.Push(std::move(pose)); });
  const auto until = std::chrono::steady_clock::now() +
                     std::chrono::milliseconds(static_cast<long>(seconds * 1000));
  int received = 0;
  std::string from;
  while (received < count && std::chrono::steady_clock::now() < until) {
    if (auto pose = queue.PopFor(std::chrono::milliseconds(100))) {
      ++received;
      from = pose->entity_id().to_string();
    }
  }
  std::cout << "dds_ping sub: " << received << " of " << count << " poses"
            << (from.empty() ? "" : " from " + from) << '\n';
  return received >= count ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("dds_ping: EntityPose publisher/subscriber for profile tests");
  std::string role, id = "ping";
  DdsOptions options;
  std::vector<std::string> files;
  int count = 10;
  double seconds = 20.0;
  app.add_option("--role", role, "pub or sub")->required()->check(CLI::IsMember({"pub", "sub"}));
  app.add_option("--profile", options.participant_profile, "Participant profile")->required();
  app.add_option("--profiles-file", files, "XML profile files")->required();
  app.add_option("--domain", options.domain_id, "DDS domain id");
  app.add_option("--id", id, "Entity id the publisher uses");
  app.add_option("--count", count, "Poses the subscriber waits for");
  app.add_option("--seconds", seconds, "How long to publish / wait");
  CLI11_PARSE(app, argc, argv);
  options.profiles_files.assign(files.begin(), files.end());
  try {
    Participant participant(options, "dds_ping");
    return role == "pub" ? Publish(participant, id, seconds) : Subscribe(participant, count, seconds);
  } catch (const std::exception& error) {
    std::cerr << "dds_ping: " << error.what() << '\n';
    return 2;
  }
}
