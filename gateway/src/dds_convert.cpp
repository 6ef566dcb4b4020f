#include "pena/gateway/dds_convert.hpp"

#include <charconv>
#include <string_view>

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

}  // namespace

PoseUpdate PoseFromDds(const pena_dds::EntityPose& sample, double stamp_s) {
  return PoseUpdate{sample.entity_id().to_string(), services::FromDds(sample.world_from_body()),
                    stamp_s};
}

pena_dds::EntityPose PoseToDds(const PoseUpdate& pose, std::uint64_t seq) {
  pena_dds::EntityPose out;
  services::SetBounded(out.entity_id(), pose.entity, "pose entity");
  out.schema_version(pena_dds::SCHEMA_VERSION);
  out.seq(seq);
  out.stamp_s(pose.stamp_s);
  out.world_from_body(services::ToDds(pose.world_from_body));
  out.odom_from_body(services::ToDds(pose.world_from_body));
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
