#include "pena/sim/laser_raycaster.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace pena::sim {

LaserPose LaserPoseFrom(const sensors::GroundTruth& truth) {
  LaserPose pose;
  pose.position_m = {truth.world_from_body.x_m, truth.world_from_body.y_m, truth.laser_height_m};
  pose.yaw_rad = truth.world_from_body.theta_rad;
  pose.pitch_rad = truth.pitch_rad;
  pose.roll_rad = truth.roll_rad;
  return pose;
}

Eigen::Vector3d BeamDirection(const LaserPose& pose, double beam_angle_rad) {
  // d = Rz(yaw) Ry(pitch) Rx(roll) (cos a, sin a, 0), multiplied out.
  const double ca = std::cos(beam_angle_rad), sa = std::sin(beam_angle_rad);
  const double cp = std::cos(pose.pitch_rad), sp = std::sin(pose.pitch_rad);
  const double cr = std::cos(pose.roll_rad), sr = std::sin(pose.roll_rad);
  const double cy = std::cos(pose.yaw_rad), sy = std::sin(pose.yaw_rad);
  const double x = cp * ca + sp * sa * sr;  // after Ry(pitch) Rx(roll)
  const double y = sa * cr;
  const double z = -sp * ca + cp * sa * sr;
  return {cy * x - sy * y, sy * x + cy * y, z};
}

LaserRaycaster::LaserRaycaster(std::vector<geometry::Segment2> walls, double ceiling_height_m)
    : walls_(std::move(walls)), ceiling_height_m_(ceiling_height_m) {
  if (!(ceiling_height_m > 0.0)) {
    throw std::invalid_argument("laser_raycaster: ceiling_height_m must be > 0 m, got " +
                                std::to_string(ceiling_height_m));
  }
}

std::vector<std::size_t> LaserRaycaster::WallsNear(const Eigen::Vector2d& center_m,
                                                   double radius_m) const {
  std::vector<std::size_t> near;
  for (std::size_t i = 0; i < walls_.size(); ++i) {
    if (geometry::DistanceToSegment(walls_[i], center_m) <= radius_m) near.push_back(i);
  }
  return near;
}

BeamHit LaserRaycaster::Cast(const LaserPose& pose, double beam_angle_rad, double max_range_m,
                             const std::vector<std::size_t>& candidate_walls) const {
  return CastDirection(pose, BeamDirection(pose, beam_angle_rad), max_range_m, &candidate_walls);
}

BeamHit LaserRaycaster::Cast(const LaserPose& pose, double beam_angle_rad,
                             double max_range_m) const {
  return CastDirection(pose, BeamDirection(pose, beam_angle_rad), max_range_m, nullptr);
}

BeamHit LaserRaycaster::CastDirection(const LaserPose& pose, const Eigen::Vector3d& direction,
                                      double max_range_m,
                                      const std::vector<std::size_t>* candidates) const {
  BeamHit hit;
  // The floor or ceiling plane first: any wall nearer than it is hit within [0, ceiling], because
  // the beam is between the two planes until it reaches one of them.
  double best = std::numeric_limits<double>::infinity();
  if (direction.z() < 0.0) {
    best = -pose.position_m.z() / direction.z();
    hit.kind = HitKind::kFloor;
  } else if (direction.z() > 0.0) {
    best = (ceiling_height_m_ - pose.position_m.z()) / direction.z();
    hit.kind = HitKind::kCeiling;
  }
  const double horizontal = direction.head<2>().norm();
  if (horizontal > 1e-12) {
    const Eigen::Vector2d origin = pose.position_m.head<2>();
    const Eigen::Vector2d heading = direction.head<2>() / horizontal;
    const std::size_t count = candidates ? candidates->size() : walls_.size();
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t i = candidates ? (*candidates)[k] : k;
      const auto distance = geometry::RaySegmentIntersection(origin, heading, walls_[i]);
      if (!distance) continue;
      const double range = *distance / horizontal;  // horizontal run -> 3D range
      if (range < best) {
        best = range;
        hit.kind = HitKind::kWall;
        hit.wall_index = i;
      }
    }
  }
  if (!(best <= max_range_m)) return BeamHit{};
  hit.range_m = best;
  hit.point_m = pose.position_m + best * direction;
  if (hit.kind == HitKind::kWall) {
    hit.along_m = (hit.point_m.head<2>() - walls_[hit.wall_index].start_m).norm();
  }
  return hit;
}

}  // namespace pena::sim
