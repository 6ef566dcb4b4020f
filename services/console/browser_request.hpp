#pragma once
// What a browser may ask pena-console, parsed and checked before anything is done: a message is
// one JSON object of at most kMaxRequestBytes with a "type", an optional request number "req"
// (echoed in the answer) and the fields of its type. Every number must be finite and within
// kMaxCoordinateM of the origin. A message that fails gives an error naming the field; nothing
// is applied.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace pena::services {

inline constexpr std::size_t kMaxRequestBytes = 4096;
inline constexpr double kMaxCoordinateM = 100'000.0;
inline constexpr std::size_t kMaxOutlinePoints = 64;  // pena_dds::OUTLINE_MAX_POINTS

// The three-point rotation (paper section 4.1): {"type": "rotate", "entity": "ff1",
// "origin": [x, y], "wrong": [x, y], "correct": [x, y]}, map frame, metres.
struct RotateRequest {
  std::string entity_id;
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d wrong_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d correct_m = Eigen::Vector2d::Zero();
};

// The translation (paper section 4.1): {"type": "translate", "entity": "ff1", "point": [x, y],
// "correct": [x, y]}: the entity's data from the moment it was at `point` moves so that `point`
// lands on `correct`. Map frame, metres.
struct TranslateRequest {
  std::string entity_id;
  Eigen::Vector2d point_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d correct_m = Eigen::Vector2d::Zero();
};

// {"type": "undo", "id": "<correction_id>"}: takes back that correction, which must be the last
// one in force on its entity (the list is undone from its end).
struct UndoRequest {
  std::string correction_id;
};

// A mark on the map: {"type": "annotate", "kind": "victim_found", "position": [x, y],
// "radius_m": 0, "text": "..."}; kind one of victim_found, dangerous_area, corridor_crossing,
// elevator, stairs, exit, free_text; radius_m in [0, 1000] (optional), text at most 255 bytes
// (optional). A dangerous area may be a polygon instead: "outline": [[x, y], ...] of 3 to
// kMaxOutlinePoints corners, whose centroid is the position (then not needed).
struct AnnotateRequest {
  std::string kind;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  double radius_m = 0.0;
  std::string text;
  std::vector<Eigen::Vector2d> outline_m;
};

// {"type": "retract", "id": "<annotation_id>"}: the mark no longer holds.
struct RetractRequest {
  std::string annotation_id;
};

// {"type": "move_mark", "id": "<annotation_id>", "position": [x, y]}: the mark (and its
// outline, by the same offset) moves there.
struct MoveMarkRequest {
  std::string annotation_id;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
};

// {"type": "ping"}: answered with "pong" (the page measures its round trip).
struct PingRequest {};

using BrowserCommand = std::variant<RotateRequest, TranslateRequest, UndoRequest, AnnotateRequest,
                                    RetractRequest, MoveMarkRequest, PingRequest>;

// A parsed request, or the reason it was refused.
struct BrowserRequest {
  std::int64_t req = 0;  // the browser's request number (0 if it gave none)
  std::variant<BrowserCommand, std::string> command_or_error;
  bool ok() const { return command_or_error.index() == 0; }
  const std::string& error() const { return std::get<std::string>(command_or_error); }
  const BrowserCommand& command() const { return std::get<BrowserCommand>(command_or_error); }
};

// Parses one WebSocket text message.
BrowserRequest ParseBrowserRequest(std::string_view text);

}  // namespace pena::services
