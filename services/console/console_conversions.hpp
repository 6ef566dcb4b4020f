#pragma once
// pena-console's conversions between the DDS types and the picture's (console_picture.hpp):
// console_from_dds.cpp one way, console_to_dds.cpp the other.

#include <cstdint>
#include <string>

#include "browser_request.hpp"
#include "console_picture.hpp"
#include "pena_dds/entity.h"
#include "pena_dds/operator.h"

namespace pena::services {

// heard_ns: this machine's clock at reception; source_ns: the writer's when it wrote it.
PoseUpdate ToPicture(const pena_dds::EntityPose& sample, std::int64_t heard_ns,
                     std::int64_t source_ns);
StatusUpdate ToPicture(const pena_dds::EntityStatus& sample, std::int64_t heard_ns);
AnnotationRecord ToPicture(const pena_dds::Annotation& sample);
// Rotations and translations carry their geometry (localisation::OperatorCorrection).
CorrectionRecord ToPicture(const pena_dds::OperatorCorrection& sample);
// A gateway endpoint's report on the radio link, heard at heard_ns.
LinkRecord ToPicture(const pena_dds::LinkHealth& sample, std::int64_t heard_ns);

// The three-point rotation as it goes on the wire: kind OPERATOR_ROTATE, applying from
// from_stamp_s (mission time). Throws std::length_error naming a field that does not fit.
pena_dds::OperatorCorrection ToDdsRotation(const RotateRequest& request, double from_stamp_s,
                                           const std::string& operator_id,
                                           const std::string& correction_id, std::uint64_t seq);

// The translation: kind OPERATOR_TRANSLATE, wrong_point = the point to move, correct_point =
// where it belongs, applying from from_stamp_s.
pena_dds::OperatorCorrection ToDdsTranslation(const TranslateRequest& request, double from_stamp_s,
                                              const std::string& operator_id,
                                              const std::string& correction_id, std::uint64_t seq);
// An undo: kind OPERATOR_UNDO of `undone` (its entity and stamp), undoes_id = its id.
pena_dds::OperatorCorrection ToDdsUndo(const CorrectionRecord& undone, const std::string& operator_id,
                                       const std::string& correction_id, std::uint64_t seq);

// An annotation as it goes on the wire (the same annotation_id again replaces it). Throws
// std::length_error naming a field that does not fit, std::invalid_argument for an unknown kind.
pena_dds::Annotation ToDdsAnnotation(const AnnotationRecord& annotation);

}  // namespace pena::services
