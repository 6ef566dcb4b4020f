// DDS -> the console's picture (console_conversions.hpp).
#include "console_conversions.hpp"

#include "from_dds.hpp"

namespace pena::services {
namespace {

const char* ToString(pena_dds::PoseStatus status) {
  switch (status) {
    case pena_dds::POSE_FIRST: return "first";
    case pena_dds::POSE_MATCHED: return "matched";
    case pena_dds::POSE_DEGENERATE: return "degenerate";
    case pena_dds::POSE_FAILED: return "failed";
    case pena_dds::POSE_NO_POINTS: return "no_points";
    case pena_dds::POSE_PRIOR_ONLY: return "prior_only";
  }
  return "unknown";
}

const char* ToString(pena_dds::EntityState state) {
  switch (state) {
    case pena_dds::ENTITY_STARTING: return "starting";
    case pena_dds::ENTITY_RUNNING: return "running";
    case pena_dds::ENTITY_FINISHED: return "finished";
    case pena_dds::ENTITY_FAILED: return "failed";
  }
  return "unknown";
}

const char* ToString(pena_dds::AnnotationKind kind) {
  switch (kind) {
    case pena_dds::ANNOTATION_DANGEROUS_AREA: return "dangerous_area";
    case pena_dds::ANNOTATION_VICTIM_FOUND: return "victim_found";
    case pena_dds::ANNOTATION_CORRIDOR_CROSSING: return "corridor_crossing";
    case pena_dds::ANNOTATION_ELEVATOR: return "elevator";
    case pena_dds::ANNOTATION_STAIRS: return "stairs";
    case pena_dds::ANNOTATION_EXIT: return "exit";
    case pena_dds::ANNOTATION_FREE_TEXT: return "free_text";
  }
  return "unknown";
}

Eigen::Vector2d FromDds(const pena_dds::Point2& point) { return {point.x_m(), point.y_m()}; }

}  // namespace

PoseUpdate ToPicture(const pena_dds::EntityPose& sample, std::int64_t heard_ns,
                     std::int64_t source_ns) {
  CheckSchemaVersion(sample.schema_version(), "EntityPose");
  PoseUpdate pose;
  pose.entity_id = sample.entity_id().to_string();
  pose.seq = sample.seq();
  pose.stamp_s = sample.stamp_s();
  pose.world_from_body = services::FromDds(sample.world_from_body());
  pose.odom_from_body = services::FromDds(sample.odom_from_body());
  for (std::size_t i = 0; i < 9; ++i) pose.covariance[i] = sample.covariance()[i];
  pose.status = ToString(sample.status());
  pose.heard_ns = heard_ns;
  pose.source_ns = source_ns;
  return pose;
}

StatusUpdate ToPicture(const pena_dds::EntityStatus& sample, std::int64_t heard_ns) {
  CheckSchemaVersion(sample.schema_version(), "EntityStatus");
  StatusUpdate status;
  status.entity_id = sample.entity_id().to_string();
  status.kind = sample.kind() == pena_dds::ENTITY_ROBOT ? "robot" : "human";
  status.state = ToString(sample.state());
  status.message = sample.message().to_string();
  status.corrections_applied = sample.corrections_applied();
  status.heard_ns = heard_ns;
  return status;
}

AnnotationRecord ToPicture(const pena_dds::Annotation& sample) {
  CheckSchemaVersion(sample.schema_version(), "Annotation");
  AnnotationRecord a;
  a.annotation_id = sample.annotation_id().to_string();
  a.author_id = sample.author_id().to_string();
  a.kind = ToString(sample.kind());
  a.stamp_s = sample.stamp_s();
  a.x_m = sample.position().x_m();
  a.y_m = sample.position().y_m();
  a.radius_m = sample.radius_m();
  for (const pena_dds::Point2& p : sample.outline()) a.outline.emplace_back(p.x_m(), p.y_m());
  a.text = sample.text().to_string();
  a.retracted = sample.retracted();
  return a;
}

CorrectionRecord ToPicture(const pena_dds::OperatorCorrection& sample) {
  CheckSchemaVersion(sample.schema_version(), "OperatorCorrection");
  CorrectionRecord c;
  c.correction_id = sample.correction_id().to_string();
  c.operator_id = sample.operator_id().to_string();
  c.entity_id = sample.target_entity_id().to_string();
  c.stamp_s = sample.stamp_s();
  switch (sample.kind()) {
    case pena_dds::OPERATOR_SET_POSE: c.kind = "set_pose"; break;
    case pena_dds::OPERATOR_REMOVE_SEGMENT: c.kind = "remove_segment"; break;
    case pena_dds::OPERATOR_ADD_SEGMENT: c.kind = "add_segment"; break;
    case pena_dds::OPERATOR_ROTATE:
      c.kind = "rotate";
      c.geometry = localisation::RotationCorrection{sample.stamp_s(),
                                                    FromDds(sample.rotation_origin()),
                                                    FromDds(sample.wrong_point()),
                                                    FromDds(sample.correct_point())};
      break;
    case pena_dds::OPERATOR_TRANSLATE:
      c.kind = "translate";
      c.geometry = localisation::TranslationCorrection{
          sample.stamp_s(), FromDds(sample.wrong_point()), FromDds(sample.correct_point())};
      break;
    case pena_dds::OPERATOR_UNDO:
      c.kind = "undo";
      c.undoes = sample.undoes_id().to_string();
      break;
  }
  c.applied = sample.applied();
  c.refusal = sample.refusal().to_string();
  // A degenerate rotation from some other publisher is listed without moving anything.
  if (c.geometry) {
    try {
      localisation::CorrectionTransform(*c.geometry);
    } catch (const std::invalid_argument&) {
      c.geometry.reset();
    }
  }
  return c;
}

LinkRecord ToPicture(const pena_dds::LinkHealth& sample, std::int64_t heard_ns) {
  CheckSchemaVersion(sample.schema_version(), "LinkHealth");
  LinkRecord link;
  link.gateway_id = sample.gateway_id().to_string();
  link.peer_alive = sample.peer_alive();
  link.peer_heard_age_s = sample.peer_heard_age_s();
  link.budget_bit_s = sample.budget_bit_s();
  link.sent_bit_s = sample.sent_bit_s();
  link.received_frames_s = sample.received_frames_s();
  link.pending_reliable = sample.pending_reliable();
  link.pending_map_updates = sample.pending_map_updates();
  link.frames_rejected = sample.frames_rejected();
  link.resyncs = sample.resyncs();
  link.heard_ns = heard_ns;
  return link;
}

}  // namespace pena::services
