// The scenario text format (docs/scenarios.md): one keyword per line, '#' starts a comment,
// metres and degrees in the text, radians in the struct. Validation of routes is at the end.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pena/sim/scenario.hpp"

namespace pena::sim {
namespace {

constexpr std::string_view kMagic = "pena-scenario";
constexpr int kFormatVersion = 1;
constexpr double kDegToRad = std::numbers::pi / 180.0;

// One line of the text (1-based number) split into blank-separated tokens, comment removed.
struct Line {
  std::size_t number = 0;
  std::vector<std::string_view> tokens;
};

std::vector<std::string_view> Tokenize(std::string_view text) {
  text = text.substr(0, text.find('#'));
  std::vector<std::string_view> tokens;
  constexpr std::string_view kBlank = " \t\r\v\f";
  std::size_t pos = text.find_first_not_of(kBlank);
  while (pos != std::string_view::npos) {
    const std::size_t end = std::min(text.find_first_of(kBlank, pos), text.size());
    tokens.push_back(text.substr(pos, end - pos));
    pos = text.find_first_not_of(kBlank, end);
  }
  return tokens;
}

// Turns the text into its collection of Scenario fields, one line at a time; every error names
// the origin and the 1-based line so that users can fix their files.
class Parser {
 public:
  explicit Parser(const std::string& origin) : origin_(origin) {}

  Scenario Parse(std::string_view text) {
    std::size_t number = 0;
    bool seen_header = false;
    while (!text.empty() || number == 0) {
      const std::size_t newline = text.find('\n');
      const std::string_view raw = text.substr(0, newline);
      text = newline == std::string_view::npos ? std::string_view{} : text.substr(newline + 1);
      Line line{++number, Tokenize(raw)};
      if (line.tokens.empty()) continue;
      if (!seen_header) {
        ParseHeader(line);
        seen_header = true;
      } else {
        ParseKeyword(line);
      }
    }
    if (!seen_header) Fail(0, "empty scenario: expected the header 'pena-scenario 1'");
    return std::move(scenario_);
  }

 private:
  [[noreturn]] void Fail(std::size_t line, const std::string& what) const {
    throw std::invalid_argument(origin_ + ":" + std::to_string(line) + ": " + what);
  }

  void ParseHeader(const Line& line) {
    if (line.tokens[0] != kMagic) {
      Fail(line.number, "missing header: the first line must be 'pena-scenario 1', got '" +
                            std::string(line.tokens[0]) + "'");
    }
    ExpectCount(line, 1, "pena-scenario <version>");
    const double version = Number(line, 1, "version");
    if (version != kFormatVersion) {
      Fail(line.number, "unsupported version " + std::string(line.tokens[1]) +
                            " (this reader knows " + std::to_string(kFormatVersion) + ")");
    }
  }

  void ParseKeyword(const Line& line) {
    const std::string_view keyword = line.tokens[0];
    if (keyword == "name") return ParseName(line);
    if (keyword == "ceiling") return ParseCeiling(line);
    if (keyword == "wall" || keyword == "polyline" || keyword == "rect") {
      return AppendSegments(line, 0, scenario_.walls);
    }
    if (keyword == "apriori") {
      if (line.tokens.size() < 2) Fail(line.number, "apriori needs wall, polyline or rect");
      if (!scenario_.apriori) scenario_.apriori.emplace();
      return AppendSegments(line, 1, *scenario_.apriori);
    }
    if (keyword == "smoke") return ParseSmoke(line);
    if (keyword == "magnetic") return ParseMagnetic(line);
    if (keyword == "entity") return ParseEntity(line);
    if (keyword == "waypoint") return ParseWaypoint(line);
    if (keyword == kMagic) Fail(line.number, "duplicate header");
    Fail(line.number, "unknown keyword '" + std::string(keyword) + "'");
  }

  // Requires exactly `count` arguments after the keyword; `usage` shows what they are.
  void ExpectCount(const Line& line, std::size_t count, const std::string& usage) const {
    if (line.tokens.size() != count + 1) {
      Fail(line.number, "expected " + usage + " (" + std::to_string(count) + " arguments), got " +
                            std::to_string(line.tokens.size() - 1));
    }
  }

