#include "pena/gateway/dds_convert.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string_view>
#include <utility>

#include "from_dds.hpp"
#include "to_dds.hpp"

namespace pena::gateway {
namespace {

constexpr std::uint64_t kKindMask = (1u << kAnnotationKindBits) - 1;
constexpr std::uint64_t kMaxAnnotationNumber = (std::uint64_t{1} << 60) - 1;

bool IsAlarmKind(pena_dds::AnnotationKind kind) {
  return kind == pena_dds::ANNOTATION_VICTIM_FOUND || kind == pena_dds::ANNOTATION_DANGEROUS_AREA;
}

// n of "<author>/<n>"; nullopt if the id has another shape.
std::optional<std::uint64_t> AnnotationNumber(std::string_view id, std::string_view author) {
  if (id.size() <= author.size() + 1 || id.substr(0, author.size()) != author ||
      id[author.size()] != '/') {
    return std::nullopt;
  }
  const std::string_view digits = id.substr(author.size() + 1);
  std::uint64_t number = 0;
  const auto [end, status] = std::from_chars(digits.data(), digits.data() + digits.size(), number);
  if (status != std::errc() || end != digits.data() + digits.size() || number > kMaxAnnotationNumber) {
    return std::nullopt;
  }
  return number;
}

// The 1-sigma radius of the x-y covariance (its largest axis) and the heading's; 0 where the
// sample's covariance is missing or malformed (not finite, not positive): unknown, not certain.
std::pair<double, double> PoseSds(const std::array<double, 9>& row_major) {
  const double xx = row_major[0], xy = row_major[1], yy = row_major[4], heading = row_major[8];
  if (!std::isfinite(xx) || !std::isfinite(xy) || !std::isfinite(yy) || !std::isfinite(heading)) {
    return {0.0, 0.0};
  }
  // The largest eigenvalue of [[xx, xy], [xy, yy]].
  const double largest = 0.5 * (xx + yy) + std::hypot(0.5 * (xx - yy), xy);
  return {largest > 0.0 ? std::sqrt(largest) : 0.0, heading > 0.0 ? std::sqrt(heading) : 0.0};
}

}  // namespace

PoseUpdate PoseFromDds(const pena_dds::EntityPose& sample, double stamp_s) {
  const auto [position_sd_m, heading_sd_rad] = PoseSds(sample.covariance());
  PoseUpdate pose{sample.entity_id().to_string(), services::FromDds(sample.world_from_body()),
                  stamp_s, position_sd_m, heading_sd_rad, std::nullopt};
  if (std::isfinite(sample.stamp_s())) pose.mission_stamp_s = sample.stamp_s();
  return pose;
}

pena_dds::EntityPose PoseToDds(const PoseUpdate& pose, std::uint64_t seq) {
  pena_dds::EntityPose out;
  services::SetBounded(out.entity_id(), pose.entity, "pose entity");
  out.schema_version(pena_dds::SCHEMA_VERSION);
  out.seq(seq);
  out.stamp_s(pose.mission_stamp_s.value_or(pose.stamp_s));
  out.world_from_body(services::ToDds(pose.world_from_body));
  out.odom_from_body(services::ToDds(pose.world_from_body));
  // The link carries a circle: the far side's covariance is diagonal, as wide as the largest axis.
  const double position_var_m2 = pose.position_sd_m * pose.position_sd_m;
  std::array<double, 9> covariance{};
  covariance[0] = covariance[4] = position_var_m2;
  covariance[8] = pose.heading_sd_rad * pose.heading_sd_rad;
  out.covariance(covariance);
  out.status(pena_dds::POSE_MATCHED);
  return out;
}

std::optional<Annotation> AnnotationFromDds(const pena_dds::Annotation& sample, double stamp_s,
                                            std::string* error) {
  const std::string id = sample.annotation_id().to_string();
  const std::string author = sample.author_id().to_string();
  const std::optional<std::uint64_t> number = AnnotationNumber(id, author);
  if (!number) {
    *error = "annotation_id '" + id + "' is not '" + author + "/<n>' (n decimal, < 2^60)";
    return std::nullopt;
  }
  const auto kind = static_cast<std::uint64_t>(sample.kind());
  if (kind > kKindMask) {
    *error = "annotation " + id + ": kind " + std::to_string(kind) + " out of range";
    return std::nullopt;
  }
  Annotation out;
  out.alarm = IsAlarmKind(sample.kind()) && !sample.retracted();
  out.entity = author;
  out.id = *number << kAnnotationIdShift | (sample.retracted() ? kAnnotationRetractedBit : 0) | kind;
  out.x_m = sample.position().x_m();
  out.y_m = sample.position().y_m();
  out.stamp_s = stamp_s;
  out.text = sample.text().to_string();
  if (std::isfinite(sample.stamp_s())) out.mission_stamp_s = sample.stamp_s();
  out.radius_m = std::isfinite(sample.radius_m()) ? std::max(0.0, double{sample.radius_m()}) : 0.0;
  for (const pena_dds::Point2& point : sample.outline()) {
    if (!std::isfinite(point.x_m()) || !std::isfinite(point.y_m())) {
      *error = "annotation " + id + ": outline point not finite";
      return std::nullopt;
    }
    out.outline_m.emplace_back(point.x_m(), point.y_m());
  }
  return out;
}

pena_dds::Annotation AnnotationToDds(const Annotation& annotation) {
  pena_dds::Annotation out;
  const std::string id =
      annotation.entity + "/" + std::to_string(annotation.id >> kAnnotationIdShift);
  services::SetBounded(out.annotation_id(), id, "annotation_id");
  out.schema_version(pena_dds::SCHEMA_VERSION);
  services::SetBounded(out.author_id(), annotation.entity, "annotation author_id");
  const std::uint64_t kind = annotation.id & kKindMask;
  out.kind(kind <= static_cast<std::uint64_t>(pena_dds::ANNOTATION_FREE_TEXT)
               ? static_cast<pena_dds::AnnotationKind>(kind)
               : pena_dds::ANNOTATION_FREE_TEXT);
  out.stamp_s(annotation.mission_stamp_s.value_or(annotation.stamp_s));
  pena_dds::Point2 position;
  position.x_m(annotation.x_m);
  position.y_m(annotation.y_m);
  out.position(position);
  services::SetBounded(out.text(), annotation.text, "annotation text");
  out.retracted((annotation.id & kAnnotationRetractedBit) != 0);
  out.radius_m(static_cast<float>(annotation.radius_m));
  if (annotation.outline_m.size() > pena_dds::OUTLINE_MAX_POINTS) {
    throw std::length_error("annotation outline: " + std::to_string(annotation.outline_m.size()) +
                            " points, at most " + std::to_string(pena_dds::OUTLINE_MAX_POINTS));
  }
  for (const auto& [x, y] : annotation.outline_m) {
    pena_dds::Point2 point;
    point.x_m(x);
    point.y_m(y);
    out.outline().push_back(point);
  }
  return out;
}

std::optional<Correction> CorrectionFromDds(const pena_dds::Correction& sample, double stamp_s,
                                            std::string* error) {
  if (sample.kind() != pena_dds::CORRECTION_MAP_FROM_ODOM) {
    *error = "correction " + std::to_string(sample.seq()) + " for " +
             sample.entity_id().to_string() +
             ": kind CORRECTION_POSE needs the mission stamp, which the link does not carry";
    return std::nullopt;
  }
  return Correction{sample.entity_id().to_string(), services::FromDds(sample.map_from_odom()),
                    sample.seq(), stamp_s, sample.operator_id().to_string()};
}

pena_dds::Correction CorrectionToDds(const Correction& correction) {
  pena_dds::Correction out;
  services::SetBounded(out.entity_id(), correction.entity, "correction entity_id");
  out.schema_version(pena_dds::SCHEMA_VERSION);
  out.seq(correction.version);
  out.kind(pena_dds::CORRECTION_MAP_FROM_ODOM);
  out.map_from_odom(services::ToDds(correction.world_from_local));
  out.stamp_s(correction.stamp_s);
  out.confidence(1.0f);
  services::SetBounded(out.operator_id(), correction.operator_id, "correction operator_id");
  return out;
}

std::optional<OperatorCorrection> OperatorCorrectionFromDds(const pena_dds::OperatorCorrection& sample,
                                                            double stamp_s, std::string* error) {
  OperatorCorrection out;
  out.correction_id = sample.correction_id().to_string();
  if (out.correction_id.empty()) {
    *error = "operator correction without correction_id";
    return std::nullopt;
  }
  out.operator_id = sample.operator_id().to_string();
  out.kind = static_cast<std::uint32_t>(sample.kind());
  out.entity = sample.target_entity_id().to_string();
  out.mission_stamp_s = sample.stamp_s();
  out.origin_x_m = sample.rotation_origin().x_m();
  out.origin_y_m = sample.rotation_origin().y_m();
  out.wrong_x_m = sample.wrong_point().x_m();
  out.wrong_y_m = sample.wrong_point().y_m();
  out.correct_x_m = sample.correct_point().x_m();
  out.correct_y_m = sample.correct_point().y_m();
  out.world_from_body = services::FromDds(sample.world_from_body());
  out.console_seq = sample.seq();
  out.segment_id = sample.segment_id();
  out.segment_x0_m = sample.segment().start_x_mm() / 1000.0;
  out.segment_y0_m = sample.segment().start_y_mm() / 1000.0;
  out.segment_x1_m = sample.segment().end_x_mm() / 1000.0;
  out.segment_y1_m = sample.segment().end_y_mm() / 1000.0;
  out.applied = sample.applied();
  out.refusal = sample.refusal().to_string();
  out.undoes_id = sample.undoes_id().to_string();
  out.stamp_s = stamp_s;
  for (double value : {out.mission_stamp_s, out.origin_x_m, out.origin_y_m, out.wrong_x_m,
                       out.wrong_y_m, out.correct_x_m, out.correct_y_m, out.world_from_body.x_m,
                       out.world_from_body.y_m, out.world_from_body.theta_rad, out.segment_x0_m,
                       out.segment_y0_m, out.segment_x1_m, out.segment_y1_m}) {
    if (!std::isfinite(value)) {
      *error = "operator correction " + out.correction_id + ": a number is not finite";
      return std::nullopt;
    }
  }
  return out;
}

pena_dds::OperatorCorrection OperatorCorrectionToDds(const OperatorCorrection& c) {
  const auto point = [](double x, double y) {
    pena_dds::Point2 p;
    p.x_m(x);
    p.y_m(y);
    return p;
  };
  pena_dds::OperatorCorrection out;
  services::SetBounded(out.correction_id(), c.correction_id, "operator correction_id");
  out.schema_version(pena_dds::SCHEMA_VERSION);
  services::SetBounded(out.operator_id(), c.operator_id, "operator correction operator_id");
  out.kind(static_cast<pena_dds::OperatorCorrectionKind>(c.kind));
  services::SetBounded(out.target_entity_id(), c.entity, "operator correction target_entity_id");
  out.stamp_s(c.mission_stamp_s);
  out.world_from_body(services::ToDds(c.world_from_body));
  out.segment_id(c.segment_id);
  const auto mm = [](double metres) { return static_cast<std::int32_t>(std::lround(metres * 1000.0)); };
  pena_dds::Segment segment;
  segment.start_x_mm(mm(c.segment_x0_m));
  segment.start_y_mm(mm(c.segment_y0_m));
  segment.end_x_mm(mm(c.segment_x1_m));
  segment.end_y_mm(mm(c.segment_y1_m));
  out.segment(segment);
  out.rotation_origin(point(c.origin_x_m, c.origin_y_m));
  out.wrong_point(point(c.wrong_x_m, c.wrong_y_m));
  out.correct_point(point(c.correct_x_m, c.correct_y_m));
  out.seq(c.console_seq);
  out.applied(c.applied);
  services::SetBounded(out.refusal(), c.refusal, "operator correction refusal");
  services::SetBounded(out.undoes_id(), c.undoes_id, "operator correction undoes_id");
  return out;
}

}  // namespace pena::gateway
