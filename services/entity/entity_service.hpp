#pragma once
// pena-entity's application class: the constructor opens the input (a log file, or the live
// sensor topics on the same participant) and creates the participant,
// writers and readers from the XML profiles (throws on failure); Run() is the one worker that
// owns the per-entity pipeline: it feeds records at the configured rate, publishes pose, line-map
// deltas, reference scans and the status heartbeat, and applies what the listeners enqueued
// (corrections, global map, sync requests). Members are destroyed readers and writers first,
// then the participant.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "dds_endpoints.hpp"
#include "dds_participant.hpp"
#include "entity_options.hpp"
#include "live_sensor_source.hpp"
#include "pena/geometry/trajectory.hpp"
#include "pena/io/log_source.hpp"
#include "pena/pipeline/entity_pipeline.hpp"
#include "pena_dds/correctionPubSubTypes.h"
#include "pena_dds/entityPubSubTypes.h"
#include "pena_dds/global_mapPubSubTypes.h"
#include "pena_dds/line_mapPubSubTypes.h"
#include "pena_dds/scanPubSubTypes.h"
#include "recorder.hpp"
#include "work_queue.hpp"

namespace pena::services {

// What a run did (logged at the end, checked by tests).
struct EntityRunSummary {
  std::string entity_id;
  long records = 0;
  long poses_sent = 0;
  long deltas_sent = 0;
  long reference_scans_sent = 0;
  long snapshots_sent = 0;
  long send_failures = 0;
  long corrections_received = 0;
  long global_deltas_received = 0;
  long corrections_out_of_sequence = 0;  // dropped: seq not above the last one seen
  long corrections_held = 0;             // not applied: beyond the entity's uncertainty
  long global_maps_refused = 0;          // global map samples for another map id than "global"
  long answers_awaited = 0;  // --await-corrections: reference scans whose answer was waited for
  long answers_missed = 0;   // ... and not received within the timeout
  std::uint64_t local_map_version = 0;
  std::size_t local_map_segments = 0;
  bool interrupted = false;  // stopped by a signal before the input ended
};

class EntityService {
 public:
  // Opens the input (io::InputError) and creates the DDS entities (DdsError).
  explicit EntityService(EntityServiceOptions options);
  ~EntityService();
  EntityService(const EntityService&) = delete;
  EntityService& operator=(const EntityService&) = delete;

  // Runs until the input ends or a stop signal; writes the outputs; returns the summary.
  EntityRunSummary Run();

 private:
  // What the listeners hand to the worker.
  using Event = std::variant<pena_dds::Correction, pena_dds::GlobalMapDelta,
                             pena_dds::GlobalMapSnapshot, pena_dds::SyncRequest>;

