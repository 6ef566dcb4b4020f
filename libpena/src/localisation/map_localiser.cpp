#include "pena/localisation/map_localiser.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "pena/options_check.hpp"
#include "pena/scan_matching/point_set.hpp"

namespace pena::localisation {
namespace {

void Require(bool ok, const std::string& field, const std::string& rule, double value) {
  RequireOption(ok, "map_localiser", field, rule, value);
}

void Validate(const MapLocaliserOptions& o) {
  scan_matching::ValidateWindow(o.window, o.matcher);
  scan_matching::ValidateWindow(o.max_window, o.matcher);
  Require(o.window_growth >= 1.0, "window_growth", ">= 1", o.window_growth);
  Require(o.min_score > 0.0 && o.min_score <= 1.0, "min_score", "in (0, 1]", o.min_score);
  Require(o.reacquire_min_score > 0.0 && o.reacquire_min_score <= 1.0, "reacquire_min_score",
          "in (0, 1]", o.reacquire_min_score);
  Require(o.min_hits >= 1, "min_hits", ">= 1", o.min_hits);
  Require(o.outside_after_failures >= 1, "outside_after_failures", ">= 1",
          o.outside_after_failures);
  Require(o.oversample >= 1, "oversample", ">= 1", o.oversample);
  Require(o.min_range_m >= 0.0, "min_range_m", ">= 0 m", o.min_range_m);
  Require(o.max_range_m > o.min_range_m, "max_range_m", "> min_range_m (m)", o.max_range_m);
  Require(o.along_probe_m > 0.0, "along_probe_m", "> 0 m", o.along_probe_m);
  Require(o.along_min_drop > 0.0, "along_min_drop", "> 0", o.along_min_drop);
  Require(o.recast_min_m > 0.0, "recast_min_m", "> 0 m", o.recast_min_m);
  Require(o.recast_min_rad > 0.0, "recast_min_rad", "> 0 rad", o.recast_min_rad);
  Require(o.along_search_m >= 0.0, "along_search_m", ">= 0 m", o.along_search_m);
  Require(o.along_search_step_m > 0.0, "along_search_step_m", "> 0 m", o.along_search_step_m);
  ValidatePlanAdaptationOptions(o.plan_adaptation);
}

// The window grown by `factor`, capped at `max` per extent.
scan_matching::SearchWindow Grown(const scan_matching::SearchWindow& w,
                                  const scan_matching::SearchWindow& max, double factor) {
  scan_matching::SearchWindow out = w;
  out.size_x_m = std::min(max.size_x_m, w.size_x_m * factor);
  out.size_y_m = std::min(max.size_y_m, w.size_y_m * factor);
  out.size_theta_rad = std::min(max.size_theta_rad, w.size_theta_rad * factor);
  return out;
}

long Candidates(const scan_matching::SearchWindow& w) {
  const auto side = [](double size, double step) { return 2L * std::lround(0.5 * size / step) + 1; };
  return side(w.size_x_m, w.step_xy_m) * side(w.size_y_m, w.step_xy_m) *
         side(w.size_theta_rad, w.step_theta_rad);
}

// How much eq. 2 falls when the best pose is moved by `probe_m` either way along `direction`
// (body frame): the correlation surface's own evidence that the weak direction is constrained.
double AlongDrop(const scan_matching::CorrelationScanMatcher& matcher, const scan_matching::Points2& real,
                 const geometry::Pose2& best, const Eigen::Vector2d& direction, double probe_m) {
  const double peak = matcher.Score(real, best);
  double side = 0.0;
  for (const double sign : {-1.0, 1.0}) {
    const geometry::Pose2 moved{best.x_m + sign * probe_m * direction.x(),
                                best.y_m + sign * probe_m * direction.y(), best.theta_rad};
    side = std::max(side, matcher.Score(real, moved));
  }
  return peak - side;
}

// What one search found: the correction (weak direction dropped where the scan does not
// constrain it), the weak translation direction of the refinement (body frame), and whether the
// search's best grid pose lies inside its window, not on its edge (only such an optimum is
// re-judged: one on the edge was not searched around, and re-casting there chained corrections
// beyond the window along office seed 3's corridor).
struct Found {
  geometry::Pose2 correction;
  Eigen::Vector2d weak = Eigen::Vector2d::UnitX();
  bool interior = false;
};

bool Interior(const scan_matching::MatchResult& match, const scan_matching::SearchWindow& w) {
  const geometry::Pose2& g = match.grid_pose;
  return match.converged && std::abs(g.x_m) < 0.5 * (w.size_x_m - w.step_xy_m) &&
         std::abs(g.y_m) < 0.5 * (w.size_y_m - w.step_xy_m) &&
         std::abs(g.theta_rad) < 0.5 * (w.size_theta_rad - w.step_theta_rad);
}

}  // namespace

struct MapLocaliser::Impl {
  MapLocaliserOptions options;
  VirtualScanner scanner;
  PlanAdaptation adaptation;
  geometry::Pose2 map_from_odom;
  MapStatus status = MapStatus::kUnknown;
  scan_matching::SearchWindow window;
  int failures = 0;
  double distance_m = 0.0;
  std::optional<geometry::Pose2> last_odom;
  // The pose on the plan at the last scan (the output).
  geometry::Pose2 pose;
  bool relocalised = false;  // Relocalise was called: the next round says so

