// The scenario text format (docs/scenarios.md): one keyword per line, '#' starts a comment,
// metres and degrees in the text, radians in the struct. Validation is in scenario_validator.cpp.

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

}  // namespace

Scenario ParseScenario(std::string_view text, const std::string& origin) {
  return Parser(origin).Parse(text);
}

}  // namespace pena::sim
