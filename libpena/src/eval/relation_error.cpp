#include "pena/eval/relation_error.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

namespace pena::eval {

namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

std::string FormatStamp(double stamp_s) {
  // Enough digits for epoch stamps with microseconds.
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.6f", stamp_s);
  return buffer;
}

}  // namespace

RelationError ComputeRelationError(const geometry::Relation& relation,
                                   const geometry::Pose2& world_from_t1,
                                   const geometry::Pose2& world_from_t2) {
  // Kuemmerle et al. 2009, eq. (1): e = delta_ij (-) delta*_ij, with the translational and
  // rotational parts taken separately. |translation of relation^-1 * estimate| equals the norm of
  // the difference of the two translations (a rotation keeps lengths), so either reading gives
  // the published numbers.
  const geometry::Pose2 estimated = geometry::Between(world_from_t1, world_from_t2);
  const geometry::Pose2 error = geometry::Between(relation.motion, estimated);
  RelationError result;
  result.t1_s = relation.t1_s;
  result.t2_s = relation.t2_s;
  result.translation_error_m = std::hypot(error.x_m, error.y_m);
  result.rotation_error_rad = std::abs(geometry::NormalizeAngle(error.theta_rad));
  return result;
}

RelationErrorSummary EvaluateRelations(const geometry::Trajectory& estimate,
                                       const std::vector<geometry::Relation>& relations,
                                       const RelationErrorOptions& options) {
  if (!(options.stamp_tolerance_s >= 0.0)) {
    throw std::invalid_argument("relation_error.stamp_tolerance_s must be >= 0 s, got " +
                                std::to_string(options.stamp_tolerance_s));
  }
  ValidateTrajectory(estimate, "estimated trajectory");
  if (relations.empty()) throw std::invalid_argument("there are no relations to evaluate");
  RelationErrorSummary summary;
  std::vector<double> translation_m, translation_sq_m2, rotation_deg, rotation_sq_deg2;
  for (const geometry::Relation& relation : relations) {
    const auto index1 = FindStamp(estimate, relation.t1_s, options.stamp_tolerance_s);
    const auto index2 = FindStamp(estimate, relation.t2_s, options.stamp_tolerance_s);
    if (!index1 || !index2) {
      ++summary.relations_skipped;
      continue;
    }
    const RelationError error =
        ComputeRelationError(relation, estimate[*index1].pose, estimate[*index2].pose);
    const double rotation_error_deg = error.rotation_error_rad * kDegPerRad;
    translation_m.push_back(error.translation_error_m);
    translation_sq_m2.push_back(error.translation_error_m * error.translation_error_m);
    rotation_deg.push_back(rotation_error_deg);
    rotation_sq_deg2.push_back(rotation_error_deg * rotation_error_deg);
    summary.errors.push_back(error);
  }
  if (summary.errors.empty()) {
    throw std::invalid_argument(
        "none of the " + std::to_string(relations.size()) +
        " relations has both stamps in the estimated trajectory (first relation t1 = " +
        FormatStamp(relations.front().t1_s) + " s, trajectory spans " +
        FormatStamp(estimate.front().stamp_s) + " to " + FormatStamp(estimate.back().stamp_s) +
        " s)");
  }
  summary.relations_used = summary.errors.size();
  summary.translation_m = ComputeMeanStd(translation_m);
  summary.translation_sq_m2 = ComputeMeanStd(translation_sq_m2);
  summary.rotation_deg = ComputeMeanStd(rotation_deg);
  summary.rotation_sq_deg2 = ComputeMeanStd(rotation_sq_deg2);
  summary.translation_spread_m = ComputeSpread(translation_m);
  summary.rotation_spread_deg = ComputeSpread(rotation_deg);
  return summary;
}

}  // namespace pena::eval
