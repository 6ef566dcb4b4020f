// DXF plans (ASCII DXF, any release from R12): group-code/value pairs, the ENTITIES section's
// LINE, LWPOLYLINE and POLYLINE/VERTEX/SEQEND entities as straight segments.
#include "dxf_plan_reader.hpp"

#include <cmath>
#include <optional>
#include <string>
#include <string_view>

#include "gz_line_reader.hpp"
#include "pena/io/input_error.hpp"
#include "text_fields.hpp"

namespace pena::io::detail {
namespace {

// One group: its code, its value (trimmed) and the file line of the value.
struct Group {
  int code = 0;
  std::string value;
  std::size_t line = 0;
};

std::string Trimmed(std::string_view text) {
  const std::size_t first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  return std::string(text.substr(first, text.find_last_not_of(" \t") - first + 1));
}

std::vector<Group> ReadGroups(const std::filesystem::path& path) {
  if (ReadHead(path, 18) == "AutoCAD Binary DXF") {
    throw InputError(path, 1, "binary DXF is not read; save the drawing as ASCII DXF");
  }
  GzLineReader reader(path);
  std::vector<Group> groups;
  std::string code_line;
  while (reader.ReadLine(code_line)) {
    const std::string code_text = Trimmed(code_line);
    if (code_text.empty() && groups.empty()) continue;
    const std::optional<std::int64_t> code = ParseInt64(code_text);
    if (!code || *code < 0 || *code > 1071) {
      throw InputError(path, reader.line_number(),
                       "expected a DXF group code (0-1071), found '" + code_text + "'");
    }
    std::string value;
    if (!reader.ReadLine(value)) {
      throw InputError(path, reader.line_number(), "group code " + code_text + " has no value");
    }
    groups.push_back({static_cast<int>(*code), Trimmed(value), reader.line_number()});
  }
  return groups;
}

double Number(const std::filesystem::path& path, const Group& group) {
  const std::optional<double> value = ParseDouble(group.value);
  if (!value || !std::isfinite(*value)) {
    throw InputError(path, group.line,
                     "group " + std::to_string(group.code) + " value '" + group.value +
                         "' is not a finite number");
  }
  return *value;
}

// A polyline vertex; bulge != 0 makes the span to the next vertex an arc.
struct Vertex {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  double bulge = 0.0;
};

// Straight spans of a vertex chain; arcs (bulged spans) are not walls and are skipped.
void AddChain(const std::vector<Vertex>& vertices, bool closed,
              std::vector<geometry::Segment2>& segments) {
  const std::size_t n = vertices.size();
  const std::size_t spans = closed && n > 2 ? n : (n > 0 ? n - 1 : 0);
  for (std::size_t i = 0; i < spans; ++i) {
    if (vertices[i].bulge != 0.0) continue;
    segments.push_back({vertices[i].point, vertices[(i + 1) % n].point});
  }
}

// Reads the entities of one ENTITIES section, from `begin` (first entity's 0 group) to ENDSEC.
class EntityWalker {
 public:
  EntityWalker(const std::filesystem::path& path, const std::vector<Group>& groups)
      : path_(path), groups_(groups) {}

  // Walks from groups_[index] to the ENDSEC group; returns the index after it.
  std::size_t Walk(std::size_t index, std::vector<geometry::Segment2>& segments) {
    while (index < groups_.size()) {
      const Group& start = groups_[index];
      if (start.code != 0) throw InputError(path_, start.line, "expected an entity (group 0)");
      if (start.value == "ENDSEC") return index + 1;
      std::size_t end = index + 1;
      while (end < groups_.size() && groups_[end].code != 0) ++end;
      Entity(index, end, segments);
      index = end;
    }
    throw InputError(path_, groups_.empty() ? 0 : groups_.back().line,
                     "unexpected end of file in the ENTITIES section (no ENDSEC)");
  }

 private:
  void Entity(std::size_t begin, std::size_t end, std::vector<geometry::Segment2>& segments) {
    const std::string& type = groups_[begin].value;
    if (type == "LINE") {
      Line(begin, end, segments);
    } else if (type == "LWPOLYLINE") {
      LightPolyline(begin, end, segments);
    } else if (type == "POLYLINE") {
      polyline_flags_ = Flags(begin, end);
      polyline_.clear();
      in_polyline_ = true;
    } else if (type == "VERTEX" && in_polyline_) {
      const int flags = Flags(begin, end);
      // Polyface and mesh records (flags 64, 128 on the vertex or 16/64 on the polyline) are 3D.
      if ((flags & 128) == 0 && (polyline_flags_ & (16 | 64)) == 0) {
        polyline_.push_back(ReadVertex(begin, end));
      }
    } else if (type == "SEQEND" && in_polyline_) {
      AddChain(polyline_, (polyline_flags_ & 1) != 0, segments);
      in_polyline_ = false;
    }
  }

