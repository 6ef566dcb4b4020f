#include "lone_walls.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace pena::fusion::detail {
namespace {

using line_map::LineSegment;

// The entity sources ("ff1") of a merged segment's provenance, and whether the plan is among them.
struct Support {
  std::set<std::string> entities;
  bool plan = false;
  bool lone() const { return entities.size() == 1 && !plan; }
  // Two entities, or an entity and the plan, put it there.
  bool corroborated() const { return entities.size() >= 2 || (plan && !entities.empty()); }
};

Support SupportOf(const LineSegment& segment) {
  Support support;
  for (const std::string& key : segment.provenance) {
    const std::string source = key.substr(0, key.rfind(':'));
    if (source == "plan") {
      support.plan = true;
    } else {
      support.entities.insert(source);
    }
  }
  return support;
}

Eigen::Vector2d Midpoint(const geometry::Segment2& segment) {
  return 0.5 * (segment.start_m + segment.end_m);
}

// Distance of `point` from the line through `wall`, m (0 for a degenerate wall).
double OffsetFromLine(const Eigen::Vector2d& point, const geometry::Segment2& wall) {
  const Eigen::Vector2d v = wall.end_m - wall.start_m;
  const double wall_m = v.norm();
  if (wall_m <= 0.0) return 0.0;
  const Eigen::Vector2d d = point - wall.start_m;
  return std::abs(v.x() * d.y() - v.y() * d.x()) / wall_m;
}

// True if `lone` lies along `wall`: parallel, its midpoint within `distance_m` of the wall's
// line, and at least half of it overlapping the wall.
bool Shadowed(const geometry::Segment2& lone, const geometry::Segment2& wall, double angle_rad,
              double distance_m) {
  const Eigen::Vector2d u = lone.end_m - lone.start_m;
  const Eigen::Vector2d v = wall.end_m - wall.start_m;
  const double lone_m = u.norm();
  const double wall_m = v.norm();
  if (lone_m <= 0.0 || wall_m <= 0.0) return false;
  const Eigen::Vector2d along = v / wall_m;
  if (std::abs(along.x() * u.y() - along.y() * u.x()) / lone_m > std::sin(angle_rad)) return false;
  if (OffsetFromLine(Midpoint(lone), wall) > distance_m) return false;
  const double t1 = (lone.start_m - wall.start_m).dot(along);
  const double t2 = (lone.end_m - wall.start_m).dot(along);
  const double overlap_m = std::min(wall_m, std::max(t1, t2)) - std::max(0.0, std::min(t1, t2));
  return overlap_m >= 0.5 * lone_m;
}

const geometry::Segment2& Deref(const geometry::Segment2* segment) { return *segment; }
const geometry::Segment2& Deref(const geometry::Segment2& segment) { return segment; }

// One of an entity's walls compared with what other sources saw there.
struct Evidence {
  Eigen::Vector2d where_m;  // its midpoint, map frame
  double length_m = 0.0;
  double offset_m = 0.0;    // from the other sources' wall
};

// The entity's wall error around `where_m`: a Gaussian noise model whose variance is estimated
// from its compared walls, each weighted by its length and a kernel of its distance
// (error_radius_m: an entity's drift is local, it grows along its path), over a prior that its
// walls are as good as the merge rule (sd half the merge distance, weight prior_evidence_m).
double EstimatedError(const std::vector<Evidence>& evidence, const Eigen::Vector2d& where_m,
                      const GlobalMapOptions& options) {
  const double prior_sd_m = 0.5 * options.merge.merge_distance_m;
  double weight = options.prior_evidence_m;
  double sum_sq = options.prior_evidence_m * prior_sd_m * prior_sd_m;
  const double two_r2 = 2.0 * options.error_radius_m * options.error_radius_m;
  for (const Evidence& item : evidence) {
    const double w = item.length_m * std::exp(-(item.where_m - where_m).squaredNorm() / two_r2);
    weight += w;
    sum_sq += w * item.offset_m * item.offset_m;
  }
  return weight > 0.0 ? std::sqrt(sum_sq / weight) : prior_sd_m;
}

}  // namespace

