#pragma once
// Occupancy grids as a ROS map_server pair: stem.pgm (binary P5) and stem.yaml (its metadata).

#include <filesystem>

#include "pena/grid/grid_image.hpp"

namespace pena::io {

// map_server's trinary thresholds on p = (255 - pixel) / 255 (negate 0), written in every yaml.
inline constexpr double kRosOccupiedThreshold = 0.65;
inline constexpr double kRosFreeThreshold = 0.196;

// Writes `path_stem`.pgm and `path_stem`.yaml (the stem's own dots are kept). Cells are written in
// map_server's trinary form: occupancy > 0.65 * 255 -> 0 (occupied), < 0.196 * 255 -> 254 (free),
// else 205 (unknown); the yaml holds image (file name, relative), resolution, origin [x, y, 0],
// negate 0, occupied_thresh 0.65, free_thresh 0.196, mode trinary. Throws std::invalid_argument
// for an empty or non-CV_8UC1 image or a non-finite resolution or origin, std::runtime_error
// naming the file when it cannot be written.
void WriteRosMap(const std::filesystem::path& path_stem, const grid::GridImage& image);

// Reads a map_server yaml and the P5 PGM it names (relative to the yaml's folder) into an image of
// 0 (free), 255 (occupied) and 128 (unknown) using the yaml's thresholds and negate flag. Throws
// InputError naming the file and line for a missing or malformed field, a rotated origin, mode
// raw, or a PGM that is not binary P5 or is truncated.
grid::GridImage ReadRosMap(const std::filesystem::path& yaml_path);

}  // namespace pena::io