  void Line(std::size_t begin, std::size_t end, std::vector<geometry::Segment2>& segments) {
    std::optional<double> v[4];
    for (std::size_t i = begin + 1; i < end; ++i) {
      const int code = groups_[i].code;
      if (code == 10 || code == 20 || code == 11 || code == 21) {
        v[(code % 10) * 2 + code / 20] = Number(path_, groups_[i]);
      }
    }
    if (!v[0] || !v[1] || !v[2] || !v[3]) {
      throw InputError(path_, groups_[begin].line, "LINE lacks one of its points (10/20, 11/21)");
    }
    segments.push_back({{*v[0], *v[1]}, {*v[2], *v[3]}});
  }

  void LightPolyline(std::size_t begin, std::size_t end,
                     std::vector<geometry::Segment2>& segments) {
    std::vector<Vertex> vertices;
    bool has_y = true;
    for (std::size_t i = begin + 1; i < end; ++i) {
      const Group& group = groups_[i];
      if (group.code == 10) {
        if (!has_y) throw InputError(path_, group.line, "LWPOLYLINE vertex lacks its y (20)");
        vertices.push_back({{Number(path_, group), 0.0}, 0.0});
        has_y = false;
      } else if (group.code == 20 && !vertices.empty()) {
        vertices.back().point.y() = Number(path_, group), has_y = true;
      } else if (group.code == 42 && !vertices.empty()) {
        vertices.back().bulge = Number(path_, group);
      }
    }
    if (!has_y)
      throw InputError(path_, groups_[end - 1].line, "LWPOLYLINE vertex lacks its y (20)");
    AddChain(vertices, (Flags(begin, end) & 1) != 0, segments);
  }

  Vertex ReadVertex(std::size_t begin, std::size_t end) const {
    Vertex vertex;
    for (std::size_t i = begin + 1; i < end; ++i) {
      if (groups_[i].code == 10) vertex.point.x() = Number(path_, groups_[i]);
      if (groups_[i].code == 20) vertex.point.y() = Number(path_, groups_[i]);
      if (groups_[i].code == 42) vertex.bulge = Number(path_, groups_[i]);
    }
    return vertex;
  }

  int Flags(std::size_t begin, std::size_t end) const {
    for (std::size_t i = begin + 1; i < end; ++i) {
      if (groups_[i].code != 70) continue;
      const std::optional<std::int64_t> flags = ParseInt64(groups_[i].value);
      if (!flags || *flags < 0 || *flags > 0xFFFF) {
        throw InputError(path_, groups_[i].line,
                         "flags (70) '" + groups_[i].value + "' is not an integer");
      }
      return static_cast<int>(*flags);
    }
    return 0;
  }

  const std::filesystem::path& path_;
  const std::vector<Group>& groups_;
  std::vector<Vertex> polyline_;
  int polyline_flags_ = 0;
  bool in_polyline_ = false;
};

}  // namespace

std::vector<geometry::Segment2> ReadDxfPlan(const std::filesystem::path& path) {
  const std::vector<Group> groups = ReadGroups(path);
  std::vector<geometry::Segment2> segments;
  bool saw_entities = false, saw_eof = false;
  EntityWalker walker(path, groups);
  for (std::size_t i = 0; i < groups.size();) {
    const Group& group = groups[i];
    if (group.code == 0 && group.value == "EOF") {
      saw_eof = true;
      break;
    }
    const bool entities = group.code == 0 && group.value == "SECTION" && i + 1 < groups.size() &&
                          groups[i + 1].code == 2 && groups[i + 1].value == "ENTITIES";
    if (!entities) {
      ++i;
      continue;
    }
    saw_entities = true;
    i = walker.Walk(i + 2, segments);
  }
  const std::size_t last_line = groups.empty() ? 0 : groups.back().line;
  if (!saw_entities) throw InputError(path, last_line, "no ENTITIES section: not a DXF drawing");
  if (!saw_eof) throw InputError(path, last_line, "unexpected end of file (no 0/EOF): truncated?");
  return segments;
}

}  // namespace pena::io::detail