  void ReadAhead();
  // --plan: reads the a priori plan and gives it to the pipeline (map localisation).
  void LoadPlan();
  // Logs the plan walls the localiser moved since the last call (plan adaptation).
  void LogPlanShifts();
  // --record: the recording directory and its native sensor log (header from the input).
  void StartRecording();
  bool FusionMatched() const;
  void WaitForReaders();
  // Handles queued events, waiting for new ones until `until_ns` (system clock; 0 = no wait).
  void DrainInbox(std::int64_t until_ns);
  void Handle(const pena_dds::Correction& sample);
  void Handle(const pena_dds::GlobalMapDelta& sample);
  void Handle(const pena_dds::GlobalMapSnapshot& sample);
  void Handle(const pena_dds::SyncRequest& sample);
  // A record read from the input: recorded (--record), then to the pipeline; Publish sends what
  // each scan step produced.
  void Take(const sensors::SensorRecord& record);
  void Publish(pipeline::ScanStep& step);
  // --await-corrections: waits (handling the inbox) until the fusion answered reference scan
  // `seq` or the timeout passed; the wait is added to the pacing.
  void AwaitAnswer(std::uint64_t seq);
  // --hold-at: stops the clock at mission time `hold_at_s` until SIGUSR1 number `next_hold_`
  // arrives, serving the inbox meanwhile; the hold is added to the pacing.
  void Hold(double hold_at_s);
  // --unknown-start (entity_unknown_start.cpp): the chain's start pose (the origin instead of
  // the log's), a step's poses in the frame the fusion sent, and the fusion's frame corrections.
  geometry::Pose2 StartFrame(const geometry::Pose2& known_world_from_start) const;
  void ToPlacedFrame(pipeline::ScanStep& step) const;
  void HandleFrameCorrection(const pena_dds::Correction& sample);
  // The gate's verdict on a correction (correction_gate.hpp): sequence, then its bound.
  GateResult Gate(const pena_dds::Correction& sample);
  // False (and counted, logged) for a global map sample of another map id.
  bool ExpectedGlobalMap(const std::string& map_id, const char* what);
  void PublishDelta(const line_map::MapDelta& delta, double stamp_s);
  void PublishSnapshot();
  void PublishStatus(pena_dds::EntityState state, const std::string& message = "");
  void HeartbeatIfDue();
  void Finish();
  void WriteOutputs() const;
  // Writes a sample; a refusal is counted and logged.
  template <class W, class S>
  void Send(W& writer, S& sample) {
    if (!writer.Write(sample)) SendFailed(writer.topic_name());
  }
  void SendFailed(const std::string& topic);

  EntityServiceOptions options_;
  std::unique_ptr<io::LogSource> source_;
  LiveSensorSource* live_source_ = nullptr;  // source_ when the input is dds, else null
  std::size_t plan_shifts_logged_ = 0;
  std::vector<sensors::SensorRecord> read_ahead_;
  sensors::EntityKind kind_ = sensors::EntityKind::kRobot;
  std::string entity_id_;
  std::optional<pipeline::EntityPipeline> pipeline_;
  std::optional<Recorder> recorder_;
  geometry::Trajectory trajectory_;
  EntityRunSummary summary_;
  double last_stamp_s_ = 0.0;
  std::uint64_t pose_seq_ = 0;
  std::uint64_t scan_seq_ = 0;
  std::uint64_t correction_seq_ = 0;
  std::int64_t next_heartbeat_ns_ = 0;
  std::int64_t last_sync_request_ns_ = 0;
  std::uint64_t answered_seq_ = 0;         // newest reference seq the fusion answered
  double last_awaited_stamp_s_ = -1e300;   // stamp of the last reference scan waited for
  std::int64_t paused_ns_ = 0;             // wall time spent waiting for answers or held
  std::size_t next_hold_ = 0;              // index into options_.hold_at_s
  // --unknown-start: map_from_entity as the fusion last sent it (nullopt: not placed yet).
  std::optional<geometry::Pose2> map_from_entity_;
  // The last step's pose (as published) and covariance, which bound frame corrections.
  geometry::Pose2 last_world_from_body_;
  Eigen::Matrix3d last_covariance_ = Eigen::Matrix3d::Zero();
  CorrectionGate gate_;

  WorkQueue<Event> inbox_;
  Participant participant_;
  Writer<pena_dds::EntityPosePubSubType> pose_writer_;
  Writer<pena_dds::EntityStatusPubSubType> status_writer_;
  Writer<pena_dds::LineMapDeltaPubSubType> delta_writer_;
  Writer<pena_dds::LineMapSnapshotPubSubType> snapshot_writer_;
  Writer<pena_dds::ReferenceScanPubSubType> scan_writer_;
  Writer<pena_dds::SyncRequestPubSubType> sync_writer_;
  Reader<pena_dds::CorrectionPubSubType> correction_reader_;
  Reader<pena_dds::GlobalMapDeltaPubSubType> global_delta_reader_;
  Reader<pena_dds::GlobalMapSnapshotPubSubType> global_snapshot_reader_;
  Reader<pena_dds::SyncRequestPubSubType> sync_reader_;
};

}  // namespace pena::services
