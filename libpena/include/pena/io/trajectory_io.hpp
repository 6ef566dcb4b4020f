#pragma once
// Trajectories as TUM text and relations as Freiburg .relations text (docs/formats.md).

#include <filesystem>
#include <vector>

#include "pena/geometry/trajectory.hpp"

namespace pena::io {

// "timestamp x y z qx qy qz qw" per line; z = 0 and the quaternion is the yaw about +z.
// Timestamps are printed with 6 decimals, so input scan stamps come back unchanged.
void WriteTum(const std::filesystem::path& path, const geometry::Trajectory& trajectory);
// Reads a TUM file, keeping x, y and the yaw of the quaternion. Throws InputError.
geometry::Trajectory ReadTum(const std::filesystem::path& path);

// "t1 t2 dx dy dz roll pitch yaw" per line (metres, radians).
void WriteRelations(const std::filesystem::path& path,
                    const std::vector<geometry::Relation>& relations);
// Reads a .relations file, keeping dx, dy, yaw. Throws InputError.
std::vector<geometry::Relation> ReadRelations(const std::filesystem::path& path);

}  // namespace pena::io
