#pragma once
// pena-fusion's application class: a thin DDS adapter over libpena's fusion::FusionStore. The
// constructor opens (and recovers) the state directory and creates the participant, writers and
// readers from the XML profiles (throws on failure). Listener callbacks only take samples and
// enqueue them; Run() is the one worker that owns the store: it turns samples into fusion inputs
// (journaled before they are applied), publishes global-map deltas and snapshots, computes and
// sends corrections at reference scans, relays annotations, and watches entities' lifecycles.

#include <cstdint>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <variant>

#include "dds_endpoints.hpp"
#include "dds_participant.hpp"
#include "fusion_options.hpp"
#include "fusion_stats.hpp"
#include "pena/fusion/correction_filter.hpp"
#include "pena/fusion/fusion_store.hpp"
#include "pena/pipeline/entity_pipeline.hpp"
#include "pena_dds/correctionPubSubTypes.h"
#include "pena_dds/entityPubSubTypes.h"
#include "pena_dds/global_mapPubSubTypes.h"
#include "pena_dds/line_mapPubSubTypes.h"
#include "pena_dds/operatorPubSubTypes.h"
#include "pena_dds/scanPubSubTypes.h"
#include "work_queue.hpp"

namespace pena::services {

// What a run did (logged at the end, checked by tests).
struct FusionRunSummary {
  std::uint64_t global_version = 0;
  std::size_t global_segments = 0;
  long inputs = 0;
  long global_deltas_sent = 0;
  long snapshots_sent = 0;
  long corrections_sent = 0;
  long problems = 0;
};

class FusionService {
 public:
  // Recovers the state (io::InputError for a corrupt journal) and creates the DDS entities
  // (DdsError).
  explicit FusionService(FusionServiceOptions options);
  ~FusionService();
  FusionService(const FusionService&) = delete;
  FusionService& operator=(const FusionService&) = delete;

  // Runs until a stop signal; checkpoints, writes the outputs, returns the summary.
  FusionRunSummary Run();

 private:
  // What the listeners hand to the worker, with the middleware's metadata.
  using Sample = std::variant<pena_dds::EntityPose, pena_dds::EntityStatus,
                              pena_dds::LineMapDelta, pena_dds::LineMapSnapshot,
                              pena_dds::ReferenceScan, pena_dds::OperatorCorrection,
                              pena_dds::Annotation, pena_dds::SyncRequest, LivelinessChange>;
  struct Event {
    Sample sample;
    SampleMeta meta;
  };
  template <class PubSubType>
  typename Reader<PubSubType>::SampleCallback Enqueue(const char* topic);

  void CreateOperatorEndpoints();
  void Startup();
  void Dispatch(const Event& event);
  void Handle(const pena_dds::EntityPose& sample, const SampleMeta& meta);
  void Handle(const pena_dds::EntityStatus& sample, const SampleMeta& meta);
  void Handle(const pena_dds::LineMapDelta& sample, const SampleMeta& meta);
  void Handle(const pena_dds::LineMapSnapshot& sample, const SampleMeta& meta);
  void Handle(const pena_dds::ReferenceScan& sample, const SampleMeta& meta);
  void Handle(const pena_dds::OperatorCorrection& sample, const SampleMeta& meta);
  void Handle(const pena_dds::Annotation& sample, const SampleMeta& meta);
  void Handle(const pena_dds::SyncRequest& sample, const SampleMeta& meta);
  void Handle(const LivelinessChange& change, const SampleMeta& meta);
  // Matches a reference scan against the global map and sends the (filtered) correction.
  void Correct(const std::string& entity_id, const pena_dds::ReferenceScan& sample);
  // The scan's body pose in the entity's frame with the last correction sent applied.
  geometry::Pose2 ExpectedPose(const std::string& entity_id,
                               const pena_dds::ReferenceScan& sample) const;
  // Sends the corrected pose to the entity, or moves a placed entity's alignment.
  void Deliver(const std::string& entity_id, const pena_dds::ReferenceScan& sample,
               const geometry::Pose2& map_from_entity, const geometry::Pose2& corrected,
               double confidence);
  // The entity's correction filter (created with its kind's options on first use).
  fusion::CorrectionFilter& FilterOf(const std::string& entity_id);

  // Feeds one input to the store and acts on its output.
  fusion::FusionOutput Apply(const fusion::FusionInput& input);
  // Makes sure the fusion knows `entity_id` (joins it at the identity: the entity's local map
  // is in the mission frame its known start pose gives) and remembers its participant.
  void EnsureJoined(const std::string& entity_id, const SampleMeta& meta);
  void PublishDelta(const line_map::MapDelta& delta);
  void PublishSnapshot();
  void RequestEntitySnapshot(const std::string& entity_id);
  void SendCorrection(const std::string& entity_id, const pipeline::Correction& correction,
                      std::uint64_t reference_seq);
  void Periodic();
  void WriteOutputs() const;
  bool FromSelf(const SampleMeta& meta) const;
  double NowS() const;

  FusionServiceOptions options_;
  std::unique_ptr<fusion::FusionStore> store_;
  FusionStats stats_;
  FusionRunSummary summary_;
  std::ofstream versions_log_;
  std::map<std::string, std::string> entity_of_participant_;  // GUID prefix bytes -> entity id
  std::map<std::string, std::int64_t> last_correction_ns_;
  std::map<std::string, std::int64_t> last_sync_request_ns_;
  std::map<std::string, std::uint64_t> correction_seq_;
  std::map<std::string, bool> is_robot_;  // from the entities' status
  std::map<std::string, fusion::CorrectionFilter> correction_filters_;
  std::map<std::string, geometry::Pose2> map_from_odom_sent_;  // what the last correction set
  std::map<std::string, std::int64_t> annotation_ids_;  // DDS annotation_id -> fusion id
  bool snapshot_dirty_ = true;
  std::int64_t next_snapshot_ns_ = 0;
  std::int64_t next_tick_ns_ = 0;
  std::int64_t start_ns_ = 0;

  WorkQueue<Event> inbox_;
  Participant participant_;
  Writer<pena_dds::GlobalMapDeltaPubSubType> delta_writer_;
  Writer<pena_dds::GlobalMapSnapshotPubSubType> snapshot_writer_;
  Writer<pena_dds::CorrectionPubSubType> correction_writer_;
  Writer<pena_dds::SyncRequestPubSubType> sync_writer_;
  Reader<pena_dds::EntityPosePubSubType> pose_reader_;
  Reader<pena_dds::EntityStatusPubSubType> status_reader_;
  Reader<pena_dds::LineMapDeltaPubSubType> delta_reader_;
  Reader<pena_dds::LineMapSnapshotPubSubType> snapshot_reader_;
  Reader<pena_dds::ReferenceScanPubSubType> scan_reader_;
  Reader<pena_dds::SyncRequestPubSubType> sync_reader_;
  // Operator topics: optional, so a QoS profile Fast DDS rejects there does not stop the map.
  std::unique_ptr<Writer<pena_dds::AnnotationPubSubType>> annotation_writer_;
  std::unique_ptr<Reader<pena_dds::OperatorCorrectionPubSubType>> operator_reader_;
  std::unique_ptr<Reader<pena_dds::AnnotationPubSubType>> annotation_reader_;
};

}  // namespace pena::services
