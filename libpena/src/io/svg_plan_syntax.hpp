#pragma once
// Private: the micro-syntaxes inside SVG attributes that a plan reader needs: number lists
// (points), path data (d) and transform lists. Each throws std::invalid_argument saying what is
// wrong; the element reader adds the file and line.

#include <Eigen/Core>
#include <string_view>
#include <vector>

#include "pena/geometry/segment2.hpp"

namespace pena::io::detail {

// An SVG affine transform matrix(a b c d e f): x' = a x + c y + e, y' = b x + d y + f.
struct SvgAffine {
  double a = 1.0, b = 0.0, c = 0.0, d = 1.0, e = 0.0, f = 0.0;
  Eigen::Vector2d Apply(const Eigen::Vector2d& p) const {
    return {a * p.x() + c * p.y() + e, b * p.x() + d * p.y() + f};
  }
};

// outer * inner: apply inner first.
SvgAffine Multiply(const SvgAffine& outer, const SvgAffine& inner);

// Numbers separated by whitespace and/or commas ("1,2 3-4" is 1 2 3 -4).
std::vector<double> ParseSvgNumbers(std::string_view text);

// One length attribute: a number, optionally followed by "px" (user units).
double ParseSvgLength(std::string_view text);

// The straight spans of path data: M/L/H/V/Z in absolute and relative form. Curves (C/S/Q/T/A)
// draw nothing here: the pen moves to their end point. Coordinates as written (no transform).
std::vector<geometry::Segment2> ParseSvgPath(std::string_view data);

// A transform list: matrix, translate, scale, rotate (with optional centre), skewX, skewY.
SvgAffine ParseSvgTransform(std::string_view text);

}  // namespace pena::io::detail
