#pragma once
// What crosses the link, as plain structs (docs/gateway.md): the gateway's view of the DDS data.
// Stamps are seconds on the clock both gateways share (wall clock, or simulated time in tests).

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/line_map/map_delta.hpp"

namespace pena::gateway {

// An entity's pose, world frame. Sent unreliably, latest per entity.
struct PoseUpdate {
  std::string entity;
  geometry::Pose2 world_from_body;
  double stamp_s = 0.0;
  // 1-sigma: the largest axis of the x-y covariance's ellipse, and the heading's (0: unknown).
  double position_sd_m = 0.0;
  double heading_sd_rad = 0.0;
  std::optional<double> mission_stamp_s = std::nullopt;  // the pose's mission time (EntityPose.stamp_s), if known
};

// The most points an annotation's outline holds (pena_dds::OUTLINE_MAX_POINTS).
inline constexpr std::size_t kMaxOutlinePoints = 64;

// An alarm or an annotation placed on the map (world frame). Sent reliably, first.
struct Annotation {
  bool alarm = false;
  std::string entity;
  std::uint64_t id = 0;  // unique per entity
  double x_m = 0.0;
  double y_m = 0.0;
  double stamp_s = 0.0;
  std::string text;
  std::optional<double> mission_stamp_s = std::nullopt;  // the mark's mission time, if known
  double radius_m = 0.0;                  // an area's extent (0: a point)
  std::vector<std::pair<double, double>> outline_m = {};  // an area's polygon, x and y
};

// The fusion service's correction of one entity's map frame. Sent reliably, newest per entity.
struct Correction {
  std::string entity;
  geometry::Pose2 world_from_local;
  std::uint64_t version = 0;  // increases per entity
  double stamp_s = 0.0;
  std::string operator_id = {};  // set when it relays an operator's correction
};

// An operator's correction (pena_dds::OperatorCorrection, paper section 4.1), or pena-fusion's
// answer to one. Sent reliably with the annotations. Points in the map frame, metres.
struct OperatorCorrection {
  std::string correction_id;
  std::string operator_id;
  std::uint32_t kind = 0;  // pena_dds::OperatorCorrectionKind
  std::string entity;
  double mission_stamp_s = 0.0;  // from when the entity's data is corrected
  double origin_x_m = 0.0, origin_y_m = 0.0;
  double wrong_x_m = 0.0, wrong_y_m = 0.0;
  double correct_x_m = 0.0, correct_y_m = 0.0;
  geometry::Pose2 world_from_body;  // OPERATOR_SET_POSE
  std::uint64_t console_seq = 0;
  std::int64_t segment_id = 0;      // OPERATOR_REMOVE_SEGMENT
  double segment_x0_m = 0.0, segment_y0_m = 0.0, segment_x1_m = 0.0, segment_y1_m = 0.0;
  bool applied = false;   // pena-fusion's answer
  std::string refusal;    // pena-fusion's answer
  double stamp_s = 0.0;   // wall clock (the link's clock)
  std::string undoes_id;  // OPERATOR_UNDO: the correction it takes back
};

// A change of one line map (an entity's or the global one): a delta or a whole snapshot.
struct MapChange {
  std::string map_id;
  std::variant<line_map::MapDelta, line_map::MapSnapshot> change;
  bool reset = false;  // snapshot only: replace even if not newer (the sender's map restarted)
};

// Anything the domain hands to the link or the link delivers into the domain.
using DomainItem = std::variant<PoseUpdate, Annotation, Correction, MapChange, OperatorCorrection>;

}  // namespace pena::gateway
