#pragma once
// Occupancy grid images drawn in code: walls, rooms with doors, noise, for line-extraction tests.

#include <cstdint>
#include <vector>

#include "pena/geometry/segment2.hpp"
#include "pena/grid/grid_image.hpp"

namespace pena::line_map::testing {

// A grid of `value` cells (default unknown, 128) with its bottom-left corner at `origin_m`.
grid::GridImage BlankGrid(const Eigen::Vector2d& origin_m, const Eigen::Vector2d& size_m,
                          double resolution_m, std::uint8_t value = 128);

// Draws `segment` (world frame, metres) with `value`, `thickness_cells` wide.
void DrawSegment(grid::GridImage& grid, const geometry::Segment2& segment, std::uint8_t value,
                 int thickness_cells);

// Fills the axis-aligned rectangle [min_m, max_m] with `value` (free space of a room).
void FillRect(grid::GridImage& grid, const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m,
              std::uint8_t value);

// The wall from `from_m` to `to_m` as two segments with a door gap of `door_m` centred in it
// (one segment when door_m is 0).
std::vector<geometry::Segment2> WallWithDoor(const Eigen::Vector2d& from_m,
                                             const Eigen::Vector2d& to_m, double door_m);

// A building of `rooms_x` x `rooms_y` rooms of `room_m` metres with doors, walls drawn
// `thickness_cells` wide, rooms free, outside unknown; doors in the bottom wall of every room and
// the left wall of every room but the leftmost; `walls` receives the true walls.
grid::GridImage Building(int rooms_x, int rooms_y, double room_m, double door_m,
                         double resolution_m, int thickness_cells,
                         std::vector<geometry::Segment2>* walls);

}  // namespace pena::line_map::testing