  double ParseDouble(const Line& line, std::string_view token, const std::string& field) const {
    double value = 0.0;
    const char* end = token.data() + token.size();
    // from_chars is locale-independent but rejects a leading '+', which people do write.
    const char* begin =
        token.size() > 1 && token[0] == '+' && token[1] != '-' ? token.data() + 1 : token.data();
    const auto [ptr, error] = std::from_chars(begin, end, value);
    if (error != std::errc{} || ptr != end) {
      Fail(line.number, field + " must be a number, got '" + std::string(token) + "'");
    }
    if (!std::isfinite(value)) {
      Fail(line.number, field + " must be finite, got '" + std::string(token) + "'");
    }
    return value;
  }

  double Number(const Line& line, std::size_t index, const std::string& field) const {
    return ParseDouble(line, line.tokens[index], field);
  }

  double Positive(const Line& line, std::size_t index, const std::string& field) const {
    const double value = Number(line, index, field);
    if (value <= 0.0)
      Fail(line.number, field + " must be > 0, got " + std::string(line.tokens[index]));
    return value;
  }

  Eigen::Vector2d Point(const Line& line, std::size_t index, const std::string& what) const {
    return {Number(line, index, what + " x_m"), Number(line, index + 1, what + " y_m")};
  }

  // Reads a box "xmin ymin xmax ymax" starting at `index`; max must exceed min.
  Box ReadBox(const Line& line, std::size_t index, const std::string& what) const {
    Box box{Point(line, index, what + " min"), Point(line, index + 2, what + " max")};
    if (!(box.max_m.array() > box.min_m.array()).all()) {
      Fail(line.number, what + " has a negative or zero size: need xmin < xmax and ymin < ymax");
    }
    return box;
  }

  void ParseName(const Line& line) {
    ExpectCount(line, 1, "name <word>");
    if (!scenario_.name.empty()) Fail(line.number, "duplicate name");
    scenario_.name = line.tokens[1];
  }

  void ParseCeiling(const Line& line) {
    ExpectCount(line, 1, "ceiling <height_m>");
    scenario_.ceiling_height_m = Positive(line, 1, "ceiling height_m");
  }

  // wall x1 y1 x2 y2 | polyline x1 y1 x2 y2 ... | rect xmin ymin xmax ymax, from token `first`.
  void AppendSegments(const Line& line, std::size_t first, std::vector<geometry::Segment2>& out) {
    const std::string_view shape = line.tokens[first];
    const std::size_t count = line.tokens.size() - first - 1;
    if (shape == "wall" || shape == "rect") {
      if (count != 4) {
        Fail(line.number, std::string(shape) + " expects 4 numbers (" +
                              (shape == "wall" ? "x1 y1 x2 y2" : "xmin ymin xmax ymax") +
                              "), got " + std::to_string(count));
      }
    } else if (shape == "polyline") {
      if (count < 4 || count % 2 != 0) {
        Fail(line.number,
             "polyline expects an even number (>= 4) of coordinates x1 y1 x2 y2 ..., got " +
                 std::to_string(count));
      }
    } else {
      Fail(line.number, "unknown shape '" + std::string(shape) + "' (wall, polyline or rect)");
    }
    if (shape == "rect") {
      const Box box = ReadBox(line, first + 1, "rect");
      const Eigen::Vector2d a = box.min_m, c = box.max_m, b{c.x(), a.y()}, d{a.x(), c.y()};
      out.insert(out.end(), {{a, b}, {b, c}, {c, d}, {d, a}});
      return;
    }
    Eigen::Vector2d previous = Point(line, first + 1, "point 1");
    for (std::size_t i = first + 3; i + 1 < line.tokens.size(); i += 2) {
      const Eigen::Vector2d next = Point(line, i, "point " + std::to_string((i - first + 1) / 2));
      out.push_back({previous, next});
      previous = next;
    }
  }

  void ParseSmoke(const Line& line) {
    ExpectCount(line, 5, "smoke <xmin> <ymin> <xmax> <ymax> <max_range_m>");
    scenario_.smoke.push_back({ReadBox(line, 1, "smoke"), Positive(line, 5, "smoke max_range_m")});
  }

