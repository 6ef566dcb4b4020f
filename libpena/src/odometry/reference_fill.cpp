#include "reference_fill.hpp"

#include <cmath>

namespace pena::odometry::internal {
namespace {

// A segment whose direction is within ~15 deg of the beam joins a foreground edge to what lies
// behind it (or a wall seen at grazing incidence): nothing is known between the two returns.
constexpr double kMaxAlongBeamCos = 0.966;

}  // namespace

scan_matching::Points2 FillReference(const scan_matching::Points2& points_world,
                                     const geometry::Pose2& world_from_sensor, double spacing_m,
                                     double max_gap_m, double max_gap_beam_spacings) {
  // Neighbouring returns on one wall are at most range * beam angle / cos(incidence) apart; 3
  // beam spacings allow incidence up to 70 deg. Farther apart, they are different objects.
  if (spacing_m <= 0.0 || points_world.size() < 2) return points_world;
  const Eigen::Vector2d origin(world_from_sensor.x_m, world_from_sensor.y_m);
  scan_matching::Points2 filled;
  filled.reserve(points_world.size() * 3);
  filled.push_back(points_world.front());
  for (std::size_t i = 1; i < points_world.size(); ++i) {
    const Eigen::Vector2d& a = points_world[i - 1];
    const Eigen::Vector2d& b = points_world[i];
    const Eigen::Vector2d step = b - a;
    const double gap_m = step.norm();
    const Eigen::Vector2d ray_a = a - origin;
    const Eigen::Vector2d ray_b = b - origin;
    const double beam_spacing_m =
        0.5 * (ray_a.norm() + ray_b.norm()) *
        std::abs(std::atan2(ray_a.x() * ray_b.y() - ray_a.y() * ray_b.x(), ray_a.dot(ray_b)));
    const Eigen::Vector2d beam = (ray_a + ray_b).normalized();
    const bool within_beams =
        max_gap_beam_spacings <= 0.0 || gap_m <= max_gap_beam_spacings * beam_spacing_m;
    if (within_beams && gap_m > spacing_m && gap_m <= max_gap_m &&
        std::abs(beam.dot(step) / gap_m) < kMaxAlongBeamCos) {
      const int extra = static_cast<int>(std::floor(gap_m / spacing_m));
      for (int k = 1; k <= extra; ++k) {
        const double fraction = static_cast<double>(k) / static_cast<double>(extra + 1);
        filled.push_back(a + fraction * step);
      }
    }
    filled.push_back(b);
  }
  return filled;
}

}  // namespace pena::odometry::internal
