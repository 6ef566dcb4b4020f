#pragma once
// A DDS sample from fuzz bytes the way a PeNa DataReader gets it: the bytes as the serialized
// payload (CDR with its encapsulation header), deserialized by the type every Participant
// registers (services/common/dds_participant.hpp: the generated type, exceptions refused).

#include <fastdds/rtps/common/SerializedPayload.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>

#include "dds_participant.hpp"

namespace pena::fuzz {

template <class PubSubType>
std::optional<typename PubSubType::type> DeserializeSample(const std::uint8_t* data, std::size_t size) {
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(size));
  if (size > 0) std::memcpy(payload.data, data, size);
  payload.length = static_cast<std::uint32_t>(size);
  pena::services::CheckedType<PubSubType> type;
  typename PubSubType::type sample;
  if (!type.deserialize(&payload, &sample)) return std::nullopt;
  return sample;
}

}  // namespace pena::fuzz
