#pragma once
// A procedural building-like plan for tests and benchmarks: a grid of rooms with a door in every
// wall, so rays end on nearby walls as they do in a real floor.

#include <Eigen/Core>
#include <vector>

#include "pena/geometry/segment2.hpp"

namespace pena::localisation::testing {

// rows x cols rooms of room_m x room_m; every wall between two corners has a 1 m door in its
// middle (two segments). 4 * rows * cols + 2 * (rows + cols) segments.
std::vector<geometry::Segment2> RoomGrid(int rows, int cols, double room_m);

// The centre of room (row, col) of RoomGrid.
Eigen::Vector2d RoomCentre(int row, int col, double room_m);

}  // namespace pena::localisation::testing
