#include "pena/localisation/global_localiser.hpp"

#include "pena/options_check.hpp"
#include "pena/localisation/virtual_scanner.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace pena::localisation {
namespace {

void Require(bool ok, const std::string& field, const std::string& rule, double value) {
  RequireOption(ok, "global_localiser", field, rule, value);
}

void Validate(const GlobalLocaliserOptions& o) {
  Require(o.sample_spacing_m > 0.0, "sample_spacing_m", "> 0 m", o.sample_spacing_m);
  Require(o.tile_size_m > 0.0, "tile_size_m", "> 0 m", o.tile_size_m);
  Require(o.margin_m >= 0.0, "margin_m", ">= 0 m", o.margin_m);
  Require(o.max_hypotheses >= 1, "max_hypotheses", ">= 1", o.max_hypotheses);
  Require(o.heading_sectors >= 1, "heading_sectors", ">= 1", o.heading_sectors);
  Require(o.refine_candidates >= 1, "refine_candidates", ">= 1", o.refine_candidates);
  Require(o.max_range_m > 0.0, "max_range_m", "> 0 m", o.max_range_m);
  Require(o.min_range_m >= 0.0 && o.min_range_m < o.max_range_m, "min_range_m", ">= 0 m and < max_range_m",
          o.min_range_m);
  Require(o.agreement_tolerance_m > 0.0, "agreement_tolerance_m", "> 0 m", o.agreement_tolerance_m);
  Require(o.coarse_step_theta_rad > 0.0, "coarse_step_theta_rad", "> 0 rad", o.coarse_step_theta_rad);
  scan_matching::ValidateWindow({o.tile_size_m, o.tile_size_m, 2.0 * std::numbers::pi / o.heading_sectors,
                                 o.coarse_step_xy_m, o.coarse_step_theta_rad},
                                o.coarse);
  scan_matching::ValidateWindow(o.fine_window, o.fine);
  scan_matching::ValidateWindow(o.verify_window, o.fine);
  scan_matching::ValidateWindow(o.final_window, o.fine);
}

// Best first by agreement, duplicates of a better hypothesis dropped, at most `keep`.
void Rank(int keep, GlobalResult& result) {
  auto& h = result.hypotheses;
  std::sort(h.begin(), h.end(), [](const PoseHypothesis& a, const PoseHypothesis& b) {
    return a.agreement != b.agreement ? a.agreement > b.agreement : a.score > b.score;
  });
  std::vector<PoseHypothesis> distinct;
  for (const PoseHypothesis& candidate : h) {
    const bool duplicate = std::any_of(distinct.begin(), distinct.end(), [&](const PoseHypothesis& d) {
      return SamePlace(d.map_from_body, candidate.map_from_body);
    });
    if (!duplicate) distinct.push_back(candidate);
    if (distinct.size() >= static_cast<std::size_t>(keep)) break;
  }
  h = std::move(distinct);
  result.margin = h.size() > 1 ? h[0].agreement - h[1].agreement : 1.0;
}

}  // namespace

bool SamePlace(const geometry::Pose2& a, const geometry::Pose2& b) {
  return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m) < 0.5 &&
         std::abs(geometry::NormalizeAngle(a.theta_rad - b.theta_rad)) < 0.1745;
}

scan_matching::Points2 SampleSegments(const std::vector<geometry::Segment2>& segments,
                                      double spacing_m) {
  scan_matching::Points2 points;
  for (const geometry::Segment2& s : segments) {
    const double length = geometry::Length(s);
    const int steps = std::max(1, static_cast<int>(std::ceil(length / spacing_m)));
    for (int i = 0; i <= steps; ++i) {
      points.push_back(s.start_m + (s.end_m - s.start_m) * (static_cast<double>(i) / steps));
    }
  }
  return points;
}

