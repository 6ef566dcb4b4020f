// The line-map delta and snapshot codec (pena/io/line_map_codec.hpp): decoded, and what decodes
// must encode and decode to the same bytes. The first byte picks delta or snapshot.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz_file.hpp"
#include "pena/io/input_error.hpp"
#include "pena/io/line_map_codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return -1;
  const auto bytes = pena::fuzz::AsText(data + 1, size - 1);
  try {
    if ((data[0] & 1) == 0) {
      const auto once = pena::io::EncodeDelta(pena::io::DecodeDelta(bytes));
      if (pena::io::EncodeDelta(pena::io::DecodeDelta(once)) != once) std::abort();
    } else {
      const auto once = pena::io::EncodeSnapshot(pena::io::DecodeSnapshot(bytes));
      if (pena::io::EncodeSnapshot(pena::io::DecodeSnapshot(once)) != once) std::abort();
    }
  } catch (const pena::io::InputError&) {
  }
  return 0;
}
