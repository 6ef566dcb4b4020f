// fusion_placement_eval: why an unknown start is (not) placed. Reads a finished pena-fusion
// run's state directory (its checkpoint and wall_stamps.csv), then replays placement of ENTITY as
// its local map grew: the entity's final segments first seen up to each step (every STEP_M of
// new walls), against the global map without the entity's walls, as FusionState calls
// PlaceLocalMap (hypotheses carried over). Prints every attempt: the decision and each
// hypothesis (pose, score, explained wall length; the local wall length within 1 m of a global
// wall and the share of it within 0.2 m; the share within 0.2 m near the entity's start, walls
// weighted by a 10 m Gaussian of their distance from it) and, with --truth, how far
// each is from the entity's true map_from_entity (docs/fusion.md, "Placement on real logs").
// The state directory is copied first and never written. Not a test.
//
//   fusion_placement_eval STATE_DIR ENTITY [--truth X_M Y_M THETA_RAD] [--step-m M]
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string>

#include "pena/fusion/fusion_store.hpp"
#include "pena/fusion/placement.hpp"

namespace fs = std::filesystem;
using namespace pena;

namespace {

// segment id -> first stamp (s) of `entity`'s walls in wall_stamps.csv.
std::map<std::uint64_t, double> ReadStamps(const fs::path& path, const std::string& entity) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::map<std::uint64_t, double> stamps;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string id, segment, stamp;
    if (!std::getline(fields, id, ',') || !std::getline(fields, segment, ',') ||
        !std::getline(fields, stamp)) {
      throw std::runtime_error(path.string() + ":" + std::to_string(number) + ": bad row");
    }
    if (id == entity) stamps[std::stoull(segment)] = std::stod(stamp);
  }
  return stamps;
}

// Points every 0.1 m along the walls, each with the wall length it stands for.
std::vector<std::pair<Eigen::Vector2d, double>> Sample(const std::vector<line_map::LineSegment>& walls) {
  std::vector<std::pair<Eigen::Vector2d, double>> samples;
  for (const line_map::LineSegment& wall : walls) {
    const double length_m = geometry::Length(wall.segment);
    const int pieces = std::max(1, static_cast<int>(std::ceil(length_m / 0.1)));
    for (int i = 0; i < pieces; ++i) {
      const double f = (i + 0.5) / pieces;
      samples.emplace_back(wall.segment.start_m + f * (wall.segment.end_m - wall.segment.start_m),
                           length_m / pieces);
    }
  }
  return samples;
}

double DistanceToWalls(const Eigen::Vector2d& p, const std::vector<line_map::LineSegment>& walls) {
  double best = std::numeric_limits<double>::infinity();
  for (const line_map::LineSegment& wall : walls) {
    const Eigen::Vector2d a = wall.segment.start_m;
    const Eigen::Vector2d ab = wall.segment.end_m - a;
    const double t = std::clamp((p - a).dot(ab) / std::max(1e-12, ab.squaredNorm()), 0.0, 1.0);
    best = std::min(best, (a + t * ab - p).norm());
  }
  return best;
}

// Other evidence than the score, for one hypothesis.
struct Evidence {
  double overlap_m = 0.0;           // local wall length within 1 m of a global wall
  double overlap_explained = 0.0;   // share of it within 0.2 m
  double near_start_explained = 0.0;  // share within 0.2 m, weighted by exp(-r^2 / 2 (10 m)^2), r
                                      // the wall's distance from the entity's start (frame origin)
};

Evidence Weigh(const std::vector<std::pair<Eigen::Vector2d, double>>& samples,
               const std::vector<line_map::LineSegment>& global,
               const geometry::Pose2& map_from_entity) {
  Evidence e;
  double explained_m = 0.0;
  double near_m = 0.0;
  double near_explained_m = 0.0;
  for (const auto& [point, weight_m] : samples) {
    const double d = DistanceToWalls(geometry::TransformPoint(map_from_entity, point), global);
    const double kernel = std::exp(-point.squaredNorm() / (2.0 * 10.0 * 10.0)) * weight_m;
    near_m += kernel;
    if (d <= 1.0) e.overlap_m += weight_m;
    if (d <= 0.2) {
      explained_m += weight_m;
      near_explained_m += kernel;
    }
  }
  e.overlap_explained = e.overlap_m > 0.0 ? explained_m / e.overlap_m : 0.0;
  e.near_start_explained = near_m > 0.0 ? near_explained_m / near_m : 0.0;
  return e;
}

}  // namespace

