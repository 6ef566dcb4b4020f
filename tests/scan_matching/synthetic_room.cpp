#include "synthetic_room.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace pena::testing {

std::vector<geometry::Segment2> SyntheticRoom() {
  auto wall = [](double x1, double y1, double x2, double y2) {
    return geometry::Segment2{{x1, y1}, {x2, y2}};
  };
  return {wall(0, 0, 8, 0),     wall(8, 0, 8, 5),       wall(8, 5, 4.5, 5),  wall(3.5, 5, 0, 5),
          wall(0, 5, 0, 0),     wall(5, 1.5, 5.4, 1.5), wall(5.4, 1.5, 5.4, 1.9),
          wall(5.4, 1.9, 5, 1.9), wall(5, 1.9, 5, 1.5), wall(1, 4.2, 2.5, 4.2),
          wall(2.5, 4.2, 2.5, 5)};
}

scan_matching::Points2 ScanRoom(const std::vector<geometry::Segment2>& walls,
                                const geometry::Pose2& world_from_laser, double noise_m,
                                std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, noise_m > 0.0 ? noise_m : 1e-12);
  scan_matching::Points2 points;
  const Eigen::Vector2d origin(world_from_laser.x_m, world_from_laser.y_m);
  for (int i = 0; i < 361; ++i) {
    const double angle = -std::numbers::pi / 2 + i * std::numbers::pi / 360.0;
    const double world_angle = world_from_laser.theta_rad + angle;
    const Eigen::Vector2d direction(std::cos(world_angle), std::sin(world_angle));
    double range = std::numeric_limits<double>::infinity();
    for (const auto& segment : walls) {
      if (const auto hit = geometry::RaySegmentIntersection(origin, direction, segment)) {
        range = std::min(range, *hit);
      }
    }
    if (!std::isfinite(range)) continue;
    range += noise_m > 0.0 ? noise(rng) : 0.0;
    points.emplace_back(range * std::cos(angle), range * std::sin(angle));
  }
  return points;
}

}  // namespace pena::testing
