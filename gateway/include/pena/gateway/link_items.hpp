#pragma once
// What crosses the link, as plain structs (docs/gateway.md): the gateway's view of the DDS data.
// Stamps are seconds on the clock both gateways share (wall clock, or simulated time in tests).

#include <cstdint>
#include <string>
#include <variant>

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
};

// An alarm or an annotation placed on the map (world frame). Sent reliably, first.
struct Annotation {
  bool alarm = false;
  std::string entity;
  std::uint64_t id = 0;  // unique per entity
  double x_m = 0.0;
  double y_m = 0.0;
  double stamp_s = 0.0;
  std::string text;
};

// The fusion service's correction of one entity's map frame. Sent reliably, newest per entity.
struct Correction {
  std::string entity;
  geometry::Pose2 world_from_local;
  std::uint64_t version = 0;  // increases per entity
  double stamp_s = 0.0;
};

// A change of one line map (an entity's or the global one): a delta or a whole snapshot.
struct MapChange {
  std::string map_id;
  std::variant<line_map::MapDelta, line_map::MapSnapshot> change;
  bool reset = false;  // snapshot only: replace even if not newer (the sender's map restarted)
};

// Anything the domain hands to the link or the link delivers into the domain.
using DomainItem = std::variant<PoseUpdate, Annotation, Correction, MapChange>;

}  // namespace pena::gateway
