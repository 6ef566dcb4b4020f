#pragma once
// A room with furniture, scanned from any pose with an ideal 361-beam laser.

#include <random>
#include <vector>

#include "pena/geometry/segment2.hpp"
#include "pena/scan_matching/point_set.hpp"

namespace pena::testing {

// An 8 m x 5 m room with a door gap, a pillar and a cabinet (walls in the world frame).
std::vector<geometry::Segment2> SyntheticRoom();

// Points of a 180 deg, 361-beam scan from world_from_laser, in the laser frame, with Gaussian
// range noise of noise_m.
scan_matching::Points2 ScanRoom(const std::vector<geometry::Segment2>& walls,
                                const geometry::Pose2& world_from_laser, double noise_m,
                                std::mt19937& rng);

}  // namespace pena::testing
