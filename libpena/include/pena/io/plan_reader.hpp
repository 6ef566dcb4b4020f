#pragma once
// A priori plans (fire brigades' building plans) read as wall segments: line CSV, SVG or DXF
// (docs/formats.md, "Plans").

#include <filesystem>
#include <vector>

#include "pena/geometry/pose2.hpp"
#include "pena/geometry/segment2.hpp"

namespace pena::io {

// How a plan's drawing units map into the mission frame.
struct PlanOptions {
  double unit_scale_m = 1.0;            // metres per drawing unit (mm drawings: 0.001)
  geometry::Pose2 mission_from_plan{};  // applied after the scale, metres and radians
};

// Throws std::invalid_argument naming the field and its unit, e.g.
// "plan.unit_scale_m must be > 0 and finite (m per drawing unit), got 0".
void ValidatePlanOptions(const PlanOptions& options);

// Reads an a priori plan (line CSV, SVG or DXF by extension; docs/formats.md, "Plans") scaled by
// unit_scale_m and mapped by mission_from_plan: segments in the mission frame, metres. Throws
// InputError "path:line: what" on bad files and std::invalid_argument on bad options.
std::vector<geometry::Segment2> ReadPlan(const std::filesystem::path& path,
                                         const PlanOptions& options = {});

}  // namespace pena::io
