// pena-entity: what the worker does with the samples its listeners queued (corrections, the
// global map, sync requests). Part of EntityService (entity_service.hpp).
#include <spdlog/spdlog.h>

#include <sstream>

#include "entity_service.hpp"
#include "from_dds.hpp"
#include "to_dds.hpp"

namespace pena::services {
namespace {

// A version gap in the global map asks for a snapshot at most this often.
constexpr std::int64_t kSyncRequestIntervalNs = 1'000'000'000;

std::string PoseCsv(const geometry::Pose2& pose) {
  std::ostringstream out;
  out.precision(9);
  out << pose.x_m << ',' << pose.y_m << ',' << pose.theta_rad;
  return out.str();
}

// The covariance a correction carries, or zero if it is not finite (unknown).
Eigen::Matrix3d CovarianceOf(const std::array<double, 9>& row_major) {
  Eigen::Matrix3d covariance;
  for (int i = 0; i < 9; ++i) covariance(i / 3, i % 3) = row_major[static_cast<std::size_t>(i)];
  if (!covariance.allFinite()) return Eigen::Matrix3d::Zero();
  return 0.5 * (covariance + covariance.transpose());
}

}  // namespace

GateResult EntityService::Gate(const pena_dds::Correction& sample) {
  const bool from_operator = !sample.operator_id().to_string().empty();
  // A lockstep answer without a correction moves nothing: only its sequence counts.
  if (sample.confidence() <= 0.0) return gate_.CheckSequenceOnly(sample.seq());
  const geometry::Pose2 frame = FromDds(sample.map_from_odom());
  if (options_.start_unknown) {
    // The first placement has nothing to keep: the entity has no world position before it.
    if (!map_from_entity_ || sample.kind() != pena_dds::CORRECTION_MAP_FROM_ODOM) {
      return gate_.CheckSequenceOnly(sample.seq());
    }
    return gate_.CheckFrame(sample.seq(), from_operator, *map_from_entity_, frame, last_world_from_body_,
                            last_covariance_);
  }
  // Nor does one the pipeline ignores for its low confidence.
  if (sample.confidence() < options_.pipeline.min_correction_confidence) {
    return gate_.CheckSequenceOnly(sample.seq());
  }
  if (sample.kind() == pena_dds::CORRECTION_MAP_FROM_ODOM) {
    return gate_.CheckFrame(sample.seq(), from_operator, pipeline_->map_from_odom(), frame,
                            last_world_from_body_, last_covariance_);
  }
  return gate_.CheckPose(sample.seq(), from_operator, sample.reference_seq(),
                         FromDds(sample.world_from_body()), CovarianceOf(sample.covariance()));
}

bool EntityService::ExpectedGlobalMap(const std::string& map_id, const char* what) {
  if (map_id == kGlobalMapId) return true;
  ++summary_.global_maps_refused;
  spdlog::warn("{}: {} for map id '{}' refused: this entity takes the '{}' map only", entity_id_,
               what, map_id, kGlobalMapId);
  return false;
}

void EntityService::Handle(const pena_dds::Correction& sample) {
  if (sample.entity_id().to_string() != entity_id_) return;
  ++summary_.corrections_received;
  const GateResult gate = Gate(sample);
  if (gate.verdict == GateVerdict::kOutOfSequence) {
    ++summary_.corrections_out_of_sequence;
    spdlog::warn("{}: correction {} dropped: {}", entity_id_, sample.seq(), gate.message);
    return;
  }
  answered_seq_ = std::max<std::uint64_t>(answered_seq_, sample.reference_seq());
  if (gate.verdict == GateVerdict::kHeld) {
    ++summary_.corrections_held;
    spdlog::warn("{}: correction {} held, not applied: {}", entity_id_, sample.seq(), gate.message);
    return;
  }
  // A lockstep answer without a correction (pena-fusion --lockstep): the attempt found nothing
  // to apply.
  if (sample.confidence() <= 0.0) return;
  if (options_.start_unknown) {
    HandleFrameCorrection(sample);
    return;
  }
  pipeline::CorrectionResult result;
  try {
    result = pipeline_->ApplyCorrection(FromDds(sample));
  } catch (const std::invalid_argument& error) {
    spdlog::warn("{}: correction {} dropped: {}", entity_id_, sample.seq(), error.what());
    return;
  }
  if (result.status == pipeline::CorrectionStatus::kApplied) correction_seq_ = sample.seq();
  spdlog::debug("{}: correction {} {}", entity_id_, sample.seq(), ToString(result.status));
  if (recorder_) {
    recorder_->Csv("received_corrections", "seq,kind,stamp_s,confidence,map_from_odom_x_m,"
                   "map_from_odom_y_m,map_from_odom_theta_rad,status",
                   std::to_string(sample.seq()) + ',' + std::to_string(sample.kind()) + ',' +
                       std::to_string(sample.stamp_s()) + ',' +
                       std::to_string(sample.confidence()) + ',' +
                       PoseCsv(pipeline_->map_from_odom()) + ',' + ToString(result.status));
  }
  if (result.map_delta) PublishDelta(*result.map_delta, last_stamp_s_);
}

void EntityService::Handle(const pena_dds::GlobalMapDelta& sample) {
  ++summary_.global_deltas_received;
  if (!ExpectedGlobalMap(sample.map_id().to_string(), "global map delta")) return;
  line_map::MapDelta delta;
  try {
    delta = FromDds(sample);
  } catch (const std::invalid_argument& error) {
    spdlog::warn("{}: global map delta dropped: {}", entity_id_, error.what());
    return;
  }
  const line_map::ApplyResult result = pipeline_->ApplyGlobalDelta(delta);
  if (recorder_) recorder_->Delta("received_global_map_deltas", delta);
  if (result.status != line_map::ApplyStatus::kVersionGap) return;
  // A delta was lost (or we joined late): ask the fusion service for its snapshot.
  const std::int64_t now_ns = NowNs();
  if (now_ns - last_sync_request_ns_ < kSyncRequestIntervalNs) return;
  last_sync_request_ns_ = now_ns;
  pena_dds::SyncRequest request;
  SetBounded(request.requester_id(), entity_id_, "entity_id");
  request.schema_version(pena_dds::SCHEMA_VERSION);
  request.target_id(kGlobalMapId);
  request.have_version(pipeline_->global_map().version());
  Send(sync_writer_, request);
  spdlog::info("{}: {}; asked for the global snapshot", entity_id_, result.message);
}

void EntityService::Handle(const pena_dds::GlobalMapSnapshot& sample) {
  if (!ExpectedGlobalMap(sample.map_id().to_string(), "global map snapshot")) return;
  try {
    const line_map::MapSnapshot snapshot = FromDds(sample);
    if (snapshot.version <= pipeline_->global_map().version()) return;
    pipeline_->ResetGlobalMap(snapshot);
    if (recorder_) recorder_->Snapshot("received_global_map_snapshots", snapshot);
    spdlog::info("{}: global map snapshot version {}", entity_id_, snapshot.version);
  } catch (const std::invalid_argument& error) {
    spdlog::warn("{}: global map snapshot dropped: {}", entity_id_, error.what());
  }
}

void EntityService::Handle(const pena_dds::SyncRequest& sample) {
  if (sample.target_id().to_string() != entity_id_) return;
  spdlog::info("{}: {} asked for our line map (it holds version {})", entity_id_,
               sample.requester_id().to_string(), sample.have_version());
  PublishSnapshot();
}

}  // namespace pena::services
