#pragma once
// Bounds a received sample must keep before the generated deserializer reads it. fastddsgen 2.3
// generates sequence<string<N>, M> (a Segment's provenance) as a resize to the length the payload
// states, with neither the IDL bound nor the bytes left checked, so a 237-byte sample could ask
// for gigabytes. Every other sequence goes through Fast CDR, which refuses a length beyond the
// bytes left. These walks read a payload's CDR up to and including its last Segment and refuse
// every Segment list and provenance list longer than its IDL bound (common.idl).

#include <fastdds/rtps/common/SerializedPayload.h>

#include "pena_dds/global_map.h"
#include "pena_dds/line_map.h"
#include "pena_dds/operator.h"

namespace pena::services {

// Whether the payload's Segment lists and provenance lists keep their IDL bounds (false also for
// a payload that ends before its last Segment). One overload per type that holds a Segment.
bool SampleKeepsBounds(eprosima::fastrtps::rtps::SerializedPayload_t& payload,
                       const pena_dds::LineMapDelta* type);
bool SampleKeepsBounds(eprosima::fastrtps::rtps::SerializedPayload_t& payload,
                       const pena_dds::LineMapSnapshot* type);
bool SampleKeepsBounds(eprosima::fastrtps::rtps::SerializedPayload_t& payload,
                       const pena_dds::GlobalMapDelta* type);
bool SampleKeepsBounds(eprosima::fastrtps::rtps::SerializedPayload_t& payload,
                       const pena_dds::GlobalMapSnapshot* type);
bool SampleKeepsBounds(eprosima::fastrtps::rtps::SerializedPayload_t& payload,
                       const pena_dds::OperatorCorrection* type);
// Every other type: its generated code has no unchecked sequence.
inline bool SampleKeepsBounds(eprosima::fastrtps::rtps::SerializedPayload_t& /*payload*/,
                              const void* /*type*/) {
  return true;
}

}  // namespace pena::services
