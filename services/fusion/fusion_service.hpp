#pragma once
// pena-fusion's application class: a thin DDS adapter over libpena's fusion::FusionStore. The
// constructor opens (and recovers) the state directory and creates the participant, writers and
// readers from the XML profiles (throws on failure). Listener callbacks only take samples and
// enqueue them; Run() is the fusion worker that owns the store: it turns samples into fusion
// inputs (journaled before they are applied), publishes global-map deltas and snapshots, places
// entities whose start is unknown, relays annotations, and watches entities' lifecycles.
// Reference scans go to the second worker, CorrectionWorker (correction_worker.hpp), which
// matches them against a copy of the global map the fusion worker hands it after every change.

#include <cstdint>
#include <map>
#include <mutex>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <variant>

#include "dds_endpoints.hpp"
#include "dds_participant.hpp"
#include "correction_worker.hpp"
#include "fusion_options.hpp"
#include "fusion_stats.hpp"
#include "lockstep_order.hpp"
#include "annotation_log.hpp"
#include "operator_log.hpp"
#include "wall_stamp_log.hpp"
#include "versions_log.hpp"
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
  // The correction worker asks to move a placed entity's alignment (journaled here).
  struct Realign {
    std::string entity_id;
    geometry::Pose2 map_from_entity;
    double confidence = 0.0;
    std::uint64_t reference_seq = 0;
  };
  // What the listeners (and the correction worker) hand to the worker, with the middleware's
  // metadata.
  using Sample = std::variant<pena_dds::EntityPose, pena_dds::EntityStatus,
                              pena_dds::LineMapDelta, pena_dds::LineMapSnapshot,
                              pena_dds::OperatorCorrection, pena_dds::Annotation,
                              pena_dds::SyncRequest, pena_dds::ReferenceScan, LivelinessChange,
                              Realign>;
  struct Event {
    Sample sample;
    SampleMeta meta;
  };
  template <class PubSubType>
  typename Reader<PubSubType>::SampleCallback Enqueue(const char* topic);

  void CreateOperatorEndpoints();
  // The wall stamps journalled before a restart, for the walls the recovered local maps hold.
  void RecoverWallStamps();
  // Journals the stamps of walls not stamped yet (before the delta or snapshot is applied).
  void RecordWallStamps(const std::string& entity_id,
                        const std::vector<line_map::LineSegment>& walls, double stamp_s);
  void Startup();
  void Dispatch(const Event& event);
  void Handle(const pena_dds::EntityPose& sample, const SampleMeta& meta);
  void Handle(const pena_dds::EntityStatus& sample, const SampleMeta& meta);
  void Handle(const pena_dds::LineMapDelta& sample, const SampleMeta& meta);
  void Handle(const pena_dds::LineMapSnapshot& sample, const SampleMeta& meta);
  void Handle(const pena_dds::OperatorCorrection& sample, const SampleMeta& meta);
  // The operator's three-point rotation or translation (paper section 4.1) of one entity.
  void HandleOperatorMove(const pena_dds::OperatorCorrection& sample);
  // Paper 4.1 for an entity with a known start: its walls mapped from the correction's origin
  // time on, until it applies the correction, move with it in the global map (MoveEntityWalls).
  // A placed entity's rotation or translation moved all its walls with its alignment: those it
  // mapped up to the correction's stamp go back (MoveEntityWalls by the inverse).
  void KeepWallsBefore(const std::string& entity_id, const OperatorLogRecord& record);
  void StartWallMove(const std::string& entity_id, const OperatorLogRecord& record,
                     const geometry::Pose2& corrected_map_from_odom);
  // A delta or pose of an entity with a wall move in flight: moves the walls the delta began in
  // the wrong frame, or notes from which stamp on the entity's data is corrected.
  void FollowWallMove(const std::string& entity_id, double delta_stamp_s,
                      const std::vector<std::int64_t>& added_ids);
  void FollowWallMove(const std::string& entity_id, double pose_stamp_s,
                      const geometry::Pose2& map_from_odom);
  // Writes the answer to an operator's correction: applied (refusal empty) or why not.
  void AnswerOperator(const pena_dds::OperatorCorrection& sample, const std::string& refusal);
  void Handle(const pena_dds::Annotation& sample, const SampleMeta& meta);
  void Handle(const pena_dds::SyncRequest& sample, const SampleMeta& meta);
  void Handle(const pena_dds::ReferenceScan& sample, const SampleMeta& meta);
  void Handle(const LivelinessChange& change, const SampleMeta& meta);
  void Handle(const Realign& request, const SampleMeta& meta);
  // The reference-scan listener: counts the sample and offers it to the correction worker (in
  // lockstep: queues it for the fusion worker, which offers it in mission-time order).
  void OnReferenceScan(pena_dds::ReferenceScan&& sample, const SampleMeta& meta);
  // Lockstep (fusion_lockstep.cpp): deltas and scans are held by lockstep_order_ and handled in
  // its order; poses and statuses tell it how far each entity got. True: the event was held.
  bool HoldInOrder(Event& event);
  void LockstepProgress(const Event& event);
  void ReleaseInOrder();
  void LockstepJoin(const std::string& entity_id);
  // Lockstep: before the first answer to an entity, waits (at most 2 s) until the correction
  // writer matched a reader of the participant that sent `meta`'s sample.
  void AwaitCorrectionReader(const std::string& entity_id, const SampleMeta& meta);
  // The correction worker's sinks (called on its thread).
  CorrectionSinks Sinks();
  // After a change of the global map or of an alignment: a new context for the correction
  // worker.
  void RefreshCorrectionContext();
  // An entity whose start was unknown: log the placement attempt; once placed, tell the entity.
  void AfterPlacement(const std::string& entity_id, const fusion::FusionOutput& output);
  // Sends a placed entity (start unknown) its frame: CORRECTION_MAP_FROM_ODOM = map_from_entity.
  void SendPlacement(const std::string& entity_id, double confidence, std::uint64_t reference_seq);

  // Feeds one input to the store and acts on its output.
  fusion::FusionOutput Apply(const fusion::FusionInput& input);
  // Makes sure the fusion knows `entity_id` and remembers its participant. An entity with a
  // known start joins at the identity (its local map is in the mission frame its start gives);
  // one whose status says its start is unknown joins unplaced (placement finds its frame).
  void EnsureJoined(const std::string& entity_id, const SampleMeta& meta,
                    bool start_unknown = false);
  void PublishDelta(const line_map::MapDelta& delta);
  void PublishSnapshot();
  void RequestEntitySnapshot(const std::string& entity_id);
  // Any thread (the correction worker sends too). operator_id: set when relaying an operator's.
  void SendCorrection(const std::string& entity_id, const pipeline::Correction& correction,
                      std::uint64_t reference_seq, std::uint64_t for_version,
                      const std::string& operator_id = "");
  void Periodic();
  void WriteOutputs() const;
  bool FromSelf(const SampleMeta& meta) const;
  double NowS() const;

  FusionServiceOptions options_;
  std::unique_ptr<fusion::FusionStore> store_;
  FusionStats stats_;
  FusionRunSummary summary_;
  std::optional<VersionsLog> versions_log_;  // OUT/global_versions.csv
  std::map<std::string, std::string> entity_of_participant_;  // GUID prefix bytes -> entity id
  std::map<std::string, std::int64_t> last_sync_request_ns_;
  std::mutex send_mutex_;  // correction_seq_, the correction writer, summary_.corrections_sent
  std::map<std::string, std::uint64_t> correction_seq_;
  std::map<std::string, bool> start_unknown_;    // from the entities' status
  std::map<std::string, bool> placement_sent_;   // this run told the entity its frame
  bool context_dirty_ = true;
  std::shared_ptr<const CorrectionContext> context_;  // the last one handed to the worker
  std::optional<LockstepOrder> lockstep_order_;
  std::map<std::uint64_t, Event> held_;  // lockstep: token -> event
  std::uint64_t next_token_ = 1;
  std::int64_t lockstep_logged_ns_ = 0;  // last "lockstep: waiting" log line
  std::set<std::string> correction_reader_seen_;  // lockstep: entities whose reader matched
  std::int64_t context_refreshed_ns_ = 0;
  std::map<std::string, std::int64_t> annotation_ids_;  // DDS annotation_id -> fusion id
  // Each entity's latest world_from_body and odom_from_body (an operator move needs its frame).
  struct LatestPose {
    double stamp_s = 0.0;
    geometry::Pose2 world_from_body;
    geometry::Pose2 odom_from_body;
  };
  std::map<std::string, LatestPose> latest_pose_;
  // Per entity, per local segment id: the mission stamp of the delta that added it (which of its
  // walls an operator's move from a stamp on concerns); journalled in wall_stamp_log_.
  std::map<std::string, std::map<std::int64_t, double>> wall_stamp_s_;
  std::optional<WallStampLog> wall_stamp_log_;  // STATE_DIR/wall_stamps.csv
  std::optional<AnnotationLog> annotation_log_;  // STATE_DIR/annotations.cdr
  // An operator's move of a known-start entity in flight (StartWallMove).
  struct WallMove {
    std::string correction_id;
    std::string author;
    geometry::Pose2 corrected_from_wrong;
    double from_stamp_s = 0.0;
    geometry::Pose2 corrected_map_from_odom;  // the frame the entity was told to take
    double applied_stamp_s = 0.0;             // its first pose in that frame (0: none yet)
    std::set<std::int64_t> moved;             // segment ids moved by this correction
  };
  std::map<std::string, WallMove> wall_moves_;
  // Under send_mutex_: per entity, the stamp of its latest pose when an operator moved it. An
  // automatic correction for a reference scan up to then was computed in the frame the operator
  // replaced: it is sent as a mere answer (confidence 0) so that it cannot undo the move.
  std::map<std::string, double> operator_barrier_s_;
  std::optional<OperatorLog> operator_log_;  // STATE_DIR/operator_corrections.csv
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
  // After the writers its sinks use, before the readers that feed it (destroyed in between).
  std::unique_ptr<CorrectionWorker> corrections_;
  Reader<pena_dds::EntityPosePubSubType> pose_reader_;
  Reader<pena_dds::EntityStatusPubSubType> status_reader_;
  Reader<pena_dds::LineMapDeltaPubSubType> delta_reader_;
  Reader<pena_dds::LineMapSnapshotPubSubType> snapshot_reader_;
  Reader<pena_dds::ReferenceScanPubSubType> scan_reader_;
  Reader<pena_dds::SyncRequestPubSubType> sync_reader_;
  // Operator topics: optional, so a QoS profile Fast DDS rejects there does not stop the map.
  std::unique_ptr<Writer<pena_dds::AnnotationPubSubType>> annotation_writer_;
  std::unique_ptr<Reader<pena_dds::OperatorCorrectionPubSubType>> operator_reader_;
  // pena-fusion's answers to operator corrections (applied or refused), on the same key.
  std::unique_ptr<Writer<pena_dds::OperatorCorrectionPubSubType>> operator_answer_writer_;
  std::unique_ptr<Reader<pena_dds::AnnotationPubSubType>> annotation_reader_;
};

}  // namespace pena::services
