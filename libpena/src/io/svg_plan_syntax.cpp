// SVG attribute micro-syntaxes (SVG 1.1, sections 7.6 transforms, 8.3 path data, 4.2 numbers).
#include "svg_plan_syntax.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

namespace pena::io::detail {
namespace {

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
bool IsDigit(char c) { return c >= '0' && c <= '9'; }
bool IsLetter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

// Reads SVG numbers, letters and punctuation from one attribute value.
class Scanner {
 public:
  explicit Scanner(std::string_view text) : text_(text) {}

  void SkipSeparators() {
    while (pos_ < text_.size() && (IsSpace(text_[pos_]) || text_[pos_] == ',')) ++pos_;
  }
  void SkipSpaces() {
    while (pos_ < text_.size() && IsSpace(text_[pos_])) ++pos_;
  }
  bool AtEnd() const { return pos_ >= text_.size(); }
  char Peek() const { return AtEnd() ? '\0' : text_[pos_]; }
  void Advance() { ++pos_; }
  std::size_t column() const { return pos_ + 1; }
  std::string_view Rest() const { return text_.substr(pos_); }

  // SVG's number grammar: sign, digits, fraction, exponent; "1.5.5" is 1.5 then .5.
  std::optional<double> TryNumber() {
    SkipSeparators();
    std::size_t end = pos_;
    if (end < text_.size() && (text_[end] == '+' || text_[end] == '-')) ++end;
    const std::size_t mantissa = end;
    while (end < text_.size() && IsDigit(text_[end])) ++end;
    if (end < text_.size() && text_[end] == '.') {
      ++end;
      while (end < text_.size() && IsDigit(text_[end])) ++end;
    }
    if (end == mantissa || (end == mantissa + 1 && text_[mantissa] == '.')) return std::nullopt;
    if (end < text_.size() && (text_[end] == 'e' || text_[end] == 'E')) {
      std::size_t exponent = end + 1;
      if (exponent < text_.size() && (text_[exponent] == '+' || text_[exponent] == '-')) ++exponent;
      if (exponent < text_.size() && IsDigit(text_[exponent])) {
        end = exponent;
        while (end < text_.size() && IsDigit(text_[end])) ++end;
      }
    }
    std::size_t first = pos_;
    if (text_[first] == '+') ++first;  // from_chars rejects a leading '+'
    double value = 0.0;
    const auto result = std::from_chars(text_.data() + first, text_.data() + end, value);
    if (result.ec != std::errc() || !std::isfinite(value)) return std::nullopt;
    pos_ = end;
    return value;
  }

  double Number(const char* what) {
    const std::optional<double> value = TryNumber();
    if (!value) {
      throw std::invalid_argument(std::string("expected a number (") + what + ") at column " +
                                  std::to_string(column()) + ", found '" +
                                  std::string(Rest().substr(0, 12)) + "'");
    }
    return *value;
  }

