#include "pena/localisation/plan_openings.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "pena/options_check.hpp"

namespace pena::localisation {
namespace {

void Require(bool ok, const std::string& field, const std::string& rule, double value) {
  RequireOption(ok, "plan_adaptation", "openings." + field, rule, value);
}

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Beams that cross a wall this near an end it was drawn with slip past corners and door jambs
// (a smaller margin cuts real walls at corners).
constexpr double kEndSkipM = 0.5;
// Parts of a cut segment shorter than this are dropped.
constexpr double kKeepM = 0.1;

}  // namespace

void ValidatePlanOpeningsOptions(const PlanOpeningsOptions& o) {
  Require(o.through_margin_m > 0.0, "through_margin_m", "> 0 m", o.through_margin_m);
  Require(o.bin_m > 0.0, "bin_m", "> 0 m", o.bin_m);
  Require(o.min_through_points >= 1, "min_through_points", ">= 1", o.min_through_points);
  Require(o.min_rounds >= 1, "min_rounds", ">= 1", o.min_rounds);
  Require(o.min_width_m >= 0.0, "min_width_m", ">= 0 m", o.min_width_m);
  Require(o.hit_m >= 0.0, "hit_m", ">= 0 m", o.hit_m);
}

PlanOpenings::PlanOpenings(const PlanOpeningsOptions& options) : options_(options) {
  ValidatePlanOpeningsOptions(options_);
}

int PlanOpenings::BinCount(const geometry::Segment2& segment) const {
  const double length_m = (segment.end_m - segment.start_m).norm();
  return std::max(1, static_cast<int>(std::ceil(length_m / options_.bin_m - 1e-9)));
}

PlanOpenings::RoundMarks PlanOpenings::Mark(const scan_matching::Points2& points, const Eigen::Vector2d& origin_m,
                                            const std::vector<geometry::Segment2>& plan) {
  Eigen::Vector2d low = origin_m, high = origin_m;
  for (const Eigen::Vector2d& p : points) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const std::vector<int> near = geometry::SegmentsInBox(plan, low, high);
  RoundMarks marks;
  marks.through.resize(plan.size());
  marks.hit.resize(plan.size());
  marks.through_points.assign(plan.size(), 0);
  for (const int i : near) {
    const auto bins = static_cast<std::size_t>(BinCount(plan[static_cast<std::size_t>(i)]));
    marks.through[static_cast<std::size_t>(i)].assign(bins, false);
    marks.hit[static_cast<std::size_t>(i)].assign(bins, false);
  }
  for (const Eigen::Vector2d& p : points) {
    const Eigen::Vector2d beam = p - origin_m;
    const double range_m = beam.norm();
    if (range_m < 1e-6) continue;
    for (const int i : near) {
      const auto k = static_cast<std::size_t>(i);
      const geometry::Segment2& s = plan[k];
      const Eigen::Vector2d wall = s.end_m - s.start_m;
      const double length_m = wall.norm();
      if (length_m < 1e-9) continue;
      const auto bin_at = [&](double along_m) {
        return std::clamp(static_cast<std::size_t>(along_m / options_.bin_m), std::size_t{0}, marks.hit[k].size() - 1);
      };
      // Seen as wall: the return lies on the segment.
      const double along_m = (p - s.start_m).dot(wall) / length_m;
      if (along_m >= 0.0 && along_m <= length_m && std::abs(Cross(wall, p - s.start_m)) / length_m < options_.hit_m) {
        marks.hit[k][bin_at(along_m)] = true;
      }
      // Seen through: the beam crosses the segment well before its return.
      const double denominator = Cross(beam, wall);
      if (std::abs(denominator) < 1e-12) continue;
      const Eigen::Vector2d to_start = s.start_m - origin_m;
      const double on_beam = Cross(to_start, wall) / denominator;  // fraction of the beam
      const double on_wall = Cross(to_start, beam) / denominator;  // fraction of the segment
      if (on_beam <= 0.0 || on_beam >= 1.0 || on_wall < 0.0 || on_wall > 1.0) continue;
      // Depth behind the wall's line, not along the beam: a grazing beam ends far along the beam
      // behind a wall drawn only a little in front of the real one.
      if (std::abs(Cross(wall, p - s.start_m)) / length_m < options_.through_margin_m) continue;
      const double crossing_m = on_wall * length_m;
      if ((crossing_m < kEndSkipM && !bins_[k].open_at_start) ||
          (crossing_m > length_m - kEndSkipM && !bins_[k].open_at_end)) {
        continue;
      }
      marks.through[k][bin_at(crossing_m)] = true;
      ++marks.through_points[k];
    }
  }
  return marks;
}

std::vector<PlanOpening> PlanOpenings::Observe(const scan_matching::Points2& map_points,
                                               const Eigen::Vector2d& origin_m,
                                               std::vector<geometry::Segment2>& plan) {
  if (!options_.enabled || map_points.empty()) return {};
  if (bins_.size() < plan.size()) bins_.resize(plan.size());
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const auto count = static_cast<std::size_t>(BinCount(plan[i]));
    if (bins_[i].through.size() != count) bins_[i] = {std::vector<int>(count, 0), std::vector<int>(count, 0), false, false};
  }
  const RoundMarks marks = Mark(map_points, origin_m, plan);
  for (std::size_t i = 0; i < plan.size(); ++i) {
    if (marks.hit[i].empty()) continue;
    const bool through_round = marks.through_points[i] >= options_.min_through_points;
    for (std::size_t b = 0; b < marks.hit[i].size(); ++b) {
      if (marks.hit[i][b]) ++bins_[i].hits[b];
      if (through_round && marks.through[i][b]) ++bins_[i].through[b];
    }
  }
  return Cut(plan);
}

