#include "dds_sample_bounds.hpp"

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <fastcdr/exceptions/Exception.h>

#include <cstdint>
#include <string>

#include "pena_dds/common.h"

namespace pena::services {
namespace {

using eprosima::fastcdr::Cdr;
using eprosima::fastrtps::rtps::SerializedPayload_t;

// A list longer than its bound: the walk stops there.
struct OverBound {};

// Reads (and drops) one field of type T, aligned as CDR aligns it.
template <class T>
void Skip(Cdr& cdr) {
  T value{};
  cdr >> value;
}

// A list's length, refused beyond `max`.
std::uint32_t Length(Cdr& cdr, std::uint32_t max) {
  std::uint32_t length = 0;
  cdr >> length;
  if (length > max) throw OverBound{};
  return length;
}

// common.idl's Segment, field by field.
void WalkSegment(Cdr& cdr) {
  Skip<std::int64_t>(cdr);  // id
  for (int i = 0; i < 4; ++i) Skip<std::int32_t>(cdr);  // start and end, mm
  Skip<std::uint64_t>(cdr);  // support_cells
  Skip<std::uint64_t>(cdr);  // observations
  Skip<std::uint32_t>(cdr);  // rms_error_100um
  const std::uint32_t entries = Length(cdr, pena_dds::PROVENANCE_MAX);
  for (std::uint32_t i = 0; i < entries; ++i) Skip<std::string>(cdr);
  Skip<std::uint16_t>(cdr);  // seen_by_entities
  Skip<std::uint16_t>(cdr);  // error_sd_cm
}

void WalkSegments(Cdr& cdr, std::uint32_t max) {
  const std::uint32_t count = Length(cdr, max);
  for (std::uint32_t i = 0; i < count; ++i) WalkSegment(cdr);
}

// Runs `walk` over the payload's CDR after its encapsulation header, as the generated
// deserializer reads it; false if a list is over its bound or the payload ends first.
template <class Walk>
bool Walks(SerializedPayload_t& payload, Walk walk) {
  try {
    eprosima::fastcdr::FastBuffer buffer(reinterpret_cast<char*>(payload.data), payload.length);
    Cdr cdr(buffer, Cdr::DEFAULT_ENDIAN, Cdr::DDS_CDR);
    cdr.read_encapsulation();
    walk(cdr);
    return true;
  } catch (const OverBound&) {
    return false;
  } catch (const eprosima::fastcdr::exception::Exception&) {
    return false;
  }
}

// The header shared by both deltas: id, schema_version, stamp_s, from_version, to_version.
void SkipDeltaHeader(Cdr& cdr) {
  Skip<std::string>(cdr);
  Skip<std::uint32_t>(cdr);
  Skip<double>(cdr);
  Skip<std::uint64_t>(cdr);
  Skip<std::uint64_t>(cdr);
}

// The header shared by both snapshots: id, schema_version, stamp_s, version, next_id.
void SkipSnapshotHeader(Cdr& cdr) {
  Skip<std::string>(cdr);
  Skip<std::uint32_t>(cdr);
  Skip<double>(cdr);
  Skip<std::uint64_t>(cdr);
  Skip<std::int64_t>(cdr);
}

}  // namespace

bool SampleKeepsBounds(SerializedPayload_t& payload, const pena_dds::LineMapDelta* /*type*/) {
  return Walks(payload, [](Cdr& cdr) {
    SkipDeltaHeader(cdr);
    WalkSegments(cdr, pena_dds::DELTA_MAX_SEGMENTS);  // added
    WalkSegments(cdr, pena_dds::DELTA_MAX_SEGMENTS);  // changed
  });
}

bool SampleKeepsBounds(SerializedPayload_t& payload, const pena_dds::LineMapSnapshot* /*type*/) {
  return Walks(payload, [](Cdr& cdr) {
    SkipSnapshotHeader(cdr);
    WalkSegments(cdr, pena_dds::SNAPSHOT_MAX_SEGMENTS);
  });
}

bool SampleKeepsBounds(SerializedPayload_t& payload, const pena_dds::GlobalMapDelta* /*type*/) {
  return Walks(payload, [](Cdr& cdr) {
    SkipDeltaHeader(cdr);
    WalkSegments(cdr, pena_dds::GLOBAL_DELTA_MAX_SEGMENTS);  // added
    WalkSegments(cdr, pena_dds::GLOBAL_DELTA_MAX_SEGMENTS);  // changed
  });
}

bool SampleKeepsBounds(SerializedPayload_t& payload, const pena_dds::GlobalMapSnapshot* /*type*/) {
  return Walks(payload, [](Cdr& cdr) {
    SkipSnapshotHeader(cdr);
    WalkSegments(cdr, pena_dds::GLOBAL_SNAPSHOT_MAX_SEGMENTS);
  });
}

bool SampleKeepsBounds(SerializedPayload_t& payload,
                       const pena_dds::OperatorCorrection* /*type*/) {
  return Walks(payload, [](Cdr& cdr) {
    Skip<std::string>(cdr);    // correction_id
    Skip<std::uint32_t>(cdr);  // schema_version
    Skip<std::string>(cdr);    // operator_id
    Skip<std::uint32_t>(cdr);  // kind (an enum is 4 bytes)
    Skip<std::string>(cdr);    // target_entity_id
    Skip<double>(cdr);         // stamp_s
    for (int i = 0; i < 3; ++i) Skip<double>(cdr);  // world_from_body
    Skip<std::int64_t>(cdr);   // segment_id
    WalkSegment(cdr);          // segment
  });
}

}  // namespace pena::services