  void ParseMagnetic(const Line& line) {
    ExpectCount(line, 4, "magnetic <cx> <cy> <radius_m> <peak_deg>");
    scenario_.magnetic.push_back({Point(line, 1, "magnetic centre"),
                                  Positive(line, 3, "magnetic radius_m"),
                                  Number(line, 4, "magnetic peak_deg") * kDegToRad});
  }

  // Splits "key=value" options from token `first` on; unknown or repeated keys are errors.
  std::vector<std::pair<std::string_view, double>> Options(
      const Line& line, std::size_t first, const std::vector<std::string_view>& keys) const {
    std::vector<std::pair<std::string_view, double>> options;
    for (std::size_t i = first; i < line.tokens.size(); ++i) {
      const std::string_view token = line.tokens[i];
      const std::size_t equals = token.find('=');
      const std::string_view key = token.substr(0, equals);
      if (equals == std::string_view::npos ||
          std::find(keys.begin(), keys.end(), key) == keys.end()) {
        Fail(line.number,
             "unexpected argument '" + std::string(token) + "' (options are key=value)");
      }
      for (const auto& option : options) {
        if (option.first == key) Fail(line.number, "duplicate option " + std::string(key));
      }
      options.emplace_back(key, ParseDouble(line, token.substr(equals + 1), std::string(key)));
    }
    return options;
  }

  // entity ID human|robot x y heading_deg [start=S] [speed=V] [laps=N]
  void ParseEntity(const Line& line) {
    if (line.tokens.size() < 6) {
      Fail(line.number,
           "expected entity <id> human|robot <x> <y> <heading_deg> [start=S] [speed=V] "
           "[laps=N], got " +
               std::to_string(line.tokens.size() - 1) + " arguments");
    }
    EntitySpec entity;
    entity.id = line.tokens[1];
    if (FindEntity(entity.id) != nullptr)
      Fail(line.number, "duplicate entity id '" + entity.id + "'");
    const auto kind = sensors::ParseEntityKind(line.tokens[2]);
    if (!kind)
      Fail(line.number,
           "entity kind must be human or robot, got '" + std::string(line.tokens[2]) + "'");
    entity.kind = *kind;
    const Eigen::Vector2d start = Point(line, 3, "entity start");
    entity.start = {start.x(), start.y(),
                    geometry::NormalizeAngle(Number(line, 5, "heading_deg") * kDegToRad)};
    for (const auto& [key, value] : Options(line, 6, {"start", "speed", "laps"})) {
      if (key == "start" && value < 0.0) Fail(line.number, "start (s) must be >= 0");
      if (key == "speed" && value <= 0.0) Fail(line.number, "speed (m/s) must be > 0");
      if (key == "laps" && (value < 1.0 || value != std::floor(value) || value > 1000.0)) {
        Fail(line.number, "laps must be a whole number in [1, 1000]");
      }
      if (key == "start") entity.start_time_s = value;
      if (key == "speed") entity.cruise_speed_m_s = value;
      if (key == "laps") entity.laps = static_cast<int>(value);
    }
    scenario_.entities.push_back(std::move(entity));
  }

  // waypoint ID x y [pause=S]
  void ParseWaypoint(const Line& line) {
    if (line.tokens.size() < 4 || line.tokens.size() > 5) {
      Fail(line.number, "expected waypoint <id> <x> <y> [pause=S], got " +
                            std::to_string(line.tokens.size() - 1) + " arguments");
    }
    EntitySpec* entity = FindEntity(line.tokens[1]);
    if (entity == nullptr) {
      Fail(line.number, "waypoint for undeclared entity '" + std::string(line.tokens[1]) +
                            "' (declare it with 'entity' first)");
    }
    Waypoint waypoint{Point(line, 2, "waypoint"), 0.0};
    for (const auto& [key, value] : Options(line, 4, {"pause"})) {
      if (value < 0.0) Fail(line.number, "pause (s) must be >= 0");
      waypoint.pause_s = value;
    }
    entity->route.push_back(waypoint);
  }

  EntitySpec* FindEntity(std::string_view id) {
    for (auto& entity : scenario_.entities) {
      if (entity.id == id) return &entity;
    }
    return nullptr;
  }

