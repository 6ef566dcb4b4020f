#include "pena/localisation/plan_adaptation.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "pena/options_check.hpp"
#include "plan_ends.hpp"

namespace pena::localisation {
namespace {

void Require(bool ok, const std::string& field, const std::string& rule, double value) {
  RequireOption(ok, "plan_adaptation", field, rule, value);
}

// Unit direction and left normal of a segment; nullopt for one too short to carry a direction.
struct Frame {
  Eigen::Vector2d along;
  Eigen::Vector2d normal;
  double length_m;
};

std::optional<Frame> FrameOf(const geometry::Segment2& s) {
  const Eigen::Vector2d d = s.end_m - s.start_m;
  const double length = d.norm();
  if (length < 1e-9) return std::nullopt;
  const Eigen::Vector2d along = d / length;
  return Frame{along, Eigen::Vector2d(-along.y(), along.x()), length};
}

// Two segments within these of one line are one wall (drawn with one error).
constexpr double kCollinearRad = 0.035;  // 2 deg
constexpr double kCollinearM = 0.05;
// Heading rows of the least squares are scaled to metres at this distance from the body.
constexpr double kHeadingLever_m = 5.0;

// Lines whose normals are within 45 deg pin each other's normal direction down.
constexpr double kFacingCos = 0.7071067811865476;

// Rounds of evidence kept per segment (the latest): a wall is judged on recent views.
constexpr std::size_t kKeptRounds = 10;

// d(residual) / d(x, y, heading) of a return at `point_m` on a wall with `normal`, the heading
// turning about the body at `origin_m`.
Eigen::Vector3d Row(const Eigen::Vector2d& normal, const Eigen::Vector2d& point_m, const Eigen::Vector2d& origin_m) {
  const Eigen::Vector2d lever = point_m - origin_m;
  return {normal.x(), normal.y(), normal.dot(Eigen::Vector2d(-lever.y(), lever.x()))};
}

double Median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

std::vector<PlanAdaptation::Half> PlanAdaptation::Halves(const Support& support, const Eigen::Vector2d& along) {
  std::vector<std::size_t> order(support.points.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return support.points[a].dot(along) < support.points[b].dot(along);
  });
  std::vector<Half> halves;
  const std::size_t middle = order.size() / 2;
  for (const auto& [from, to] : {std::pair{std::size_t{0}, middle}, std::pair{middle, order.size()}}) {
    if (to <= from) continue;
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    std::vector<double> residuals;
    for (std::size_t k = from; k < to; ++k) {
      centroid += support.points[order[k]];
      residuals.push_back(support.residuals_m[order[k]]);
    }
    const double n = static_cast<double>(to - from);
    halves.push_back({centroid / n, Median(std::move(residuals))});
  }
  return halves;
}

void ValidatePlanAdaptationOptions(const PlanAdaptationOptions& o) {
  Require(o.association_m > 0.0, "association_m", "> 0 m", o.association_m);
  Require(o.end_margin_m >= 0.0, "end_margin_m", ">= 0 m", o.end_margin_m);
  Require(o.min_points >= 1, "min_points", ">= 1", o.min_points);
  Require(o.min_other_information > 0.0, "min_other_information", "> 0", o.min_other_information);
  Require(o.min_rounds >= 1, "min_rounds", ">= 1", o.min_rounds);
  Require(o.min_offset_m >= 0.0 && o.min_offset_m < o.association_m, "min_offset_m",
          "in [0, association_m) m", o.min_offset_m);
  Require(o.max_spread_m >= 0.0, "max_spread_m", ">= 0 m", o.max_spread_m);
  Require(o.wall_sigma_m > 0.0, "wall_sigma_m", "> 0 m", o.wall_sigma_m);
  Require(o.prior_sigma_m > 0.0, "prior_sigma_m", "> 0 m", o.prior_sigma_m);
  Require(o.prior_sigma_per_m >= 0.0, "prior_sigma_per_m", ">= 0", o.prior_sigma_per_m);
  Require(o.prior_sigma_rad > 0.0, "prior_sigma_rad", "> 0 rad", o.prior_sigma_rad);
  Require(o.prior_sigma_rad_per_m >= 0.0, "prior_sigma_rad_per_m", ">= 0 rad/m", o.prior_sigma_rad_per_m);
  Require(o.prior_facing_sigma_m >= 0.0, "prior_facing_sigma_m", ">= 0 m", o.prior_facing_sigma_m);
  ValidatePlanOpeningsOptions(o.openings);
  const PlanEndOptions& e = o.ends;
  Require(e.join_m >= 0.0, "ends.join_m", ">= 0 m", e.join_m);
  Require(e.across_m > 0.0, "ends.across_m", "> 0 m", e.across_m);
  Require(e.window_m > 0.0, "ends.window_m", "> 0 m", e.window_m);
  Require(e.min_points >= 2, "ends.min_points", ">= 2", e.min_points);
  Require(e.max_gap_m > 0.0, "ends.max_gap_m", "> 0 m", e.max_gap_m);
  Require(e.past_rad > 0.0, "ends.past_rad", "> 0 rad", e.past_rad);
  Require(e.past_m >= 0.0, "ends.past_m", ">= 0 m", e.past_m);
  Require(e.min_ends >= 1, "ends.min_ends", ">= 1", e.min_ends);
  Require(e.max_spread_m >= 0.0, "ends.max_spread_m", ">= 0 m", e.max_spread_m);
  Require(e.min_error_m >= 0.0, "ends.min_error_m", ">= 0 m", e.min_error_m);
}

PlanAdaptation::PlanAdaptation(const PlanAdaptationOptions& options, std::vector<geometry::Segment2> plan)
    : options_(options), plan_(std::move(plan)), evidence_(plan_.size()), openings_(options.openings) {
  ValidatePlanAdaptationOptions(options_);
  ends_ = internal::FreeEnds(plan_, options_.ends.join_m);
}

std::vector<int> PlanAdaptation::SegmentsNear(const scan_matching::Points2& points) const {
  Eigen::Vector2d low = points.front();
  Eigen::Vector2d high = points.front();
  for (const Eigen::Vector2d& p : points) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const Eigen::Vector2d grow = Eigen::Vector2d::Constant(options_.association_m);
  return geometry::SegmentsInBox(plan_, low - grow, high + grow);
}

std::vector<PlanAdaptation::Support> PlanAdaptation::Associate(const scan_matching::Points2& points) const {
  const std::vector<int> near = SegmentsNear(points);
  std::vector<Support> support(plan_.size());
  for (const Eigen::Vector2d& p : points) {
    int segment = -1;
    double residual_m = 0.0;
    double best_distance = options_.association_m;
    for (const int i : near) {
      const geometry::Segment2& s = plan_[static_cast<std::size_t>(i)];
      const std::optional<Frame> f = FrameOf(s);
      if (!f) continue;
      const double along = (p - s.start_m).dot(f->along);
      if (along < options_.end_margin_m || along > f->length_m - options_.end_margin_m) continue;
      const double across = (p - s.start_m).dot(f->normal);
      if (std::abs(across) < best_distance) {
        best_distance = std::abs(across);
        segment = i;
        residual_m = across;
      }
    }
    if (segment >= 0) {
      support[static_cast<std::size_t>(segment)].points.push_back(p);
      support[static_cast<std::size_t>(segment)].residuals_m.push_back(residual_m);
    }
  }
  return support;
}

std::optional<PlanAdaptation::PoseError> PlanAdaptation::ErrorFromOthers(int measured, const std::vector<Support>& support,
                                                                        const RoundView& view) const {
  // Least squares on the other walls (the median of each half of each: a long wall alone fixes
  // the heading) and on the motion prior. Each half counts as one measurement of wall_sigma_m: a
  // drawing error is per wall, not per return.
  const Eigen::Vector2d normal = FrameOf(plan_[static_cast<std::size_t>(measured)])->normal;
  std::vector<Measurement> rows = PriorRows(view);
  int facing_lines = Facing(view) ? 1 : 0;  // the prior counts as one line when it is recent
  std::vector<int> seen_lines;
  for (std::size_t i = 0; i < support.size(); ++i) {
    const int other = static_cast<int>(i);
    if (other == measured || OnOneLine(measured, other)) continue;  // one line: one drawing error
    if (static_cast<int>(support[i].points.size()) < options_.min_points) continue;
    const Eigen::Vector2d other_normal = FrameOf(plan_[i])->normal;
    if (std::abs(other_normal.dot(normal)) >= kFacingCos &&
        std::none_of(seen_lines.begin(), seen_lines.end(), [&](int line) { return OnOneLine(line, other); })) {
      seen_lines.push_back(other);
      ++facing_lines;
    }
    for (const Half& half : support[i].halves) {
      rows.push_back({Row(other_normal, half.centroid_m, view.origin_m), half.median_m, 1.0});
    }
  }
  // Two references that disagree cannot say which one is drawn off (a room drawn too narrow):
  // the measured wall is judged against at least two others, and only if those agree.
  if (facing_lines < 2) return std::nullopt;
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity() * 1e-9;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (const Measurement& m : rows) {
    information += m.weight * m.row * m.row.transpose();
    moment += m.weight * m.value_m * m.row;
  }
  PoseError fit{information.inverse() * moment, information.inverse()};
  double misfit = 0.0, weight = 0.0;
  for (const Measurement& m : rows) {
    misfit += m.weight * std::pow(m.value_m - m.row.dot(fit.error), 2);
    weight += m.weight;
  }
  if (std::sqrt(misfit / weight) > options_.max_spread_m) return std::nullopt;
  return fit;
}

std::optional<double> PlanAdaptation::OffsetAgainstOthers(int measured, const std::vector<Support>& support,
                                                          const RoundView& view) const {
  const std::optional<PoseError> fit = ErrorFromOthers(measured, support, view);
  if (!fit) return std::nullopt;
  const Eigen::Vector2d normal = FrameOf(plan_[static_cast<std::size_t>(measured)])->normal;
  const Support& own = support[static_cast<std::size_t>(measured)];
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : own.points) centroid += p;
  centroid /= static_cast<double>(own.points.size());
  const Eigen::Vector3d at_centroid = Row(normal, centroid, view.origin_m);
  if (1.0 / at_centroid.dot(fit->covariance * at_centroid) < options_.min_other_information) return std::nullopt;
  std::vector<double> offsets;
  offsets.reserve(own.points.size());
  for (std::size_t k = 0; k < own.points.size(); ++k) {
    offsets.push_back(own.residuals_m[k] - Row(normal, own.points[k], view.origin_m).dot(fit->error));
  }
  return Median(std::move(offsets));
}

