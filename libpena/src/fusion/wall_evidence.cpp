#include "wall_evidence.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>
#include <tuple>

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
  // Some source of `other` is not among these: `other` was seen by someone else.
  bool LacksSomeOf(const Support& other) const {
    return (other.plan && !plan) ||
           std::any_of(other.entities.begin(), other.entities.end(),
                       [&](const std::string& e) { return !entities.contains(e); });
  }
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


// Axis-aligned box of a segment grown by `margin_m`.
struct Box {
  double min_x, min_y, max_x, max_y;
};

Box BoxOf(const geometry::Segment2& segment, double margin_m) {
  return {std::min(segment.start_m.x(), segment.end_m.x()) - margin_m,
          std::min(segment.start_m.y(), segment.end_m.y()) - margin_m,
          std::max(segment.start_m.x(), segment.end_m.x()) + margin_m,
          std::max(segment.start_m.y(), segment.end_m.y()) + margin_m};
}

// For each wall, the other walls whose boxes (grown by `margin_m`) overlap its own: a sweep
// along x, so the pairs cost what they are rather than n^2.
std::vector<std::vector<std::size_t>> Neighbours(const std::vector<LineSegment>& walls,
                                                 double margin_m) {
  std::vector<Box> boxes;
  for (const LineSegment& wall : walls) boxes.push_back(BoxOf(wall.segment, margin_m));
  std::vector<std::size_t> order(walls.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::tie(boxes[a].min_x, a) < std::tie(boxes[b].min_x, b);
  });
  std::vector<std::vector<std::size_t>> neighbours(walls.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Box& a = boxes[order[k]];
    for (std::size_t l = k + 1; l < order.size() && boxes[order[l]].min_x <= a.max_x; ++l) {
      const Box& b = boxes[order[l]];
      if (b.min_y > a.max_y || a.min_y > b.max_y) continue;
      neighbours[order[k]].push_back(order[l]);
      neighbours[order[l]].push_back(order[k]);
    }
  }
  for (auto& list : neighbours) std::sort(list.begin(), list.end());
  return neighbours;
}

}  // namespace