std::map<std::string, EntityAgreement> DropLoneWalls(
    std::vector<LineSegment>& merged,
    const std::unordered_map<std::string, geometry::Segment2>& source_by_key,
    const std::vector<geometry::Segment2>& plan, const GlobalMapOptions& options) {
  std::vector<Support> support;
  std::vector<const geometry::Segment2*> corroborated;
  for (const LineSegment& segment : merged) {
    support.push_back(SupportOf(segment));
    if (support.back().corroborated()) corroborated.push_back(&segment.segment);
  }
  const auto source_of = [&](const std::string& key) -> const geometry::Segment2* {
    const auto it = source_by_key.find(key);
    return it == source_by_key.end() ? nullptr : &it->second;
  };
  // The first of `walls` that `segment` lies along, or nullptr.
  const auto along = [&](const geometry::Segment2& segment,
                         const auto& walls) -> const geometry::Segment2* {
    if (options.lone_duplicate_distance_m <= 0.0) return nullptr;
    for (const auto& wall : walls) {
      if (Shadowed(segment, Deref(wall), options.merge.merge_angle_rad,
                   options.lone_duplicate_distance_m)) {
        return &Deref(wall);
      }
    }
    return nullptr;
  };
  // Lone weak walls and lone drifted copies; what each entity's comparable walls say: a wall
  // merged with another source's is off the merged wall by its midpoint's distance, a drifted
  // copy by its distance from the wall it copies.
  std::vector<bool> weak(merged.size(), false), duplicate(merged.size(), false);
  std::map<std::string, EntityAgreement> agreement;
  std::map<std::string, std::vector<Evidence>> evidence;
  for (std::size_t i = 0; i < merged.size(); ++i) {
    const LineSegment& segment = merged[i];
    weak[i] = support[i].lone() && segment.support_cells < options.min_lone_support_per_m *
                                                               geometry::Length(segment.segment);
    const geometry::Segment2* copied =
        support[i].lone() && !weak[i] ? along(segment.segment, corroborated) : nullptr;
    duplicate[i] = copied != nullptr;
    if (!support[i].corroborated() && !duplicate[i]) continue;
    const geometry::Segment2& reference = duplicate[i] ? *copied : segment.segment;
    for (const std::string& key : segment.provenance) {
      const std::string source = key.substr(0, key.rfind(':'));
      const geometry::Segment2* own = source_of(key);
      if (source == "plan" || own == nullptr) continue;
      const double length_m = geometry::Length(*own);
      const double offset_m = OffsetFromLine(Midpoint(*own), reference);
      EntityAgreement& entity = agreement[source];
      (duplicate[i] ? entity.disagree_m : entity.agree_m) += length_m;
      entity.offset_sq_m3 += length_m * offset_m * offset_m;
      evidence[source].push_back({Midpoint(*own), length_m, offset_m});
    }
  }
  // An entity is trusted at a wall if its walls around it are within max_lone_error_m.
  const auto trusted = [&](const std::string& entity, const geometry::Segment2& wall) {
    const auto it = evidence.find(entity);
    if (it == evidence.end()) return true;
    return EstimatedError(it->second, Midpoint(wall), options) <= options.max_lone_error_m;
  };
  std::vector<LineSegment> kept;
  for (std::size_t i = 0; i < merged.size(); ++i) {
    if (weak[i] || duplicate[i]) continue;
    // Only entities whose walls around it are off put it there: alone, or along a plan wall it
    // does not confirm (several of them drifted alike), it is not trusted.
    const bool untrusted =
        !support[i].plan &&
        std::none_of(support[i].entities.begin(), support[i].entities.end(),
                     [&](const std::string& entity) { return trusted(entity, merged[i].segment); });
    if (untrusted && (support[i].lone() || along(merged[i].segment, plan) != nullptr)) continue;
    kept.push_back(std::move(merged[i]));
  }
  merged = std::move(kept);
  return agreement;
}

}  // namespace pena::fusion::detail
