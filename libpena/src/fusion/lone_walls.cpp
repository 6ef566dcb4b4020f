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
  const Eigen::Vector2d mid = 0.5 * (lone.start_m + lone.end_m) - wall.start_m;
  if (std::abs(along.x() * mid.y() - along.y() * mid.x()) > distance_m) return false;
  const double t1 = (lone.start_m - wall.start_m).dot(along);
  const double t2 = (lone.end_m - wall.start_m).dot(along);
  const double overlap_m = std::min(wall_m, std::max(t1, t2)) - std::max(0.0, std::min(t1, t2));
  return overlap_m >= 0.5 * lone_m;
}

const geometry::Segment2& Deref(const geometry::Segment2* segment) { return *segment; }
const geometry::Segment2& Deref(const geometry::Segment2& segment) { return segment; }

}  // namespace

std::map<std::string, EntityAgreement> DropLoneWalls(
    std::vector<LineSegment>& merged, const std::unordered_map<std::string, double>& length_by_key,
    const std::vector<geometry::Segment2>& plan, const GlobalMapOptions& options) {
  std::vector<Support> support;
  std::vector<const geometry::Segment2*> corroborated;
  for (const LineSegment& segment : merged) {
    support.push_back(SupportOf(segment));
    if (support.back().corroborated()) corroborated.push_back(&segment.segment);
  }
  const auto length_of = [&](const std::string& key) {
    const auto it = length_by_key.find(key);
    return it == length_by_key.end() ? 0.0 : it->second;
  };
  const auto along = [&](const geometry::Segment2& segment, const auto& walls) {
    return options.lone_duplicate_distance_m > 0.0 &&
           std::any_of(walls.begin(), walls.end(), [&](const auto& wall) {
             return Shadowed(segment, Deref(wall), options.merge.merge_angle_rad,
                             options.lone_duplicate_distance_m);
           });
  };
  // Lone weak walls and lone drifted copies, and what each entity's comparable walls say.
  std::vector<bool> weak(merged.size(), false), duplicate(merged.size(), false);
  std::map<std::string, EntityAgreement> agreement;
  for (std::size_t i = 0; i < merged.size(); ++i) {
    const LineSegment& segment = merged[i];
    weak[i] = support[i].lone() && segment.support_cells < options.min_lone_support_per_m *
                                                               geometry::Length(segment.segment);
    duplicate[i] = support[i].lone() && !weak[i] && along(segment.segment, corroborated);
    if (!support[i].corroborated() && !duplicate[i]) continue;
    for (const std::string& key : segment.provenance) {
      const std::string source = key.substr(0, key.rfind(':'));
      if (source == "plan") continue;
      EntityAgreement& entity = agreement[source];
      (duplicate[i] ? entity.disagree_m : entity.agree_m) += length_of(key);
    }
  }
  const auto trusted = [&](const std::string& entity) {
    const auto it = agreement.find(entity);
    return it == agreement.end() || it->second.compared_m() < options.min_agreement_evidence_m ||
           it->second.ratio() >= options.min_lone_agreement;
  };
  std::vector<LineSegment> kept;
  for (std::size_t i = 0; i < merged.size(); ++i) {
    if (weak[i] || duplicate[i]) continue;
    // Only entities that disagree elsewhere put it there: alone, or along a plan wall it does
    // not confirm (several of them drifted alike), it is not trusted.
    const bool untrusted = !support[i].plan && std::none_of(support[i].entities.begin(),
                                                            support[i].entities.end(), trusted);
    if (untrusted && (support[i].lone() || along(merged[i].segment, plan))) continue;
    kept.push_back(std::move(merged[i]));
  }
  merged = std::move(kept);
  return agreement;
}

}  // namespace pena::fusion::detail
