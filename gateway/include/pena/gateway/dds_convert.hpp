#pragma once
// DDS samples (idl/dds/*.idl) <-> the gateway's link items (docs/gateway.md, "DDS domain side").
// The link carries less than the DDS types: what is kept, what is rebuilt on the far side and what
// is dropped is listed per type below and in the docs. Stamps on the link are wall-clock seconds
// (the DDS source timestamp), because both gateways share one clock; mission time does not cross.

#include <cstdint>
#include <optional>
#include <string>

#include "pena/gateway/link_items.hpp"
#include "pena_dds/correction.h"
#include "pena_dds/entity.h"
#include "pena_dds/operator.h"

namespace pena::gateway {

// An annotation's link id packs "<author>/<n>", the kind and the retracted flag:
// id = n << 4 | retracted << 3 | kind (pena_dds::AnnotationKind, 0..6).
inline constexpr unsigned kAnnotationKindBits = 3;
inline constexpr std::uint64_t kAnnotationRetractedBit = 1u << kAnnotationKindBits;
inline constexpr unsigned kAnnotationIdShift = 4;

// An entity's pose: entity, world_from_body and its 1-sigma position radius (the largest axis of
// the covariance's x-y ellipse) and heading (0 for a missing or malformed covariance);
// `stamp_s` is the sample's wall-clock source time.
PoseUpdate PoseFromDds(const pena_dds::EntityPose& sample, double stamp_s);
// The far side's pose sample: odom_from_body = world_from_body, a diagonal covariance from the
// sigmas (the position's a circle), POSE_MATCHED, stamp_s = the mission time (the wall-clock
// stamp when the sender did not know it), `seq` counted by the publisher.
pena_dds::EntityPose PoseToDds(const PoseUpdate& pose, std::uint64_t seq);

// An annotation whose id is "<author_id>/<n>" (n decimal, < 2^60); kinds VICTIM_FOUND and
// DANGEROUS_AREA become alarms (sent at once). Mission time, radius and outline are carried
// (1 ms, 1 cm). nullopt and
// `error` naming the field for anything the link cannot represent.
std::optional<Annotation> AnnotationFromDds(const pena_dds::Annotation& sample, double stamp_s,
                                            std::string* error);
// The far side's sample: id "<entity>/<n>", kind and retracted from the link id, stamp_s = the
// mission time (the wall-clock stamp when the sender did not know it). Throws std::length_error naming the field for a name or text too long.
pena_dds::Annotation AnnotationToDds(const Annotation& annotation);

// A fusion correction of kind CORRECTION_MAP_FROM_ODOM (world_from_local = map_from_odom,
// version = seq). CORRECTION_POSE needs the mission stamp, which the link does not carry:
// nullopt and `error`.
std::optional<Correction> CorrectionFromDds(const pena_dds::Correction& sample, double stamp_s,
                                            std::string* error);
// The far side's sample: CORRECTION_MAP_FROM_ODOM, seq = version, confidence 1, operator_id.
pena_dds::Correction CorrectionToDds(const Correction& correction);

// An operator's correction or pena-fusion's answer to it, whole (points at 1 mm, stamp_s at
// 1 us); nullopt and `error` for an empty correction_id or a non-finite number.
std::optional<OperatorCorrection> OperatorCorrectionFromDds(const pena_dds::OperatorCorrection& sample,
                                                            double stamp_s, std::string* error);
// The far side's sample. Throws std::length_error naming the field for a text too long.
pena_dds::OperatorCorrection OperatorCorrectionToDds(const OperatorCorrection& correction);

}  // namespace pena::gateway