std::vector<PlanOpening> PlanOpenings::Cut(std::vector<geometry::Segment2>& plan) {
  std::vector<PlanOpening> cuts;
  const std::size_t segments = plan.size();  // parts appended now are judged from the next round
  for (std::size_t i = 0; i < segments; ++i) {
    const Bins& bins = bins_[i];
    const auto open = [&](std::size_t b) {
      return bins.through[b] >= options_.min_rounds && 3 * bins.hits[b] <= bins.through[b];
    };
    // The first run of open stretches wide enough, or any width where it continues an opening
    // cut before.
    const std::size_t count = bins.through.size();
    const geometry::Segment2 segment = plan[i];
    const double length_m = (segment.end_m - segment.start_m).norm();
    std::size_t first = 0, last = 0;
    double from_m = 0.0, to_m = 0.0;
    bool found = false;
    while (!found && last < count) {
      first = last;
      while (first < count && !open(first)) ++first;
      last = first;
      while (last < count && open(last)) ++last;
      if (first == last) break;
      from_m = static_cast<double>(first) * options_.bin_m;
      to_m = std::min(static_cast<double>(last) * options_.bin_m, length_m);
      found = to_m - from_m >= options_.min_width_m || (first == 0 && bins.open_at_start) ||
              (last == count && bins.open_at_end);
    }
    if (!found) continue;
    const Eigen::Vector2d along = (segment.end_m - segment.start_m) / length_m;
    const geometry::Segment2 before{segment.start_m, segment.start_m + from_m * along};
    const geometry::Segment2 after{segment.start_m + to_m * along, segment.end_m};
    const bool keep_before = from_m >= kKeepM;
    const bool keep_after = length_m - to_m >= kKeepM;
    if (!keep_before && !keep_after) continue;  // all of it open: left to the shifts and rounds
    PlanOpening cut{static_cast<int>(i), from_m, to_m, {before.end_m, after.start_m}, bins.through[first], -1};
    // The parts keep what their stretches collected (the cut is on the bin grid).
    const auto slice = [&](std::size_t from, std::size_t to) {
      const auto at = [](std::size_t k) { return static_cast<std::ptrdiff_t>(k); };
      return Bins{{bins.through.begin() + at(from), bins.through.begin() + at(to)},
                  {bins.hits.begin() + at(from), bins.hits.begin() + at(to)}, false, false};
    };
    Bins bins_before = slice(0, first);
    bins_before.open_at_start = bins.open_at_start;
    bins_before.open_at_end = true;
    Bins bins_after = slice(last, count);
    bins_after.open_at_start = true;
    bins_after.open_at_end = bins.open_at_end;
    plan[i] = keep_before ? before : after;
    bins_[i] = keep_before ? std::move(bins_before) : bins_after;
    if (keep_before && keep_after) {
      plan.push_back(after);
      bins_.push_back(std::move(bins_after));
      cut.added_index = static_cast<int>(plan.size() - 1);
    }
    cuts.push_back(cut);
    openings_.push_back(cut);
  }
  return cuts;
}

}  // namespace pena::localisation