struct GlobalLocaliser::Impl {
  GlobalLocaliserOptions options;
  scan_matching::Points2 reference;
  scan_matching::CorrelationScanMatcher coarse;
  scan_matching::CorrelationScanMatcher fine;
  std::vector<geometry::Pose2> tile_centres;
  VirtualScanner scanner;
  Eigen::Vector2d box_low_m = Eigen::Vector2d::Zero();   // the plan's bounding box
  Eigen::Vector2d box_high_m = Eigen::Vector2d::Zero();

  bool InBox(const Eigen::Vector2d& p) const {
    return (p.array() >= box_low_m.array()).all() && (p.array() <= box_high_m.array()).all();
  }

  void MakeTiles(const std::vector<geometry::Segment2>& plan) {
    if (plan.empty()) return;
    Eigen::Vector2d low = plan.front().start_m, high = low;
    for (const auto& s : plan) {
      low = low.cwiseMin(s.start_m).cwiseMin(s.end_m);
      high = high.cwiseMax(s.start_m).cwiseMax(s.end_m);
    }
    box_low_m = low;
    box_high_m = high;
    low.array() -= options.margin_m;
    high.array() += options.margin_m;
    const double t = options.tile_size_m;
    const int nx = std::max(1, static_cast<int>(std::ceil((high.x() - low.x()) / t)));
    const int ny = std::max(1, static_cast<int>(std::ceil((high.y() - low.y()) / t)));
    for (int ix = 0; ix < nx; ++ix) {
      for (int iy = 0; iy < ny; ++iy) tile_centres.push_back({low.x() + (ix + 0.5) * t, low.y() + (iy + 0.5) * t, 0.0});
    }
  }

  // Best coarse pose of every tile and heading sector (branch and bound), the best
  // refine_candidates of them by coarse score.
  // With a heading bound only its interval is searched, in as many sectors as it spans (at most
  // heading_sectors' width each).
  std::vector<PoseHypothesis> CoarseCandidates(const scan_matching::Points2& scan, long& scored,
                                               const std::optional<HeadingBound>& bound,
                                               const std::optional<SearchRegion>& region = std::nullopt) const {
    const double full_sector_rad = 2.0 * std::numbers::pi / options.heading_sectors;
    double first_rad = -std::numbers::pi, span_rad = 2.0 * std::numbers::pi;
    int sectors = options.heading_sectors;
    if (bound && bound->tolerance_rad < std::numbers::pi) {
      first_rad = bound->heading_rad - bound->tolerance_rad;
      span_rad = 2.0 * bound->tolerance_rad;
      sectors = std::max(1, static_cast<int>(std::ceil(span_rad / full_sector_rad - 1e-9)));
    }
    const double sector_rad = span_rad / sectors;
    const scan_matching::SearchWindow window{options.tile_size_m, options.tile_size_m, sector_rad,
                                             options.coarse_step_xy_m, options.coarse_step_theta_rad};
    std::vector<PoseHypothesis> candidates;
    // A tile reaches into the region if its centre lies within the radius plus half its diagonal.
    const double tile_reach_m = options.tile_size_m * std::numbers::sqrt2 / 2.0;
    for (const geometry::Pose2& tile : tile_centres) {
      if (region && std::hypot(tile.x_m - region->centre_m.x(), tile.y_m - region->centre_m.y()) >
                        region->radius_m + tile_reach_m) {
        continue;
      }
      for (int sector = 0; sector < sectors; ++sector) {
        const geometry::Pose2 centre{tile.x_m, tile.y_m, first_rad + (sector + 0.5) * sector_rad};
        const scan_matching::MatchResult match = coarse.MatchBranchAndBound(scan, centre, window);
        scored += match.candidates_scored;
        if (!match.converged) continue;
        candidates.push_back({match.grid_pose, match.score, match.hits, match.score});
      }
    }
    const auto keep = std::min<std::size_t>(candidates.size(), static_cast<std::size_t>(options.refine_candidates));
    std::partial_sort(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(keep), candidates.end(),
                      [](const PoseHypothesis& a, const PoseHypothesis& b) { return a.coarse_score > b.coarse_score; });
    candidates.resize(keep);
    return candidates;
  }

