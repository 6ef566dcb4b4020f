// pena-fusion: corrections (docs/fusion-service.md): each reference scan is matched against
// virtual scans of the global map, gated and blended by the entity's fusion::CorrectionFilter,
// and the corrected pose sent back. Part of FusionService (fusion_service.hpp).
#include <spdlog/spdlog.h>

#include <cmath>

#include "from_dds.hpp"
#include "fusion_service.hpp"
#include "pena/fusion/correction.hpp"
#include "to_dds.hpp"

namespace pena::services {
namespace {

template <class PubSubType>
std::uint32_t SizeOf(const typename PubSubType::type& sample) {
  PubSubType type;
  return type.getSerializedSizeProvider(const_cast<typename PubSubType::type*>(&sample))();
}

bool IsIdentity(const geometry::Pose2& pose) {
  return pose.x_m == 0.0 && pose.y_m == 0.0 && pose.theta_rad == 0.0;
}

}  // namespace

void FusionService::Handle(const pena_dds::ReferenceScan& sample, const SampleMeta& /*meta*/) {
  const std::string entity_id = sample.entity_id().to_string();
  stats_.Count("received", topics::kReferenceScan.name, entity_id,
               SizeOf<pena_dds::ReferenceScanPubSubType>(sample));
  if (!options_.corrections) return;
  CheckSchemaVersion(sample.schema_version(), "ReferenceScan");
  // The entity's own odometry grows its uncertainty at every reference, attempted or not.
  FilterOf(entity_id).Predict(services::FromDds(sample.odom_from_body()));
  const std::int64_t now_ns = NowNs();
  std::int64_t& last = last_correction_ns_[entity_id];
  if (now_ns - last < static_cast<std::int64_t>(options_.correction_interval_s * 1e9)) return;
  const fusion::EntityStatus* status = store_->state().entity(entity_id);
  if (status == nullptr || !status->map_from_entity) return;
  last = now_ns;
  Correct(entity_id, sample);
  stats_.Add("correction_attempts");
  stats_.Add("correction_compute_us", (NowNs() - now_ns) / 1000);
}

fusion::CorrectionFilter& FusionService::FilterOf(const std::string& entity_id) {
  auto it = correction_filters_.find(entity_id);
  if (it == correction_filters_.end()) {
    const bool robot = is_robot_.count(entity_id) != 0 && is_robot_.at(entity_id);
    it = correction_filters_
             .emplace(entity_id, fusion::CorrectionFilter(robot ? options_.robot_filter
                                                                 : options_.human_filter))
             .first;
  }
  return it->second;
}

geometry::Pose2 FusionService::ExpectedPose(const std::string& entity_id,
                                           const pena_dds::ReferenceScan& sample) const {
  // The pose the entity will hold once it applied what was sent (a scan taken before the last
  // correction arrived still carries the old one: blending against it would undo that one).
  const auto sent = map_from_odom_sent_.find(entity_id);
  if (options_.filter_corrections && sent != map_from_odom_sent_.end()) {
    return geometry::Compose(sent->second, services::FromDds(sample.odom_from_body()));
  }
  return services::FromDds(sample.world_from_body());
}

void FusionService::Correct(const std::string& entity_id, const pena_dds::ReferenceScan& sample) {
  fusion::CorrectionFilter& filter = FilterOf(entity_id);
  const geometry::Pose2 entity_from_body = ExpectedPose(entity_id, sample);
  const geometry::Pose2 map_from_entity = *store_->state().entity(entity_id)->map_from_entity;
  const geometry::Pose2 predicted = geometry::Compose(map_from_entity, entity_from_body);
  fusion::CorrectionOptions options = options_.correction;
  // Section 4.2's window, sized to the prediction's uncertainty: a drifted entity searches wide,
  // one just corrected searches narrowly (fewer aliased junctions within reach).
  options.window = options_.filter_corrections ? filter.Window(options_.correction.window)
                                               : fusion::CorrectionOptions{}.window;
  const fusion::FusionCorrection match =
      fusion::ComputeCorrection(entity_id, services::FromDds(sample), entity_from_body,
                                map_from_entity, store_->state().CorrectionMap(entity_id), options);
  if (!match.accepted) {
    stats_.Add("corrections_rejected");
    spdlog::debug("{}: no correction at reference {}: {}", entity_id, sample.seq(), match.reason);
    return;
  }
  geometry::Pose2 corrected = match.matched_map_from_body;
  if (options_.filter_corrections) {
    const fusion::FilteredCorrection filtered = filter.Update(predicted, match);
    if (filtered.degenerate) stats_.Add("corrections_degenerate");
    if (!filtered.accepted) {
      stats_.Add("corrections_gated");
      spdlog::debug("{}: correction at reference {} refused: {}", entity_id, sample.seq(),
                    filtered.reason);
      return;
    }
    corrected = filtered.map_from_body;
  }
  const geometry::Pose2 move = geometry::Between(predicted, corrected);
  // Raw corrections below the minimum are not sent; filtered ones always are, because the
  // filter has counted them as applied.
  if (!options_.filter_corrections && std::hypot(move.x_m, move.y_m) < options_.correction_min_m &&
      std::abs(move.theta_rad) < options_.correction_min_rad) {
    stats_.Add("corrections_small");
    return;
  }
  spdlog::info("{}: correction at reference {} moves it ({:.3f} m, {:.3f} m, {:.4f} rad), "
               "score {:.2f}, confidence {:.2f}",
               entity_id, sample.seq(), move.x_m, move.y_m, move.theta_rad, match.score,
               match.confidence);
  Deliver(entity_id, sample, map_from_entity, corrected, match.confidence);
}

void FusionService::Deliver(const std::string& entity_id, const pena_dds::ReferenceScan& sample,
                            const geometry::Pose2& map_from_entity,
                            const geometry::Pose2& corrected, double confidence) {
  if (IsIdentity(map_from_entity)) {
    // The entity corrects its own frame, so its later walls arrive corrected: the fusion keeps
    // map_from_entity = I (docs/fusion.md, "Contract with the entity").
    pipeline::Correction correction;
    correction.kind = pipeline::Correction::Kind::kPose;
    correction.stamp_s = sample.stamp_s();
    correction.world_from_body = corrected;
    correction.confidence = confidence;
    SendCorrection(entity_id, correction, sample.seq());
    // The entity solves world_from_body = map_from_odom * odom_from_body at the stamp.
    map_from_odom_sent_[entity_id] =
        geometry::Compose(corrected, geometry::Inverse(services::FromDds(sample.odom_from_body())));
  } else {
    // A placed entity keeps its own frame: the fusion moves its walls instead (journaled).
    const geometry::Pose2 entity_from_body = services::FromDds(sample.world_from_body());
    Apply(fusion::AlignmentCorrection{
        NowS(), entity_id, geometry::Compose(corrected, geometry::Inverse(entity_from_body)),
        confidence});
  }
}

}  // namespace pena::services
