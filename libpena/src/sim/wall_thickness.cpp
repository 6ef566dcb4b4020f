#include "pena/sim/wall_thickness.hpp"

#include <Eigen/Core>

namespace pena::sim {

std::vector<geometry::Segment2> ThickWallFaces(const std::vector<geometry::Segment2>& walls,
                                               double thickness_m) {
  const double half_m = thickness_m / 2.0;
  std::vector<geometry::Segment2> faces;
  faces.reserve(walls.size() * kFacesPerThickWall);
  for (const geometry::Segment2& wall : walls) {
    Eigen::Vector2d along = wall.end_m - wall.start_m;
    const double length_m = along.norm();
    along = length_m > 0.0 ? Eigen::Vector2d(along / length_m) : Eigen::Vector2d::UnitX();
    const Eigen::Vector2d left(-along.y(), along.x());
    const Eigen::Vector2d start = wall.start_m - half_m * along;
    const Eigen::Vector2d end = wall.end_m + half_m * along;
    faces.push_back({start + half_m * left, end + half_m * left});
    faces.push_back({start - half_m * left, end - half_m * left});
    faces.push_back({start - half_m * left, start + half_m * left});
    faces.push_back({end - half_m * left, end + half_m * left});
  }
  return faces;
}

}  // namespace pena::sim
