#include "pena/grid/bent_scan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "pena/options_check.hpp"

namespace pena::grid {
namespace {

void Require(bool ok, const char* field, const char* rule, double value) {
  RequireOption(ok, "bent_scan", field, rule, value);
}

}  // namespace

void ValidateBentScanOptions(const BentScanOptions& o) {
  Require(std::isfinite(o.free_log_odds) && o.free_log_odds < 0.0, "free_log_odds",
          "finite and < 0 (log-odds)", o.free_log_odds);
  Require(o.min_free_ends >= 4, "min_free_ends", ">= 4", o.min_free_ends);
  Require(std::isfinite(o.min_ahead_m) && o.min_ahead_m >= 0.0, "min_ahead_m",
          "finite and >= 0 m", o.min_ahead_m);
  Require(std::isfinite(o.max_ahead_m) && o.max_ahead_m > o.min_ahead_m, "max_ahead_m",
          "finite and > min_ahead_m (m)", o.max_ahead_m);
  Require(std::isfinite(o.max_spread) && o.max_spread > 0.0, "max_spread", "finite and > 0",
          o.max_spread);
  Require(std::isfinite(o.laser_height_m) && o.laser_height_m > 0.0, "laser_height_m",
          "finite and > 0 m", o.laser_height_m);
  Require(std::isfinite(o.floor_band) && o.floor_band >= 0.0 && o.floor_band < 1.0, "floor_band",
          "in [0, 1)", o.floor_band);
}

BentScanLeveller::BentScanLeveller(const BentScanOptions& options) : options_(options) {
  ValidateBentScanOptions(options_);
}

std::optional<FloorLine> BentScanLeveller::FloorLineOf(
    const OccupancyGrid& reference, const sensors::LaserScan& scan,
    const geometry::Pose2& world_from_laser) const {
  const std::vector<Eigen::Vector2d> ends_m =
      reference.FreeEnds(scan, world_from_laser, options_.free_log_odds);
  if (static_cast<int>(ends_m.size()) < options_.min_free_ends) return std::nullopt;
  // Total least squares: the line through the centroid along the principal axis.
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : ends_m) centroid += p;
  centroid /= static_cast<double>(ends_m.size());
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const Eigen::Vector2d& p : ends_m) scatter += (p - centroid) * (p - centroid).transpose();
  const double half_trace = 0.5 * scatter.trace();
  const double off = std::hypot(0.5 * (scatter(0, 0) - scatter(1, 1)), scatter(0, 1));
  // Eigenvector of the smaller eigenvalue (half_trace - off): the line's normal.
  Eigen::Vector2d normal(scatter(0, 1), (half_trace - off) - scatter(0, 0));
  if (normal.norm() < 1e-12) normal = scatter(0, 0) <= scatter(1, 1) ? Eigen::Vector2d::UnitX()
                                                                       : Eigen::Vector2d::UnitY();
  normal.normalize();
  double distance_m = normal.dot(centroid);
  if (distance_m < 0.0) {
    normal = -normal;
    distance_m = -distance_m;
  }
  if (distance_m < options_.min_ahead_m || distance_m > options_.max_ahead_m) return std::nullopt;
  // The floor seen by a tilted plane lies on one line; scattered free ends are something else
  // (people, a door, a pose error).
  std::vector<double> residuals_m;
  residuals_m.reserve(ends_m.size());
  for (const Eigen::Vector2d& p : ends_m) residuals_m.push_back(std::abs(normal.dot(p) - distance_m));
  std::nth_element(residuals_m.begin(), residuals_m.begin() + residuals_m.size() / 2, residuals_m.end());
  if (residuals_m[residuals_m.size() / 2] > options_.max_spread * distance_m) return std::nullopt;
  return FloorLine{normal, distance_m};
}

sensors::LaserScan BentScanLeveller::Level(const sensors::LaserScan& scan,
                                           const FloorLine& floor) const {
  sensors::LaserScan level = scan;
  if (!(floor.distance_m > 0.0)) return level;
  // The scan reports the slant range, so the floor's returns r (cos a, sin a) lie on the line at
  // h / sin(tilt) (a: beam angle from the tilt's normal; the beam falls by r sin(tilt) cos a).
  const double sin_tilt = std::min(options_.laser_height_m / floor.distance_m, 1.0);
  for (std::size_t i = 0; i < level.ranges_m.size(); ++i) {
    if (!level.IsReturn(i)) continue;
    const double angle_rad = level.BeamAngle(i);
    const double towards = floor.normal.x() * std::cos(angle_rad) + floor.normal.y() * std::sin(angle_rad);
    const double range_m = level.ranges_m[i];
    if (range_m * towards >= (1.0 - options_.floor_band) * floor.distance_m) {
      level.ranges_m[i] = std::numeric_limits<float>::quiet_NaN();  // the floor, not a wall
      continue;
    }
    const double down = towards * sin_tilt;  // sine of the beam's elevation
    level.ranges_m[i] = static_cast<float>(range_m * std::sqrt(1.0 - down * down));
  }
  return level;
}

}  // namespace pena::grid
