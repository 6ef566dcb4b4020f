#pragma once
// Line-map deltas and snapshots as bytes (idl/line_map.proto, docs/line-map.md): the Protobuf
// encoding the gateway uses on its link. Exact for what a LineMap produces (quantised values).

#include <cstdint>
#include <string>
#include <string_view>

#include "pena/line_map/map_delta.hpp"

namespace pena::io {

// The schema_version written, and the only one read.
inline constexpr std::uint32_t kLineMapSchemaVersion = 1;

// Serialises a delta. Throws std::invalid_argument for a value the wire cannot carry exactly
// (an endpoint not on whole millimetres, a fractional count, id <= 0): only LineMap output is.
std::string EncodeDelta(const line_map::MapDelta& delta);
// Parses bytes from EncodeDelta. Throws InputError(name, 0, what) for garbage, another schema
// version or an invalid field; `name` says where the bytes came from.
line_map::MapDelta DecodeDelta(std::string_view bytes, const std::string& name = "line map delta");

// Serialises a snapshot; throws like EncodeDelta.
std::string EncodeSnapshot(const line_map::MapSnapshot& snapshot);
// Parses bytes from EncodeSnapshot; throws like DecodeDelta.
line_map::MapSnapshot DecodeSnapshot(std::string_view bytes,
                                     const std::string& name = "line map snapshot");

}  // namespace pena::io