  // Beam-by-beam agreement of the real scan with the virtual scan from `map_from_body`.
  BeamAgreement Agreement(const sensors::LaserScan& scan, const geometry::Pose2& map_from_body) const {
    std::vector<float> virtual_m;
    sensors::LaserGeometry geometry = scan.geometry;
    geometry.max_range_m = options.max_range_m;
    scanner.CastScan(map_from_body, geometry, scan.ranges_m.size(), virtual_m);
    BeamAgreement counts;
    for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
      const double real = scan.ranges_m[i];
      if (!scan.IsReturn(i) || real < options.min_range_m || real > options.max_range_m) continue;
      ++counts.returns;
      const double expected = virtual_m[i];  // +inf when the plan has nothing there
      if (std::abs(real - expected) <= options.agreement_tolerance_m) ++counts.agree;
      else if (real > expected) {  // the beam passed where the plan has a wall
        ++counts.through;
        const double angle = map_from_body.theta_rad + scan.BeamAngle(i);
        const Eigen::Vector2d end(map_from_body.x_m + real * std::cos(angle), map_from_body.y_m + real * std::sin(angle));
        if (!InBox(end)) ++counts.beyond;
      }
    }
    return counts;
  }

  // Fine match around a coarse pose; the score is eq. 2 with the fine threshold.
  PoseHypothesis Refine(const scan_matching::Points2& scan, const PoseHypothesis& coarse_pose,
                        const scan_matching::SearchWindow& window) const {
    const scan_matching::MatchResult match = fine.MatchExhaustive(scan, coarse_pose.map_from_body, window);
    PoseHypothesis refined = coarse_pose;
    refined.map_from_body = match.reference_from_scan;
    refined.score = fine.Score(scan, match.reference_from_scan);
    refined.hits = static_cast<int>(std::lround(refined.score * static_cast<double>(scan.size())));
    return refined;
  }
};

GlobalLocaliser::GlobalLocaliser(std::vector<geometry::Segment2> plan,
                                 const GlobalLocaliserOptions& options) {
  Validate(options);
  scan_matching::Points2 reference = SampleSegments(plan, options.sample_spacing_m);
  impl_ = std::make_unique<Impl>(Impl{options, reference,
                                      scan_matching::CorrelationScanMatcher(options.coarse, reference),
                                      scan_matching::CorrelationScanMatcher(options.fine, reference),
                                      {}, VirtualScanner(plan)});
  impl_->MakeTiles(plan);
}

GlobalLocaliser::~GlobalLocaliser() = default;
GlobalLocaliser::GlobalLocaliser(GlobalLocaliser&&) noexcept = default;
GlobalLocaliser& GlobalLocaliser::operator=(GlobalLocaliser&&) noexcept = default;

GlobalResult GlobalLocaliser::Localise(const scan_matching::Points2& scan_body) const {
  GlobalResult result;
  scan_matching::Points2 scan = scan_body;
  std::erase_if(scan, [&](const Eigen::Vector2d& p) { return p.norm() > impl_->options.max_range_m; });
  if (scan.empty() || impl_->reference.empty()) return result;
  for (const PoseHypothesis& candidate : impl_->CoarseCandidates(scan, result.candidates_scored, std::nullopt)) {
    PoseHypothesis refined = impl_->Refine(scan, candidate, impl_->options.fine_window);
    refined.agreement = refined.score;
    result.hypotheses.push_back(refined);
  }
  Rank(impl_->options.max_hypotheses, result);
  return result;
}

GlobalResult GlobalLocaliser::Localise(const sensors::LaserScan& scan) const {
  return Localise(scan, impl_->options.max_hypotheses);
}

