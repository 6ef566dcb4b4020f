#include "pena/slam/keyframe_slam.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "edge_information.hpp"
#include "submap_matcher.hpp"

namespace pena::slam {
namespace {

using geometry::Pose2;

// A scan: its odometry pose and the keyframe it hangs from.
struct ScanRecord {
  double stamp_s = 0.0;
  Pose2 world_from_odometry;
  int keyframe = 0;
};

double Distance(const Pose2& a, const Pose2& b) {
  return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m);
}

}  // namespace

struct KeyframeSlam::Impl {
  explicit Impl(const SlamOptions& o) : options(o), submaps(o, clock) {}

  using Timed = StageClock<SlamStage>::Scope;
  // Where Add's and Finish's time goes; mutable: the const candidate search is timed too.
  mutable StageClock<SlamStage> clock;
  SlamOptions options;
  PoseGraph graph;
  std::vector<internal::Keyframe> keyframes;
  std::vector<ScanRecord> scans;
  internal::SubmapMatcher submaps;
  SlamCounts counts;
  std::vector<LoopClosureRecord> closures;
  double path_m = 0.0;
  double last_closure_path_m = 0.0;
  long graph_version = 0;
  std::optional<Pose2> last_odometry;

  bool IsKeyframe(const Pose2& world_from_odometry) const {
    if (keyframes.empty()) return true;
    const Pose2 motion = geometry::Between(keyframes.back().world_from_odometry,
                                           world_from_odometry);
    return std::hypot(motion.x_m, motion.y_m) >= options.keyframe_distance_m ||
           std::abs(motion.theta_rad) >= options.keyframe_angle_rad;
  }

  // Appends a node chained to the previous one by the odometry's motion.
  void AddKeyframe(const sensors::LaserScan& scan, const Pose2& world_from_odometry) {
    std::optional<Timed> timed(std::in_place, clock, SlamStage::kKeyframes);
    internal::Keyframe keyframe{scan.stamp_s, world_from_odometry,
                                internal::KeyframePoints(scan, options), path_m};
    if (keyframes.empty()) {
      graph.AddNode(world_from_odometry);
    } else {
      const Pose2 motion = geometry::Between(keyframes.back().world_from_odometry,
                                             world_from_odometry);
      const int node = graph.AddNode(geometry::Compose(graph.nodes().back(), motion));
      const double distance_m = std::hypot(motion.x_m, motion.y_m);
      const double sigma_m = options.odometry_sigma_m + options.odometry_sigma_per_m * distance_m;
      const double sigma_rad =
          options.odometry_sigma_rad + options.odometry_sigma_rad_per_m * distance_m;
      PoseEdge edge{node - 1, node, motion, internal::IsotropicInformation(sigma_m, sigma_rad),
                    false};
      graph.AddEdge(edge);
    }
    keyframes.push_back(std::move(keyframe));
    ++counts.keyframes;
    timed.reset();
    const int index = static_cast<int>(keyframes.size()) - 1;
    if (index % options.loop_check_every == 0) TryLoopClosure(index);
  }

  // The nearest keyframe at least `min_path_m` back along the path, within `radius_m`.
  int LoopCandidate(int index, double radius_m, double min_path_m) const {
    const Timed timed(clock, SlamStage::kCandidates);
    const Pose2& pose = graph.nodes()[static_cast<std::size_t>(index)];
    int best = -1;
    double best_m = radius_m;
    for (int j = 0; j < index; ++j) {
      const internal::Keyframe& old = keyframes[static_cast<std::size_t>(j)];
      if (keyframes[static_cast<std::size_t>(index)].path_m - old.path_m < min_path_m) {
        break;
      }
      const double d = Distance(pose, graph.nodes()[static_cast<std::size_t>(j)]);
      if (d < best_m) {
        best_m = d;
        best = j;
      }
    }
    return best;
  }

  // The last keyframe at least `back_m` back along the path from `index` (-1: none).
  int LastAllowed(int index, double back_m) const {
    const Timed timed(clock, SlamStage::kCandidates);
    const double limit_m = keyframes[static_cast<std::size_t>(index)].path_m - back_m;
    int last = -1;
    while (last + 1 < index && keyframes[static_cast<std::size_t>(last + 1)].path_m <= limit_m) {
      ++last;
    }
    return last;
  }