int main(int argc, char** argv) try {
  if (argc < 3) {
    throw std::invalid_argument("usage: fusion_placement_eval STATE_DIR ENTITY [--truth X_M Y_M "
                                "THETA_RAD] [--step-m M]");
  }
  const fs::path state_dir = argv[1];
  const std::string entity = argv[2];
  std::optional<geometry::Pose2> truth;
  double step_m = 10.0;
  for (int i = 3; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--truth" && i + 3 < argc) {
      truth = geometry::Pose2{std::stod(argv[i + 1]), std::stod(argv[i + 2]), std::stod(argv[i + 3])};
      i += 3;
    } else if (flag == "--step-m" && i + 1 < argc) {
      step_m = std::stod(argv[++i]);
    } else {
      throw std::invalid_argument("unknown option or missing value: " + flag);
    }
  }
  const fs::path copy =
      fs::temp_directory_path() / ("fusion_placement_eval_" + std::to_string(::getpid()));
  fs::remove_all(copy);
  fs::copy(state_dir, copy, fs::copy_options::recursive);
  fusion::FusionCheckpoint checkpoint;
  {
    const fusion::FusionStore store(copy);
    checkpoint = store.state().Checkpoint();
  }
  fs::remove_all(copy);

  std::vector<line_map::LineSegment> global;
  for (const line_map::LineSegment& s : checkpoint.global.segments) {
    const bool own = std::any_of(s.provenance.begin(), s.provenance.end(), [&](const auto& key) {
      return key.rfind(entity + ":", 0) == 0;
    });
    if (!own) global.push_back(s);
  }
  const auto found = std::find_if(checkpoint.entities.begin(), checkpoint.entities.end(),
                                  [&](const auto& e) { return e.status.entity_id == entity; });
  if (found == checkpoint.entities.end()) throw std::invalid_argument("no entity " + entity);
  const std::map<std::uint64_t, double> stamps = ReadStamps(state_dir / "wall_stamps.csv", entity);
  std::vector<std::pair<double, line_map::LineSegment>> by_stamp;
  for (const line_map::LineSegment& s : found->local.segments) {
    const auto stamp = stamps.find(s.id);
    by_stamp.emplace_back(stamp == stamps.end() ? 1e300 : stamp->second, s);
  }
  std::stable_sort(by_stamp.begin(), by_stamp.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });

  const fusion::PlacementOptions options;
  std::vector<line_map::LineSegment> local;
  std::vector<fusion::PlacementHypothesis> previous;
  double length_m = 0.0;
  double attempted_at_m = 0.0;
  for (std::size_t i = 0; i < by_stamp.size(); ++i) {
    local.push_back(by_stamp[i].second);
    length_m += geometry::Length(by_stamp[i].second.segment);
    const bool last = i + 1 == by_stamp.size();
    if (length_m < options.min_local_length_m || (length_m < attempted_at_m + step_m && !last)) {
      continue;
    }
    attempted_at_m = length_m;
    const fusion::PlacementResult p = fusion::PlaceLocalMap(local, global, previous, options);
    previous = p.hypotheses;
    std::printf("%s at %.1f s: %.1f m of walls, %s, margin %.1f m: %s\n", entity.c_str(),
                by_stamp[i].first, p.local_length_m, p.placed ? "PLACED" : "pending", p.margin_m,
                p.reason.c_str());
    const auto samples = Sample(local);
    for (const fusion::PlacementHypothesis& h : p.hypotheses) {
      const geometry::Pose2& pose = h.map_from_entity;
      const Evidence e = Weigh(samples, global, pose);
      std::printf("  (%8.3f, %8.3f, %7.4f) score %.3f explained %6.1f m; within 1 m %6.1f m, of it "
                  "within 0.2 m %.2f; near the start %.2f", pose.x_m, pose.y_m, pose.theta_rad,
                  h.score, h.explained_m, e.overlap_m, e.overlap_explained,
                  e.near_start_explained);
      if (truth) {
        std::printf("  off truth %.2f m %.1f deg",
                    std::hypot(pose.x_m - truth->x_m, pose.y_m - truth->y_m),
                    std::abs(geometry::NormalizeAngle(pose.theta_rad - truth->theta_rad)) *
                        180.0 / M_PI);
      }
      std::printf("\n");
    }

  }
  return 0;
} catch (const std::exception& e) {
  std::cerr << "fusion_placement_eval: " << e.what() << "\n";
  return 1;
}
