#include "pena/line_map/line_extractor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "extract_steps.hpp"
#include "skeleton.hpp"
#include "pena/options_check.hpp"

namespace pena::line_map {

namespace {

using internal::GridFrame;
using internal::Piece;

void Require(bool ok, const char* field, const char* rule, double value) {
  RequireOption(ok, "line_extraction", field, rule, value);
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

// Per segment: what supports it (the cells, their hits, the scans that last hit them).
struct Support {
  double cells = 0.0;
  double hits = 0.0;
  double sum_sq_m2 = 0.0;
  std::vector<std::int32_t> scans;
};

// Each occupied cell within the split distance supports the segment of its nearest skeleton
// pixel (a discrete Voronoi diagram of the skeleton); its distance to the line gives the RMS.
std::vector<Support> SupportOf(const std::vector<Piece>& pieces, const grid::GridImage& grid,
                               const cv::Mat& occupied, const cv::Mat& owners,
                               const GridFrame& frame) {
  const bool has_hits = grid.hit_counts.size() == grid.occupancy.size();
  const bool has_scans = grid.first_hit_scans.size() == grid.occupancy.size() &&
                         grid.last_hit_scans.size() == grid.occupancy.size();
  std::vector<Support> support(pieces.size());
  std::vector<cv::Point> cells;
  cv::findNonZero(occupied, cells);
  for (const cv::Point& cell : cells) {
    const int s = owners.at<std::int32_t>(cell);
    if (s < 0) continue;
    Support& of = support[static_cast<std::size_t>(s)];
    of.cells += 1.0;
    // The grid image may hold no hit counts: each occupied cell was hit at least once.
    of.hits += has_hits ? grid.hit_counts.at<std::uint16_t>(cell) : 1.0;
    if (has_scans) {
      of.scans.push_back(grid.first_hit_scans.at<std::int32_t>(cell));
      of.scans.push_back(grid.last_hit_scans.at<std::int32_t>(cell));
    }
    const double d_m =
        geometry::DistanceToSegment(pieces[static_cast<std::size_t>(s)].fit.segment,
                                    frame.ToWorld(cell));
    of.sum_sq_m2 += d_m * d_m;
  }
  return support;
}

// How many different scans first or last hit the supporting cells: a lower bound of the scans that
// hit them, exact up to 2 (one scan alone leaves first == last everywhere).
std::size_t DistinctScans(std::vector<std::int32_t> scans) {
  std::sort(scans.begin(), scans.end());
  scans.erase(std::unique(scans.begin(), scans.end()), scans.end());
  std::erase(scans, 0);
  return scans.size();
}

// The segments with their support; those resting on fewer than min_scans scans are dropped
// (floor reflections, see LineExtractionOptions::min_scans).
std::vector<LineSegment> WithSupport(const std::vector<Piece>& pieces,
                                     const std::vector<Support>& support,
                                     const grid::GridImage& grid, int min_scans) {
  const bool has_scans = grid.first_hit_scans.size() == grid.occupancy.size() &&
                         grid.last_hit_scans.size() == grid.occupancy.size();
  std::vector<LineSegment> segments;
  for (std::size_t s = 0; s < pieces.size(); ++s) {
    if (has_scans && min_scans > 1 &&
        DistinctScans(support[s].scans) < static_cast<std::size_t>(min_scans)) {
      continue;
    }
    LineSegment segment;
    segment.id = static_cast<std::int64_t>(segments.size());
    segment.segment = pieces[s].fit.segment;
    segment.support_cells = support[s].cells;
    segment.observations = support[s].hits;
    if (support[s].cells > 0.0) {
      segment.rms_error_m = std::sqrt(support[s].sum_sq_m2 / support[s].cells);
    }
    segments.push_back(std::move(segment));
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
  Require(o.min_scans >= 0, "min_scans", ">= 0 (scans)", o.min_scans);
}

std::vector<LineSegment> ExtractLines(const grid::GridImage& grid,
                                      const LineExtractionOptions& options) {
  ValidateLineExtractionOptions(options);
  if (grid.occupancy.type() != CV_8UC1) {
    throw std::invalid_argument("line_extraction: grid.occupancy must be CV_8UC1");
  }
  Require(grid.resolution_m > 0.0 && std::isfinite(grid.resolution_m), "grid.resolution_m",
          "> 0 m and finite", grid.resolution_m);
  const auto check_layer = [&grid](const cv::Mat& layer, int type, const char* what) {
    if (!layer.empty() && (layer.type() != type || layer.size() != grid.occupancy.size())) {
      throw std::invalid_argument(std::string("line_extraction: grid.") + what +
                                  " must be empty or match occupancy in size, with its type");
    }
  };
  check_layer(grid.hit_counts, CV_16UC1, "hit_counts");
  check_layer(grid.first_hit_scans, CV_32SC1, "first_hit_scans");
  check_layer(grid.last_hit_scans, CV_32SC1, "last_hit_scans");
  if (grid.occupancy.empty()) return {};
  const GridFrame frame{grid.origin_m, grid.resolution_m, grid.occupancy.rows};
  const cv::Mat occupied = Threshold(grid.occupancy, options.occupied_probability);
  const cv::Mat closed = Close(occupied, Cells(options.closing_radius_m, grid.resolution_m));
  const cv::Mat walls = RemoveSpeckle(closed, options.min_blob_m / grid.resolution_m);
  const cv::Mat skeleton = PrunedSkeleton(walls, options.min_length_m / grid.resolution_m);
  std::vector<Piece> pieces = StraightPieces(skeleton, frame, options);
  const cv::Mat owners = internal::PieceOwners(pieces, skeleton, frame, options.split_distance_m);
  internal::ExtendEnds(pieces, occupied, owners, frame, options.merge_gap_m,
                       options.merge_angle_rad);
  const std::vector<Support> support = SupportOf(pieces, grid, occupied, owners, frame);
  return WithSupport(pieces, support, grid, options.min_scans);
}

}  // namespace pena::line_map