  // Matches keyframe `index` against the submap around the loop candidate; true when a closure
  // was kept.
  bool TryLoopClosure(int index) {
    const double since_m = path_m - last_closure_path_m;
    const double half_m = std::min(options.loop_window_max_m,
                                   options.loop_window_m + options.loop_window_per_m * since_m);
    const double half_rad =
        std::min(options.loop_window_max_rad,
                 options.loop_window_rad + options.loop_window_rad_per_m * since_m);
    const int candidate =
        LoopCandidate(index, half_m + options.keyframe_distance_m, options.loop_min_path_m);
    if (candidate >= 0) {
      if (auto found = MatchCandidate(index, candidate, half_m, half_rad, SlamStage::kLoopMatch)) {
        if (Close(*found)) {
          if (pending) Refuse(*pending);  // the graph moved: its correction is stale
          return true;
        }
      }
    }
    return TryWideClosure(index);
  }

  // A match found, not yet in the graph.
  struct Found {
    int centre = 0;
    int index = 0;
    internal::LoopMatch match;
    LoopClosureRecord record;
    // The world correction the match asks for: it moves the new keyframe's graph pose onto the
    // matched one (world_from_world').
    Pose2 correction;
  };
  std::optional<Found> pending;  // a wide closure held for confirmation

  // A revisit after a long walk, beyond the narrow window: searched in the wide window around the
  // nearest keyframe at least loop_wide_min_path_m back, every loop_wide_check_every keyframes
  // (every keyframe while a wide closure is held). A wide match is an alias as often as not, so
  // it is held until the wide match of a later keyframe, at most loop_wide_check_every
  // keyframes on, asks for the same world correction within the narrow window; then both close.
  bool TryWideClosure(int index) {
    if (pending && index - pending->index > options.loop_wide_check_every) Refuse(*pending);
    if (options.loop_wide_window_m <= 0.0 ||
        (!pending && index % options.loop_wide_check_every != 0)) {
      return false;
    }
    const int candidate =
        LoopCandidate(index, options.loop_wide_window_m + options.keyframe_distance_m,
                      options.loop_wide_min_path_m);
    if (candidate < 0) return false;
    ++counts.wide_checks;
    // The window doubles from twice the narrow one up to loop_wide_window_m, and the first whose
    // best pose is inside it (not on its edge) answers: of two places that fit, the one nearer
    // the graph's prediction is taken, and a farther alias is found only where nothing nearer
    // fits.
    std::optional<Found> found;
    for (double half_m = std::min(2.0 * options.loop_window_m, options.loop_wide_window_m); !found;
         half_m = std::min(2.0 * half_m, options.loop_wide_window_m)) {
      found = MatchCandidate(index, candidate, half_m, options.loop_window_max_rad,
                             SlamStage::kWideMatch);
      if (half_m >= options.loop_wide_window_m) break;
    }
    if (!found) return false;
    if (!pending) {
      pending = std::move(found);
      return false;
    }
    const Pose2& node = graph.nodes()[static_cast<std::size_t>(index)];
    const Pose2 apart = geometry::Between(geometry::Compose(pending->correction, node),
                                          geometry::Compose(found->correction, node));
    if (std::hypot(apart.x_m, apart.y_m) > options.loop_window_m ||
        std::abs(apart.theta_rad) > options.loop_window_rad) {
      Refuse(*pending);
      pending = std::move(found);
      return false;
    }
    Found held = std::move(*pending);
    pending.reset();
    const bool first = Close(held);
    const bool second = Close(*found);
    return first || second;
  }

  // stage: kLoopMatch or kWideMatch, what the match's time counts to.
  std::optional<Found> MatchCandidate(int index, int candidate, double half_m, double half_rad,
                                      SlamStage stage) {
    const Timed timed(clock, stage);
    ++counts.loop_checks;
    const auto match = submaps.Match(keyframes, graph.nodes(), candidate, options.submap_keyframes,
                                     LastAllowed(index, options.loop_min_path_m), graph_version,
                                     keyframes[static_cast<std::size_t>(index)].points,
                                     Prior(candidate, index), half_m, half_rad);
    if (!match) return std::nullopt;
    ++counts.loop_matched;
    Found found{candidate, index, *match,
                LoopClosureRecord{keyframes[static_cast<std::size_t>(candidate)].stamp_s,
                                  keyframes[static_cast<std::size_t>(index)].stamp_s,
                                  match->centre_from_scan, Prior(candidate, index), match->score,
                                  half_m, false},
                {}};
    const Pose2& centre_pose = graph.nodes()[static_cast<std::size_t>(candidate)];
    const Pose2& node = graph.nodes()[static_cast<std::size_t>(index)];
    found.correction = geometry::Compose(geometry::Compose(centre_pose, match->centre_from_scan),
                                         geometry::Inverse(node));
    return found;
  }