  std::string origin_;
  Scenario scenario_;
};

// ---- Validation ------------------------------------------------------------------------------

constexpr double kClosedRouteTolerance_m = 0.5;
constexpr double kMaxSpeed_m_s = 5.0;

std::string Format(const char* format, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer), format, a, b, c, d);
  return buffer;
}

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// True when two non-collinear segments share a point (cross or touch). Collinear overlaps are
// caught by the endpoint distances in SegmentDistance.
bool SegmentsIntersect(const geometry::Segment2& p, const geometry::Segment2& q) {
  const Eigen::Vector2d r = p.end_m - p.start_m, s = q.end_m - q.start_m;
  const double d1 = Cross(r, q.start_m - p.start_m), d2 = Cross(r, q.end_m - p.start_m);
  const double d3 = Cross(s, p.start_m - q.start_m), d4 = Cross(s, p.end_m - q.start_m);
  auto straddles = [](double a, double b) {
    return (a <= 0.0 && b >= 0.0) || (a >= 0.0 && b <= 0.0);
  };
  if (d1 == 0.0 && d2 == 0.0) return false;
  return straddles(d1, d2) && straddles(d3, d4);
}

// Shortest distance between two segments: zero if they cross, else an endpoint-to-segment distance.
double SegmentDistance(const geometry::Segment2& p, const geometry::Segment2& q) {
  if (SegmentsIntersect(p, q)) return 0.0;
  return std::min(
      {geometry::DistanceToSegment(q, p.start_m), geometry::DistanceToSegment(q, p.end_m),
       geometry::DistanceToSegment(p, q.start_m), geometry::DistanceToSegment(p, q.end_m)});
}

std::string PointName(std::size_t index) {
  return index == 0 ? std::string("the start") : "waypoint " + std::to_string(index);
}

// Checks one leg between route points `from` and `to` (0 = start pose, i = waypoint i, 1-based).
std::string CheckLeg(const Scenario& scenario, const std::vector<Eigen::Vector2d>& points,
                     std::size_t from, std::size_t to, double clearance_m) {
  const geometry::Segment2 leg{points[from], points[to]};
  for (std::size_t w = 0; w < scenario.walls.size(); ++w) {
    const geometry::Segment2& wall = scenario.walls[w];
    const double distance_m = SegmentDistance(leg, wall);
    if (distance_m >= clearance_m) continue;
    const std::string wall_name = "wall " + std::to_string(w) +
                                  Format(" (%.2f %.2f %.2f %.2f)", wall.start_m.x(),
                                         wall.start_m.y(), wall.end_m.x(), wall.end_m.y());
    const std::string leg_name = "leg from " + PointName(from) + " to " + PointName(to);
    if (distance_m == 0.0) return leg_name + " crosses " + wall_name;
    return leg_name + " passes " + Format("%.2f m", distance_m) + " from " + wall_name +
           Format(" (clearance_m %.2f)", clearance_m);
  }
  return "";
}

std::string CheckEntityNumbers(const EntitySpec& entity) {
  if (entity.id.empty()) return "an entity has an empty id";
  const std::string prefix = "entity " + entity.id + ": ";
  const auto& start = entity.start;
  if (!std::isfinite(start.x_m) || !std::isfinite(start.y_m) || !std::isfinite(start.theta_rad)) {
    return prefix + "start pose must be finite";
  }
  if (!(entity.start_time_s >= 0.0) || !std::isfinite(entity.start_time_s))
    return prefix + "start_time_s must be >= 0";
  if (!(entity.cruise_speed_m_s > 0.0 && entity.cruise_speed_m_s <= kMaxSpeed_m_s)) {
    return prefix + Format("cruise_speed_m_s must be in (0, %.1f], got %g", kMaxSpeed_m_s,
                           entity.cruise_speed_m_s);
  }
  if (entity.laps < 1) return prefix + "laps must be >= 1, got " + std::to_string(entity.laps);
  if (entity.route.empty()) return prefix + "has no waypoints";
  for (std::size_t i = 0; i < entity.route.size(); ++i) {
    const Waypoint& waypoint = entity.route[i];
    if (!waypoint.position_m.allFinite() || !(waypoint.pause_s >= 0.0) ||
        !std::isfinite(waypoint.pause_s)) {
      return prefix + "waypoint " + std::to_string(i + 1) +
             " needs a finite position and pause_s >= 0";
    }
  }
  return "";
}

