#pragma once
// What the DDS Security tests share (docs/security.md): the mission's identities made by
// deploy/security/make-identities.sh, secured DDS options, and a rogue participant with a probe
// that counts the rogue's samples it hears.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "dds_endpoints.hpp"
#include "pena/line_map/line_map.hpp"
#include "pena_dds/correctionPubSubTypes.h"
#include "pena_dds/entityPubSubTypes.h"
#include "pena_dds/global_mapPubSubTypes.h"
#include "pena_dds/operatorPubSubTypes.h"
#include "service_test_support.hpp"
#include "to_dds.hpp"

namespace pena::services::security_testing {

namespace fs = std::filesystem;

inline const fs::path kRepo = PENA_SOURCE_DIR;

inline void Shell(const std::string& command) {
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
}

// The mission's identities (robot1, robot2, ff9 and the roles) and, for the rogue (b), a whole
// other mission's: generated once per test process.
struct Identities {
  fs::path mission;
  fs::path foreign;
};
inline const Identities& MissionIdentities() {
  static const Identities identities = [] {
    const fs::path root = testing::ScratchDir("identities");
    const std::string script = (kRepo / "deploy" / "security" / "make-identities.sh").string();
    Identities out{root / "mission", root / "foreign"};
    Shell(script + " " + out.mission.string() + " robot1 robot2 ff9 > /dev/null");
    Shell(script + " " + out.foreign.string() + " robot1 > /dev/null");
    return out;
  }();
  return identities;
}

inline DdsOptions Secured(int domain, const fs::path& identity) {
  DdsOptions options = testing::LoopbackDds(domain);
  options.security_dir = identity;
  return options;
}

// The rogue's samples carry these marks (and operator id "rogue"), so a receiver can tell them
// from the team's: x = 99 m in poses and corrections (IsRogueX: a gateway carries positions to
// the centimetre), sequence numbers and map versions from kRogueSeq.
inline constexpr double kRogueX = 99.0;
inline constexpr std::uint64_t kRogueSeq = 7'000'000'000ULL;
inline bool IsRogueX(double x_m) { return x_m > kRogueX - 0.5 && x_m < kRogueX + 0.5; }

// A receiver that counts the rogue's samples it is handed: one on each topic the rogue writes.
struct Probe {
  Probe(const DdsOptions& dds, const std::string& name)
      : participant(dds, name),
        poses(participant, topics::kPose,
              [this](pena_dds::EntityPose&& s, const SampleMeta&) {
                if (IsRogueX(s.world_from_body().x_m())) {
                  ++rogue;
                  const std::lock_guard<std::mutex> lock(mutex);
                  rogue_ids.insert(s.entity_id().to_string());
                } else {
                  ++team;
                }
              }),
        corrections(participant, topics::kCorrection,
                    [this](pena_dds::Correction&& s, const SampleMeta&) {
                      if (s.operator_id().to_string() == "rogue") ++rogue;
                      else ++team;
                    }),
        operator_corrections(participant, topics::kOperatorCorrection,
                             [this](pena_dds::OperatorCorrection&& s, const SampleMeta&) {
                               if (IsRogueX(s.world_from_body().x_m())) ++rogue;
                             }),
        snapshots(participant, topics::kGlobalMapSnapshot,
                  [this](pena_dds::GlobalMapSnapshot&& s, const SampleMeta&) {
                    if (s.version() >= kRogueSeq) ++rogue;
                  }) {}
  std::atomic<int> rogue{0};
  std::atomic<int> team{0};
  std::mutex mutex;
  std::set<std::string> rogue_ids;  // entity ids of the marked poses heard
  Participant participant;
  Reader<pena_dds::EntityPosePubSubType> poses;
  Reader<pena_dds::CorrectionPubSubType> corrections;
  Reader<pena_dds::OperatorCorrectionPubSubType> operator_corrections;
  Reader<pena_dds::GlobalMapSnapshotPubSubType> snapshots;
};

// The rogue: writes forged samples (a pose of `victim`, a fusion correction and an operator
// correction for it, a global map snapshot of version kRogueSeq and up) on whichever of the
// four topics it was allowed a writer, 20 a second, until stopped.
class Rogue {
 public:
  Rogue(const DdsOptions& dds, const std::string& name, const std::string& victim)
      : participant_(dds, name), victim_(victim) {
    TryCreate(pose_, topics::kPose, "pose");
    TryCreate(correction_, topics::kCorrection, "correction");
    TryCreate(operator_, topics::kOperatorCorrection, "operator correction");
    TryCreate(snapshot_, topics::kGlobalMapSnapshot, "global map snapshot");
    thread_ = std::thread([this] { Loop(); });
  }
  ~Rogue() {
    stop_ = true;
    thread_.join();
  }
  // Which writers the middleware let it create.
  const std::vector<std::string>& refused() const { return refused_; }
  int written() const { return written_.load(); }