double PlanAdaptation::PriorSigma(const RoundView& view) const {
  return options_.prior_sigma_m + options_.prior_sigma_per_m * view.walked_m;
}

bool PlanAdaptation::Facing(const RoundView& view) const {
  return PriorSigma(view) <= options_.prior_facing_sigma_m;
}

std::vector<PlanAdaptation::Measurement> PlanAdaptation::PriorRows(const RoundView& view) const {
  // Had the motion prior been right, the pose error of the corrected pose would be the
  // correction itself. Heading rows are scaled to metres at kHeadingLever_m.
  const double sigma_m = PriorSigma(view);
  const double weight = std::pow(options_.wall_sigma_m / sigma_m, 2);
  const double sigma_heading_m = kHeadingLever_m * (options_.prior_sigma_rad + options_.prior_sigma_rad_per_m * view.walked_m);
  return {{Eigen::Vector3d::UnitX(), view.correction.x(), weight},
          {Eigen::Vector3d::UnitY(), view.correction.y(), weight},
          {Eigen::Vector3d(0.0, 0.0, kHeadingLever_m), kHeadingLever_m * view.correction.z(),
           std::pow(options_.wall_sigma_m / sigma_heading_m, 2)}};
}

bool PlanAdaptation::Observe(const scan_matching::Points2& map_points, const RoundView& view) {
  if (!options_.enabled || map_points.empty()) return false;
  std::vector<Support> support = Associate(map_points);
  // Each wall's halves once per round: every measured wall uses all the others'.
  for (std::size_t i = 0; i < support.size(); ++i) {
    if (static_cast<int>(support[i].points.size()) < options_.min_points) continue;
    support[i].halves = Halves(support[i], FrameOf(plan_[i])->along);
  }
  bool moved = false;
  for (std::size_t i = 0; i < support.size(); ++i) {
    if (static_cast<int>(support[i].points.size()) < options_.min_points) continue;
    const std::optional<double> offset = OffsetAgainstOthers(static_cast<int>(i), support, view);
    if (offset) moved = Weigh(static_cast<int>(i), *offset) || moved;
  }
  const std::vector<PlanOpening> cuts = openings_.Observe(map_points, view.origin_m, plan_);
  evidence_.resize(plan_.size());
  for (const PlanOpening& cut : cuts) evidence_[static_cast<std::size_t>(cut.index)] = {};
  EndsAfterCuts(cuts);
  return moved || !cuts.empty();
}

