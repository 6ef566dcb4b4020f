// SVG plans: a small XML tag scanner (no DTDs, no entities in geometry) feeding the straight
// strokes of line, polyline, polygon, rect and path elements through their transforms.
#include "svg_plan_reader.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "gz_line_reader.hpp"
#include "pena/io/input_error.hpp"
#include "svg_plan_syntax.hpp"

namespace pena::io::detail {
namespace {

// One start or end tag with its attributes (values verbatim) and the line it starts on.
struct Tag {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
  bool closing = false;
  bool self_closing = false;
  std::size_t line = 0;

  std::optional<std::string_view> Attribute(std::string_view key) const {
    for (const auto& [attribute_name, value] : attributes) {
      if (attribute_name == key) return value;
    }
    return std::nullopt;
  }
};

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
bool IsNameChar(char c) { return !IsSpace(c) && c != '=' && c != '>' && c != '/' && c != '<'; }

// Walks the tags of an XML text, skipping comments, processing instructions, CDATA and DTDs.
class TagScanner {
 public:
  TagScanner(const std::filesystem::path& path, std::string_view text) : path_(path), text_(text) {}

  std::optional<Tag> Next() {
    while (true) {
      const std::size_t open = text_.find('<', pos_);
      if (open == std::string_view::npos) return std::nullopt;
      pos_ = open;
      const std::string_view rest = text_.substr(pos_);
      if (rest.starts_with("<!--"))
        SkipPast("-->", "comment");
      else if (rest.starts_with("<![CDATA["))
        SkipPast("]]>", "CDATA section");
      else if (rest.starts_with("<?"))
        SkipPast("?>", "processing instruction");
      else if (rest.starts_with("<!"))
        SkipPast(">", "declaration");
      else
        return ReadTag();
    }
  }

  std::size_t LineAt(std::size_t position) {
    for (; counted_ < position && counted_ < text_.size(); ++counted_)
      line_ += text_[counted_] == '\n';
    return line_;
  }
  std::size_t end_line() { return LineAt(text_.size()); }

 private:
  void SkipPast(std::string_view terminator, const char* what) {
    const std::size_t end = text_.find(terminator, pos_);
    if (end == std::string_view::npos) {
      throw InputError(path_, LineAt(pos_), std::string("unterminated ") + what);
    }
    pos_ = end + terminator.size();
  }

  [[noreturn]] void Fail(const std::string& what) { throw InputError(path_, LineAt(pos_), what); }

  Tag ReadTag() {
    Tag tag;
    tag.line = LineAt(pos_);
    ++pos_;
    if (Peek() == '/') tag.closing = true, ++pos_;
    while (pos_ < text_.size() && IsNameChar(text_[pos_])) tag.name += text_[pos_++];
    if (tag.name.empty()) Fail("expected an element name after '<'");
    while (true) {
      while (pos_ < text_.size() && IsSpace(text_[pos_])) ++pos_;
      if (pos_ >= text_.size())
        Fail("unterminated tag <" + tag.name + "> from line " + std::to_string(tag.line));
      if (text_.substr(pos_).starts_with("/>")) return pos_ += 2, tag.self_closing = true, tag;
      if (text_[pos_] == '>') return ++pos_, tag;
      tag.attributes.push_back(ReadAttribute(tag.name));
    }
  }

  std::pair<std::string, std::string> ReadAttribute(const std::string& element) {
    std::string name;
    while (pos_ < text_.size() && IsNameChar(text_[pos_])) name += text_[pos_++];
    while (pos_ < text_.size() && IsSpace(text_[pos_])) ++pos_;
    if (name.empty() || Peek() != '=') Fail("malformed attribute in <" + element + ">");
    ++pos_;
    while (pos_ < text_.size() && IsSpace(text_[pos_])) ++pos_;
    const char quote = Peek();
    if (quote != '"' && quote != '\'')
      Fail("attribute " + name + " of <" + element + "> is not quoted");
    const std::size_t end = text_.find(quote, pos_ + 1);
    if (end == std::string_view::npos) Fail("unterminated value of attribute " + name);
    std::string value(text_.substr(pos_ + 1, end - pos_ - 1));
    pos_ = end + 1;
    return {std::move(name), std::move(value)};
  }

  char Peek() const { return pos_ < text_.size() ? text_[pos_] : '\0'; }

