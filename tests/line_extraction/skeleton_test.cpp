#include "pena/line_map/internal/skeleton.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace pena::line_map::internal {
namespace {

int Neighbours(const cv::Mat& skeleton, int row, int col) {
  int count = 0;
  for (int dr = -1; dr <= 1; ++dr) {
    for (int dc = -1; dc <= 1; ++dc) {
      const int r = row + dr, c = col + dc;
      if ((dr != 0 || dc != 0) && r >= 0 && c >= 0 && r < skeleton.rows && c < skeleton.cols &&
          skeleton.at<std::uint8_t>(r, c) != 0) {
        ++count;
      }
    }
  }
  return count;
}

// Counts skeleton pixels by their number of 8-neighbours: [0] isolated ... [3] three or more.
std::array<int, 4> Degrees(const cv::Mat& skeleton) {
  std::array<int, 4> degrees{};
  for (int r = 0; r < skeleton.rows; ++r) {
    for (int c = 0; c < skeleton.cols; ++c) {
      if (skeleton.at<std::uint8_t>(r, c) != 0) ++degrees[std::min(3, Neighbours(skeleton, r, c))];
    }
  }
  return degrees;
}

int Components(const cv::Mat& binary) {
  cv::Mat labels;
  return cv::connectedComponents(binary, labels, 8) - 1;
}

TEST(Skeleton, ThinsThickBarToOnePixelLine) {
  cv::Mat bar = cv::Mat::zeros(40, 100, CV_8UC1);
  cv::rectangle(bar, cv::Point(10, 15), cv::Point(89, 21), cv::Scalar(255), cv::FILLED);
  const cv::Mat skeleton = Skeletonize(bar);
  const std::array<int, 4> degrees = Degrees(skeleton);
  EXPECT_EQ(degrees[1], 2);  // two ends
  EXPECT_EQ(degrees[3], 0);  // no junctions
  EXPECT_GT(degrees[2], 60);
  // Centred in the bar: every pixel on the middle rows.
  for (int r = 0; r < skeleton.rows; ++r) {
    if (r >= 17 && r <= 19) continue;
    EXPECT_EQ(cv::countNonZero(skeleton.row(r)), 0) << "row " << r;
  }
}

TEST(Skeleton, KeepsRingClosedAndDiagonalThin) {
  cv::Mat image = cv::Mat::zeros(120, 120, CV_8UC1);
  cv::circle(image, cv::Point(40, 40), 25, cv::Scalar(255), 4);
  cv::line(image, cv::Point(70, 110), cv::Point(115, 75), cv::Scalar(255), 3);
  const cv::Mat skeleton = Skeletonize(image);
  EXPECT_EQ(Components(skeleton), Components(image));
  const std::array<int, 4> degrees = Degrees(skeleton);
  EXPECT_EQ(degrees[0], 0);
  EXPECT_EQ(degrees[1], 2);  // the ends of the diagonal; the ring has none
  EXPECT_EQ(degrees[3], 0);  // no staircase pixels with three neighbours
}

TEST(Skeleton, KeepsCrossConnectedWithJunction) {
  cv::Mat image = cv::Mat::zeros(80, 80, CV_8UC1);
  cv::rectangle(image, cv::Point(10, 38), cv::Point(69, 41), cv::Scalar(255), cv::FILLED);
  cv::rectangle(image, cv::Point(38, 10), cv::Point(41, 69), cv::Scalar(255), cv::FILLED);
  const cv::Mat skeleton = Skeletonize(image);
  EXPECT_EQ(Components(skeleton), 1);
  const std::array<int, 4> degrees = Degrees(skeleton);
  EXPECT_EQ(degrees[1], 4);
  EXPECT_GE(degrees[3], 1);
}

TEST(Skeleton, RejectsNonByteImage) {
  EXPECT_THROW(Skeletonize(cv::Mat::zeros(4, 4, CV_32F)), std::invalid_argument);
}

}  // namespace
}  // namespace pena::line_map::internal
