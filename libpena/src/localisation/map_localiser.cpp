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
  Require(o.uncertain_sigma_m > 0.0, "uncertain_sigma_m", "> 0 m", o.uncertain_sigma_m);
  Require(o.uncertain_every_scans >= 1, "uncertain_every_scans", ">= 1 scans", o.uncertain_every_scans);
  Require(o.innovation_chi2 > 0.0, "innovation_chi2", "> 0", o.innovation_chi2);
  Require(o.match_sigma_m > 0.0, "match_sigma_m", "> 0 m", o.match_sigma_m);
  Require(o.match_sigma_rad > 0.0, "match_sigma_rad", "> 0 rad", o.match_sigma_rad);
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
  if (prior_covariance) {
    round.uncertain = true;
    if (round.accepted) {
      // The innovation gate: the correction against the odometry's spread plus the match's own.
      const geometry::Pose2& c = round.correction;
      const geometry::Pose2 after = geometry::Compose(round.map_from_body_before, c);
      const Eigen::Vector3d innovation(after.x_m - round.map_from_body_before.x_m,
                                       after.y_m - round.map_from_body_before.y_m, c.theta_rad);
      Eigen::Matrix3d s = *prior_covariance;
      s.diagonal() += Eigen::Vector3d(options.match_sigma_m * options.match_sigma_m,
                                      options.match_sigma_m * options.match_sigma_m,
                                      options.match_sigma_rad * options.match_sigma_rad);
      round.innovation_nees = innovation.dot(s.inverse() * innovation);
      if (round.innovation_nees > options.innovation_chi2) round.accepted = false, round.correction = {};
    }
    if (!round.accepted) {
      // A refused round between keyframes changes nothing: the keyframe rounds judge the place.
      round.map_from_body_after = round.map_from_body_before;
      round.status = status;
      return round;
    }
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
                                      std::nullopt, map_from_odom, false, 0, Eigen::Matrix3d::Zero(), std::nullopt});
}

MapLocaliser::~MapLocaliser() = default;
MapLocaliser::MapLocaliser(MapLocaliser&&) noexcept = default;
MapLocaliser& MapLocaliser::operator=(MapLocaliser&&) noexcept = default;

std::optional<MapCorrection> MapLocaliser::Update(const sensors::LaserScan& scan,
                                                  const odometry::OdometryEstimate& estimate,
                                                  bool force) {
  Impl& m = *impl_;
  m.pose = MapFromBody(estimate.world_from_body);
  m.Accumulate(estimate.world_from_body);
  ++m.scans_since_round;
  const bool matched = estimate.status == odometry::MatchStatus::kMatched ||
                       estimate.status == odometry::MatchStatus::kFirst;
  const bool keyframe = estimate.reference_changed || force || m.options.every_scan;
  m.prior_covariance.reset();
  if (!keyframe) {
    if (!m.options.uncertain_scans || m.status == MapStatus::kUnknown ||
        m.scans_since_round < m.options.uncertain_every_scans) {
      return std::nullopt;
    }
    // The odometry's spread since the last accepted round, turned into the map frame.
    const Eigen::Matrix3d grown = estimate.covariance - m.good_covariance;
    const double c = std::cos(m.map_from_odom.theta_rad), s = std::sin(m.map_from_odom.theta_rad);
    Eigen::Matrix3d rotation;
    rotation << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
    Eigen::Matrix3d prior = rotation * (0.5 * (grown + grown.transpose())) * rotation.transpose();
    prior.diagonal() = prior.diagonal().cwiseMax(0.0);
    const double sigma_m = std::sqrt(prior(0, 0) + prior(1, 1));
    const bool unsure = !matched || estimate.gated || estimate.refused || sigma_m >= m.options.uncertain_sigma_m;
    if (!unsure) return std::nullopt;
    m.prior_covariance = prior;
    // The window covers 3 sigma of the spread (full extents), within the largest window.
    const scan_matching::SearchWindow kept = m.window;
    m.window.size_x_m = std::clamp(6.0 * std::sqrt(prior(0, 0)), kept.size_x_m, m.options.max_window.size_x_m);
    m.window.size_y_m = std::clamp(6.0 * std::sqrt(prior(1, 1)), kept.size_y_m, m.options.max_window.size_y_m);
    m.window.size_theta_rad =
        std::clamp(6.0 * std::sqrt(prior(2, 2)), kept.size_theta_rad, m.options.max_window.size_theta_rad);
    MapCorrection round = m.Round(scan, estimate.world_from_body, true);
    if (!round.accepted) m.window = kept;
    else m.good_covariance = estimate.covariance;
    m.scans_since_round = 0;
    return round;
  }
  m.scans_since_round = 0;
  MapCorrection round = m.Round(scan, estimate.world_from_body, !matched || estimate.gated);
  if (round.accepted) m.good_covariance = estimate.covariance;
  return round;
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
  impl_->good_covariance.setZero();
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