  const std::filesystem::path& path_;
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t counted_ = 0;
  std::size_t line_ = 1;
};

// An element that is open, with everything it passes to its children.
struct OpenElement {
  std::string name;
  SvgAffine transform;
  bool hidden = false;  // inside defs and the like: drawn only where referenced, which we do not
  std::size_t line = 0;
};

bool HidesContent(std::string_view name) {
  constexpr std::array<std::string_view, 6> kHidden = {"defs", "symbol", "clipPath",
                                                       "mask", "marker", "pattern"};
  return std::find(kHidden.begin(), kHidden.end(), name) != kHidden.end();
}

double Length(const Tag& tag, std::string_view key) {
  const std::optional<std::string_view> value = tag.Attribute(key);
  return value ? ParseSvgLength(*value) : 0.0;
}

// Points of a polyline/polygon as a chain of segments (closed for a polygon).
std::vector<geometry::Segment2> Chain(const Tag& tag, bool closed) {
  const std::vector<double> numbers = ParseSvgNumbers(tag.Attribute("points").value_or(""));
  if (numbers.size() % 2 != 0) throw std::invalid_argument("points has an odd count of numbers");
  std::vector<geometry::Segment2> chain;
  for (std::size_t i = 2; i < numbers.size(); i += 2) {
    chain.push_back({{numbers[i - 2], numbers[i - 1]}, {numbers[i], numbers[i + 1]}});
  }
  if (closed && numbers.size() >= 6) {
    chain.push_back({chain.back().end_m, chain.front().start_m});
  }
  return chain;
}

// Sizes in % of the viewport mark a background or a frame, not a wall.
bool ViewportRelative(const Tag& tag) {
  for (const char* key : {"x", "y", "width", "height", "x1", "y1", "x2", "y2"}) {
    if (tag.Attribute(key).value_or("").ends_with('%')) return true;
  }
  return false;
}

// The straight strokes of one element in its own coordinates.
std::vector<geometry::Segment2> Strokes(const Tag& tag) {
  if (ViewportRelative(tag)) return {};
  if (tag.name == "line") {
    return {{{Length(tag, "x1"), Length(tag, "y1")}, {Length(tag, "x2"), Length(tag, "y2")}}};
  }
  if (tag.name == "polyline" || tag.name == "polygon") return Chain(tag, tag.name == "polygon");
  if (tag.name == "path") return ParseSvgPath(tag.Attribute("d").value_or(""));
  if (tag.name == "rect") {
    const double x = Length(tag, "x"), y = Length(tag, "y");
    const double w = Length(tag, "width"), h = Length(tag, "height");
    if (w < 0.0 || h < 0.0) throw std::invalid_argument("rect has a negative width or height");
    if (w == 0.0 || h == 0.0) return {};  // not rendered (SVG 1.1, 9.2)
    const Eigen::Vector2d a{x, y}, b{x + w, y}, c{x + w, y + h}, d{x, y + h};
    return {{a, b}, {b, c}, {c, d}, {d, a}};
  }
  return {};
}

}  // namespace

std::vector<geometry::Segment2> ReadSvgPlan(const std::filesystem::path& path) {
  std::string text;
  {
    GzLineReader reader(path);
    std::string line;
    while (reader.ReadLine(line)) text += line + '\n';
  }
  TagScanner scanner(path, text);
  std::vector<OpenElement> open;
  std::vector<geometry::Segment2> segments;
  bool saw_svg = false;
  while (const std::optional<Tag> tag = scanner.Next()) {
    if (tag->closing) {
      if (open.empty() || open.back().name != tag->name) {
        throw InputError(path, tag->line,
                         "</" + tag->name + "> does not close " +
                             (open.empty() ? std::string("any element")
                                           : "<" + open.back().name + "> from line " +
                                                 std::to_string(open.back().line)));
      }
      open.pop_back();
      continue;
    }
    saw_svg = saw_svg || tag->name == "svg";
    OpenElement element{tag->name, open.empty() ? SvgAffine{} : open.back().transform,
                        (!open.empty() && open.back().hidden) || HidesContent(tag->name),
                        tag->line};
    try {
      if (const auto transform = tag->Attribute("transform")) {
        element.transform = Multiply(element.transform, ParseSvgTransform(*transform));
      }
      if (!element.hidden) {
        for (const geometry::Segment2& s : Strokes(*tag)) {
          const Eigen::Vector2d a = element.transform.Apply(s.start_m);
          const Eigen::Vector2d b = element.transform.Apply(s.end_m);
          segments.push_back({{a.x(), -a.y()}, {b.x(), -b.y()}});  // SVG's y points down
        }
      }
    } catch (const std::invalid_argument& error) {
      throw InputError(path, tag->line, "<" + tag->name + ">: " + error.what());
    }
    if (!tag->self_closing) open.push_back(std::move(element));
  }
  if (!open.empty()) {
    throw InputError(path, scanner.end_line(),
                     "unexpected end of file: <" + open.back().name + "> from line " +
                         std::to_string(open.back().line) + " is not closed");
  }
  if (!saw_svg) throw InputError(path, 1, "not an SVG drawing: no <svg> element");
  return segments;
}

}  // namespace pena::io::detail
