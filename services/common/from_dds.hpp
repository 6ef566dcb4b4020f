#pragma once
// DDS -> libpena: every conversion from the IDL types (idl/dds/*.idl) to PeNa's types. A sample
// of another schema_version throws std::invalid_argument naming the type and both versions.

#include <string>

#include "pena/geometry/pose2.hpp"
#include "pena/line_map/map_delta.hpp"
#include "pena/pipeline/entity_pipeline.hpp"
#include "pena/sensors/laser_scan.hpp"
#include "pena_dds/correction.h"
#include "pena_dds/entity.h"
#include "pena_dds/global_map.h"
#include "pena_dds/line_map.h"
#include "pena_dds/scan.h"

namespace pena::services {

geometry::Pose2 FromDds(const pena_dds::Pose2& pose);
line_map::LineSegment FromDds(const pena_dds::Segment& segment);
line_map::MapDelta FromDds(const pena_dds::LineMapDelta& delta);
line_map::MapSnapshot FromDds(const pena_dds::LineMapSnapshot& snapshot);
line_map::MapDelta FromDds(const pena_dds::GlobalMapDelta& delta);
line_map::MapSnapshot FromDds(const pena_dds::GlobalMapSnapshot& snapshot);
pipeline::Correction FromDds(const pena_dds::Correction& correction);
// The scan in its laser frame (ranges dequantised; 0 becomes LaserScan::kNoReturn).
sensors::LaserScan FromDds(const pena_dds::ReferenceScan& scan);

// Throws std::invalid_argument if `version` is not pena_dds::SCHEMA_VERSION.
void CheckSchemaVersion(std::uint32_t version, const char* type_name);

}  // namespace pena::services