  // Adds the closure unless it contradicts the optimised graph; records it.
  bool Close(Found& found) {
    found.record.kept = AddMatchEdge(found.centre, found.index, found.match);
    closures.push_back(found.record);
    if (!found.record.kept) {
      ++counts.loop_rejected;
      return false;
    }
    ++counts.loop_closures;
    last_closure_path_m = path_m;
    return true;
  }

  void Refuse(Found& found) {
    found.record.kept = false;
    closures.push_back(found.record);
    ++counts.loop_rejected;
    if (pending && &found == &*pending) pending.reset();
  }

  Pose2 Prior(int centre, int index) const {
    return geometry::Between(graph.nodes()[static_cast<std::size_t>(centre)],
                             graph.nodes()[static_cast<std::size_t>(index)]);
  }

  // Adds a robust match edge and re-optimises; drops it again when it disagrees with the graph.
  bool AddMatchEdge(int centre, int index, const internal::LoopMatch& match) {
    graph.AddEdge({centre, index, match.centre_from_scan,
                   internal::ClosureInformation(match, options), true});
    Optimize();
    if (graph.EdgeChi2(graph.edges().back()) > options.max_loop_chi2) {
      graph.RemoveEdge(graph.edges().size() - 1);
      Optimize();
      return false;
    }
    return true;
  }

  void Optimize() {
    const Timed timed(clock, SlamStage::kOptimisation);
    graph.Optimize(options.optimize_iterations);
    ++graph_version;
    ++counts.optimisations;
  }

  Pose2 Corrected(const ScanRecord& scan) const {
    const internal::Keyframe& keyframe = keyframes[static_cast<std::size_t>(scan.keyframe)];
    return geometry::Compose(graph.nodes()[static_cast<std::size_t>(scan.keyframe)],
                             geometry::Between(keyframe.world_from_odometry,
                                               scan.world_from_odometry));
  }
};

KeyframeSlam::KeyframeSlam(const SlamOptions& options, sensors::EntityKind kind) {
  ValidateSlamOptions(options);
  impl_ = std::make_unique<Impl>(ForEntity(options, kind));
}

KeyframeSlam::~KeyframeSlam() = default;
KeyframeSlam::KeyframeSlam(KeyframeSlam&&) noexcept = default;
KeyframeSlam& KeyframeSlam::operator=(KeyframeSlam&&) noexcept = default;

Pose2 KeyframeSlam::Add(const sensors::LaserScan& scan, const Pose2& world_from_odometry) {
  Impl& s = *impl_;
  const StageClock<SlamStage>::Call call(s.clock, SlamStage::kOther);
  if (s.last_odometry) s.path_m += Distance(*s.last_odometry, world_from_odometry);
  s.last_odometry = world_from_odometry;
  ++s.counts.scans;
  if (s.IsKeyframe(world_from_odometry)) s.AddKeyframe(scan, world_from_odometry);
  s.scans.push_back({scan.stamp_s, world_from_odometry, static_cast<int>(s.keyframes.size()) - 1});
  return s.Corrected(s.scans.back());
}

void KeyframeSlam::Finish() {
  const StageClock<SlamStage>::Call call(impl_->clock, SlamStage::kOther);
  if (impl_->pending) impl_->Refuse(*impl_->pending);  // never confirmed
  impl_->Optimize();
}

geometry::Trajectory KeyframeSlam::Trajectory() const {
  geometry::Trajectory trajectory;
  trajectory.reserve(impl_->scans.size());
  for (const ScanRecord& scan : impl_->scans) {
    trajectory.push_back({scan.stamp_s, impl_->Corrected(scan)});
  }
  return trajectory;
}

const PoseGraph& KeyframeSlam::graph() const { return impl_->graph; }
const SlamCounts& KeyframeSlam::counts() const { return impl_->counts; }
const SlamStageTimes& KeyframeSlam::stage_times() const { return impl_->clock.times(); }

const char* ToString(SlamStage stage) {
  switch (stage) {
    case SlamStage::kKeyframes: return "keyframes";
    case SlamStage::kCandidates: return "candidates";
    case SlamStage::kSubmapBuild: return "submap_build";
    case SlamStage::kLoopMatch: return "loop_match";
    case SlamStage::kWideMatch: return "wide_match";
    case SlamStage::kOptimisation: return "optimisation";
    case SlamStage::kOther: return "other";
    case SlamStage::kCount: break;
  }
  return "unknown";
}
const std::vector<LoopClosureRecord>& KeyframeSlam::closures() const { return impl_->closures; }

}  // namespace pena::slam
