#pragma once
// Thinning of a binary image to a one-pixel-wide, 8-connected skeleton (Zhang and Suen 1984).
//
// Written by hand because OpenCV's thinning (cv::ximgproc::thinning) lives in opencv_contrib, whose
// Debian package pulls about 150 packages (VTK, Qt) into every setup for this one function.

#include <opencv2/core.hpp>

namespace pena::line_map::internal {

// The skeleton of `binary` (CV_8UC1, nonzero = foreground) as CV_8UC1 of 0/1, same size: Zhang-Suen
// thinning, then staircase corners removed so that pixels inside a line have exactly two
// 8-neighbours. Connectivity of each foreground component is preserved. Throws
// std::invalid_argument if `binary` is not CV_8UC1.
cv::Mat Skeletonize(const cv::Mat& binary);

}  // namespace pena::line_map::internal
