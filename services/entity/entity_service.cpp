#include "entity_service.hpp"

#include <spdlog/spdlog.h>

#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <thread>

#include "pena/io/input_error.hpp"
#include "pena/io/line_csv.hpp"
#include "pena/io/mission_log.hpp"
#include "pena/io/plan_reader.hpp"
#include "pena/io/trajectory_io.hpp"
#include "pena/pipeline/start_pose.hpp"
#include "log_start.hpp"
#include "signals.hpp"
#include "to_dds.hpp"

namespace pena::services {
namespace {

// The worker wakes at least this often to look at the stop flag and the heartbeat.
constexpr std::int64_t kPollNs = 50'000'000;
// --await-corrections: an answer not received within this (wall) is given up (fusion restarted,
// sample lost); the entity goes on and waits again at the next attempted scan.
constexpr std::int64_t kAwaitTimeoutNs = 15'000'000'000;

std::int64_t SecondsToNs(double seconds) { return static_cast<std::int64_t>(seconds * 1e9); }

// A secured entity writes in the partition of its id, the only one its permissions allow
// (docs/security.md); an open one in the default partition.
DdsOptions InOwnPartition(DdsOptions dds) {
  dds.own_partition = true;
  return dds;
}

// --hold-at: SIGUSR1s received; hold k (from 1) ends when there have been k.
std::atomic<int> g_hold_releases{0};
extern "C" void OnHoldRelease(int /*signal_number*/) { g_hold_releases.fetch_add(1); }

}  // namespace

EntityService::EntityService(EntityServiceOptions options)
    : options_(std::move(options)),
      source_(IsLiveInput(options_.input) ? nullptr : io::OpenLog(options_.input, options_.read)),
      gate_(options_.corrections),
      participant_(InOwnPartition(options_.dds), "pena-entity"),
      pose_writer_(participant_, topics::kPose),
      status_writer_(participant_, topics::kStatus),
      delta_writer_(participant_, topics::kLineMapDelta),
      snapshot_writer_(participant_, topics::kLineMapSnapshot),
      scan_writer_(participant_, topics::kReferenceScan),
      sync_writer_(participant_, topics::kSyncRequest),
      correction_reader_(participant_, topics::kCorrection,
                         [this](pena_dds::Correction&& s, const SampleMeta&) {
                           inbox_.Push(std::move(s));
                         }),
      global_delta_reader_(participant_, topics::kGlobalMapDelta,
                           [this](pena_dds::GlobalMapDelta&& s, const SampleMeta&) {
                             inbox_.Push(std::move(s));
                           }),
      global_snapshot_reader_(participant_, topics::kGlobalMapSnapshot,
                              [this](pena_dds::GlobalMapSnapshot&& s, const SampleMeta&) {
                                inbox_.Push(std::move(s));
                              }),
      sync_reader_(participant_, topics::kSyncRequest,
                   [this](pena_dds::SyncRequest&& s, const SampleMeta&) {
                     inbox_.Push(std::move(s));
                   }) {
  if (!source_) {
    // The live input's readers live on this participant; ~EntityService releases them first.
    auto live = std::make_unique<LiveSensorSource>(participant_, LiveOptionsOf(options_));
    live_source_ = live.get();
    source_ = std::move(live);
  }
  try {
    ReadAhead();
    if (options_.record) StartRecording();
  } catch (...) {
    source_.reset();  // ~EntityService does not run for a constructor that throws
    throw;
  }
}

void EntityService::StartRecording() {
  recorder_.emplace(options_.output_dir / "recording");
  io::MissionLogHeader header;
  header.mission = source_->description().mission;
  header.entity_id = entity_id_;
  header.kind = kind_;
  for (const sensors::SensorRecord& record : read_ahead_) {
    if (const auto* scan = std::get_if<sensors::LaserScan>(&record)) header.laser = scan->geometry;
  }
  if (const auto* native = dynamic_cast<const io::MissionLogReader*>(source_.get())) {
    header.laser_height_m = native->header().laser_height_m;
  }
  header.producer = "pena-entity --record (input " + options_.input.string() + ")";
  recorder_->OpenSensorLog(header);
}

EntityService::~EntityService() {
  // Members go in reverse order and the participant is declared after source_: a live source's
  // readers must go while the participant still exists.
  source_.reset();
}

void EntityService::ReadAhead() {
  LogStart log_start = ReadLogStart(*source_, options_.input, options_.entity_id, options_.kind);
  read_ahead_ = std::move(log_start.records);
  if (read_ahead_.empty()) {
    throw io::InputError(options_.input, 0,
                         live_source_ ? "no sensor record for " + options_.entity_id +
                                            " before the live input ended (" +
                                            live_source_->end_reason() + ")"
                                      : std::string("the log holds no records"));
  }
  const io::LogDescription& description = source_->description();
  kind_ = log_start.kind;
  entity_id_ = std::move(log_start.entity_id);
  if (participant_.secured() && entity_id_ != participant_.common_name()) {
    throw DdsError("entity id '" + entity_id_ + "' is not the identity's (" +
                   participant_.identity() + "): an entity publishes only as itself");
  }
  pena_dds::EntityPose probe;
  SetBounded(probe.entity_id(), entity_id_, "entity_id");
  // The live input states a known start as a ground-truth record too (LiveSensorSource).
  const pipeline::StartPose start = pipeline::StartPoseOf(
      read_ahead_, description.format == "pena-log" || description.format == kLiveInput);
  pipeline_.emplace(options_.pipeline, kind_, entity_id_, StartFrame(start.world_from_body),
                    sensors::StampOf(read_ahead_.front()));
  summary_.entity_id = entity_id_;
  if (!options_.plan.empty()) LoadPlan();
  spdlog::info("{}: {} ({}), {} log, start pose from {} ({:.3f}, {:.3f}, {:.3f})", entity_id_,
               options_.input.string(), sensors::ToString(kind_), description.format,
               start.source, start.world_from_body.x_m, start.world_from_body.y_m,
               start.world_from_body.theta_rad);
}

void EntityService::LoadPlan() {
  std::vector<geometry::Segment2> plan = io::ReadPlan(options_.plan);
  if (plan.empty()) throw io::InputError(options_.plan, 0, "the plan has no segments");
  spdlog::info("{}: localising against the plan {} ({} walls)", entity_id_,
               options_.plan.string(), plan.size());
  pipeline_->SetPlan(std::move(plan));
}

void EntityService::LogPlanShifts() {
  const std::vector<localisation::SegmentShift>& shifts = pipeline_->plan_shifts();
  for (; plan_shifts_logged_ < shifts.size(); ++plan_shifts_logged_) {
    const localisation::SegmentShift& shift = shifts[plan_shifts_logged_];
    spdlog::info("{}: plan wall #{} seen {:.2f} m off its drawing in {} rounds: moved there", entity_id_,
                 shift.index, shift.offset_m, shift.rounds);
  }
}

bool EntityService::FusionMatched() const {
  // Each endpoint pair matches on its own: a reference scan written before the fusion's scan
  // reader matched is lost (volatile), and in lockstep its answer would then be awaited in vain.
  // So the wait covers every endpoint the fusion's first answer travels through.
  if (delta_writer_.matched() == 0) return false;
  if (options_.await_corrections_s <= 0.0) return true;
  // In lockstep the run must not depend on discovery either: a pose written before the fusion's
  // pose reader matched is lost (volatile), and the fusion's picture would then differ by it.
  return scan_writer_.matched() > 0 && correction_reader_.matched() > 0 &&
         pose_writer_.matched() > 0;
}

void EntityService::WaitForReaders() {
  const std::int64_t until_ns = NowNs() + SecondsToNs(options_.wait_for_readers_s);
  while (!FusionMatched() && NowNs() < until_ns && !StopRequested()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (options_.wait_for_readers_s > 0.0 && !FusionMatched()) {
    spdlog::warn("{}: the fusion's readers did not all match within {} s (line map {}, reference "
                 "scans {}, corrections {}, poses {}); starting anyway",
                 entity_id_, options_.wait_for_readers_s, delta_writer_.matched(),
                 scan_writer_.matched(), correction_reader_.matched(), pose_writer_.matched());
  }
}

EntityRunSummary EntityService::Run() {
  // Before anything else: a release sent early must not end the process (SIGUSR1's default).
  if (!options_.hold_at_s.empty()) std::signal(SIGUSR1, OnHoldRelease);
  WaitForReaders();
  PublishStatus(pena_dds::ENTITY_RUNNING);
  const double first_stamp_s = sensors::StampOf(read_ahead_.front());
  const std::int64_t wall_start_ns = NowNs();
  next_heartbeat_ns_ = wall_start_ns + SecondsToNs(options_.heartbeat_period_s);
  std::size_t ahead = 0;
  // Live input: the sensors pace the stream; while it waits for them the inbox and the
  // heartbeat are served as between records.
  if (live_source_) {
    live_source_->SetWaitHook([this] {
      DrainInbox(0);
      HeartbeatIfDue();
    });
  }
  while (!StopRequested()) {
    std::optional<sensors::SensorRecord> record = NextRecord(read_ahead_, ahead, *source_);
    if (!record) break;
    // Pace the log: mission time runs `rate` times faster than wall time.
    if (options_.rate > 0.0 && !live_source_) {
      const double offset_s = (sensors::StampOf(*record) - first_stamp_s) / options_.rate;
      DrainInbox(wall_start_ns + paused_ns_ + SecondsToNs(offset_s));
    } else {
      DrainInbox(0);
    }
    while (next_hold_ < options_.hold_at_s.size() &&
           sensors::StampOf(*record) >= options_.hold_at_s[next_hold_] && !StopRequested()) {
      Hold(options_.hold_at_s[next_hold_]);
    }
    Take(*record);
    HeartbeatIfDue();
  }
  if (live_source_) live_source_->SetWaitHook({});
  // What the stride spreading still holds was accepted: it goes through, stop or not.
  pipeline_->EndOfInput();
  while (std::optional<pipeline::ScanStep> step = pipeline_->Next()) Publish(*step);
  if (const auto spread = pipeline_->stride_spreading()) {
    spdlog::info("{}: {} strides spread over {} scans, {} records released by the hold",
                 entity_id_, spread->strides_spread, spread->pieces, spread->released_unspread);
  }
  summary_.interrupted = StopRequested();
  Finish();
  return summary_;
}

void EntityService::DrainInbox(std::int64_t until_ns) {
  while (true) {
    const std::int64_t now_ns = NowNs();
    const std::int64_t wait_ns = std::min(std::max<std::int64_t>(until_ns - now_ns, 0), kPollNs);
    std::optional<Event> event = inbox_.PopFor(std::chrono::nanoseconds(wait_ns));
    if (event) {
      std::visit([this](const auto& sample) { Handle(sample); }, *event);
    } else if (NowNs() >= until_ns || StopRequested()) {
      return;
    }
    HeartbeatIfDue();
  }
}

void EntityService::Take(const sensors::SensorRecord& record) {
  ++summary_.records;
  if (recorder_) {
    // The input as it came: a replay of the recording spreads its strides again.
    try {
      recorder_->Sensor(record);
    } catch (const std::invalid_argument& error) {
      // The native log refuses it (a stamp going back); the chain still gets it.
      spdlog::warn("{}: record {} not recorded: {}", entity_id_, summary_.records, error.what());
    }
  }
  // One step at a time: what the inbox brings while a step is published (lockstep answers) acts
  // on the next scan.
  pipeline_->Push(record);
  while (std::optional<pipeline::ScanStep> step = pipeline_->Next()) Publish(*step);
}

void EntityService::Publish(pipeline::ScanStep& step) {
  if (options_.start_unknown) ToPlacedFrame(step);
  last_stamp_s_ = step.odometry.stamp_s;
  last_world_from_body_ = step.world_from_body;
  last_covariance_ = step.covariance;
  trajectory_.push_back({last_stamp_s_, step.world_from_body});
  if (step.plan_round) LogPlanShifts();
  // The scan's map change, then its reference scan, then its pose: each carries what came
  // before it on the other topics (versions, reference scans sent), so a lockstep fusion
  // (services/fusion/lockstep_order.hpp) can put the topics back in this order.
  if (step.map_delta) PublishDelta(*step.map_delta, last_stamp_s_);
  const std::uint64_t map_version = pipeline_->local_map().version();
  if (step.odometry.reference_changed) {
    pena_dds::ReferenceScan scan =
        ToDdsReferenceScan(step.scan, step, entity_id_, ++scan_seq_,
                           map_version, options_.range_quantum_m);
    Send(scan_writer_, scan);
    gate_.Remember(scan_seq_, step.world_from_body, step.covariance);
    ++summary_.reference_scans_sent;
  }
  pena_dds::EntityPose pose =
      ToDdsPose(step, entity_id_, ++pose_seq_, map_version, correction_seq_);
  pose.reference_scans_sent(scan_seq_);
  Send(pose_writer_, pose);
  ++summary_.poses_sent;
  // The same rule as the fusion's in lockstep: the scans it attempts are the ones waited for.
  if (step.odometry.reference_changed && options_.await_corrections_s > 0.0 &&
      step.odometry.stamp_s - last_awaited_stamp_s_ >= options_.await_corrections_s) {
    last_awaited_stamp_s_ = step.odometry.stamp_s;
    AwaitAnswer(scan_seq_);
  }
}

void EntityService::AwaitAnswer(std::uint64_t seq) {
  // Without a fusion listening nobody answers: the entity runs on its own.
  if (correction_reader_.matched() == 0) return;
  ++summary_.answers_awaited;
  const std::int64_t start_ns = NowNs();
  const std::int64_t until_ns = start_ns + kAwaitTimeoutNs;
  while (answered_seq_ < seq && !StopRequested() && NowNs() < until_ns) {
    if (std::optional<Event> event = inbox_.PopFor(std::chrono::milliseconds(20))) {
      std::visit([this](const auto& sample) { Handle(sample); }, *event);
    }
    HeartbeatIfDue();
  }
  if (answered_seq_ < seq) {
    ++summary_.answers_missed;
    spdlog::warn("{}: no answer to reference scan {} within {} s; going on", entity_id_, seq,
                 static_cast<double>(kAwaitTimeoutNs) * 1e-9);
  }
  paused_ns_ += NowNs() - start_ns;
}

void EntityService::Hold(double hold_at_s) {
  const int hold = static_cast<int>(++next_hold_);
  const std::int64_t start_ns = NowNs();
  // The lines a test waits for: flushed at once, whatever the log level's flush policy.
  spdlog::info("{}: held at {:.3f} s of mission time (last pose {:.3f} s); SIGUSR1 to pid {} "
               "releases hold {}",
               entity_id_, hold_at_s, last_stamp_s_, static_cast<long>(::getpid()), hold);
  spdlog::default_logger()->flush();
  std::uint64_t applied_seq = correction_seq_;
  while (g_hold_releases.load() < hold && !StopRequested()) {
    DrainInbox(NowNs() + kPollNs);
    if (correction_seq_ != applied_seq) {
      applied_seq = correction_seq_;
      spdlog::info("{}: held: correction {} applied", entity_id_, applied_seq);
      spdlog::default_logger()->flush();
    }
  }
  paused_ns_ += NowNs() - start_ns;
  spdlog::info("{}: hold {} {} after {:.1f} wall s", entity_id_, hold,
               StopRequested() ? "ended by a stop signal" : "released",
               static_cast<double>(NowNs() - start_ns) * 1e-9);
}

void EntityService::SendFailed(const std::string& topic) {
  ++summary_.send_failures;
  spdlog::warn("{}: DDS refused a sample on {}", entity_id_, topic);
}

void EntityService::PublishDelta(const line_map::MapDelta& delta, double stamp_s) {
  try {
    pena_dds::LineMapDelta sample = ToDdsLineMapDelta(delta, entity_id_, stamp_s);
    sample.reference_scans_sent(scan_seq_);
    Send(delta_writer_, sample);
    ++summary_.deltas_sent;
    if (recorder_) recorder_->Delta("sent_line_map_deltas", delta);
    spdlog::debug("{}: line map {} -> {} (+{} ~{} -{})", entity_id_, delta.from_version,
                  delta.to_version, delta.added.size(), delta.changed.size(),
                  delta.removed.size());
  } catch (const std::exception& error) {
    // Readers see a version gap and ask for a snapshot (SyncRequest).
    ++summary_.send_failures;
    spdlog::error("{}: line-map delta {} -> {} not sent: {}", entity_id_, delta.from_version,
                  delta.to_version, error.what());
  }
}

void EntityService::PublishSnapshot() {
  const line_map::MapSnapshot snapshot = pipeline_->local_map().Snapshot();
  try {
    pena_dds::LineMapSnapshot sample = ToDdsLineMapSnapshot(snapshot, entity_id_, last_stamp_s_);
    Send(snapshot_writer_, sample);
    ++summary_.snapshots_sent;
    if (recorder_) recorder_->Snapshot("sent_line_map_snapshots", snapshot);
  } catch (const std::exception& error) {
    ++summary_.send_failures;
    spdlog::error("{}: line-map snapshot {} not sent: {}", entity_id_, snapshot.version,
                  error.what());
  }
}

void EntityService::PublishStatus(pena_dds::EntityState state, const std::string& message) {
  pena_dds::EntityStatus status;
  SetBounded(status.entity_id(), entity_id_, "entity_id");
  status.schema_version(pena_dds::SCHEMA_VERSION);
  status.kind(ToDds(kind_));
  status.state(state);
  status.mission(source_->description().mission.substr(0, 64));
  status.stamp_s(last_stamp_s_);
  const odometry::OdometryCounts& counts = pipeline_->odometry_counts();
  status.scans(static_cast<std::uint64_t>(counts.scans));
  status.matched(static_cast<std::uint64_t>(counts.matched + counts.degenerate));
  status.failed(static_cast<std::uint64_t>(counts.failed));
  status.local_map_version(pipeline_->local_map().version());
  status.local_map_segments(pipeline_->local_map().size());
  status.global_map_version(pipeline_->global_map().version());
  status.corrections_applied(static_cast<std::uint64_t>(pipeline_->counts().corrections_applied));
  status.message(message.substr(0, 128));
  status.start_unknown(options_.start_unknown);
  status.reference_scans_sent(scan_seq_);
  Send(status_writer_, status);
}

void EntityService::HeartbeatIfDue() {
  const std::int64_t now_ns = NowNs();
  if (now_ns < next_heartbeat_ns_) return;
  next_heartbeat_ns_ = now_ns + SecondsToNs(options_.heartbeat_period_s);
  PublishStatus(pena_dds::ENTITY_RUNNING);
}

void EntityService::Finish() {
  // What the last window holds goes into the map; the final snapshot lets any reader check.
  const line_map::MapDelta last = pipeline_->Flush();
  if (!last.empty()) PublishDelta(last, last_stamp_s_);
  PublishSnapshot();
  PublishStatus(pena_dds::ENTITY_FINISHED, summary_.interrupted ? "stopped by a signal" : "");
  summary_.local_map_version = pipeline_->local_map().version();
  summary_.local_map_segments = pipeline_->local_map().size();
  if (pipeline_->has_plan()) {
    spdlog::info("{}: plan localisation: {} rounds, {} corrections, {} plan walls moved", entity_id_,
                 pipeline_->counts().plan_rounds, pipeline_->counts().plan_corrections,
                 pipeline_->plan_shifts().size());
  }
  if (!delta_writer_.WaitForAcknowledgments(options_.linger_s) ||
      !snapshot_writer_.WaitForAcknowledgments(options_.linger_s)) {
    spdlog::warn("{}: not every reader acknowledged the last line-map samples within {} s",
                 entity_id_, options_.linger_s);
  }
  status_writer_.WaitForAcknowledgments(options_.linger_s);
  if (recorder_) recorder_->Close();
  WriteOutputs();
}

void EntityService::WriteOutputs() const {
  if (options_.output_dir.empty()) return;
  std::filesystem::create_directories(options_.output_dir);
  io::WriteTum(options_.output_dir / "trajectory.tum", trajectory_);
  std::vector<io::LineRow> rows;
  for (const line_map::LineSegment& line : pipeline_->local_map().segments()) {
    rows.push_back({line.id, line.segment, ""});
  }
  io::WriteLineCsv(options_.output_dir / "line_map.csv", rows);
  spdlog::info("{}: wrote {} and line_map.csv", entity_id_,
               (options_.output_dir / "trajectory.tum").string());
}

}  // namespace pena::services
