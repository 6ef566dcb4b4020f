#pragma once
// A picture of a map in world metres: a fixed resolution, a margin, y up. Draws segments,
// polylines, points, boxes, circles, text, a scale bar and a legend into a BGR cv::Mat. Encoding
// (PNG) is left to the caller (io layer or CLI).

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "pena/geometry/segment2.hpp"

namespace pena::viz {

// Colours as OpenCV BGR.
namespace colors {
inline const cv::Scalar kBlack{0, 0, 0};
inline const cv::Scalar kGray{150, 150, 150};
inline const cv::Scalar kLightGray{220, 220, 220};
inline const cv::Scalar kWhite{255, 255, 255};
inline const cv::Scalar kBlue{200, 90, 20};
inline const cv::Scalar kOrange{0, 140, 255};
inline const cv::Scalar kRed{40, 40, 220};
inline const cv::Scalar kGreen{60, 160, 40};
inline const cv::Scalar kPurple{160, 60, 150};
inline const cv::Scalar kTeal{150, 150, 0};
}  // namespace colors

// Picture layout.
struct MapCanvasOptions {
  double resolution_m = 0.05;  // metres per pixel (before max_size_px applies)
  int margin_px = 40;          // blank border around the world box
  int max_size_px = 2000;      // the larger map side; resolution is coarsened to fit
  int legend_panel_px = 0;     // > 0: a blank panel this wide right of the map holds the legend
  cv::Scalar background = colors::kWhite;
};

// A canvas covering the world box [min_m, max_m] (mission frame, metres).
class MapCanvas {
 public:
  // Throws std::invalid_argument for an empty box or non-positive resolution/size.
  MapCanvas(const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m,
            const MapCanvasOptions& options = {});

  // Pixel coordinates (x right, y down; sub-pixel) of a world point.
  cv::Point2d ToPixel(const Eigen::Vector2d& point_m) const;

  void DrawSegment(const geometry::Segment2& segment, const cv::Scalar& color,
                   int thickness_px = 1);
  void DrawSegments(const std::vector<geometry::Segment2>& segments, const cv::Scalar& color,
                    int thickness_px = 1);
  void DrawPolyline(const std::vector<Eigen::Vector2d>& points_m, const cv::Scalar& color,
                    int thickness_px = 1);
  void DrawPoints(const std::vector<Eigen::Vector2d>& points_m, const cv::Scalar& color,
                  int radius_px = 1);
  // One pixel per point, no anti-aliasing, clipped to the map area: dense clouds (every scan).
  void DrawPixels(const std::vector<Eigen::Vector2d>& points_m, const cv::Scalar& color);
  // An axis-aligned box (world corners), outlined or filled.
  void DrawBox(const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m, const cv::Scalar& color,
               bool filled);
  void DrawCircle(const Eigen::Vector2d& center_m, double radius_m, const cv::Scalar& color,
                  int thickness_px = 1);
  // Text with its bottom-left corner at a world point.
  void DrawText(const Eigen::Vector2d& anchor_m, const std::string& text, const cv::Scalar& color,
                double scale = 0.45);
  // A bar of a round length (1, 2 or 5 x 10^k m, about a fifth of the width), bottom left.
  void DrawScaleBar();
  // Queues a legend line; DrawLegend paints all queued lines in a box at the top left (or at
  // the top of the legend panel).
  void AddLegendEntry(const std::string& label, const cv::Scalar& color);
  void DrawLegend();

  const cv::Mat& image() const { return image_; }
  double resolution_m() const { return resolution_m_; }
  // The length in metres of the bar DrawScaleBar draws.
  double ScaleBarLength() const;

 private:
  Eigen::Vector2d min_m_;
  Eigen::Vector2d max_m_;
  double resolution_m_;
  int margin_px_;
  int legend_panel_px_;
  cv::Mat image_;
  std::vector<std::pair<std::string, cv::Scalar>> legend_;
};

}  // namespace pena::viz
