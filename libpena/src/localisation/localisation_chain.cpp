#include "pena/localisation/localisation_chain.hpp"

#include "pena/scan_matching/point_set.hpp"

namespace pena::localisation {

struct LocalisationChain::Impl {
  LocalisationChainOptions options;
  odometry::LaserOdometry odometry;
  MapLocaliser map;
  std::unique_ptr<GlobalLocaliser> global;  // only while the start is still unknown
  bool anchored = true;

  // Unknown start: the odometry runs in its own frame until a scan localises on the plan with a
  // clear winner; then map_from_odom places that frame (section 4 needs a known start; this
  // supplies it).
  void TryGlobal(const sensors::LaserScan& scan, LocalisedPose& out) {
    out.global = global->Localise(scan_matching::ScanToPoints(scan, options.odometry.min_range_m));
    const GlobalResult& result = *out.global;
    if (result.hypotheses.empty() || result.hypotheses[0].score < options.global_min_score ||
        result.margin < options.global_min_margin) {
      return;
    }
    const geometry::Pose2& map_from_body = result.hypotheses[0].map_from_body;
    map.Reset(geometry::Compose(map_from_body, geometry::Inverse(out.odometry.world_from_body)));
    anchored = true;
    global.reset();
  }
};

LocalisationChain::LocalisationChain(const LocalisationChainOptions& options,
                                     sensors::EntityKind kind, std::vector<geometry::Segment2> plan,
                                     const geometry::Pose2& map_from_start, double start_stamp_s) {
  const geometry::Pose2 odom_from_start = options.global_start ? geometry::Pose2{} : map_from_start;
  std::unique_ptr<GlobalLocaliser> global;
  if (options.global_start) global = std::make_unique<GlobalLocaliser>(plan, options.global);
  impl_ = std::make_unique<Impl>(Impl{
      options, odometry::LaserOdometry(options.odometry, kind, odom_from_start, start_stamp_s),
      MapLocaliser(options.map, std::move(plan), geometry::Pose2{}), std::move(global),
      !options.global_start});
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
  if (!impl_->anchored && (first || estimate->reference_changed)) impl_->TryGlobal(scan, out);
  if (impl_->anchored) {
    // Right after anchoring (or at the first scan) a round checks the start against the plan.
    const bool force = first || out.global.has_value();
    out.correction = impl_->map.Update(scan, *estimate, force);
  }
  out.map_from_body = impl_->map.MapFromBody(estimate->world_from_body);
  out.status = impl_->map.status();
  out.anchored = impl_->anchored;
  return out;
}

const odometry::OdometryCounts& LocalisationChain::odometry_counts() const {
  return impl_->odometry.counts();
}

}  // namespace pena::localisation
