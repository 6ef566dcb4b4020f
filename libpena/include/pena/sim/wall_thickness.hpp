#pragma once
// Walls as the laser meets them in a real building: a slab of some thickness, whose door jambs
// face along the corridor. The scenarios draw walls as lines; the simulator can give the laser
// (and the observed walls) boxes around those lines instead (SimulationOptions::wall_thickness_m).

#include <cstddef>
#include <vector>

#include "pena/geometry/segment2.hpp"

namespace pena::sim {

// Each wall becomes this many faces, in this order: the face on its left (seen from start to
// end), the face on its right, the cap at its start, the cap at its end.
inline constexpr std::size_t kFacesPerThickWall = 4;

// The faces of boxes `thickness_m` thick centred on the walls, each box reaching thickness_m / 2
// past both ends of its wall so that walls meeting at a corner close it. Face i belongs to wall
// i / kFacesPerThickWall. A wall of zero length becomes a square of side thickness_m.
std::vector<geometry::Segment2> ThickWallFaces(const std::vector<geometry::Segment2>& walls,
                                               double thickness_m);

}  // namespace pena::sim
