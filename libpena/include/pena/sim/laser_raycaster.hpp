#pragma once
// Casts the beams of a tilted planar laser into a building of vertical walls between a floor
// (z = 0) and a ceiling (z = ceiling height): the 3D geometry behind floor and ceiling hits.

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <vector>

#include "pena/geometry/segment2.hpp"
#include "pena/sensors/ground_truth.hpp"

namespace pena::sim {

// What a beam hit first.
enum class HitKind { kNothing, kWall, kFloor, kCeiling };

// The first surface along one beam.
struct BeamHit {
  HitKind kind = HitKind::kNothing;
  double range_m = std::numeric_limits<double>::infinity();  // along the 3D beam
  std::size_t wall_index = 0;                                // kWall: index into the wall list
  double along_m = 0.0;                               // kWall: distance from the wall's start point
  Eigen::Vector3d point_m = Eigen::Vector3d::Zero();  // mission frame, z up from the floor
};

// Where the laser is and how it is tilted: the pose and tilt of sensors::GroundTruth (laser at
// the body origin). Orientation = Rz(yaw) * Ry(pitch) * Rx(roll), so positive pitch turns the
// beam ahead down and positive roll lifts the left (+y) side.
struct LaserPose {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  double yaw_rad = 0.0;
  double pitch_rad = 0.0;
  double roll_rad = 0.0;
};

// The laser pose implied by a ground-truth record.
LaserPose LaserPoseFrom(const sensors::GroundTruth& truth);

// Unit direction in the mission frame of the beam at `beam_angle_rad` (laser frame, CCW).
Eigen::Vector3d BeamDirection(const LaserPose& pose, double beam_angle_rad);

// Ray casting against one building. Holds a copy of the walls.
class LaserRaycaster {
 public:
  // Throws std::invalid_argument unless ceiling_height_m > 0.
  LaserRaycaster(std::vector<geometry::Segment2> walls, double ceiling_height_m);

  // Walls within `radius_m` (horizontally) of `center_m`: the candidates for one scan.
  std::vector<std::size_t> WallsNear(const Eigen::Vector2d& center_m, double radius_m) const;

  // The first hit within max_range_m of the beam at `beam_angle_rad` (laser frame), testing only
  // `candidate_walls` (e.g. from WallsNear) besides the floor and ceiling planes.
  BeamHit Cast(const LaserPose& pose, double beam_angle_rad, double max_range_m,
               const std::vector<std::size_t>& candidate_walls) const;
  // Same, testing every wall.
  BeamHit Cast(const LaserPose& pose, double beam_angle_rad, double max_range_m) const;

  const std::vector<geometry::Segment2>& walls() const { return walls_; }
  double ceiling_height_m() const { return ceiling_height_m_; }

 private:
  BeamHit CastDirection(const LaserPose& pose, const Eigen::Vector3d& direction, double max_range_m,
                        const std::vector<std::size_t>* candidates) const;

  std::vector<geometry::Segment2> walls_;
  double ceiling_height_m_;
};

}  // namespace pena::sim
