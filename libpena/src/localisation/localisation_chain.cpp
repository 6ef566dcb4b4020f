#include "pena/localisation/localisation_chain.hpp"

#include <cmath>

namespace pena::localisation {
namespace {

// The odometry of the unknown phase: its frame starts at an arbitrary heading, so an absolute
// compass heading would fight the gyro; a huge compass noise gives its readings no weight.
odometry::LaserOdometryOptions UnknownPhase(odometry::LaserOdometryOptions options) {
  options.dead_reckoning.heading.compass_noise_rad = 1e6;
  return options;
}

}  // namespace

struct LocalisationChain::Impl {
  LocalisationChainOptions options;
  sensors::EntityKind kind;
  odometry::LaserOdometry odometry;
  MapLocaliser map;
  std::unique_ptr<GlobalLocaliser> global;  // only while the start is still unknown
  std::unique_ptr<GlobalTracker> tracker;
  bool anchored = true;

  // Unknown start: hypotheses are followed over keyframes until one wins (section 4 needs a known
  // start; this supplies it). Then the odometry restarts at the winner on the plan, with the
  // compass, exactly as with a known start.
  void TryGlobal(const sensors::SensorRecord& record, const sensors::LaserScan& scan, LocalisedPose& out) {
    const TrackerUpdate update = tracker->Update(scan, out.odometry.world_from_body);
    out.global = update.ranked;
    out.global_searched = update.searched;
    if (!update.decided) return;
    odometry = odometry::LaserOdometry(options.odometry, kind, update.decided->map_from_body, scan.stamp_s);
    if (const auto restarted = odometry.Add(record)) out.odometry = *restarted;
    map.Reset(geometry::Pose2{});
    anchored = true;
    tracker.reset();
    global.reset();
  }
};

LocalisationChain::LocalisationChain(const LocalisationChainOptions& options,
                                     sensors::EntityKind kind, std::vector<geometry::Segment2> plan,
                                     const geometry::Pose2& map_from_start, double start_stamp_s) {
  const bool unknown = options.global_start;
  std::unique_ptr<GlobalLocaliser> global;
  std::unique_ptr<GlobalTracker> tracker;
  if (unknown) {
    global = std::make_unique<GlobalLocaliser>(plan, options.global);
    tracker = std::make_unique<GlobalTracker>(*global, options.tracker);
  }
  impl_ = std::make_unique<Impl>(Impl{
      options, kind,
      odometry::LaserOdometry(unknown ? UnknownPhase(options.odometry) : options.odometry, kind,
                              unknown ? geometry::Pose2{} : map_from_start, start_stamp_s),
      MapLocaliser(options.map, std::move(plan), geometry::Pose2{}), std::move(global), std::move(tracker),
      !unknown});
}

LocalisationChain::~LocalisationChain() = default;
LocalisationChain::LocalisationChain(LocalisationChain&&) noexcept = default;
LocalisationChain& LocalisationChain::operator=(LocalisationChain&&) noexcept = default;

std::optional<LocalisedPose> LocalisationChain::Add(const sensors::SensorRecord& record) {
  std::optional<odometry::OdometryEstimate> estimate = impl_->odometry.Add(record);
  if (!estimate) return std::nullopt;
  const auto& scan = std::get<sensors::LaserScan>(record);
  LocalisedPose out;
  out.stamp_s = estimate->stamp_s;
  out.odometry = *estimate;
  const bool first = estimate->status == odometry::MatchStatus::kFirst;
  if (!impl_->anchored && (first || estimate->reference_changed)) impl_->TryGlobal(record, scan, out);
  if (impl_->anchored) {
    // Right after anchoring (or at the first scan) a round checks the start against the plan.
    const bool force = first || out.global.has_value();
    out.correction = impl_->map.Update(scan, out.odometry, force);
  }
  out.map_from_body = impl_->anchored ? impl_->map.map_from_body()
                                      : impl_->map.MapFromBody(out.odometry.world_from_body);
  out.status = impl_->map.status();
  out.anchored = impl_->anchored;
  return out;
}

const odometry::OdometryCounts& LocalisationChain::odometry_counts() const {
  return impl_->odometry.counts();
}

}  // namespace pena::localisation
