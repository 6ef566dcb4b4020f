// AutoCAD R12 (AC1009) ASCII DXF: HEADER (version, extents), TABLES (one line type, the layers),
// ENTITIES (LINE). R12 is the release every CAD reader still imports (LibreCAD, QCAD, AutoCAD).
#include "pena/io/dxf_writer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "text_fields.hpp"
#include "text_writer.hpp"

namespace pena::io {
namespace {

// 0.1 mm: finer than any map; CAD tools keep it.
constexpr int kDecimals = 4;

bool ValidLayerName(const std::string& name) {
  if (name.empty() || name.size() > 31) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-' || c == '$';
  });
}

void Validate(const std::vector<DxfLayer>& layers) {
  for (const DxfLayer& layer : layers) {
    if (!ValidLayerName(layer.name)) {
      throw std::invalid_argument("dxf layer name '" + layer.name +
                                  "' must be 1-31 characters of A-Z a-z 0-9 _ - $");
    }
    if (layer.colour < 1 || layer.colour > 255) {
      throw std::invalid_argument("dxf layer " + layer.name + ": colour must be in 1-255, got " +
                                  std::to_string(layer.colour));
    }
    for (const geometry::Segment2& s : layer.segments) {
      if (!s.start_m.allFinite() || !s.end_m.allFinite()) {
        throw std::invalid_argument("dxf layer " + layer.name + ": a segment is not finite");
      }
    }
  }
}

// Appends DXF group pairs: code right-aligned in 3 columns, as AutoCAD writes them.
class Groups {
 public:
  Groups& Add(int code, const std::string& value) {
    const std::string code_text = std::to_string(code);
    text_ += std::string(code_text.size() < 3 ? 3 - code_text.size() : 0, ' ') + code_text + "\n" +
             value + "\n";
    return *this;
  }
  Groups& Add(int code, double value) { return Add(code, detail::FormatFixed(value, kDecimals)); }
  Groups& Add(int code, int value) { return Add(code, std::to_string(value)); }
  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

void Header(Groups& g, const std::vector<DxfLayer>& layers) {
  double min_x = std::numeric_limits<double>::infinity(), min_y = min_x;
  double max_x = -min_x, max_y = -min_x;
  for (const DxfLayer& layer : layers) {
    for (const geometry::Segment2& s : layer.segments) {
      for (const Eigen::Vector2d& p : {s.start_m, s.end_m}) {
        min_x = std::min(min_x, p.x()), min_y = std::min(min_y, p.y());
        max_x = std::max(max_x, p.x()), max_y = std::max(max_y, p.y());
      }
    }
  }
  if (!std::isfinite(min_x)) min_x = min_y = max_x = max_y = 0.0;
  g.Add(0, "SECTION").Add(2, "HEADER").Add(9, "$ACADVER").Add(1, "AC1009");
  g.Add(9, "$EXTMIN").Add(10, min_x).Add(20, min_y).Add(30, 0.0);
  g.Add(9, "$EXTMAX").Add(10, max_x).Add(20, max_y).Add(30, 0.0);
  g.Add(0, "ENDSEC");
}

void Tables(Groups& g, const std::vector<DxfLayer>& layers) {
  g.Add(0, "SECTION").Add(2, "TABLES");
  g.Add(0, "TABLE").Add(2, "LTYPE").Add(70, 1);
  g.Add(0, "LTYPE").Add(2, "CONTINUOUS").Add(70, 0).Add(3, "Solid line").Add(72, 65).Add(73, 0);
  g.Add(40, 0.0).Add(0, "ENDTAB");
  g.Add(0, "TABLE").Add(2, "LAYER").Add(70, static_cast<int>(layers.size()));
  for (const DxfLayer& layer : layers) {
    g.Add(0, "LAYER").Add(2, layer.name).Add(70, 0).Add(62, layer.colour).Add(6, "CONTINUOUS");
  }
  g.Add(0, "ENDTAB").Add(0, "ENDSEC");
}

}  // namespace

void WriteLineDxf(const std::filesystem::path& path, const std::vector<DxfLayer>& layers) {
  Validate(layers);
  Groups g;
  Header(g, layers);
  Tables(g, layers);
  g.Add(0, "SECTION").Add(2, "ENTITIES");
  for (const DxfLayer& layer : layers) {
    for (const geometry::Segment2& s : layer.segments) {
      g.Add(0, "LINE").Add(8, layer.name);
      g.Add(10, s.start_m.x()).Add(20, s.start_m.y()).Add(30, 0.0);
      g.Add(11, s.end_m.x()).Add(21, s.end_m.y()).Add(31, 0.0);
    }
  }
  g.Add(0, "ENDSEC").Add(0, "EOF");
  detail::TextWriter out(path);
  out.Put(g.text());
  out.Close();
}

void WriteLineDxf(const std::filesystem::path& path,
                  const std::vector<geometry::Segment2>& segments, const std::string& layer) {
  WriteLineDxf(path, std::vector<DxfLayer>{DxfLayer{layer, 7, segments}});
}

}  // namespace pena::io
