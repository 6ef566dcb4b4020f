#include "fusion_service.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "pena/io/line_csv.hpp"
#include "pena/io/plan_reader.hpp"
#include "signals.hpp"
#include "to_dds.hpp"

namespace pena::services {
namespace {

// The worker wakes at least this often to look at the stop flag and the periodic work.
constexpr auto kPoll = std::chrono::milliseconds(50);

std::int64_t SecondsToNs(double seconds) { return static_cast<std::int64_t>(seconds * 1e9); }

// The a priori plan as fusion segments (ids 1, 2, ... in file order: provenance "plan:<id>").
std::vector<line_map::LineSegment> ReadPlanSegments(const std::filesystem::path& path) {
  std::vector<line_map::LineSegment> plan;
  for (const geometry::Segment2& wall : io::ReadPlan(path)) {
    line_map::LineSegment segment;
    segment.id = static_cast<std::int64_t>(plan.size() + 1);
    segment.segment = wall;
    plan.push_back(segment);
  }
  return plan;
}

// Who saw each global wall and its estimated error sd (docs/fusion.md, "The global map"):
// "id,seen_by,error_sd_m", seen_by space separated. Empty after a restart until the next rebuild.
void WriteWallSupport(const std::filesystem::path& path,
                      const std::map<std::int64_t, fusion::WallSupport>& support) {
  std::ofstream out(path);
  out << "id,seen_by,error_sd_m\n";
  for (const auto& [id, wall] : support) {
    std::string seen_by;
    for (const std::string& who : wall.seen_by) seen_by += (seen_by.empty() ? "" : " ") + who;
    char sd[32];
    std::snprintf(sd, sizeof sd, "%.3f", wall.error_sd_m);
    out << id << ',' << seen_by << ',' << sd << '\n';
  }
  if (!out) spdlog::warn("could not write {}", path.string());
}

}  // namespace

template <class PubSubType>
typename Reader<PubSubType>::SampleCallback FusionService::Enqueue(const char* /*topic*/) {
  return [this](typename PubSubType::type&& sample, const SampleMeta& meta) {
    inbox_.Push(Event{Sample(std::move(sample)), meta});
  };
}

FusionService::FusionService(FusionServiceOptions options)
    : options_(std::move(options)),
      store_(std::make_unique<fusion::FusionStore>(options_.state_dir, options_.store)),
      participant_(options_.dds, "pena-fusion"),
      delta_writer_(participant_, topics::kGlobalMapDelta),
      snapshot_writer_(participant_, topics::kGlobalMapSnapshot),
      correction_writer_(participant_, topics::kCorrection),
      sync_writer_(participant_, topics::kSyncRequest),
      corrections_(options_.corrections
                       ? std::make_unique<CorrectionWorker>(options_, stats_, Sinks())
                       : nullptr),
      pose_reader_(participant_, topics::kPose, Enqueue<pena_dds::EntityPosePubSubType>("pose")),
      status_reader_(participant_, topics::kStatus,
                     Enqueue<pena_dds::EntityStatusPubSubType>("status"),
                     [this](const LivelinessChange& change) {
                       inbox_.Push(Event{Sample(change), SampleMeta{NowNs(), NowNs(), {}}});
                     }),
      delta_reader_(participant_, topics::kLineMapDelta,
                    Enqueue<pena_dds::LineMapDeltaPubSubType>("line_map_delta")),
      snapshot_reader_(participant_, topics::kLineMapSnapshot,
                       Enqueue<pena_dds::LineMapSnapshotPubSubType>("line_map_snapshot")),
      scan_reader_(participant_, topics::kReferenceScan,
                   [this](pena_dds::ReferenceScan&& sample, const SampleMeta& meta) {
                     OnReferenceScan(std::move(sample), meta);
                   }),
      sync_reader_(participant_, topics::kSyncRequest,
                   Enqueue<pena_dds::SyncRequestPubSubType>("sync_request")) {
  operator_log_.emplace(options_.state_dir / "operator_corrections.csv");
  wall_stamp_log_.emplace(options_.state_dir / "wall_stamps.csv");
  annotation_log_.emplace(options_.state_dir / "annotations.cdr");
  RecoverWallStamps();
  CreateOperatorEndpoints();
  if (options_.lockstep) lockstep_order_.emplace(options_.lockstep_order);
  const fusion::FusionRecovery& recovery = store_->recovery();
  spdlog::info("state {}: {}; {} journal records replayed; global map version {} ({} segments), "
               "{} entities known{}",
               options_.state_dir.string(),
               recovery.from_checkpoint
                   ? "checkpoint at record " + std::to_string(recovery.checkpoint_sequence)
                   : std::string("no checkpoint"),
               recovery.replayed, store_->state().global_version(),
               store_->state().GlobalSnapshot().segments.size(),
               store_->state().entity_ids().size(),
               recovery.torn_tail.empty() ? "" : "; " + recovery.torn_tail);
  if (!options_.output_dir.empty()) {
    std::filesystem::create_directories(options_.output_dir);
    versions_log_.emplace(options_.output_dir / "global_versions.csv");
  }
}

FusionService::~FusionService() = default;

void FusionService::RecoverWallStamps() {
  std::size_t recovered = 0;
  for (const auto& [entity_id, journalled] : wall_stamp_log_->stamps()) {
    std::map<std::int64_t, double>& stamps = wall_stamp_s_[entity_id];
    for (const line_map::LineSegment& wall : store_->state().local_map(entity_id).segments()) {
      if (const auto it = journalled.find(wall.id); it != journalled.end()) {
        stamps[wall.id] = it->second;
        ++recovered;
      }
    }
  }
  if (recovered > 0) spdlog::info("{} wall stamps recovered from the journal", recovered);
}

void FusionService::RecordWallStamps(const std::string& entity_id,
                                     const std::vector<line_map::LineSegment>& walls,
                                     double stamp_s) {
  std::map<std::int64_t, double>& stamps = wall_stamp_s_[entity_id];
  std::vector<std::pair<std::int64_t, double>> fresh;
  for (const line_map::LineSegment& wall : walls) {
    if (stamps.emplace(wall.id, stamp_s).second) fresh.emplace_back(wall.id, stamp_s);
  }
  try {
    wall_stamp_log_->Append(entity_id, fresh);
  } catch (const std::runtime_error& error) {
    // The map goes on; only a rotation after a restart would then leave these walls where they are.
    spdlog::error("{}: wall stamps not journalled: {}", entity_id, error.what());
  }
}

void FusionService::CreateOperatorEndpoints() {
  try {
    annotation_writer_ =
        std::make_unique<Writer<pena_dds::AnnotationPubSubType>>(participant_, topics::kAnnotation);
    operator_reader_ = std::make_unique<Reader<pena_dds::OperatorCorrectionPubSubType>>(
        participant_, topics::kOperatorCorrection,
        Enqueue<pena_dds::OperatorCorrectionPubSubType>("operator_correction"));
    annotation_reader_ = std::make_unique<Reader<pena_dds::AnnotationPubSubType>>(
        participant_, topics::kAnnotation, Enqueue<pena_dds::AnnotationPubSubType>("annotation"));
  } catch (const DdsError& error) {
    annotation_reader_.reset();
    operator_reader_.reset();
    annotation_writer_.reset();
    spdlog::error("operator topics unavailable, annotations and operator corrections are NOT "
                  "handled: {}", error.what());
    return;
  }
  // The answer (applied or refused) only tells the consoles: without it corrections still apply.
  try {
    operator_answer_writer_ = std::make_unique<Writer<pena_dds::OperatorCorrectionPubSubType>>(
        participant_, topics::kOperatorCorrection);
  } catch (const DdsError& error) {
    spdlog::error("operator corrections are applied, but the consoles are not told whether: {}",
                  error.what());
  }
}

double FusionService::NowS() const { return static_cast<double>(NowNs()) * 1e-9; }

void FusionService::Startup() {
  start_ns_ = NowNs();
  if (versions_log_) {
    const std::uint64_t recovered = store_->state().global_version();
    if (const auto first_missed = versions_log_->CatchUp(recovered, NowNs())) {
      spdlog::info("global map versions {}-{} were journaled but not published before the "
                   "restart; the startup snapshot publishes them",
                   *first_missed, recovered);
    }
  }
  // The plan is loaded once: after a restart the journal already holds it.
  if (!options_.plan.empty() && store_->state().Checkpoint().plan.empty()) {
    std::vector<line_map::LineSegment> plan = ReadPlanSegments(options_.plan);
    spdlog::info("a priori plan {}: {} walls", options_.plan.string(), plan.size());
    Apply(fusion::SetPlan{NowS(), std::move(plan)});
  }
  // A restarted fusion republishes its map at once; entities resynchronise by version.
  PublishSnapshot();
  // And the operator's marks, as last relayed, for the consoles that connect from now on.
  if (annotation_writer_) {
    std::vector<pena_dds::Annotation> marks = annotation_log_->Latest();
    for (pena_dds::Annotation& mark : marks) annotation_writer_->Write(mark);
    if (!marks.empty()) {
      spdlog::info("{} operator marks published again from the journal", marks.size());
    }
  }
  RefreshCorrectionContext();
  next_tick_ns_ = NowNs() + SecondsToNs(options_.tick_period_s);
}

FusionRunSummary FusionService::Run() {
  Startup();
  while (!StopRequested()) {
    if (std::optional<Event> event = inbox_.PopFor(kPoll)) {
      LockstepProgress(*event);
      if (!HoldInOrder(*event)) Dispatch(*event);
    }
    ReleaseInOrder();
    Periodic();
  }
  if (corrections_) corrections_->Stop();
  spdlog::info("stopping ({}): {} events still queued are dropped; the entities' durable "
               "samples are received again at the next start",
               StopSignal() != 0 ? "signal " + std::to_string(StopSignal()) : "requested",
               inbox_.size());
  PublishSnapshot();
  store_->Checkpoint();
  if (!delta_writer_.WaitForAcknowledgments(2.0) ||
      !snapshot_writer_.WaitForAcknowledgments(2.0)) {
    spdlog::warn("not every reader acknowledged the last global map samples within 2 s");
  }
  WriteOutputs();
  summary_.global_version = store_->state().global_version();
  summary_.global_segments = store_->state().GlobalSnapshot().segments.size();
  return summary_;
}

void FusionService::Periodic() {
  const std::int64_t now_ns = NowNs();
  if (now_ns >= next_tick_ns_) {
    next_tick_ns_ = now_ns + SecondsToNs(options_.tick_period_s);
    Apply(fusion::Tick{NowS()});
  }
  if (snapshot_dirty_ && now_ns >= next_snapshot_ns_) PublishSnapshot();
  // The correction worker's copy follows every change, but at most every 100 ms while samples
  // are queued (a burst of deltas rebuilds the map many times).
  if (context_dirty_ && (inbox_.size() == 0 || now_ns - context_refreshed_ns_ > 100'000'000)) {
    RefreshCorrectionContext();
  }
}

fusion::FusionOutput FusionService::Apply(const fusion::FusionInput& input) {
  fusion::FusionOutput output = store_->Handle(input);
  ++summary_.inputs;
  if (!output.problem.empty()) {
    ++summary_.problems;
    spdlog::warn("input refused: {}", output.problem);
    return output;
  }
  for (const fusion::LifecycleChange& change : output.lifecycle) {
    if (change.appeared) {
      spdlog::info("{} joined", change.entity_id);
    } else {
      spdlog::info("{}: {} -> {}", change.entity_id, fusion::ToString(change.from),
                   fusion::ToString(change.to));
    }
    // A lost entity is not waited for in lockstep. One that left is not waited for once its
    // last samples arrived (LockstepOrder::Finished, from its status): its goodbye can overtake
    // its last delta.
    if (lockstep_order_ && change.to == fusion::EntityLifecycle::kLost) {
      lockstep_order_->Drop(change.entity_id);
    }
  }
  // The correction worker needs the new walls or alignments.
  if (output.global_delta || output.placement ||
      std::holds_alternative<fusion::EntityJoin>(input) ||
      std::holds_alternative<fusion::AlignmentCorrection>(input)) {
    context_dirty_ = true;
  }
  if (output.global_delta) PublishDelta(*output.global_delta);
  if (output.snapshot_request) RequestEntitySnapshot(*output.snapshot_request);
  if (output.annotation) {
    spdlog::info("annotation set version {}: {} #{} by {}", output.annotation->version,
                 output.annotation->removed ? "removed" : "put", output.annotation->annotation.id,
                 output.annotation->annotation.author);
  }
  return output;
}

void FusionService::PublishDelta(const line_map::MapDelta& delta) {
  snapshot_dirty_ = true;
  if (versions_log_) versions_log_->Append(delta.from_version, delta.to_version, NowNs());
  try {
    pena_dds::GlobalMapDelta sample = ToDdsGlobalMapDelta(delta, kGlobalMapId, NowS());
    if (!delta_writer_.Write(sample)) spdlog::warn("DDS refused global map delta {}", delta.to_version);
    stats_.Count("sent", topics::kGlobalMapDelta.name, "",
                 pena_dds::GlobalMapDeltaPubSubType().getSerializedSizeProvider(&sample)());
    ++summary_.global_deltas_sent;
    spdlog::debug("global map {} -> {} (+{} ~{} -{})", delta.from_version, delta.to_version,
                  delta.added.size(), delta.changed.size(), delta.removed.size());
  } catch (const std::exception& error) {
    // Too large for one sample: readers see the gap and get the snapshot.
    spdlog::error("global map delta {} not sent: {}; publishing the snapshot", delta.to_version,
                  error.what());
    next_snapshot_ns_ = 0;
  }
}

void FusionService::PublishSnapshot() {
  snapshot_dirty_ = false;
  next_snapshot_ns_ = NowNs() + SecondsToNs(options_.snapshot_period_s);
  try {
    pena_dds::GlobalMapSnapshot sample =
        ToDdsGlobalMapSnapshot(store_->state().GlobalSnapshot(), kGlobalMapId, NowS());
    if (!snapshot_writer_.Write(sample)) spdlog::warn("DDS refused the global map snapshot");
    stats_.Count("sent", topics::kGlobalMapSnapshot.name, "",
                 pena_dds::GlobalMapSnapshotPubSubType().getSerializedSizeProvider(&sample)());
    ++summary_.snapshots_sent;
  } catch (const std::exception& error) {
    spdlog::error("global map snapshot not sent: {}", error.what());
  }
}

void FusionService::RequestEntitySnapshot(const std::string& entity_id) {
  const std::int64_t now_ns = NowNs();
  std::int64_t& last = last_sync_request_ns_[entity_id];
  if (now_ns - last < 1'000'000'000) return;
  last = now_ns;
  pena_dds::SyncRequest request;
  request.requester_id("fusion");
  request.schema_version(pena_dds::SCHEMA_VERSION);
  SetBounded(request.target_id(), entity_id, "entity_id");
  request.have_version(store_->state().local_map(entity_id).version());
  sync_writer_.Write(request);
  spdlog::info("{}: local map version gap; asked for its snapshot", entity_id);
}

void FusionService::SendCorrection(const std::string& entity_id,
                                   const pipeline::Correction& correction,
                                   std::uint64_t reference_seq, std::uint64_t for_version,
                                   const std::string& operator_id) {
  const std::lock_guard<std::mutex> lock(send_mutex_);
  pipeline::Correction out = correction;
  if (reference_seq > 0 && out.kind == pipeline::Correction::Kind::kPose && out.confidence > 0.0) {
    const auto barrier = operator_barrier_s_.find(entity_id);
    if (barrier != operator_barrier_s_.end() && out.stamp_s <= barrier->second) {
      out.confidence = 0.0;  // from before the operator's move: an answer, not a correction
      stats_.Add("corrections_superseded_by_operator");
    }
  }
  // Entities drop a seq that does not increase: starting from the clock (ms) keeps a restarted
  // fusion above what it sent before.
  std::uint64_t& seq = correction_seq_[entity_id];
  seq = std::max(seq + 1, static_cast<std::uint64_t>(std::max<std::int64_t>(0, NowNs() / 1'000'000)));
  pena_dds::Correction sample = ToDdsCorrection(out, entity_id, seq, for_version, reference_seq);
  SetBounded(sample.operator_id(), operator_id, "operator_id");
  if (!correction_writer_.Write(sample)) spdlog::warn("DDS refused a correction for {}", entity_id);
  stats_.Count("sent", topics::kCorrection.name, entity_id,
               pena_dds::CorrectionPubSubType().getSerializedSizeProvider(&sample)());
  ++summary_.corrections_sent;
}

void FusionService::WriteOutputs() const {
  if (options_.output_dir.empty()) return;
  std::vector<io::LineRow> rows;
  for (const line_map::LineSegment& line : store_->state().GlobalSnapshot().segments) {
    std::string sources;
    for (const std::string& key : line.provenance) sources += (sources.empty() ? "" : " ") + key;
    char counts[96];
    std::snprintf(counts, sizeof counts, "%.0f,%.0f,%.4f,", line.observations,
                  line.support_cells, line.rms_error_m);
    rows.push_back({line.id, line.segment, counts + sources});
  }
  io::WriteLineCsv(options_.output_dir / "global_map.csv", rows,
                   ",observations,support_cells,rms_error_m,provenance");
  WriteWallSupport(options_.output_dir / "global_wall_support.csv",
                   store_->state().GlobalSupport());
  stats_.Write(options_.output_dir, static_cast<double>(NowNs() - start_ns_) * 1e-9);
  spdlog::info("wrote {} (version {}, {} segments) and fusion_stats.json",
               (options_.output_dir / "global_map.csv").string(),
               store_->state().global_version(), rows.size());
}

}  // namespace pena::services
