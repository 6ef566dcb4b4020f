// The console's gestures -> DDS (console_conversions.hpp).
#include "console_conversions.hpp"

#include "to_dds.hpp"

namespace pena::services {
namespace {

pena_dds::Point2 ToDdsPoint(const Eigen::Vector2d& point) {
  pena_dds::Point2 out;
  out.x_m(point.x());
  out.y_m(point.y());
  return out;
}

}  // namespace

pena_dds::OperatorCorrection ToDdsRotation(const RotateRequest& request, double from_stamp_s,
                                           const std::string& operator_id,
                                           const std::string& correction_id, std::uint64_t seq) {
  pena_dds::OperatorCorrection sample;
  SetBounded(sample.correction_id(), correction_id, "correction_id");
  sample.schema_version(pena_dds::SCHEMA_VERSION);
  SetBounded(sample.operator_id(), operator_id, "operator_id");
  sample.kind(pena_dds::OPERATOR_ROTATE);
  SetBounded(sample.target_entity_id(), request.entity_id, "target_entity_id");
  sample.stamp_s(from_stamp_s);
  sample.rotation_origin(ToDdsPoint(request.origin_m));
  sample.wrong_point(ToDdsPoint(request.wrong_m));
  sample.correct_point(ToDdsPoint(request.correct_m));
  sample.seq(seq);
  return sample;
}

}  // namespace pena::services
