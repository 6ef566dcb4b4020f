// DDS -> libpena conversions of the daemons (services/common/from_dds.cpp): a sample of the type
// the first byte picks, deserialized from the rest as a DataReader would, converted, and map
// changes applied to a line map as the fusion service does. Accepted outcomes: a refused payload,
// std::invalid_argument for another schema version, a map that refuses the delta.
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "dds_sample.hpp"
#include "from_dds.hpp"
#include "pena/line_map/line_map.hpp"
#include "pena_dds/correctionPubSubTypes.h"
#include "pena_dds/global_mapPubSubTypes.h"
#include "pena_dds/line_mapPubSubTypes.h"
#include "pena_dds/scanPubSubTypes.h"

namespace {

using pena::fuzz::DeserializeSample;
namespace line_map = pena::line_map;

template <class PubSubType>
void MapDelta(const std::uint8_t* data, std::size_t size) {
  if (const auto sample = DeserializeSample<PubSubType>(data, size)) {
    line_map::LineMap map;
    (void)map.Apply(pena::services::FromDds(*sample));
  }
}

template <class PubSubType>
void MapSnapshot(const std::uint8_t* data, std::size_t size) {
  if (const auto sample = DeserializeSample<PubSubType>(data, size)) {
    (void)line_map::LineMap::FromSnapshot(pena::services::FromDds(*sample));
  }
}

template <class PubSubType>
void Convert(const std::uint8_t* data, std::size_t size) {
  if (const auto sample = DeserializeSample<PubSubType>(data, size)) {
    (void)pena::services::FromDds(*sample);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return -1;
  try {
    switch (data[0] % 6) {
      case 0: MapDelta<pena_dds::LineMapDeltaPubSubType>(data + 1, size - 1); break;
      case 1: MapSnapshot<pena_dds::LineMapSnapshotPubSubType>(data + 1, size - 1); break;
      case 2: MapDelta<pena_dds::GlobalMapDeltaPubSubType>(data + 1, size - 1); break;
      case 3: MapSnapshot<pena_dds::GlobalMapSnapshotPubSubType>(data + 1, size - 1); break;
      case 4: Convert<pena_dds::CorrectionPubSubType>(data + 1, size - 1); break;
      default: Convert<pena_dds::ReferenceScanPubSubType>(data + 1, size - 1); break;
    }
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
