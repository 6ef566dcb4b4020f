#pragma once
// The vector half of line extraction: skeleton pixels -> chains -> straight pieces -> fitted lines.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "pena/geometry/segment2.hpp"

namespace pena::line_map::internal {

// Pixel (col, row) of a grid image to the world position of the cell centre, metres.
struct GridFrame {
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();
  double resolution_m = 0.05;
  int rows = 0;

  Eigen::Vector2d ToWorld(const cv::Point& pixel) const {
    return {origin_m.x() + (pixel.x + 0.5) * resolution_m,
            origin_m.y() + (rows - pixel.y - 0.5) * resolution_m};
  }
};

// Skeleton pixels in path order. A closed loop repeats its first pixel at the end.
using PixelChain = std::vector<cv::Point>;

// The paths of a skeleton (CV_8UC1 of 0/1, as Skeletonize makes it) between endpoints and
// junctions, junction pixels included at both ends; plus closed loops without junctions.
std::vector<PixelChain> TraceChains(const cv::Mat& skeleton);

// Clears from `skeleton` the chains that run from an endpoint to a junction and are shorter than
// `max_spur_px` pixels (such spurs come from speckle next to a wall); the junction pixel stays.
// Returns whether anything was cleared.
bool PruneSpurs(cv::Mat& skeleton, double max_spur_px);

// A total-least-squares line through points, world frame, metres.
struct LineFit {
  geometry::Segment2 segment;    // the line between the extreme projections of the points
  double max_deviation_m = 0.0;  // largest point-to-line distance
};

// Fits the principal axis through `points_m` (at least one point).
LineFit FitLine(const std::vector<Eigen::Vector2d>& points_m);

// A straight part of the skeleton: its pixels and their fit.
struct Piece {
  std::vector<cv::Point> pixels;
  LineFit fit;
};

// Recursive splitting (Douglas-Peucker) of one chain where it leaves its chord by more than
// `split_distance_m`; each piece is fitted. Split pixels belong to both neighbouring pieces.
std::vector<Piece> SplitChain(const PixelChain& chain, const GridFrame& frame,
                              double split_distance_m);

// Merges pieces whose ends are within `gap_m`, whose directions differ by at most `angle_rad`
// and whose fitted ends all lie within split_distance_m / 2 of their joint fit; repeats until
// none merge.
std::vector<Piece> MergeCollinear(std::vector<Piece> pieces, const GridFrame& frame, double gap_m,
                                  double angle_rad, double split_distance_m);

// Per pixel (CV_32SC1, the skeleton's size): the index of the piece owning the nearest skeleton
// pixel when that pixel is within `max_distance_m`, else -1. A discrete Voronoi diagram of the
// skeleton; where pieces share a pixel (a split or junction), the later piece owns it.
cv::Mat PieceOwners(const std::vector<Piece>& pieces, const cv::Mat& skeleton,
                    const GridFrame& frame, double max_distance_m);

// Moves each piece's fitted ends outwards along its line over the occupied cells that continue it
// (within one cell of the line, gaps up to `gap_m`), stopping before cells owned by another piece
// whose direction is within `angle_rad` (its own wall). Thinning and the closing shorten a wall
// at its ends and at junctions; sparse dots of a wall seen at a grazing angle continue it.
void ExtendEnds(std::vector<Piece>& pieces, const cv::Mat& occupied, const cv::Mat& owners,
                const GridFrame& frame, double gap_m, double angle_rad);

}  // namespace pena::line_map::internal
