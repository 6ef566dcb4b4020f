#include "pena/localisation/operator_corrections.hpp"

#include <cmath>
#include <stdexcept>

namespace pena::localisation {
namespace {

// Section 4.1's three points: the angle between origin -> wrong and origin -> correct, about the
// origin: p' = origin + R (p - origin), i.e. the transform (origin - R origin, angle).
geometry::Pose2 RotationTransform(const RotationCorrection& r) {
  const Eigen::Vector2d wrong = r.wrong_m - r.origin_m;
  const Eigen::Vector2d correct = r.correct_m - r.origin_m;
  if (wrong.norm() < 1e-9 || correct.norm() < 1e-9) {
    throw std::invalid_argument(
        "operator rotation: the wrong and correct direction points must differ from the origin");
  }
  const double angle = std::atan2(correct.y(), correct.x()) - std::atan2(wrong.y(), wrong.x());
  const double c = std::cos(angle), s = std::sin(angle);
  const Eigen::Vector2d rotated_origin(c * r.origin_m.x() - s * r.origin_m.y(),
                                      s * r.origin_m.x() + c * r.origin_m.y());
  const Eigen::Vector2d shift = r.origin_m - rotated_origin;
  return {shift.x(), shift.y(), geometry::NormalizeAngle(angle)};
}

}  // namespace

geometry::Pose2 CorrectionTransform(const OperatorCorrection& correction) {
  if (const auto* rotation = std::get_if<RotationCorrection>(&correction)) {
    return RotationTransform(*rotation);
  }
  const auto& translation = std::get<TranslationCorrection>(correction);
  const Eigen::Vector2d shift = translation.correct_m - translation.point_m;
  return {shift.x(), shift.y(), 0.0};
}

double FromStamp(const OperatorCorrection& correction) {
  return std::visit([](const auto& c) { return c.from_stamp_s; }, correction);
}

}  // namespace pena::localisation