 private:
  template <class W>
  void TryCreate(std::unique_ptr<W>& writer, const TopicSpec& spec, const std::string& what) {
    try {
      writer = std::make_unique<W>(participant_, spec);
    } catch (const DdsError&) {
      refused_.push_back(what);
    }
  }

  void Loop() {
    for (std::uint64_t i = 0; !stop_; ++i) {
      if (pose_) {
        pena_dds::EntityPose pose;
        SetBounded(pose.entity_id(), victim_, "entity_id");
        pose.schema_version(pena_dds::SCHEMA_VERSION);
        pose.seq(kRogueSeq + i);
        pose.world_from_body().x_m(kRogueX);
        if (pose_->Write(pose)) ++written_;
      }
      if (correction_) {
        pena_dds::Correction correction;
        SetBounded(correction.entity_id(), victim_, "entity_id");
        SetBounded(correction.operator_id(), std::string("rogue"), "operator_id");
        correction.schema_version(pena_dds::SCHEMA_VERSION);
        correction.seq(kRogueSeq + i);
        correction.kind(pena_dds::CORRECTION_MAP_FROM_ODOM);
        correction.map_from_odom().x_m(kRogueX);
        correction.confidence(1.0F);
        if (correction_->Write(correction)) ++written_;
      }
      if (operator_) {
        pena_dds::OperatorCorrection move;
        SetBounded(move.correction_id(), "rogue/" + std::to_string(i), "correction_id");
        SetBounded(move.operator_id(), std::string("rogue"), "operator_id");
        SetBounded(move.target_entity_id(), victim_, "target_entity_id");
        move.schema_version(pena_dds::SCHEMA_VERSION);
        move.kind(pena_dds::OPERATOR_SET_POSE);
        move.world_from_body().x_m(kRogueX);
        if (operator_->Write(move)) ++written_;
      }
      if (snapshot_) {
        line_map::LineSegment wall;
        wall.segment.start_m = {kRogueX, 0.0};
        wall.segment.end_m = {kRogueX, 10.0};
        line_map::LineMap map;
        map.Integrate({wall}, kGlobalMapId);
        pena_dds::GlobalMapSnapshot snapshot =
            ToDdsGlobalMapSnapshot(map.Snapshot(), kGlobalMapId, 0.0);
        snapshot.version(kRogueSeq + i);
        if (snapshot_->Write(snapshot)) ++written_;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }

  Participant participant_;
  std::string victim_;
  std::unique_ptr<Writer<pena_dds::EntityPosePubSubType>> pose_;
  std::unique_ptr<Writer<pena_dds::CorrectionPubSubType>> correction_;
  std::unique_ptr<Writer<pena_dds::OperatorCorrectionPubSubType>> operator_;
  std::unique_ptr<Writer<pena_dds::GlobalMapSnapshotPubSubType>> snapshot_;
  std::vector<std::string> refused_;
  std::atomic<int> written_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace pena::services::security_testing