  // Real returns in the body (laser) frame within the usable range band.
  scan_matching::Points2 RealPoints(const sensors::LaserScan& scan) const {
    scan_matching::Points2 points = scan_matching::ScanToPoints(scan, options.min_range_m);
    std::erase_if(points, [&](const Eigen::Vector2d& p) { return p.norm() > options.max_range_m; });
    return points;
  }

  // The plan seen from `map_from_body` by the same laser, oversampled, in the body frame.
  scan_matching::Points2 VirtualPoints(const sensors::LaserScan& scan,
                                       const geometry::Pose2& map_from_body) const {
    if (scan.ranges_m.empty()) return {};
    sensors::LaserGeometry geometry = scan.geometry;
    geometry.angle_increment_rad /= options.oversample;
    geometry.max_range_m = std::min(options.max_range_m, scan.geometry.max_range_m > 0.0
                                                             ? scan.geometry.max_range_m
                                                             : options.max_range_m);
    const std::size_t beams = (scan.ranges_m.size() - 1) * static_cast<std::size_t>(options.oversample) + 1;
    return scan_matching::ScanToPoints(scanner.Scan(map_from_body, geometry, beams), 0.0);
  }

  void Accumulate(const geometry::Pose2& odom_from_body) {
    if (last_odom) {
      distance_m += std::hypot(odom_from_body.x_m - last_odom->x_m, odom_from_body.y_m - last_odom->y_m);
    }
    last_odom = odom_from_body;
  }

