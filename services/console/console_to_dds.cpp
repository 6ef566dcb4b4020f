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

pena_dds::OperatorCorrection ToDdsTranslation(const TranslateRequest& request, double from_stamp_s,
                                              const std::string& operator_id,
                                              const std::string& correction_id, std::uint64_t seq) {
  pena_dds::OperatorCorrection sample;
  SetBounded(sample.correction_id(), correction_id, "correction_id");
  sample.schema_version(pena_dds::SCHEMA_VERSION);
  SetBounded(sample.operator_id(), operator_id, "operator_id");
  sample.kind(pena_dds::OPERATOR_TRANSLATE);
  SetBounded(sample.target_entity_id(), request.entity_id, "target_entity_id");
  sample.stamp_s(from_stamp_s);
  sample.wrong_point(ToDdsPoint(request.point_m));
  sample.correct_point(ToDdsPoint(request.correct_m));
  sample.seq(seq);
  return sample;
}

pena_dds::OperatorCorrection ToDdsUndo(const CorrectionRecord& undone, const std::string& operator_id,
                                       const std::string& correction_id, std::uint64_t seq) {
  pena_dds::OperatorCorrection sample;
  SetBounded(sample.correction_id(), correction_id, "correction_id");
  sample.schema_version(pena_dds::SCHEMA_VERSION);
  SetBounded(sample.operator_id(), operator_id, "operator_id");
  sample.kind(pena_dds::OPERATOR_UNDO);
  SetBounded(sample.target_entity_id(), undone.entity_id, "target_entity_id");
  sample.stamp_s(undone.stamp_s);
  SetBounded(sample.undoes_id(), undone.correction_id, "undoes_id");
  sample.seq(seq);
  return sample;
}

pena_dds::Annotation ToDdsAnnotation(const AnnotationRecord& a) {
  static const std::pair<const char*, pena_dds::AnnotationKind> kKinds[] = {
      {"dangerous_area", pena_dds::ANNOTATION_DANGEROUS_AREA},
      {"victim_found", pena_dds::ANNOTATION_VICTIM_FOUND},
      {"corridor_crossing", pena_dds::ANNOTATION_CORRIDOR_CROSSING},
      {"elevator", pena_dds::ANNOTATION_ELEVATOR},
      {"stairs", pena_dds::ANNOTATION_STAIRS},
      {"exit", pena_dds::ANNOTATION_EXIT},
      {"free_text", pena_dds::ANNOTATION_FREE_TEXT}};
  pena_dds::Annotation sample;
  SetBounded(sample.annotation_id(), a.annotation_id, "annotation_id");
  sample.schema_version(pena_dds::SCHEMA_VERSION);
  SetBounded(sample.author_id(), a.author_id, "author_id");
  bool known = false;
  for (const auto& [name, kind] : kKinds) {
    if (a.kind == name) {
      sample.kind(kind);
      known = true;
    }
  }
  if (!known) throw std::invalid_argument("annotation kind: unknown '" + a.kind + "'");
  sample.stamp_s(a.stamp_s);
  sample.position(ToDdsPoint({a.x_m, a.y_m}));
  sample.radius_m(static_cast<float>(a.radius_m));
  if (a.outline.size() > pena_dds::OUTLINE_MAX_POINTS) {
    throw std::length_error("annotation outline: at most " +
                            std::to_string(pena_dds::OUTLINE_MAX_POINTS) + " points");
  }
  for (const auto& [x, y] : a.outline) sample.outline().push_back(ToDdsPoint({x, y}));
  SetBounded(sample.text(), a.text, "text");
  sample.retracted(a.retracted);
  return sample;
}

}  // namespace pena::services
