#include "pena/localisation/map_localiser.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "map_localiser_impl.hpp"
#include "pena/options_check.hpp"

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

}  // namespace

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

bool MapLocaliser::Impl::WeakReacquisition(const MapCorrection& round) const {
  return options.reacquire_pinned && (round.degenerate || round.along_drop < options.along_min_drop);
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
  const std::optional<internal::Found> found = Search(scan, real, round.map_from_body_before, window, round);
  round.first_score = round.score;
  if (found && found->interior && NeedsRecast(found->correction)) {
    // A large correction is judged on the plan as seen from where it puts the entity.
    round = Recast(scan, real, round, found->correction);
  } else if (found && round.degenerate && options.along_search_m > 0.0 &&
             ((round.accepted && on_prior) || (!round.accepted && options.along_search_failed))) {
    // The odometry's own position along the weak direction came from its motion prior, which
    // may have slid by half a metre in one keyframe, or the plan does not fit where the odometry
    // put the entity (along_search_failed).
    if (auto along = AlongSearch(scan, real, round, *found)) round = *along;
  }
  // The ends first: a round they move back is pinned by them, wherever the match's optimum lay.
  if (round.accepted) CheckEnds(real, round);
  if (round.accepted && options.require_interior && found && !found->interior_xy && !round.recast &&
      !round.ends_corrected) {
    round.accepted = false;  // an edge optimum: the place may lie beyond the window
    round.correction = {};
  }
  if (status == MapStatus::kOutsideMap && round.accepted && WeakReacquisition(round)) {
    round.accepted = false;
    round.correction = {};
  }
  const double walked_m = distance_m;  // since the round before (Conclude resets it)
  Conclude(odom_from_body, round);
  if (round.accepted) Learn(real, round, walked_m);
  return round;
}

void MapLocaliser::Impl::CheckEnds(const scan_matching::Points2& real, MapCorrection& round) const {
  const PlanEndOptions& o = options.plan_adaptation.ends;
  if (!o.enabled) return;
  const geometry::Pose2 after = geometry::Compose(round.map_from_body_before, round.correction);
  scan_matching::Points2 on_map;
  on_map.reserve(real.size());
  for (const Eigen::Vector2d& p : real) on_map.push_back(geometry::TransformPoint(after, p));
  const std::optional<Eigen::Vector2d> error =
      adaptation.ErrorAtEnds(on_map, Eigen::Vector2d(after.x_m, after.y_m), after.theta_rad);
  if (!error || error->norm() < o.min_error_m) return;
  // The round matched onto walls drawn off while the plan's own ends say otherwise (the office's
  // east end: rooms' end walls 0.3 m east seen through the doors, the jambs drawn right).
  const geometry::Pose2 moved{after.x_m - error->x(), after.y_m - error->y(), after.theta_rad};
  round.correction = geometry::Between(round.map_from_body_before, moved);
  round.ends_corrected = true;
}

void MapLocaliser::Impl::Learn(const scan_matching::Points2& real, const MapCorrection& round, double walked_m) {
  if (!options.plan_adaptation.enabled) return;
  const geometry::Pose2& map_from_body = round.map_from_body_after;
  const geometry::Pose2& before = round.map_from_body_before;
  const RoundView view{Eigen::Vector2d(map_from_body.x_m, map_from_body.y_m),
                       Eigen::Vector3d(map_from_body.x_m - before.x_m, map_from_body.y_m - before.y_m,
                                       geometry::NormalizeAngle(map_from_body.theta_rad - before.theta_rad)),
                       walked_m, map_from_body.theta_rad};
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
const std::vector<PlanOpening>& MapLocaliser::plan_openings() const { return impl_->adaptation.openings(); }

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
