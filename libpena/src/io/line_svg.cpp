#include "pena/io/line_svg.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace pena::io {
namespace {

struct Bounds {
  double min_x = std::numeric_limits<double>::infinity(), min_y = min_x;
  double max_x = -std::numeric_limits<double>::infinity(), max_y = max_x;
  void Add(const Eigen::Vector2d& p) {
    min_x = std::min(min_x, p.x()), min_y = std::min(min_y, p.y());
    max_x = std::max(max_x, p.x()), max_y = std::max(max_y, p.y());
  }
};

// A 1, 2 or 5 x 10^k metre bar of about a fifth of the width.
double ScaleBarLength(double width_m) {
  const double target = std::max(width_m / 5.0, 1e-3);
  const double decade = std::pow(10.0, std::floor(std::log10(target)));
  for (const double factor : {5.0, 2.0, 1.0}) {
    if (factor * decade <= target) return factor * decade;
  }
  return decade;
}

}  // namespace

void WriteLineSvg(const std::filesystem::path& path, const std::vector<SvgLayer>& layers,
                  double margin_m) {
  Bounds bounds;
  for (const auto& layer : layers) {
    for (const auto& segment : layer.segments) bounds.Add(segment.start_m), bounds.Add(segment.end_m);
  }
  if (!std::isfinite(bounds.min_x)) bounds = {0.0, 0.0, 1.0, 1.0};
  const double width = bounds.max_x - bounds.min_x + 2.0 * margin_m;
  const double legend_m = 0.6 * static_cast<double>(layers.size() + 2);
  const double height = bounds.max_y - bounds.min_y + 2.0 * margin_m + legend_m;
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path.string() + ": cannot write SVG");
  out.precision(4);
  out << std::fixed;
  // viewBox in metres; the map group flips y so the mission frame's +y points up on screen.
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width * 20 << "\" height=\""
      << height * 20 << "\" viewBox=\"0 0 " << width << ' ' << height << "\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<g transform=\"translate(" << margin_m - bounds.min_x << ' '
      << bounds.max_y + margin_m << ") scale(1 -1)\" stroke-linecap=\"round\">\n";
  for (const auto& layer : layers) {
    out << "<g id=\"" << layer.name << "\" stroke=\"" << layer.colour << "\" stroke-width=\""
        << layer.stroke_width_m << "\">\n";
    for (const auto& s : layer.segments) {
      out << "<line x1=\"" << s.start_m.x() << "\" y1=\"" << s.start_m.y() << "\" x2=\""
          << s.end_m.x() << "\" y2=\"" << s.end_m.y() << "\"/>\n";
    }
    out << "</g>\n";
  }
  out << "</g>\n";
  const double bar = ScaleBarLength(width);
  const double base = height - legend_m + 0.5;
  out << "<g font-family=\"sans-serif\" font-size=\"0.4\">\n<line x1=\"" << margin_m << "\" y1=\""
      << base << "\" x2=\"" << margin_m + bar << "\" y2=\"" << base
      << "\" stroke=\"black\" stroke-width=\"0.08\"/>\n<text x=\"" << margin_m + bar + 0.2
      << "\" y=\"" << base + 0.15 << "\">" << bar << " m</text>\n";
  for (std::size_t i = 0; i < layers.size(); ++i) {
    const double y = base + 0.6 * static_cast<double>(i + 1);
    out << "<line x1=\"" << margin_m << "\" y1=\"" << y << "\" x2=\"" << margin_m + 0.8
        << "\" y2=\"" << y << "\" stroke=\"" << layers[i].colour
        << "\" stroke-width=\"0.12\"/>\n<text x=\"" << margin_m + 1.0 << "\" y=\"" << y + 0.15
        << "\">" << layers[i].name << "</text>\n";
  }
  out << "</g>\n</svg>\n";
  if (!out) throw std::runtime_error(path.string() + ": write failed");
}

}  // namespace pena::io
