#pragma once
// Options of the occupancy grids (Elfes 1990 log-odds model), shared by the global and local grid.

namespace pena::grid {

// Per-cell Bayesian update in log-odds, l = ln(p / (1 - p)); 0 is unknown (p = 0.5).
struct GridOptions {
  double resolution_m = 0.05;   // cell side
  double hit_log_odds = 0.85;   // added to the cell holding a return (p(occ | hit) = 0.70)
  double miss_log_odds = -0.4;  // added to each cell a beam crosses (p(occ | miss) = 0.40)
  double min_log_odds = -2.0;   // clamp below (p = 0.12), so a free cell can still turn occupied
  double max_log_odds = 3.5;    // clamp above (p = 0.97), so an occupied cell can still clear
  double no_return_clear_m =
      5.0;                     // a beam without a usable return clears this far (0 = not at all)
  double max_range_m = 30.0;   // returns at or beyond this are untrusted and used as no-returns
  // A return does not clear the cells within this distance of the surface it hit: a beam grazing
  // a wall runs inside the wall's cells for surface_band_m / sin(incidence) before its hit, and
  // would otherwise clear the wall that other beams hit (docs/grid.md). 0 = off.
  double surface_band_m = 0.05;
  double max_surface_skip_m = 1.0;  // cap on that uncleared length of one beam
  double max_size_m = 2000.0;  // largest side the grid may grow to; scans needing more are refused
};

// Throws std::invalid_argument naming the field and its unit, e.g.
// "grid.resolution_m must be > 0 m, got -1".
void ValidateGridOptions(const GridOptions& options);

// Probability of occupancy of a log-odds value.
double ProbabilityFromLogOdds(double log_odds);

}  // namespace pena::grid