  // An arc flag: a single '0' or '1', which may be written without separators ("a1 1 0 011 2").
  double Flag() {
    SkipSeparators();
    const char c = Peek();
    if (c != '0' && c != '1') {
      throw std::invalid_argument("expected an arc flag 0 or 1 at column " +
                                  std::to_string(column()));
    }
    Advance();
    return c == '1' ? 1.0 : 0.0;
  }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
};

// How many numbers one instance of a path command takes; 0 for an unknown command.
int ArgumentCount(char upper) {
  switch (upper) {
    case 'M':
    case 'L':
    case 'T':
      return 2;
    case 'H':
    case 'V':
      return 1;
    case 'S':
    case 'Q':
      return 4;
    case 'C':
      return 6;
    case 'A':
      return 7;
    case 'Z':
      return 0;
    default:
      return -1;
  }
}

// The pen state of path data.
struct Pen {
  Eigen::Vector2d current = Eigen::Vector2d::Zero();
  Eigen::Vector2d subpath_start = Eigen::Vector2d::Zero();
  std::vector<geometry::Segment2> segments;
  void DrawTo(const Eigen::Vector2d& to) {
    segments.push_back({current, to});
    current = to;
  }
};

// Executes one instance of `command` (its numbers still to be read from `scanner`).
void Execute(char command, Scanner& scanner, Pen& pen) {
  const char upper = static_cast<char>(std::toupper(static_cast<unsigned char>(command)));
  const bool relative = command != upper;
  const Eigen::Vector2d origin = relative ? pen.current : Eigen::Vector2d::Zero();
  std::vector<double> args;
  for (int i = 0; i < ArgumentCount(upper); ++i) {
    const bool flag = upper == 'A' && (i == 3 || i == 4);
    args.push_back(flag ? scanner.Flag() : scanner.Number("path coordinate"));
  }
  if (upper == 'M') {
    pen.current = origin + Eigen::Vector2d(args[0], args[1]);
    pen.subpath_start = pen.current;
  } else if (upper == 'L') {
    pen.DrawTo(origin + Eigen::Vector2d(args[0], args[1]));
  } else if (upper == 'H') {
    pen.DrawTo({(relative ? pen.current.x() : 0.0) + args[0], pen.current.y()});
  } else if (upper == 'V') {
    pen.DrawTo({pen.current.x(), (relative ? pen.current.y() : 0.0) + args[0]});
  } else if (upper == 'Z') {
    pen.DrawTo(pen.subpath_start);
  } else {  // a curve or arc: no wall, the pen moves to its end point
    pen.current = origin + Eigen::Vector2d(args[args.size() - 2], args.back());
  }
}

SvgAffine TransformFunction(const std::string& name, const std::vector<double>& v) {
  const std::size_t n = v.size();
  const double to_rad = std::numbers::pi / 180.0;
  if (name == "matrix" && n == 6) return {v[0], v[1], v[2], v[3], v[4], v[5]};
  if (name == "translate" && (n == 1 || n == 2)) return {1, 0, 0, 1, v[0], n == 2 ? v[1] : 0.0};
  if (name == "scale" && (n == 1 || n == 2)) return {v[0], 0, 0, n == 2 ? v[1] : v[0], 0, 0};
  if (name == "skewX" && n == 1) return {1, 0, std::tan(v[0] * to_rad), 1, 0, 0};
  if (name == "skewY" && n == 1) return {1, std::tan(v[0] * to_rad), 0, 1, 0, 0};
  if (name == "rotate" && (n == 1 || n == 3)) {
    const double c = std::cos(v[0] * to_rad), s = std::sin(v[0] * to_rad);
    const SvgAffine rotation{c, s, -s, c, 0, 0};
    if (n == 1) return rotation;
    return Multiply(Multiply({1, 0, 0, 1, v[1], v[2]}, rotation), {1, 0, 0, 1, -v[1], -v[2]});
  }
  throw std::invalid_argument("unknown transform '" + name + "' with " + std::to_string(n) +
                              " numbers");
}

}  // namespace

SvgAffine Multiply(const SvgAffine& outer, const SvgAffine& inner) {
  return {outer.a * inner.a + outer.c * inner.b,
          outer.b * inner.a + outer.d * inner.b,
          outer.a * inner.c + outer.c * inner.d,
          outer.b * inner.c + outer.d * inner.d,
          outer.a * inner.e + outer.c * inner.f + outer.e,
          outer.b * inner.e + outer.d * inner.f + outer.f};
}

std::vector<double> ParseSvgNumbers(std::string_view text) {
  Scanner scanner(text);
  std::vector<double> numbers;
  for (scanner.SkipSeparators(); !scanner.AtEnd(); scanner.SkipSeparators()) {
    numbers.push_back(scanner.Number("coordinate"));
  }
  return numbers;
}

double ParseSvgLength(std::string_view text) {
  Scanner scanner(text);
  const double value = scanner.Number("length");
  scanner.SkipSpaces();
  const std::string_view unit = scanner.Rest();
  if (!unit.empty() && unit != "px") {
    throw std::invalid_argument("length '" + std::string(text) +
                                "' has a unit; only user units (or px) are read, scale them "
                                "with the plan's unit scale");
  }
  return value;
}

std::vector<geometry::Segment2> ParseSvgPath(std::string_view data) {
  Scanner scanner(data);
  Pen pen;
  char command = '\0';
  bool started = false;
  for (scanner.SkipSeparators(); !scanner.AtEnd(); scanner.SkipSeparators()) {
    if (IsLetter(scanner.Peek())) {
      command = scanner.Peek();
      scanner.Advance();
      const char upper = static_cast<char>(std::toupper(static_cast<unsigned char>(command)));
      if (ArgumentCount(upper) < 0) {
        throw std::invalid_argument(std::string("unknown path command '") + command + "'");
      }
      if (!started && upper != 'M') throw std::invalid_argument("path data must start with M or m");
      started = true;
    } else if (command == '\0' || command == 'Z' || command == 'z') {
      throw std::invalid_argument("expected a path command at column " +
                                  std::to_string(scanner.column()));
    }
    Execute(command, scanner, pen);
    if (command == 'M') command = 'L';  // further pairs after a moveto are linetos
    if (command == 'm') command = 'l';
  }
  return std::move(pen.segments);
}

SvgAffine ParseSvgTransform(std::string_view text) {
  Scanner scanner(text);
  SvgAffine total;
  for (scanner.SkipSeparators(); !scanner.AtEnd(); scanner.SkipSeparators()) {
    std::string name;
    while (IsLetter(scanner.Peek())) name += scanner.Peek(), scanner.Advance();
    scanner.SkipSpaces();
    if (name.empty() || scanner.Peek() != '(') {
      throw std::invalid_argument("expected a transform like translate(x y) at column " +
                                  std::to_string(scanner.column()));
    }
    scanner.Advance();
    std::vector<double> values;
    for (scanner.SkipSeparators(); scanner.Peek() != ')'; scanner.SkipSeparators()) {
      if (scanner.AtEnd()) throw std::invalid_argument("transform '" + name + "' lacks ')'");
      values.push_back(scanner.Number("transform argument"));
    }
    scanner.Advance();
    total = Multiply(total, TransformFunction(name, values));
  }
  return total;
}

}  // namespace pena::io::detail
