#pragma once
// Optional payload compression for link frames: raw zlib deflate (no header; the frame has a CRC).

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace pena::gateway {

// Deflates `bytes` at the best compression level (frames are small; CPU is not the bottleneck).
std::string Deflate(std::string_view bytes);
// Inflates; nullopt if the data is not valid deflate or would exceed `max_bytes`.
std::optional<std::string> Inflate(std::string_view bytes, std::size_t max_bytes);

}  // namespace pena::gateway
