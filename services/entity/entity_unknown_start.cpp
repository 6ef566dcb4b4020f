// pena-entity --unknown-start (docs/services.md, "Unknown start"): the log's start pose is not
// used; the chain runs in the entity's own frame (its first pose is the origin), so its local map
// and odom_from_body stay in that frame for the whole run, and the status says start_unknown.
// The fusion places the entity by matching that map to the global map and sends its frame as a
// CORRECTION_MAP_FROM_ODOM (map_from_entity); later alignment moves come the same way. The frame
// is applied to the poses the entity publishes (world_from_body), never to its chain, whose map
// must stay in one frame for the fusion's placement to hold. Part of EntityService.
#include <spdlog/spdlog.h>

#include <cmath>

#include "entity_service.hpp"
#include "from_dds.hpp"

namespace pena::services {

geometry::Pose2 EntityService::StartFrame(const geometry::Pose2& known_world_from_start) const {
  if (!options_.start_unknown) return known_world_from_start;
  spdlog::info("{}: start unknown (--unknown-start): the log's start pose ({:.3f}, {:.3f}, "
               "{:.3f}) is not used; running in the entity's own frame until the fusion places "
               "it",
               entity_id_, known_world_from_start.x_m, known_world_from_start.y_m,
               known_world_from_start.theta_rad);
  return geometry::Pose2{};
}

void EntityService::ToPlacedFrame(pipeline::ScanStep& step) const {
  if (!map_from_entity_) return;
  step.world_from_body = geometry::Compose(*map_from_entity_, step.world_from_body);
  // The covariance turns with the frame: R P R^T on the position block and its cross terms.
  const double c = std::cos(map_from_entity_->theta_rad);
  const double s = std::sin(map_from_entity_->theta_rad);
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  rotation.topLeftCorner<2, 2>() << c, -s, s, c;
  step.covariance = rotation * step.covariance * rotation.transpose();
}

void EntityService::HandleFrameCorrection(const pena_dds::Correction& sample) {
  const std::string status = [&]() -> std::string {
    if (sample.kind() != pena_dds::CORRECTION_MAP_FROM_ODOM) {
      // A pose at a stamp (an operator's) would need the fusion's frame; not handled here.
      return "ignored: an entity with an unknown start takes only its frame "
             "(CORRECTION_MAP_FROM_ODOM)";
    }
    const geometry::Pose2 frame = FromDds(sample.map_from_odom());
    if (!std::isfinite(frame.x_m) || !std::isfinite(frame.y_m) || !std::isfinite(frame.theta_rad)) {
      return "ignored: frame not finite";
    }
    if (!map_from_entity_) {
      spdlog::info("{}: placed by the fusion: map_from_entity ({:.3f} m, {:.3f} m, {:.4f} rad)",
                   entity_id_, frame.x_m, frame.y_m, frame.theta_rad);
    }
    map_from_entity_ = frame;
    correction_seq_ = sample.seq();
    return "applied";
  }();
  spdlog::debug("{}: frame correction {} {}", entity_id_, sample.seq(), status);
  if (status != "applied") spdlog::warn("{}: correction {} {}", entity_id_, sample.seq(), status);
  if (recorder_) {
    const geometry::Pose2 frame = map_from_entity_.value_or(geometry::Pose2{});
    recorder_->Csv("received_corrections", "seq,kind,stamp_s,confidence,map_from_odom_x_m,"
                   "map_from_odom_y_m,map_from_odom_theta_rad,status",
                   std::to_string(sample.seq()) + ',' + std::to_string(sample.kind()) + ',' +
                       std::to_string(sample.stamp_s()) + ',' +
                       std::to_string(sample.confidence()) + ',' + std::to_string(frame.x_m) +
                       ',' + std::to_string(frame.y_m) + ',' + std::to_string(frame.theta_rad) +
                       ',' + (status == "applied" ? "applied" : "ignored"));
  }
}

}  // namespace pena::services