PoseHypothesis GlobalLocaliser::Verify(const sensors::LaserScan& scan,
                                       const geometry::Pose2& map_from_body_guess) const {
  scan_matching::Points2 points = scan_matching::ScanToPoints(scan, impl_->options.min_range_m);
  std::erase_if(points, [&](const Eigen::Vector2d& p) { return p.norm() > impl_->options.max_range_m; });
  PoseHypothesis guess{map_from_body_guess, 0.0, 0, 0.0, 0.0};
  if (points.empty() || impl_->reference.empty()) return guess;
  PoseHypothesis refined = impl_->Refine(points, guess, impl_->options.verify_window);
  refined.agreement = impl_->Agreement(scan, refined.map_from_body).fraction();
  return refined;
}

PoseHypothesis GlobalLocaliser::FitMerged(const scan_matching::Points2& points_body,
                                          const geometry::Pose2& map_from_body_guess) const {
  PoseHypothesis guess{map_from_body_guess, 0.0, 0, 0.0, 0.0};
  if (points_body.empty() || impl_->reference.empty()) return guess;
  return impl_->Refine(points_body, guess, impl_->options.final_window);
}

GlobalResult GlobalLocaliser::Localise(const sensors::LaserScan& scan, int max_hypotheses) const {
  return Localise(scan, max_hypotheses, std::nullopt);
}

GlobalResult GlobalLocaliser::Localise(const sensors::LaserScan& scan, int max_hypotheses,
                                       const std::optional<HeadingBound>& bound) const {
  return Localise(scan, max_hypotheses, bound, std::nullopt);
}

bool GlobalLocaliser::Covers(const SearchRegion& region) const {
  const Eigen::Vector2d low = impl_->box_low_m.array() - impl_->options.margin_m;
  const Eigen::Vector2d high = impl_->box_high_m.array() + impl_->options.margin_m;
  const Eigen::Vector2d far = (region.centre_m - low).cwiseAbs().cwiseMax((high - region.centre_m).cwiseAbs());
  return far.norm() <= region.radius_m;
}

GlobalResult GlobalLocaliser::Localise(const sensors::LaserScan& scan, int max_hypotheses,
                                       const std::optional<HeadingBound>& bound,
                                       const std::optional<SearchRegion>& region) const {
  scan_matching::Points2 points = scan_matching::ScanToPoints(scan, impl_->options.min_range_m);
  std::erase_if(points, [&](const Eigen::Vector2d& p) { return p.norm() > impl_->options.max_range_m; });
  GlobalResult result;
  if (points.empty() || impl_->reference.empty()) return result;
  for (const PoseHypothesis& candidate : impl_->CoarseCandidates(points, result.candidates_scored, bound, region)) {
    PoseHypothesis refined = impl_->Refine(points, candidate, impl_->options.fine_window);
    // The refinement may step a little past the bound's edge: such a pose is outside it.
    if (bound && std::abs(geometry::NormalizeAngle(refined.map_from_body.theta_rad - bound->heading_rad)) >
                     bound->tolerance_rad) {
      continue;
    }
    if (region && std::hypot(refined.map_from_body.x_m - region->centre_m.x(),
                             refined.map_from_body.y_m - region->centre_m.y()) > region->radius_m) {
      continue;
    }
    refined.agreement = impl_->Agreement(scan, refined.map_from_body).fraction();
    result.hypotheses.push_back(refined);
  }
  Rank(std::max(1, max_hypotheses), result);
  return result;
}

BeamAgreement GlobalLocaliser::Agreement(const sensors::LaserScan& scan, const geometry::Pose2& map_from_body) const {
  return impl_->Agreement(scan, map_from_body);
}

bool GlobalLocaliser::Inside(const geometry::Pose2& map_from_body) const {
  return impl_->InBox({map_from_body.x_m, map_from_body.y_m});
}

bool GlobalLocaliser::Blocked(const geometry::Pose2& from, const geometry::Pose2& to) const {
  const Eigen::Vector2d step(to.x_m - from.x_m, to.y_m - from.y_m);
  const double length = step.norm();
  if (length < 1e-6) return false;
  return std::isfinite(impl_->scanner.CastRay({from.x_m, from.y_m}, step / length, length));
}

const scan_matching::Points2& GlobalLocaliser::reference() const { return impl_->reference; }

}  // namespace pena::localisation