void PlanAdaptation::EndsAfterCuts(const std::vector<PlanOpening>& cuts) {
  ends_.resize(plan_.size());
  for (const PlanOpening& cut : cuts) {
    SegmentEnds& kept = ends_[static_cast<std::size_t>(cut.index)];
    if (cut.added_index >= 0) {  // both parts: the kept one ends at the cut, the added one starts there
      ends_[static_cast<std::size_t>(cut.added_index)] = {false, kept.end};
      kept.end = false;
    } else if ((plan_[static_cast<std::size_t>(cut.index)].end_m - cut.stretch.start_m).norm() < 1e-9) {
      kept.end = false;  // only the part before the opening was kept
    } else {
      kept.start = false;  // only the part after it
    }
  }
}

bool PlanAdaptation::Weigh(int segment, double offset_m) {
  std::vector<double>& offsets = evidence_[static_cast<std::size_t>(segment)].offsets_m;
  offsets.push_back(offset_m);
  if (offsets.size() > kKeptRounds) offsets.erase(offsets.begin());
  if (static_cast<int>(offsets.size()) < options_.min_rounds) return false;
  double mean = 0.0;
  for (const double o : offsets) mean += o;
  mean /= static_cast<double>(offsets.size());
  double spread = 0.0;
  for (const double o : offsets) spread += (o - mean) * (o - mean);
  spread = std::sqrt(spread / static_cast<double>(offsets.size()));
  if (spread > options_.max_spread_m) {
    offsets.erase(offsets.begin());  // the oldest goes: a window of the latest rounds
    return false;
  }
  if (std::abs(mean) < options_.min_offset_m) return false;
  Move(segment, mean, static_cast<int>(offsets.size()));
  offsets.clear();
  return true;
}

