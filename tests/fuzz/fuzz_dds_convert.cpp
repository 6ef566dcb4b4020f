// DDS -> link conversions of the gateway (gateway/src/dds_convert.cpp): a pose, annotation or
// correction sample (first byte) deserialized from the rest as a DataReader would and converted
// to a link item. Accepted outcomes: a refused payload, nullopt with an error naming the field.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "dds_sample.hpp"
#include "pena/gateway/dds_convert.hpp"
#include "pena_dds/correctionPubSubTypes.h"
#include "pena_dds/entityPubSubTypes.h"
#include "pena_dds/operatorPubSubTypes.h"

namespace gateway = pena::gateway;
using pena::fuzz::DeserializeSample;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return -1;
  const double stamp_s = 1.7e9;
  std::string error;
  switch (data[0] % 3) {
    case 0:
      if (const auto sample = DeserializeSample<pena_dds::EntityPosePubSubType>(data + 1, size - 1)) {
        (void)gateway::PoseFromDds(*sample, stamp_s);
      }
      break;
    case 1:
      if (const auto sample = DeserializeSample<pena_dds::AnnotationPubSubType>(data + 1, size - 1)) {
        if (!gateway::AnnotationFromDds(*sample, stamp_s, &error) && error.empty()) std::abort();
      }
      break;
    default:
      if (const auto sample = DeserializeSample<pena_dds::CorrectionPubSubType>(data + 1, size - 1)) {
        if (!gateway::CorrectionFromDds(*sample, stamp_s, &error) && error.empty()) std::abort();
      }
      break;
  }
  return 0;
}
