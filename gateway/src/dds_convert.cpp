#include "pena/gateway/dds_convert.hpp"

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
  return PoseUpdate{sample.entity_id().to_string(), services::FromDds(sample.world_from_body()),
                    stamp_s, position_sd_m, heading_sd_rad};
}

pena_dds::EntityPose PoseToDds(const PoseUpdate& pose, std::uint64_t seq) {
  pena_dds::EntityPose out;
  services::SetBounded(out.entity_id(), pose.entity, "pose entity");
  out.schema_version(pena_dds::SCHEMA_VERSION);
  out.seq(seq);
  out.stamp_s(pose.stamp_s);
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
  out.stamp_s(annotation.stamp_s);
  pena_dds::Point2 position;
  position.x_m(annotation.x_m);
  position.y_m(annotation.y_m);
  out.position(position);
  services::SetBounded(out.text(), annotation.text, "annotation text");
  out.retracted((annotation.id & kAnnotationRetractedBit) != 0);
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
                    sample.seq(), stamp_s};
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
  return out;
}

}  // namespace pena::gateway
