#pragma once
// libpena -> DDS: every conversion from PeNa's types to the IDL types (idl/dds/*.idl). Values
// that do not fit the IDL's bounds throw std::length_error naming the field; everything a
// LineMap produces (quantised) converts exactly.

#include <cstdint>
#include <string>

#include "pena/geometry/pose2.hpp"
#include "pena/line_map/map_delta.hpp"
#include "pena/pipeline/entity_pipeline.hpp"
#include "pena/sensors/entity.hpp"
#include "pena/sensors/laser_scan.hpp"
#include "pena_dds/correction.h"
#include "pena_dds/entity.h"
#include "pena_dds/global_map.h"
#include "pena_dds/line_map.h"
#include "pena_dds/scan.h"

namespace pena::services {

pena_dds::Pose2 ToDds(const geometry::Pose2& pose);
pena_dds::EntityKind ToDds(sensors::EntityKind kind);
pena_dds::PoseStatus ToDds(odometry::MatchStatus status);
// One segment; throws std::length_error (provenance) or std::invalid_argument (not quantised).
pena_dds::Segment ToDds(const line_map::LineSegment& segment);

// An entity's line-map change (`stamp_s`: mission time).
pena_dds::LineMapDelta ToDdsLineMapDelta(const line_map::MapDelta& delta,
                                         const std::string& entity_id, double stamp_s);
// An entity's whole line map.
pena_dds::LineMapSnapshot ToDdsLineMapSnapshot(const line_map::MapSnapshot& snapshot,
                                               const std::string& entity_id, double stamp_s);
// The global map's change.
pena_dds::GlobalMapDelta ToDdsGlobalMapDelta(const line_map::MapDelta& delta,
                                             const std::string& map_id, double stamp_s);
// The whole global map.
pena_dds::GlobalMapSnapshot ToDdsGlobalMapSnapshot(const line_map::MapSnapshot& snapshot,
                                                   const std::string& map_id, double stamp_s);

// The pose of a scan step; seq counts the entity's poses from 1.
pena_dds::EntityPose ToDdsPose(const pipeline::ScanStep& step, const std::string& entity_id,
                               std::uint64_t seq, std::uint64_t local_map_version,
                               std::uint64_t correction_seq);
// A reference scan with its poses, ranges in whole `range_quantum_m` units (0 = no return;
// ranges beyond 65535 quanta become no-returns).
pena_dds::ReferenceScan ToDdsReferenceScan(const sensors::LaserScan& scan,
                                           const pipeline::ScanStep& step,
                                           const std::string& entity_id, std::uint64_t seq,
                                           std::uint64_t local_map_version,
                                           double range_quantum_m);
// A correction for `entity_id`.
pena_dds::Correction ToDdsCorrection(const pipeline::Correction& correction,
                                     const std::string& entity_id, std::uint64_t seq,
                                     std::uint64_t for_version, std::uint64_t reference_seq);

// Copies `text` into a bounded IDL string; throws std::length_error naming `field` if too long.
template <std::size_t N>
void SetBounded(eprosima::fastrtps::fixed_string<N>& out, const std::string& text,
                const char* field) {
  if (text.size() > N) {
    throw std::length_error(std::string(field) + " holds at most " + std::to_string(N) +
                            " characters, got " + std::to_string(text.size()) + " ('" + text +
                            "')");
  }
  out = text;
}

}  // namespace pena::services
