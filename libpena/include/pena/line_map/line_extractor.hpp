#pragma once
// Line extraction from an occupancy grid (paper section 3): threshold, morphological closing,
// skeleton, skeleton chains split into straight pieces, a least-squares line per piece.
// Steps, defaults and measured figures: docs/line-extraction.md.

#include <vector>

#include "pena/grid/grid_image.hpp"
#include "pena/line_map/line_segment.hpp"

namespace pena::line_map {

// Tuning of ExtractLines; defaults suit a 5 cm laser grid of a building.
struct LineExtractionOptions {
  // Cells with occupancy probability above this are walls; weak, sparse floor reflections and
  // unknown cells (0.5) fall below it. Unitless, in (0, 1).
  double occupied_probability = 0.65;
  // Radius of the closing's dilation disk (its erosion disk is one cell smaller): dotted walls
  // with dots up to twice this apart are joined. Metres, >= 0 (0 = no closing).
  double closing_radius_m = 0.10;
  // Occupied blobs (after closing) whose bounding-box diagonal is below this are speckle and
  // dropped before the skeleton. Metres, >= 0.
  double min_blob_m = 0.20;
  // A skeleton chain is split where it deviates more than this from the chord (Douglas-Peucker);
  // pieces merge only if their fitted ends lie within half of it of the joint fit. Metres, > 0.
  double split_distance_m = 0.10;
  // Pieces whose ends are at most this far apart (e.g. across a skeleton junction left by a
  // speckle next to a wall) merge when collinear. Metres, >= 0.
  double merge_gap_m = 0.15;
  // Collinearity limit for that merge. Radians, in [0, pi/2].
  double merge_angle_rad = 0.0873;  // 5 deg
  // Segments shorter than this are dropped. Metres, >= 0.
  double min_length_m = 0.30;
  // Different scans that must hit a segment's cells (a floor reflection is one tilted scan's hits;
  // needs GridImage's first/last scan records). 0 or 1 = off.
  int min_scans = 2;
};

// Throws std::invalid_argument naming the field and its unit when an option is out of range.
void ValidateLineExtractionOptions(const LineExtractionOptions& options);

// The walls of `grid` as segments in the grid's (world) frame, metres, ids 0..n-1, with support,
// observations (hit_counts, else one per cell) and RMS fit error. Throws std::invalid_argument
// for invalid options or a grid that is not CV_8UC1 with resolution_m > 0.
std::vector<LineSegment> ExtractLines(const grid::GridImage& grid,
                                      const LineExtractionOptions& options = {});

}  // namespace pena::line_map