WallJudgement JudgeWalls(std::vector<LineSegment>& merged,
                         const std::unordered_map<std::string, geometry::Segment2>& source_by_key,
                         const std::vector<geometry::Segment2>& plan,
                         const GlobalMapOptions& options) {
  const std::size_t n = merged.size();
  const double copy_distance_m = options.lone_duplicate_distance_m;
  std::vector<Support> support;
  std::vector<bool> weak(n, false);
  for (const LineSegment& segment : merged) {
    support.push_back(SupportOf(segment));
    weak[support.size() - 1] =
        support.back().lone() &&
        segment.support_cells < options.min_lone_support_per_m * geometry::Length(segment.segment);
  }
  const std::vector<std::vector<std::size_t>> neighbours = Neighbours(merged, copy_distance_m);
  // The wall of someone else that wall i lies along, nearest first (n: none), and how far off.
  const auto copied_from = [&](std::size_t i, const auto& candidate) {
    std::pair<std::size_t, double> best{n, 0.0};
    if (copy_distance_m <= 0.0) return best;
    for (const std::size_t j : neighbours[i]) {
      if (!candidate(j) || !support[i].LacksSomeOf(support[j])) continue;
      if (!Shadowed(merged[i].segment, merged[j].segment, options.merge.merge_angle_rad,
                    copy_distance_m)) {
        continue;
      }
      const double offset_m = OffsetFromLine(Midpoint(merged[i].segment), merged[j].segment);
      if (best.first == n || offset_m < best.second) best = {j, offset_m};
    }
    return best;
  };
  // What each entity's comparable walls say (the noise model's evidence): a wall merged with
  // another source's is off the merged wall by its midpoint's distance; a wall lying along
  // someone else's is off it by its distance, all of it against a corroborated wall, half of
  // the variance each when both are single observations (which of them is off is unknown).
  std::map<std::string, EntityAgreement> agreement;
  std::map<std::string, std::vector<Evidence>> evidence;
  const auto source_of = [&](const std::string& key) -> const geometry::Segment2* {
    const auto it = source_by_key.find(key);
    return it == source_by_key.end() ? nullptr : &it->second;
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (weak[i]) continue;
    const auto [copied, copy_offset_m] =
        copied_from(i, [&](std::size_t j) { return !weak[j]; });
    const bool copy = copied != n && !support[i].corroborated();
    if (!support[i].corroborated() && !copy) continue;
    const double share = copy && !support[copied].corroborated() ? std::sqrt(0.5) : 1.0;
    for (const std::string& key : merged[i].provenance) {
      const std::string source = key.substr(0, key.rfind(':'));
      const geometry::Segment2* own = source_of(key);
      if (source == "plan" || own == nullptr) continue;
      const double length_m = geometry::Length(*own);
      const double offset_m = share * (copy ? copy_offset_m
                                            : OffsetFromLine(Midpoint(*own), merged[i].segment));
      EntityAgreement& entity = agreement[source];
      (copy ? entity.disagree_m : entity.agree_m) += length_m;
      entity.offset_sq_m3 += length_m * offset_m * offset_m;
      evidence[source].push_back({Midpoint(*own), length_m, offset_m});
    }
  }
  const auto entity_sd = [&](const std::string& entity, const geometry::Segment2& wall) {
    const auto it = evidence.find(entity);
    return EstimatedError(it == evidence.end() ? std::vector<Evidence>{} : it->second,
                          Midpoint(wall), options);
  };
  // A wall's error sd: its entities' estimates combined as independent measurements.
  std::vector<double> sd_m(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    double information = 0.0;
    for (const std::string& entity : support[i].entities) {
      const double sd = entity_sd(entity, merged[i].segment);
      information += 1.0 / (sd * sd);
    }
    sd_m[i] = information > 0.0 ? 1.0 / std::sqrt(information) : 0.0;
  }
  // Walls entities with a large error there left along a plan wall they do not confirm (several
  // of them drifted alike): contradicted by the plan.
  const auto off_the_plan = [&](std::size_t i) {
    if (support[i].plan || copy_distance_m <= 0.0) return false;
    const bool untrusted = std::none_of(
        support[i].entities.begin(), support[i].entities.end(), [&](const std::string& entity) {
          return entity_sd(entity, merged[i].segment) <= options.max_lone_error_m;
        });
    return untrusted && std::any_of(plan.begin(), plan.end(), [&](const geometry::Segment2& wall) {
             return Shadowed(merged[i].segment, wall, options.merge.merge_angle_rad,
                             copy_distance_m);
           });
  };
  // Copies: best supported first (more sources, smaller estimated error, longer), a wall lying
  // along one already kept that someone else saw is withheld as its copy, and its entities are
  // credited to that wall: of two entities that saw one wall apart, the one whose walls agree
  // with the others' around it places it.
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < n; ++i) {
    if (!weak[i] && !off_the_plan(i)) order.push_back(i);
  }
  const auto sources = [&](std::size_t i) { return support[i].entities.size() + (support[i].plan ? 1 : 0); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const double length_a = geometry::Length(merged[a].segment);
    const double length_b = geometry::Length(merged[b].segment);
    return std::make_tuple(-static_cast<double>(sources(a)), sd_m[a], -length_a, a) <
           std::make_tuple(-static_cast<double>(sources(b)), sd_m[b], -length_b, b);
  });
  std::vector<bool> kept(n, false);
  std::vector<std::set<std::string>> seen_by(n);
  for (std::size_t i = 0; i < n; ++i) {
    seen_by[i] = support[i].entities;
    if (support[i].plan) seen_by[i].insert("plan");
  }
  for (const std::size_t i : order) {
    const std::size_t copied = copied_from(i, [&](std::size_t j) { return kept[j]; }).first;
    if (copied != n) {
      seen_by[copied].insert(support[i].entities.begin(), support[i].entities.end());
      continue;
    }
    kept[i] = true;
  }
  WallJudgement judgement;
  judgement.agreement = std::move(agreement);
  std::vector<LineSegment> published;
  for (std::size_t i = 0; i < n; ++i) {
    if (!kept[i]) continue;
    published.push_back(std::move(merged[i]));
    judgement.support.push_back({{seen_by[i].begin(), seen_by[i].end()}, sd_m[i]});
  }
  merged = std::move(published);
  return judgement;
}

}  // namespace pena::fusion::detail
