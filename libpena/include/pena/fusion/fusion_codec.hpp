#pragma once
// Fusion inputs and checkpoints as bytes (the journal's records, docs/formats.md): a compact,
// versioned little-endian encoding in which doubles keep every bit, so a replayed journal rebuilds
// bit-identical state.

#include <cstdint>
#include <string>
#include <string_view>

#include "pena/fusion/fusion_input.hpp"
#include "pena/fusion/fusion_state.hpp"

namespace pena::fusion {

// The encoding version written; every version from 1 up to it is read (2 added the outline of an
// annotation, 3 an entity's operator-moved walls, 4 a global wall's support).
inline constexpr std::uint8_t kFusionCodecVersion = 4;

// Serialises one input.
std::string EncodeInput(const FusionInput& input);
// Parses EncodeInput's bytes; throws io::InputError(name, 0, what) naming the byte offset for
// truncated or malformed bytes or an unknown encoding version.
FusionInput DecodeInput(std::string_view bytes, const std::string& name = "fusion input");

// Serialises the whole state.
std::string EncodeCheckpoint(const FusionCheckpoint& checkpoint);
// Parses EncodeCheckpoint's bytes; throws like DecodeInput.
FusionCheckpoint DecodeCheckpoint(std::string_view bytes,
                                  const std::string& name = "fusion checkpoint");

}  // namespace pena::fusion