  // `on_prior`: the odometry took this pose, or a direction of it, from its motion prior.
  MapCorrection Round(const sensors::LaserScan& scan, const geometry::Pose2& odom_from_body, bool on_prior);
  // One search against the plan seen from `map_from_body` in `searched`; fills the round's
  // figures and acceptance, returns the correction it found (weak direction dropped where the
  // scan does not constrain it), also when rejected. nullopt: the plan is not in sight.
  std::optional<Found> Search(const sensors::LaserScan& scan, const scan_matching::Points2& real,
                              const geometry::Pose2& map_from_body,
                              const scan_matching::SearchWindow& searched, MapCorrection& round) const;
  // The round judged again from where `correction` puts the entity (see recast_min_m).
  MapCorrection Recast(const sensors::LaserScan& scan, const scan_matching::Points2& real,
                       const MapCorrection& round, const geometry::Pose2& correction) const;
  // A degenerate round: the places along the weak direction, each judged from where it is.
  std::optional<MapCorrection> AlongSearch(const sensors::LaserScan& scan, const scan_matching::Points2& real,
                                           const MapCorrection& round, const Found& found) const;
  Found Judge(const scan_matching::MatchResult& match, const scan_matching::CorrelationScanMatcher& matcher,
              const scan_matching::Points2& real, const scan_matching::SearchWindow& searched,
              MapCorrection& round) const;
  bool NeedsRecast(const geometry::Pose2& correction) const {
    return std::hypot(correction.x_m, correction.y_m) >= options.recast_min_m ||
           std::abs(correction.theta_rad) >= options.recast_min_rad;
  }
  void Conclude(const geometry::Pose2& odom_from_body, MapCorrection& round);
  // An accepted round's returns (body frame) measure the plan's walls (plan_adaptation).
  void Learn(const scan_matching::Points2& real, const MapCorrection& round, double walked_m);
};

// Accepts or rejects a round on the paper's correlation threshold, and keeps the least-squares
// refinement only along directions the scan constrains.
Found MapLocaliser::Impl::Judge(const scan_matching::MatchResult& match,
                                const scan_matching::CorrelationScanMatcher& matcher,
                                const scan_matching::Points2& real, const scan_matching::SearchWindow& searched,
                                MapCorrection& round) const {
  round.score = match.score;
  round.hits = match.hits;
  geometry::Pose2 correction = match.reference_from_scan;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(match.information.topLeftCorner<2, 2>());
  const Eigen::Vector2d values = solver.eigenvalues();  // ascending
  round.constraint_ratio = values(1) > 0.0 ? std::max(0.0, values(0)) / values(1) : 0.0;
  const Eigen::Vector2d weak = solver.eigenvectors().col(0);
  round.weak_axis_rad = std::atan2(weak.y(), weak.x());
  round.along_drop = AlongDrop(matcher, real, correction, weak, options.along_probe_m);
  if (round.constraint_ratio < options.degenerate_eigen_ratio && round.along_drop < options.along_min_drop) {
    // Along a corridor the point-to-line information is weak by construction; the correlation
    // surface tells whether door frames and corridor ends still pin the pose down (the score
    // falls off along the corridor). Where it is flat, a plan wall drawn across an opening
    // could drag the pose: the odometry is kept in the weak direction.
    const Eigen::Vector2d strong = solver.eigenvectors().col(1);
    const Eigen::Vector2d kept = strong * strong.dot(Eigen::Vector2d(correction.x_m, correction.y_m));
    correction.x_m = kept.x();
    correction.y_m = kept.y();
    round.degenerate = true;
  }
  const double min_score =
      status == MapStatus::kOutsideMap ? options.reacquire_min_score : options.min_score;
  // The least-squares refinement after the search is not bounded by the window. It may finish a
  // little beyond it, but a correction more than twice the searched half-extent was not searched
  // for (intel: a -17 deg turn out of a +/-2 deg window lost the entity for good).
  const geometry::Pose2& found = match.reference_from_scan;
  const bool in_window = std::abs(found.x_m) <= searched.size_x_m &&
                         std::abs(found.y_m) <= searched.size_y_m &&
                         std::abs(found.theta_rad) <= searched.size_theta_rad;
  round.accepted =
      match.converged && in_window && match.hits >= options.min_hits && match.score >= min_score;
  round.confidence = match.score * std::min(1.0, match.hits / (2.0 * options.min_hits));
  round.correction = round.accepted ? correction : geometry::Pose2{};
  return {correction, weak, in_window && Interior(match, searched)};
}

void MapLocaliser::Impl::Conclude(const geometry::Pose2& odom_from_body, MapCorrection& round) {
  round.map_from_body_after = geometry::Compose(round.map_from_body_before, round.correction);
  if (round.accepted) {
    map_from_odom = geometry::Compose(round.map_from_body_after, geometry::Inverse(odom_from_body));
    pose = geometry::Compose(map_from_odom, odom_from_body);
    status = relocalised                          ? MapStatus::kRelocalised
             : status == MapStatus::kOutsideMap ? MapStatus::kReacquired
                                                : MapStatus::kInMap;
    failures = 0;
    distance_m = 0.0;
    window = options.window;
  } else {
    ++failures;
    if (failures >= options.outside_after_failures) status = MapStatus::kOutsideMap;
    window = Grown(window, options.max_window, options.window_growth);
    if (relocalised) status = MapStatus::kRelocalised;
  }
  relocalised = false;
  round.status = status;
}

std::optional<Found> MapLocaliser::Impl::Search(const sensors::LaserScan& scan, const scan_matching::Points2& real,
                                                const geometry::Pose2& map_from_body,
                                                const scan_matching::SearchWindow& searched,
                                                MapCorrection& round) const {
  const scan_matching::Points2 virtual_points = VirtualPoints(scan, map_from_body);
  round.virtual_points = static_cast<int>(virtual_points.size());
  round.accepted = false;
  round.degenerate = false;
  round.correction = {};
  if (real.empty() || virtual_points.size() < static_cast<std::size_t>(options.min_hits)) {
    return std::nullopt;
  }
  const scan_matching::CorrelationScanMatcher matcher(options.matcher, virtual_points);
  // Exhaustive search is cheaper for the paper's small window (no max-grids to build).
  const scan_matching::MatchResult match =
      Candidates(searched) > 20000 ? matcher.MatchBranchAndBound(real, {}, searched)
                                   : matcher.MatchExhaustive(real, {}, searched);
  return Judge(match, matcher, real, searched, round);
}

MapCorrection MapLocaliser::Impl::Recast(const sensors::LaserScan& scan, const scan_matching::Points2& real,
                                         const MapCorrection& round, const geometry::Pose2& correction) const {
  MapCorrection again = round;
  const auto refined =
      Search(scan, real, geometry::Compose(round.map_from_body_before, correction), options.window, again);
  again.recast = true;
  again.first_score = round.first_score;
  if (refined && again.accepted) again.correction = geometry::Compose(correction, again.correction);
  return again;
}

std::optional<MapCorrection> MapLocaliser::Impl::AlongSearch(const sensors::LaserScan& scan,
                                                             const scan_matching::Points2& real,
                                                             const MapCorrection& round, const Found& found) const {
  std::optional<MapCorrection> best;
  const int steps = static_cast<int>(std::floor(options.along_search_m / options.along_search_step_m + 1e-9));
  for (int k = -steps; k <= steps; ++k) {
    if (k == 0) continue;
    const double along_m = k * options.along_search_step_m;
    const geometry::Pose2 moved{found.correction.x_m + along_m * found.weak.x(),
                                found.correction.y_m + along_m * found.weak.y(), found.correction.theta_rad};
    MapCorrection candidate = Recast(scan, real, round, moved);
    // Only a place the scan pins down there (door frames, a corridor end) can tell, and it
    // needs the evidence of a re-acquisition: a search this wide errs more (the team building's
    // disturbed-compass walk took a place 1.3 m off that scored 0.68).
    if (!candidate.accepted || candidate.degenerate || candidate.score < options.reacquire_min_score) continue;
    if (!best || candidate.score > best->score) best = candidate;
  }
  if (!best || best->score < round.score + options.along_min_drop) return std::nullopt;
  return best;
}

MapCorrection MapLocaliser::Impl::Round(const sensors::LaserScan& scan,
                                        const geometry::Pose2& odom_from_body, bool on_prior) {
  MapCorrection round;
  round.stamp_s = scan.stamp_s;
  round.map_from_body_before = pose;  // map_from_odom * odom_from_body
  round.window_xy_m = std::max(window.size_x_m, window.size_y_m);
  round.window_theta_rad = window.size_theta_rad;
  const scan_matching::Points2 real = RealPoints(scan);
  round.points = static_cast<int>(real.size());
  const std::optional<Found> found = Search(scan, real, round.map_from_body_before, window, round);
  round.first_score = round.score;
  if (found && found->interior && NeedsRecast(found->correction)) {
    // A large correction is judged on the plan as seen from where it puts the entity.
    round = Recast(scan, real, round, found->correction);
  } else if (found && round.accepted && round.degenerate && on_prior && options.along_search_m > 0.0) {
    // The odometry's own position along the weak direction came from its motion prior, which
    // may have slid (office seed 1 at 166.5 s: 0.47 m along the corridor in one keyframe).
    if (auto along = AlongSearch(scan, real, round, *found)) round = *along;
  }
  const double walked_m = distance_m;  // since the round before (Conclude resets it)
  Conclude(odom_from_body, round);
  if (round.accepted) Learn(real, round, walked_m);
  return round;
}

void MapLocaliser::Impl::Learn(const scan_matching::Points2& real, const MapCorrection& round, double walked_m) {
  if (!options.plan_adaptation.enabled) return;
  const geometry::Pose2& map_from_body = round.map_from_body_after;
  const geometry::Pose2& before = round.map_from_body_before;
  const RoundView view{Eigen::Vector2d(map_from_body.x_m, map_from_body.y_m),
                       Eigen::Vector3d(map_from_body.x_m - before.x_m, map_from_body.y_m - before.y_m,
                                       geometry::NormalizeAngle(map_from_body.theta_rad - before.theta_rad)),
                       walked_m};
  scan_matching::Points2 on_map;
  on_map.reserve(real.size());
  for (const Eigen::Vector2d& p : real) on_map.push_back(geometry::TransformPoint(map_from_body, p));
  if (adaptation.Observe(on_map, view)) scanner = VirtualScanner(adaptation.plan(), options.scanner);
}

MapLocaliser::MapLocaliser(const MapLocaliserOptions& options, std::vector<geometry::Segment2> plan,
                           const geometry::Pose2& map_from_odom) {
  Validate(options);
  PlanAdaptation adaptation(options.plan_adaptation, plan);
  impl_ = std::make_unique<Impl>(Impl{options, VirtualScanner(std::move(plan), options.scanner),
                                      std::move(adaptation), map_from_odom, MapStatus::kUnknown, options.window, 0, 0.0,
                                      std::nullopt, map_from_odom, false});
}

MapLocaliser::~MapLocaliser() = default;
MapLocaliser::MapLocaliser(MapLocaliser&&) noexcept = default;
MapLocaliser& MapLocaliser::operator=(MapLocaliser&&) noexcept = default;

std::optional<MapCorrection> MapLocaliser::Update(const sensors::LaserScan& scan,
                                                  const odometry::OdometryEstimate& estimate,
                                                  bool force) {
  impl_->pose = MapFromBody(estimate.world_from_body);
  impl_->Accumulate(estimate.world_from_body);
  if (!estimate.reference_changed && !force && !impl_->options.every_scan) return std::nullopt;
  const bool matched = estimate.status == odometry::MatchStatus::kMatched ||
                       estimate.status == odometry::MatchStatus::kFirst;
  return impl_->Round(scan, estimate.world_from_body, !matched || estimate.gated);
}

geometry::Pose2 MapLocaliser::MapFromBody(const geometry::Pose2& odom_from_body) const {
  return geometry::Compose(impl_->map_from_odom, odom_from_body);
}

const geometry::Pose2& MapLocaliser::map_from_odom() const { return impl_->map_from_odom; }
const geometry::Pose2& MapLocaliser::map_from_body() const { return impl_->pose; }

void MapLocaliser::Reset(const geometry::Pose2& map_from_odom) {
  impl_->map_from_odom = map_from_odom;
  impl_->status = MapStatus::kUnknown;
  impl_->failures = 0;
  impl_->distance_m = 0.0;
  impl_->window = impl_->options.window;
  impl_->pose = map_from_odom;
}

void MapLocaliser::Relocalise(const geometry::Pose2& map_from_odom) {
  Reset(map_from_odom);
  impl_->relocalised = true;
}

MapStatus MapLocaliser::status() const { return impl_->status; }
double MapLocaliser::distance_since_correction_m() const { return impl_->distance_m; }
const VirtualScanner& MapLocaliser::scanner() const { return impl_->scanner; }
const std::vector<SegmentShift>& MapLocaliser::plan_shifts() const { return impl_->adaptation.shifts(); }

const char* ToString(MapStatus status) {
  switch (status) {
    case MapStatus::kUnknown: return "unknown";
    case MapStatus::kInMap: return "in_map";
    case MapStatus::kOutsideMap: return "outside_map";
    case MapStatus::kReacquired: return "reacquired";
    case MapStatus::kRelocalised: return "relocalised";
  }
  return "unknown";
}

}  // namespace pena::localisation
