#include "pena/scan_matching/correlation_scan_matcher.hpp"

#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "branch_and_bound.hpp"
#include "least_squares_refiner.hpp"
#include "nearest_neighbours.hpp"
#include "pena/options_check.hpp"
#include "pena/scan_matching/hit_grid.hpp"
#include "window_grid.hpp"

namespace pena::scan_matching {
namespace {

void Require(bool ok, const std::string& field, const std::string& unit, double value) {
  RequireOption(ok, "scan_matcher", field, "> 0" + unit, value);
}

}  // namespace

struct CorrelationScanMatcher::Impl {
  HitGrid hits;
  internal::NearestNeighbours neighbours;
  // Max-grids by step (in cells), built on first use and kept for the reference's lifetime:
  // building them costs more than a search. This makes matching not thread-safe.
  std::map<int, std::unique_ptr<internal::MaxGrids>> max_grids;

  // built_s: the time spent building them now (0 when cached).
  const internal::MaxGrids& MaxGridsFor(const internal::WindowGrid& grid, double& built_s) {
    auto& slot = max_grids[grid.step_cells];
    const int levels = internal::TopLevel(grid) + 1;
    built_s = 0.0;
    if (!slot || slot->levels() < levels) {
      const auto started = std::chrono::steady_clock::now();
      slot = std::make_unique<internal::MaxGrids>(hits, grid.step_cells, 1 << (levels - 1));
      built_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    }
    return *slot;
  }
};

void ValidateOptions(const CorrelationMatcherOptions& options) {
  Require(options.threshold_m > 0.0, "threshold_m", " m", options.threshold_m);
  Require(options.grid_resolution_m > 0.0, "grid_resolution_m", " m", options.grid_resolution_m);
  Require(options.refine_iterations >= 0, "refine_iterations", " (or 0)",
          options.refine_iterations);
  // NaN fails both checks as well.
}

void ValidateWindow(const SearchWindow& window, const CorrelationMatcherOptions& options) {
  ValidateOptions(options);
  Require(window.size_x_m >= 0.0, "window.size_x_m", " m (or 0)", window.size_x_m);
  Require(window.size_y_m >= 0.0, "window.size_y_m", " m (or 0)", window.size_y_m);
  Require(window.size_theta_rad >= 0.0, "window.size_theta_rad", " rad (or 0)",
          window.size_theta_rad);
  Require(window.step_xy_m > 0.0, "window.step_xy_m", " m", window.step_xy_m);
  Require(window.step_theta_rad > 0.0, "window.step_theta_rad", " rad", window.step_theta_rad);
  const double cells = window.step_xy_m / options.grid_resolution_m;
  if (std::abs(cells - std::round(cells)) > 1e-6 || std::round(cells) < 1.0) {
    throw std::invalid_argument("scan_matcher.window.step_xy_m (" +
                                std::to_string(window.step_xy_m) +
                                " m) must be a whole multiple of grid_resolution_m (" +
                                std::to_string(options.grid_resolution_m) + " m)");
  }
}

CorrelationScanMatcher::CorrelationScanMatcher(const CorrelationMatcherOptions& options,
                                               const Points2& reference)
    : options_(options) {
  ValidateOptions(options);
  impl_ = std::make_unique<Impl>(Impl{HitGrid(reference, options.grid_resolution_m,
                                              options.threshold_m, options.graded),
                                      internal::NearestNeighbours(reference), {}});
}

CorrelationScanMatcher::~CorrelationScanMatcher() = default;
CorrelationScanMatcher::CorrelationScanMatcher(CorrelationScanMatcher&&) noexcept = default;
CorrelationScanMatcher& CorrelationScanMatcher::operator=(CorrelationScanMatcher&&) noexcept =
    default;

MatchResult CorrelationScanMatcher::MatchExhaustive(const Points2& scan,
                                                    const geometry::Pose2& reference_from_prior,
                                                    const SearchWindow& window,
                                                    Polish polish) const {
  ValidateWindow(window, options_);
  const internal::WindowGrid grid = internal::MakeWindowGrid(window, options_);
  internal::Candidate best;
  long scored = 0;
  for (int angle = 0; angle < grid.num_angles; ++angle) {
    const auto cells = internal::DiscretizeScan(impl_->hits, scan, reference_from_prior, grid, angle);
    for (int x = 0; x < grid.num_x; ++x) {
      for (int y = 0; y < grid.num_y; ++y) {
        long hits = 0;
        for (const auto& cell : cells) {
          hits += impl_->hits.At(cell.x() + x * grid.step_cells, cell.y() + y * grid.step_cells);
        }
        const internal::Candidate candidate = internal::MakeCandidate(grid, angle, x, y, hits);
        if (internal::Better(candidate, best)) best = candidate;
        ++scored;
      }
    }
  }
  return internal::Finish(impl_->neighbours, impl_->hits, options_, scan, grid, reference_from_prior, best,
                          scored, polish);
}

MatchResult CorrelationScanMatcher::MatchBranchAndBound(const Points2& scan,
                                                        const geometry::Pose2& reference_from_prior,
                                                        const SearchWindow& window,
                                                        Polish polish) const {
  ValidateWindow(window, options_);
  const internal::WindowGrid grid = internal::MakeWindowGrid(window, options_);
  long scored = 0;
  double max_grids_s = 0.0;
  const internal::MaxGrids& max_grids = impl_->MaxGridsFor(grid, max_grids_s);
  const internal::Candidate best =
      internal::BranchAndBound(impl_->hits, max_grids, scan, reference_from_prior, grid, scored);
  MatchResult result = internal::Finish(impl_->neighbours, impl_->hits, options_, scan, grid,
                                        reference_from_prior, best, scored, polish);
  result.max_grids_s = max_grids_s;
  return result;
}

void CorrelationScanMatcher::Refine(const Points2& scan, MatchResult& result) const {
  internal::RefineResult(impl_->neighbours, impl_->hits, options_, scan, result);
}

double CorrelationScanMatcher::Score(const Points2& scan,
                                     const geometry::Pose2& reference_from_scan) const {
  if (scan.empty()) return 0.0;
  const int hits = internal::CountHits(impl_->hits, scan, reference_from_scan);
  return static_cast<double>(hits) / static_cast<double>(scan.size());
}

bool OnWindowEdge(const geometry::Pose2& grid_pose, const geometry::Pose2& prior,
                  const SearchWindow& window) {
  auto edge = [](double offset, double size, double step) {
    const double steps_per_side = std::floor(0.5 * size / step + 1e-9);
    return steps_per_side > 0.0 && std::abs(offset) >= (steps_per_side - 0.5) * step;
  };
  return edge(grid_pose.x_m - prior.x_m, window.size_x_m, window.step_xy_m) ||
         edge(grid_pose.y_m - prior.y_m, window.size_y_m, window.step_xy_m) ||
         edge(geometry::NormalizeAngle(grid_pose.theta_rad - prior.theta_rad), window.size_theta_rad,
              window.step_theta_rad);
}

}  // namespace pena::scan_matching
