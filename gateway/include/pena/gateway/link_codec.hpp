#pragma once
// Conversions between the gateway's items and idl/link.proto, in one place (quantising on the
// way out: poses 1 cm / 0.1 deg, corrections 1 mm / 0.01 deg, stamps in ms relative to the
// envelope's base stamp). FromProto validates every field and never throws.

#include <cstdint>
#include <optional>
#include <string>

#include "link.pb.h"
#include "pena/gateway/link_items.hpp"

namespace pena::gateway {

// The link schema version written, and the only one read (Envelope.schema_version).
inline constexpr std::uint32_t kLinkSchemaVersion = 1;

// Milliseconds of a stamp in seconds (>= 0; negative stamps clamp to 0).
std::uint64_t StampMs(double stamp_s);

// Fills `out`'s body from `item`; throws std::invalid_argument for a map change whose values are
// not on the map's quanta (only LineMap output is exact).
void ToProto(const DomainItem& item, std::uint64_t base_stamp_ms, link::Item* out);
// The domain item in `item`'s body; nullopt and `error` (naming the field) if malformed or if the
// body is not a domain item (resync messages are handled by the session).
std::optional<DomainItem> FromProto(const link::Item& item, std::uint64_t base_stamp_ms,
                                    std::string* error);

}  // namespace pena::gateway
