// Link frames (gateway/src/frame.cpp, docs/gateway.md): DecodeFrame on a datagram and the stream
// decoder on the same bytes in two pieces. A rejection must say why; an accepted frame must not
// claim more bytes than it had.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz_file.hpp"
#include "pena/gateway/frame.hpp"

namespace gateway = pena::gateway;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto bytes = pena::fuzz::AsText(data, size);
  const gateway::FrameResult frame = gateway::DecodeFrame(bytes);
  if (!frame.ok() && frame.message.empty()) std::abort();
  if (frame.ok() && (frame.consumed == 0 || frame.consumed > size)) std::abort();

  gateway::FrameStreamDecoder stream;
  const std::size_t cut = size / 2;
  for (const auto& piece : {bytes.substr(0, cut), bytes.substr(cut)}) {
    for (const gateway::FrameResult& result : stream.Feed(piece)) {
      if (!result.ok() && result.message.empty()) std::abort();
    }
  }
  if (stream.skipped_bytes() > size) std::abort();
  return 0;
}
