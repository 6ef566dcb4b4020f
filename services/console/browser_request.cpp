#include "browser_request.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace pena::services {
namespace {

using nlohmann::json;

// Thrown inside the parser with a message naming the field; becomes the request's error.
struct Refused : std::runtime_error {
  using std::runtime_error::runtime_error;
};

const json& Field(const json& object, const char* type, const char* name) {
  const auto it = object.find(name);
  if (it == object.end()) throw Refused(std::string(type) + "." + name + ": missing");
  return *it;
}

Eigen::Vector2d PointValue(const json& value, const std::string& where) {
  if (!value.is_array() || value.size() != 2) {
    throw Refused(where + ": must be an array [x_m, y_m]");
  }
  Eigen::Vector2d point;
  for (std::size_t i = 0; i < 2; ++i) {
    const json& v = value[i];
    if (!v.is_number()) throw Refused(where + "[" + std::to_string(i) + "]: not a number");
    const double d = v.get<double>();
    if (!std::isfinite(d) || std::abs(d) > kMaxCoordinateM) {
      throw Refused(where + "[" + std::to_string(i) + "]: must be finite and within " +
                    std::to_string(static_cast<long>(kMaxCoordinateM)) + " m");
    }
    point[static_cast<Eigen::Index>(i)] = d;
  }
  return point;
}

Eigen::Vector2d PointField(const json& object, const char* type, const char* name) {
  return PointValue(Field(object, type, name), std::string(type) + "." + name);
}

// 3 to kMaxOutlinePoints corners of a polygon.
std::vector<Eigen::Vector2d> OutlineField(const json& object, const char* type) {
  const json& value = Field(object, type, "outline");
  const std::string where = std::string(type) + ".outline";
  if (!value.is_array() || value.size() < 3 || value.size() > kMaxOutlinePoints) {
    throw Refused(where + ": must be an array of 3 to " + std::to_string(kMaxOutlinePoints) +
                  " points [x_m, y_m]");
  }
  std::vector<Eigen::Vector2d> outline;
  for (std::size_t i = 0; i < value.size(); ++i) {
    outline.push_back(PointValue(value[i], where + "[" + std::to_string(i) + "]"));
  }
  return outline;
}

std::string EntityField(const json& object, const char* type) {
  const json& value = Field(object, type, "entity");
  if (!value.is_string()) throw Refused(std::string(type) + ".entity: not a string");
  const std::string id = value.get<std::string>();
  if (id.empty() || id.size() > 31) {
    throw Refused(std::string(type) + ".entity: must be 1 to 31 characters");
  }
  for (const char c : id) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                       (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
    if (!plain) throw Refused(std::string(type) + ".entity: only letters, digits, _ - .");
  }
  return id;
}

std::string StringField(const json& object, const char* type, const char* name,
                        std::size_t max_bytes) {
  const json& value = Field(object, type, name);
  if (!value.is_string()) throw Refused(std::string(type) + "." + name + ": not a string");
  std::string text = value.get<std::string>();
  if (text.size() > max_bytes) {
    throw Refused(std::string(type) + "." + name + ": at most " + std::to_string(max_bytes) +
                  " bytes, got " + std::to_string(text.size()));
  }
  return text;
}

AnnotateRequest ParseAnnotate(const json& message) {
  static const char* const kKinds[] = {"victim_found", "dangerous_area", "corridor_crossing",
                                       "elevator",     "stairs",         "exit",
                                       "free_text"};
  AnnotateRequest a;
  a.kind = StringField(message, "annotate", "kind", 32);
  if (std::find(std::begin(kKinds), std::end(kKinds), a.kind) == std::end(kKinds)) {
    throw Refused("annotate.kind: unknown kind '" + a.kind + "'");
  }
  if (message.contains("outline")) {
    if (a.kind != "dangerous_area") throw Refused("annotate.outline: only a dangerous_area has one");
    a.outline_m = OutlineField(message, "annotate");
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& corner : a.outline_m) sum += corner;
    a.position_m = sum / static_cast<double>(a.outline_m.size());
    for (const Eigen::Vector2d& corner : a.outline_m) {
      a.radius_m = std::max(a.radius_m, (corner - a.position_m).norm());
    }
    if (message.contains("position")) a.position_m = PointField(message, "annotate", "position");
  } else {
    a.position_m = PointField(message, "annotate", "position");
  }
  if (message.contains("radius_m")) {
    const json& r = message["radius_m"];
    if (!r.is_number()) throw Refused("annotate.radius_m: not a number");
    a.radius_m = r.get<double>();
    if (!std::isfinite(a.radius_m) || a.radius_m < 0.0 || a.radius_m > 1000.0) {
      throw Refused("annotate.radius_m: must be in [0, 1000] m");
    }
  }
  if (message.contains("text")) a.text = StringField(message, "annotate", "text", 255);
  return a;
}

BrowserCommand ParseCommand(const json& message) {
  const json& type_value = Field(message, "message", "type");
  if (!type_value.is_string()) throw Refused("message.type: not a string");
  const std::string type = type_value.get<std::string>();
  if (type == "ping") return PingRequest{};
  if (type == "rotate") {
    RotateRequest r;
    r.entity_id = EntityField(message, "rotate");
    r.origin_m = PointField(message, "rotate", "origin");
    r.wrong_m = PointField(message, "rotate", "wrong");
    r.correct_m = PointField(message, "rotate", "correct");
    return r;
  }
  if (type == "translate") {
    TranslateRequest t;
    t.entity_id = EntityField(message, "translate");
    t.point_m = PointField(message, "translate", "point");
    t.correct_m = PointField(message, "translate", "correct");
    return t;
  }
  if (type == "undo") return UndoRequest{StringField(message, "undo", "id", 48)};
  if (type == "annotate") return ParseAnnotate(message);
  if (type == "retract") return RetractRequest{StringField(message, "retract", "id", 48)};
  if (type == "move_mark") {
    return MoveMarkRequest{StringField(message, "move_mark", "id", 48),
                           PointField(message, "move_mark", "position")};
  }
  throw Refused("message.type: unknown type '" + type.substr(0, 32) +
                "' (rotate, translate, undo, annotate, retract, move_mark, ping)");
}

}  // namespace

BrowserRequest ParseBrowserRequest(std::string_view text) {
  BrowserRequest request;
  if (text.size() > kMaxRequestBytes) {
    request.command_or_error = "message of " + std::to_string(text.size()) +
                               " bytes is larger than " + std::to_string(kMaxRequestBytes);
    return request;
  }
  const json message = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (message.is_discarded()) {
    request.command_or_error = std::string("message is not valid JSON");
    return request;
  }
  if (!message.is_object()) {
    request.command_or_error = std::string("message must be a JSON object");
    return request;
  }
  if (const auto req = message.find("req"); req != message.end()) {
    if (!req->is_number_integer()) {
      request.command_or_error = std::string("message.req: not an integer");
      return request;
    }
    request.req = req->get<std::int64_t>();
  }
  try {
    request.command_or_error = ParseCommand(message);
  } catch (const Refused& refused) {
    request.command_or_error = std::string(refused.what());
  }
  return request;
}

}  // namespace pena::services
