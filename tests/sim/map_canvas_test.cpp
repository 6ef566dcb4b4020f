#include "pena/viz/map_canvas.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace pena::viz {
namespace {

MapCanvasOptions Options() {
  MapCanvasOptions options;
  options.resolution_m = 0.1;
  options.margin_px = 20;
  return options;
}

TEST(MapCanvas, MapsWorldToPixelsWithYUpAndAMargin) {
  const MapCanvas canvas({0.0, 0.0}, {10.0, 5.0}, Options());
  EXPECT_EQ(canvas.image().cols, 100 + 40);
  EXPECT_EQ(canvas.image().rows, 50 + 40);
  const cv::Point2d top_left = canvas.ToPixel({0.0, 5.0});
  EXPECT_DOUBLE_EQ(top_left.x, 20.0);
  EXPECT_DOUBLE_EQ(top_left.y, 20.0);
  const cv::Point2d bottom_right = canvas.ToPixel({10.0, 0.0});
  EXPECT_DOUBLE_EQ(bottom_right.x, 120.0);
  EXPECT_DOUBLE_EQ(bottom_right.y, 70.0);
}

TEST(MapCanvas, DrawsASegmentWhereItLies) {
  MapCanvas canvas({0.0, 0.0}, {10.0, 5.0}, Options());
  canvas.DrawSegment({{1.0, 2.0}, {9.0, 2.0}}, colors::kBlack, 1);
  const cv::Point2d on = canvas.ToPixel({5.0, 2.0});
  const cv::Point2d off = canvas.ToPixel({5.0, 3.0});
  const auto at = [&](const cv::Point2d& p) {
    return canvas.image().at<cv::Vec3b>(static_cast<int>(std::lround(p.y)),
                                        static_cast<int>(std::lround(p.x)));
  };
  EXPECT_LT(at(on)[0], 100);
  EXPECT_EQ(at(off), cv::Vec3b(255, 255, 255));
}

TEST(MapCanvas, CoarsensTheResolutionToFitTheMaximumSize) {
  MapCanvasOptions options = Options();
  options.max_size_px = 540;
  const MapCanvas canvas({0.0, 0.0}, {100.0, 10.0}, options);
  EXPECT_NEAR(canvas.resolution_m(), 0.2, 1e-12);
  EXPECT_LE(canvas.image().cols, 540);
}

TEST(MapCanvas, ScaleBarHasARoundLengthAboutAFifthOfTheWidth) {
  MapCanvas canvas({0.0, 0.0}, {37.0, 20.0}, Options());
  const double length = canvas.ScaleBarLength();
  const double mantissa = length / std::pow(10.0, std::floor(std::log10(length)));
  EXPECT_TRUE(std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 ||
              std::abs(mantissa - 5) < 1e-9)
      << length;
  const double width_m = canvas.image().cols * canvas.resolution_m();
  EXPECT_LE(length, 0.2 * width_m);
  EXPECT_GT(length, 0.04 * width_m);
  const cv::Mat before = canvas.image().clone();
  canvas.DrawScaleBar();
  canvas.AddLegendEntry("walls", colors::kBlack);
  canvas.DrawLegend();
  EXPECT_GT(cv::norm(before, canvas.image(), cv::NORM_L1), 0.0);
}

TEST(MapCanvas, RejectsAnEmptyWorldBox) {
  EXPECT_THROW(MapCanvas({0.0, 0.0}, {0.0, 5.0}), std::invalid_argument);
}

}  // namespace
}  // namespace pena::viz
