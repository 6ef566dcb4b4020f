// Piece ownership of grid cells and the extension of fitted ends over the cells that continue a
// wall (paper section 3's segments, made to reach the corners and ends the skeleton cuts short).
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "extract_steps.hpp"

namespace pena::line_map::internal {
namespace {

// Largest extension of one end: far beyond what thinning and closing cut off, and it bounds the
// walk along a long dotted wall.
constexpr double kMaxExtension_m = 3.0;

Eigen::Vector2d Direction(const geometry::Segment2& segment) {
  const Eigen::Vector2d along = segment.end_m - segment.start_m;
  const double length_m = along.norm();
  return length_m > 0.0 ? Eigen::Vector2d(along / length_m) : Eigen::Vector2d::UnitX();
}

// The pixel holding a world point, if inside the image.
bool PixelAt(const GridFrame& frame, const cv::Size& size, const Eigen::Vector2d& point_m,
             cv::Point& pixel) {
  const double col = (point_m.x() - frame.origin_m.x()) / frame.resolution_m;
  const double row_from_bottom = (point_m.y() - frame.origin_m.y()) / frame.resolution_m;
  pixel = {static_cast<int>(std::floor(col)),
           frame.rows - 1 - static_cast<int>(std::floor(row_from_bottom))};
  return pixel.x >= 0 && pixel.y >= 0 && pixel.x < size.width && pixel.y < size.height;
}

// How far beyond `end` (along unit `outward`) occupied cells continue piece `self`'s line.
double Extension(std::size_t self, const std::vector<Piece>& pieces, const Eigen::Vector2d& end,
                 const Eigen::Vector2d& outward, const cv::Mat& occupied, const cv::Mat& owners,
                 const GridFrame& frame, double gap_m, double min_cos) {
  const double res = frame.resolution_m;
  const Eigen::Vector2d normal(-outward.y(), outward.x());
  double reached_m = 0.0;
  for (double t = 0.5 * res; t - reached_m <= gap_m && t <= kMaxExtension_m; t += 0.5 * res) {
    for (const double k : {0.0, -1.0, 1.0}) {
      cv::Point pixel;
      if (!PixelAt(frame, occupied.size(), end + t * outward + k * res * normal, pixel)) continue;
      if (occupied.at<std::uint8_t>(pixel) == 0) continue;
      const int owner = owners.at<std::int32_t>(pixel);
      if (owner >= 0 && static_cast<std::size_t>(owner) != self &&
          std::abs(Direction(pieces[static_cast<std::size_t>(owner)].fit.segment).dot(outward)) >=
              min_cos) {
        return reached_m;  // the next piece of this wall begins here
      }
      reached_m = std::max(reached_m, outward.dot(frame.ToWorld(pixel) - end));
    }
  }
  return reached_m;
}

}  // namespace

cv::Mat PieceOwners(const std::vector<Piece>& pieces, const cv::Mat& skeleton,
                    const GridFrame& frame, double max_distance_m) {
  cv::Mat off_skeleton, distance_px, labels;
  cv::compare(skeleton, 0, off_skeleton, cv::CMP_EQ);
  cv::distanceTransform(off_skeleton, distance_px, labels, cv::DIST_L2, cv::DIST_MASK_5,
                        cv::DIST_LABEL_PIXEL);
  std::vector<int> piece_of_label(static_cast<std::size_t>(cv::countNonZero(skeleton)) + 1, -1);
  for (std::size_t s = 0; s < pieces.size(); ++s) {
    for (const cv::Point& pixel : pieces[s].pixels) {
      piece_of_label[static_cast<std::size_t>(labels.at<int>(pixel))] = static_cast<int>(s);
    }
  }
  cv::Mat owners(skeleton.size(), CV_32SC1);
  for (int row = 0; row < owners.rows; ++row) {
    const int* label = labels.ptr<int>(row);
    const float* distance = distance_px.ptr<float>(row);
    std::int32_t* owner = owners.ptr<std::int32_t>(row);
    for (int col = 0; col < owners.cols; ++col) {
      owner[col] = distance[col] * frame.resolution_m <= max_distance_m
                       ? piece_of_label[static_cast<std::size_t>(label[col])]
                       : -1;
    }
  }
  return owners;
}

void ExtendEnds(std::vector<Piece>& pieces, const cv::Mat& occupied, const cv::Mat& owners,
                const GridFrame& frame, double gap_m, double angle_rad) {
  const double min_cos = std::cos(angle_rad);
  std::vector<geometry::Segment2> extended;
  extended.reserve(pieces.size());
  for (std::size_t s = 0; s < pieces.size(); ++s) {
    const geometry::Segment2& segment = pieces[s].fit.segment;
    const Eigen::Vector2d forward = Direction(segment);
    const double ahead_m = Extension(s, pieces, segment.end_m, forward, occupied, owners, frame,
                                     gap_m, min_cos);
    const double behind_m = Extension(s, pieces, segment.start_m, -forward, occupied, owners,
                                      frame, gap_m, min_cos);
    extended.push_back({segment.start_m - behind_m * forward, segment.end_m + ahead_m * forward});
  }
  // Applied after all are measured, so no piece's extension depends on the order.
  for (std::size_t s = 0; s < pieces.size(); ++s) pieces[s].fit.segment = extended[s];
}

}  // namespace pena::line_map::internal
