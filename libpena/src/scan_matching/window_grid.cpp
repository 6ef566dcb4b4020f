#include "window_grid.hpp"

#include <cmath>
#include <tuple>

namespace pena::scan_matching::internal {
namespace {

// Steps on each side of the centre that fit in half the window (a small slack so 0.3 / 0.06 = 5).
int StepsPerSide(double size, double step) {
  return static_cast<int>(std::floor(0.5 * size / step + 1e-9));
}

}  // namespace

WindowGrid MakeWindowGrid(const SearchWindow& window, const CorrelationMatcherOptions& options) {
  const double resolution_m = options.grid_resolution_m;
  WindowGrid grid;
  grid.center_x = StepsPerSide(window.size_x_m, window.step_xy_m);
  grid.center_y = StepsPerSide(window.size_y_m, window.step_xy_m);
  grid.center_angle = StepsPerSide(window.size_theta_rad, window.step_theta_rad);
  grid.num_x = 2 * grid.center_x + 1;
  grid.num_y = 2 * grid.center_y + 1;
  grid.num_angles = 2 * grid.center_angle + 1;
  grid.step_cells = static_cast<int>(std::lround(window.step_xy_m / resolution_m));
  grid.step_xy_m = grid.step_cells * resolution_m;
  grid.step_theta_rad = window.step_theta_rad;
  return grid;
}

bool Better(const Candidate& a, const Candidate& b) {
  if (a.score != b.score) return a.score > b.score;
  return std::tie(a.distance_sq, a.angle, a.x, a.y) < std::tie(b.distance_sq, b.angle, b.x, b.y);
}

long DistanceSq(const WindowGrid& grid, int angle, int x, int y) {
  const long da = angle - grid.center_angle;
  const long dx = x - grid.center_x;
  const long dy = y - grid.center_y;
  return da * da + dx * dx + dy * dy;
}

Candidate MakeCandidate(const WindowGrid& grid, int angle, int x, int y, long score) {
  return {angle, x, y, score, DistanceSq(grid, angle, x, y)};
}

std::vector<Eigen::Vector2i> DiscretizeScan(const HitGrid& hits, const Points2& scan,
                                            const geometry::Pose2& reference_from_prior,
                                            const WindowGrid& grid, int angle) {
  const geometry::Pose2 lowest{
      reference_from_prior.x_m - grid.center_x * grid.step_xy_m,
      reference_from_prior.y_m - grid.center_y * grid.step_xy_m,
      reference_from_prior.theta_rad + (angle - grid.center_angle) * grid.step_theta_rad};
  std::vector<Eigen::Vector2i> cells;
  cells.reserve(scan.size());
  const geometry::PointTransform transform(lowest);
  for (const auto& point : scan) cells.push_back(hits.CellOf(transform(point)));
  return cells;
}

geometry::Pose2 PoseOf(const WindowGrid& grid, const geometry::Pose2& reference_from_prior,
                       const Candidate& candidate) {
  return {reference_from_prior.x_m + (candidate.x - grid.center_x) * grid.step_xy_m,
          reference_from_prior.y_m + (candidate.y - grid.center_y) * grid.step_xy_m,
          geometry::NormalizeAngle(reference_from_prior.theta_rad +
                                   (candidate.angle - grid.center_angle) * grid.step_theta_rad)};
}

}  // namespace pena::scan_matching::internal