// Route legs: start -> waypoint 1 -> ... -> waypoint N. With laps > 1 the route must be closed
// (waypoint N within kClosedRouteTolerance_m of the start) and the next lap walks N -> 1.
std::string CheckRoute(const Scenario& scenario, const EntitySpec& entity, double clearance_m) {
  const std::string prefix = "entity " + entity.id + ": ";
  std::vector<Eigen::Vector2d> points{{entity.start.x_m, entity.start.y_m}};
  for (const Waypoint& waypoint : entity.route) points.push_back(waypoint.position_m);
  for (std::size_t w = 0; w < scenario.walls.size(); ++w) {
    const double distance_m = geometry::DistanceToSegment(scenario.walls[w], points[0]);
    if (distance_m < clearance_m) {
      return prefix + "the start is " +
             Format("%.2f m from wall %.0f", distance_m, static_cast<double>(w));
    }
  }
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (std::string error = CheckLeg(scenario, points, i - 1, i, clearance_m); !error.empty()) {
      return prefix + error;
    }
  }
  if (entity.laps > 1) {
    const double gap_m = (points.back() - points.front()).norm();
    if (gap_m > kClosedRouteTolerance_m) {
      return prefix + "laps=" + std::to_string(entity.laps) +
             " needs a closed route: " + PointName(points.size() - 1) +
             Format(" ends %.2f m from the start (max %.2f m)", gap_m, kClosedRouteTolerance_m);
    }
    if (std::string error = CheckLeg(scenario, points, points.size() - 1, 1, clearance_m);
        !error.empty()) {
      return prefix + error + " (next lap)";
    }
  }
  return "";
}

std::string CheckBuilding(const Scenario& scenario) {
  if (!(scenario.ceiling_height_m > 0.0) || !std::isfinite(scenario.ceiling_height_m)) {
    return "ceiling_height_m must be > 0";
  }
  auto finite = [](const geometry::Segment2& s) {
    return s.start_m.allFinite() && s.end_m.allFinite();
  };
  if (!std::all_of(scenario.walls.begin(), scenario.walls.end(), finite))
    return "walls must be finite";
  if (scenario.apriori &&
      !std::all_of(scenario.apriori->begin(), scenario.apriori->end(), finite)) {
    return "a priori walls must be finite";
  }
  for (const SmokeZone& smoke : scenario.smoke) {
    if (!(smoke.area.max_m.array() > smoke.area.min_m.array()).all() ||
        !(smoke.max_range_m > 0.0)) {
      return "smoke zones need min_m < max_m and max_range_m > 0";
    }
  }
  for (const MagneticDisturbance& magnetic : scenario.magnetic) {
    if (!magnetic.center_m.allFinite() || !(magnetic.radius_m > 0.0) ||
        !(std::abs(magnetic.peak_offset_rad) <= std::numbers::pi)) {
      return "magnetic disturbances need radius_m > 0 and |peak_offset_rad| <= pi";
    }
  }
  return "";
}

}  // namespace

Scenario ParseScenario(std::string_view text, const std::string& origin) {
  return Parser(origin).Parse(text);
}

std::string ValidateScenario(const Scenario& scenario, double clearance_m) {
  if (!(clearance_m >= 0.0) || !std::isfinite(clearance_m)) return "clearance_m must be >= 0";
  if (std::string error = CheckBuilding(scenario); !error.empty()) return error;
  if (scenario.entities.empty()) return "the scenario has no entities";
  std::set<std::string> ids;
  for (const EntitySpec& entity : scenario.entities) {
    if (std::string error = CheckEntityNumbers(entity); !error.empty()) return error;
    if (!ids.insert(entity.id).second) return "duplicate entity id " + entity.id;
    if (std::string error = CheckRoute(scenario, entity, clearance_m); !error.empty()) return error;
  }
  return "";
}

}  // namespace pena::sim
