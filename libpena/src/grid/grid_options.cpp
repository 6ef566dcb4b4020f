#include "pena/grid/grid_options.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "pena/options_check.hpp"

namespace pena::grid {
namespace {

void Require(bool ok, const char* field, const char* rule, double value) {
  RequireOption(ok, "grid", field, rule, value);
}

}  // namespace

void ValidateGridOptions(const GridOptions& options) {
  // !(x > 0) rather than x <= 0 so NaN is refused too.
  Require(std::isfinite(options.resolution_m) && options.resolution_m > 0.0, "resolution_m",
          "finite and > 0 m", options.resolution_m);
  Require(std::isfinite(options.hit_log_odds) && options.hit_log_odds > 0.0, "hit_log_odds",
          "finite and > 0 (log-odds)", options.hit_log_odds);
  Require(std::isfinite(options.miss_log_odds) && options.miss_log_odds < 0.0, "miss_log_odds",
          "finite and < 0 (log-odds)", options.miss_log_odds);
  Require(std::isfinite(options.min_log_odds) && options.min_log_odds < 0.0, "min_log_odds",
          "finite and < 0 (log-odds)", options.min_log_odds);
  Require(std::isfinite(options.max_log_odds) && options.max_log_odds > 0.0, "max_log_odds",
          "finite and > 0 (log-odds)", options.max_log_odds);
  Require(std::isfinite(options.no_return_clear_m) && options.no_return_clear_m >= 0.0,
          "no_return_clear_m", "finite and >= 0 m", options.no_return_clear_m);
  Require(std::isfinite(options.max_range_m) && options.max_range_m > 0.0, "max_range_m",
          "finite and > 0 m", options.max_range_m);
  Require(std::isfinite(options.surface_band_m) && options.surface_band_m >= 0.0, "surface_band_m",
          "finite and >= 0 m", options.surface_band_m);
  Require(std::isfinite(options.max_surface_skip_m) && options.max_surface_skip_m >= 0.0,
          "max_surface_skip_m", "finite and >= 0 m", options.max_surface_skip_m);
  Require(std::isfinite(options.max_size_m) && options.max_size_m >= options.resolution_m,
          "max_size_m", "finite and >= resolution_m (m)", options.max_size_m);
  // Cells are indexed with int; keep the largest grid well inside it.
  Require(options.max_size_m / options.resolution_m <= 1.0e5, "max_size_m",
          "at most 100000 cells (max_size_m / resolution_m)", options.max_size_m);
}

double ProbabilityFromLogOdds(double log_odds) { return 1.0 - 1.0 / (1.0 + std::exp(log_odds)); }

}  // namespace pena::grid
