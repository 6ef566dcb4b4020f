#include "pena/sim/wall_coverage.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pena::sim {

WallCoverage::WallCoverage(const std::vector<geometry::Segment2>& walls,
                           const WallCoverageOptions& options)
    : walls_(walls), options_(options) {
  if (!(options.bin_m > 0.0)) throw std::invalid_argument("wall_coverage.bin_m must be > 0 m");
  if (!(options.max_gap_m >= 0.0)) {
    throw std::invalid_argument("wall_coverage.max_gap_m must be >= 0 m");
  }
  hit_.reserve(walls_.size());
  for (const geometry::Segment2& wall : walls_) {
    const double bins = std::max(1.0, std::round(geometry::Length(wall) / options.bin_m));
    hit_.emplace_back(static_cast<std::size_t>(bins), false);
  }
}

void WallCoverage::Mark(std::size_t wall_index, double along_m) {
  if (wall_index >= hit_.size()) return;
  std::vector<bool>& bins = hit_[wall_index];
  const double length_m = geometry::Length(walls_[wall_index]);
  const double fraction = length_m > 0.0 ? along_m / length_m : 0.0;
  const double bin = std::floor(fraction * static_cast<double>(bins.size()));
  const double last = static_cast<double>(bins.size() - 1);
  bins[static_cast<std::size_t>(std::clamp(bin, 0.0, last))] = true;
}

std::vector<ObservedSegment> WallCoverage::Segments() const {
  std::vector<ObservedSegment> segments;
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    const std::vector<bool>& bins = hit_[w];
    const double count = static_cast<double>(bins.size());
    const double bin_length_m = geometry::Length(walls_[w]) / count;
    // Gaps up to max_gap_m are bridged: at 0.5 deg beam spacing a wall 10 m away is sampled
    // every ~9 cm, which would otherwise shred it into 5 cm pieces.
    const auto max_gap_bins =
        static_cast<std::size_t>(std::floor(options_.max_gap_m / bin_length_m + 1e-9));
    const Eigen::Vector2d edge = walls_[w].end_m - walls_[w].start_m;
    std::size_t i = 0;
    while (i < bins.size()) {
      if (!bins[i]) {
        ++i;
        continue;
      }
      std::size_t last = i;  // last hit bin of the run
      for (std::size_t j = i + 1; j < bins.size() && j - last <= max_gap_bins + 1; ++j) {
        if (bins[j]) last = j;
      }
      const double from = static_cast<double>(i) / count;
      const double to = static_cast<double>(last + 1) / count;
      segments.push_back({w, {walls_[w].start_m + from * edge, walls_[w].start_m + to * edge}});
      i = last + 1;
    }
  }
  return segments;
}

}  // namespace pena::sim
