#include "pena/line_map/line_extractor.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "extract_steps.hpp"
#include "skeleton.hpp"

namespace pena::line_map {

namespace {

using internal::GridFrame;
using internal::Piece;

void Require(bool ok, const char* field, const char* rule, double value) {
  if (!ok) {
    throw std::invalid_argument(std::string("line_extraction.") + field + " must be " + rule +
                                ", got " + std::to_string(value));
  }
}

int Cells(double length_m, double resolution_m) {
  return static_cast<int>(std::lround(length_m / resolution_m));
}

// Paper section 3: "thresholding into a binary image". Floor reflections are weak (few hits among
// many misses) or cleared by later beams, so they stay below the occupied probability.
cv::Mat Threshold(const cv::Mat& occupancy, double occupied_probability) {
  cv::Mat occupied;
  cv::threshold(occupancy, occupied, occupied_probability * 255.0, 255.0, cv::THRESH_BINARY);
  return occupied;
}

// "Morphological closing (dilation followed by erosion) to join split obstacles". The erosion
// disk is one cell smaller than the dilation disk: with equal digital disks the one-cell tip of
// the disk slips between the dots of a one-cell-thin dotted wall (a wall seen at a grazing angle,
// partly cleared by later beams), so a true closing never joins it. With the smaller erosion,
// dots up to 2 * radius cells apart join in every direction; the wall comes out a cell thicker
// on each side, which the skeleton removes again.
cv::Mat Close(const cv::Mat& occupied, int radius_cells) {
  if (radius_cells <= 0) return occupied.clone();
  cv::Mat dilated, closed;
  cv::dilate(occupied, dilated, cv::getStructuringElement(cv::MORPH_ELLIPSE,
                                                          cv::Size(2 * radius_cells + 1,
                                                                   2 * radius_cells + 1)));
  cv::erode(dilated, closed, cv::getStructuringElement(cv::MORPH_ELLIPSE,
                                                       cv::Size(2 * radius_cells - 1,
                                                                2 * radius_cells - 1)));
  return closed;
}

// Drops blobs whose bounding-box diagonal is under `min_blob_cells`: speckle would only add
// skeleton stubs.
cv::Mat RemoveSpeckle(const cv::Mat& walls, double min_blob_cells) {
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(walls, labels, stats, centroids, 8, CV_32S);
  std::vector<std::uint8_t> keep(static_cast<std::size_t>(count), 0);
  for (int label = 1; label < count; ++label) {
    const double diagonal = std::hypot(stats.at<int>(label, cv::CC_STAT_WIDTH),
                                       stats.at<int>(label, cv::CC_STAT_HEIGHT));
    keep[static_cast<std::size_t>(label)] = diagonal >= min_blob_cells ? 255 : 0;
  }
  cv::Mat kept(walls.size(), CV_8UC1);
  for (int r = 0; r < walls.rows; ++r) {
    const int* label_row = labels.ptr<int>(r);
    std::uint8_t* out = kept.ptr<std::uint8_t>(r);
    for (int c = 0; c < walls.cols; ++c) out[c] = keep[static_cast<std::size_t>(label_row[c])];
  }
  return kept;
}

// "A skeleton of the filtered image", without the short spurs that speckle next to a wall leaves
// (they would cut the wall's chain at a junction). Thinning again after pruning removes the
// corners that a cleared spur leaves at its junction. A few rounds: pruning can expose spurs.
cv::Mat PrunedSkeleton(const cv::Mat& walls, double max_spur_px) {
  cv::Mat skeleton = internal::Skeletonize(walls);
  for (int round = 0; round < 3 && internal::PruneSpurs(skeleton, max_spur_px); ++round) {
    skeleton = internal::Skeletonize(skeleton);
  }
  return skeleton;
}

// Skeleton chains cut into straight pieces, merged across junctions, short ones dropped.
std::vector<Piece> StraightPieces(const cv::Mat& skeleton, const GridFrame& frame,
                                  const LineExtractionOptions& options) {
  std::vector<Piece> pieces;
  for (const internal::PixelChain& chain : internal::TraceChains(skeleton)) {
    for (Piece& piece : internal::SplitChain(chain, frame, options.split_distance_m)) {
      pieces.push_back(std::move(piece));
    }
  }
  pieces = internal::MergeCollinear(std::move(pieces), frame, options.merge_gap_m,
                                    options.merge_angle_rad, options.split_distance_m);
  std::erase_if(pieces, [&options](const Piece& piece) {
    return geometry::Length(piece.fit.segment) < options.min_length_m;
  });
  return pieces;
}

// Each occupied cell within the split distance supports the segment of its nearest skeleton
// pixel (a discrete Voronoi diagram of the skeleton); its distance to the line gives the RMS.
std::vector<LineSegment> WithSupport(const std::vector<Piece>& pieces, const cv::Mat& occupied,
                                     const cv::Mat& skeleton, const GridFrame& frame,
                                     double split_distance_m) {
  cv::Mat off_skeleton, distance_px, labels;
  cv::compare(skeleton, 0, off_skeleton, cv::CMP_EQ);
  cv::distanceTransform(off_skeleton, distance_px, labels, cv::DIST_L2, cv::DIST_MASK_5,
                        cv::DIST_LABEL_PIXEL);
  std::vector<int> segment_of_label(static_cast<std::size_t>(cv::countNonZero(skeleton)) + 1, -1);
  for (std::size_t s = 0; s < pieces.size(); ++s) {
    for (const cv::Point& pixel : pieces[s].pixels) {
      segment_of_label[static_cast<std::size_t>(labels.at<int>(pixel))] = static_cast<int>(s);
    }
  }
  std::vector<LineSegment> segments(pieces.size());
  std::vector<double> sum_sq_m2(pieces.size(), 0.0);
  std::vector<cv::Point> cells;
  cv::findNonZero(occupied, cells);
  for (const cv::Point& cell : cells) {
    if (distance_px.at<float>(cell) * frame.resolution_m > split_distance_m) continue;
    const int s = segment_of_label[static_cast<std::size_t>(labels.at<int>(cell))];
    if (s < 0) continue;
    const auto index = static_cast<std::size_t>(s);
    segments[index].support_cells += 1.0;
    const double d_m = geometry::DistanceToSegment(pieces[index].fit.segment, frame.ToWorld(cell));
    sum_sq_m2[index] += d_m * d_m;
  }
  for (std::size_t s = 0; s < pieces.size(); ++s) {
    segments[s].id = static_cast<std::int64_t>(s);
    segments[s].segment = pieces[s].fit.segment;
    // The grid image holds no hit counts; each occupied cell was hit at least once.
    segments[s].observations = segments[s].support_cells;
    if (segments[s].support_cells > 0.0) {
      segments[s].rms_error_m = std::sqrt(sum_sq_m2[s] / segments[s].support_cells);
    }
  }
  return segments;
}

}  // namespace

void ValidateLineExtractionOptions(const LineExtractionOptions& o) {
  Require(o.occupied_probability > 0.0 && o.occupied_probability < 1.0, "occupied_probability",
          "in (0, 1)", o.occupied_probability);
  Require(o.closing_radius_m >= 0.0 && std::isfinite(o.closing_radius_m), "closing_radius_m",
          ">= 0 m and finite", o.closing_radius_m);
  Require(o.min_blob_m >= 0.0 && std::isfinite(o.min_blob_m), "min_blob_m", ">= 0 m and finite",
          o.min_blob_m);
  Require(o.split_distance_m > 0.0 && std::isfinite(o.split_distance_m), "split_distance_m",
          "> 0 m and finite", o.split_distance_m);
  Require(o.merge_gap_m >= 0.0 && std::isfinite(o.merge_gap_m), "merge_gap_m", ">= 0 m and finite",
          o.merge_gap_m);
  Require(o.merge_angle_rad >= 0.0 && o.merge_angle_rad <= std::numbers::pi / 2, "merge_angle_rad",
          "in [0, pi/2] rad", o.merge_angle_rad);
  Require(o.min_length_m >= 0.0 && std::isfinite(o.min_length_m), "min_length_m",
          ">= 0 m and finite", o.min_length_m);
}

std::vector<LineSegment> ExtractLines(const grid::GridImage& grid,
                                      const LineExtractionOptions& options) {
  ValidateLineExtractionOptions(options);
  if (grid.occupancy.type() != CV_8UC1) {
    throw std::invalid_argument("line_extraction: grid.occupancy must be CV_8UC1");
  }
  Require(grid.resolution_m > 0.0 && std::isfinite(grid.resolution_m), "grid.resolution_m",
          "> 0 m and finite", grid.resolution_m);
  if (grid.occupancy.empty()) return {};
  const GridFrame frame{grid.origin_m, grid.resolution_m, grid.occupancy.rows};
  const cv::Mat occupied = Threshold(grid.occupancy, options.occupied_probability);
  const cv::Mat closed = Close(occupied, Cells(options.closing_radius_m, grid.resolution_m));
  const cv::Mat walls = RemoveSpeckle(closed, options.min_blob_m / grid.resolution_m);
  const cv::Mat skeleton = PrunedSkeleton(walls, options.min_length_m / grid.resolution_m);
  const std::vector<Piece> pieces = StraightPieces(skeleton, frame, options);
  return WithSupport(pieces, occupied, skeleton, frame, options.split_distance_m);
}

}  // namespace pena::line_map
