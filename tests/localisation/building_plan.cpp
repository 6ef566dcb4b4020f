#include "building_plan.hpp"

namespace pena::localisation::testing {
namespace {

// A wall from a to b with a 1 m door in its middle.
void WallWithDoor(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                  std::vector<geometry::Segment2>& out) {
  const Eigen::Vector2d middle = 0.5 * (a + b);
  const Eigen::Vector2d half_door = 0.5 * (b - a).normalized();
  out.push_back({a, middle - half_door});
  out.push_back({middle + half_door, b});
}

}  // namespace

std::vector<geometry::Segment2> RoomGrid(int rows, int cols, double room_m) {
  std::vector<geometry::Segment2> plan;
  for (int r = 0; r <= rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      WallWithDoor({c * room_m, r * room_m}, {(c + 1) * room_m, r * room_m}, plan);
    }
  }
  for (int c = 0; c <= cols; ++c) {
    for (int r = 0; r < rows; ++r) {
      WallWithDoor({c * room_m, r * room_m}, {c * room_m, (r + 1) * room_m}, plan);
    }
  }
  return plan;
}

Eigen::Vector2d RoomCentre(int row, int col, double room_m) {
  return {(col + 0.5) * room_m, (row + 0.5) * room_m};
}

}  // namespace pena::localisation::testing
