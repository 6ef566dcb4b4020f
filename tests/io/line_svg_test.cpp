#include "pena/io/line_svg.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "scoped_temp_dir.hpp"

namespace pena::io {
namespace {

std::string Slurp(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(LineSvg, DrawsEveryLayerWithLegendAndScaleBar) {
  const pena::testing::ScopedTempDir dir("line-svg");
  const auto path = dir / "plan.svg";
  WriteLineSvg(path, {{"walls", "#808080", 0.1, {{{0, 0}, {10, 0}}, {{10, 0}, {10, 6}}}},
                      {"plan", "#ff8000", 0.05, {{{0, 0.2}, {10, 0.2}}}}});
  const std::string svg = Slurp(path);
  const std::regex line_element("<line ");
  const auto lines =
      std::distance(std::sregex_iterator(svg.begin(), svg.end(), line_element), std::sregex_iterator());
  EXPECT_EQ(lines, 3 + 1 + 2);  // segments, scale bar, one legend swatch per layer
  EXPECT_NE(svg.find("<g id=\"walls\""), std::string::npos);
  EXPECT_NE(svg.find(">plan</text>"), std::string::npos);
  EXPECT_NE(svg.find(">2.0000 m</text>"), std::string::npos) << svg;  // 12 m wide: a 2 m bar
  EXPECT_NE(svg.find("scale(1 -1)"), std::string::npos);             // y up
}

TEST(LineSvg, UnwritablePathIsAnErrorNamingIt) {
  EXPECT_THROW(WriteLineSvg("/nonexistent-dir/plan.svg", {}), std::runtime_error);
}

}  // namespace
}  // namespace pena::io