std::optional<Eigen::Vector2d> PlanAdaptation::ErrorAtEnds(const scan_matching::Points2& map_points,
                                                            const Eigen::Vector2d& origin_m, double heading_rad) const {
  const PlanEndOptions& o = options_.ends;
  const std::vector<internal::EndMeasurement> ends =
      internal::MeasureEnds(plan_, ends_, map_points, origin_m, heading_rad, o);
  if (static_cast<int>(ends.size()) < o.min_ends) return std::nullopt;
  Eigen::Matrix2d information = Eigen::Matrix2d::Zero();
  Eigen::Vector2d moment = Eigen::Vector2d::Zero();
  for (const internal::EndMeasurement& end : ends) {
    information += end.outward * end.outward.transpose();
    moment += end.residual_m * end.outward;
  }
  // Only the directions that min_ends ends pin down: a corridor's jambs say nothing across it.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(information);
  Eigen::Vector2d error = Eigen::Vector2d::Zero();
  bool pinned = false;
  for (int k = 0; k < 2; ++k) {
    const double value = solver.eigenvalues()(k);
    if (value < 0.9 * o.min_ends) continue;
    const Eigen::Vector2d direction = solver.eigenvectors().col(k);
    error += direction * direction.dot(moment) / value;
    pinned = true;
  }
  if (!pinned) return std::nullopt;
  double misfit = 0.0;
  for (const internal::EndMeasurement& end : ends) misfit += std::pow(end.residual_m - end.outward.dot(error), 2);
  if (std::sqrt(misfit / static_cast<double>(ends.size())) > o.max_spread_m) return std::nullopt;
  return error;
}

bool PlanAdaptation::OnOneLine(int a, int b) const {
  const geometry::Segment2& s = plan_[static_cast<std::size_t>(a)];
  const geometry::Segment2& t = plan_[static_cast<std::size_t>(b)];
  const std::optional<Frame> f = FrameOf(s);
  const std::optional<Frame> g = FrameOf(t);
  if (!f || !g || std::abs(f->normal.dot(g->normal)) < std::cos(kCollinearRad)) return false;
  return std::abs((t.start_m - s.start_m).dot(f->normal)) < kCollinearM &&
         std::abs((t.end_m - s.start_m).dot(f->normal)) < kCollinearM;
}

void PlanAdaptation::Move(int index, double offset_m, int rounds) {
  geometry::Segment2& s = plan_[static_cast<std::size_t>(index)];
  const Eigen::Vector2d step = offset_m * FrameOf(s)->normal;
  s.start_m += step;
  s.end_m += step;
  const auto known = std::find_if(shifts_.begin(), shifts_.end(),
                                  [&](const SegmentShift& shift) { return shift.index == index; });
  if (known == shifts_.end()) {
    shifts_.push_back({index, offset_m, rounds});
  } else {
    known->offset_m += offset_m;
    known->rounds = rounds;
  }
}

}  // namespace pena::localisation
