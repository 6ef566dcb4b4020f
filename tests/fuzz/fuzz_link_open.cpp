// The sealed link (gateway/src/link_crypto.cpp, docs/security.md): LinkSeal::Open on a datagram
// from anyone (first byte 0: the input as received), and a seal-open round trip of the input as a
// frame (first byte 1: must open to the same bytes, once; a second copy is a replay).
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz_file.hpp"
#include "pena/gateway/link_crypto.hpp"

namespace gateway = pena::gateway;

namespace {

gateway::LinkKey FixedKey() {
  gateway::LinkKey key;
  for (std::size_t i = 0; i < key.bytes.size(); ++i) key.bytes[i] = static_cast<std::uint8_t>(i + 1);
  return key;
}

gateway::SealOptions End(std::uint32_t sender_id) {
  gateway::SealOptions options;
  options.sender_id = sender_id;
  return options;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return -1;
  static const gateway::LinkKey key = FixedKey();
  const auto bytes = pena::fuzz::AsText(data + 1, size - 1);
  const double now_s = 1.7e9;
  gateway::LinkSeal receiver(key, End(2));
  if ((data[0] & 1) == 0) {
    const gateway::FrameResult opened = receiver.Open(bytes, now_s);
    if (!opened.ok() && opened.message.empty()) std::abort();
    return 0;
  }
  gateway::LinkSeal sender(key, End(1));
  const std::string datagram = sender.Seal(bytes, now_s);
  const gateway::FrameResult opened = receiver.Open(datagram, now_s + 0.1);
  if (!opened.ok() || opened.payload != bytes) std::abort();
  if (receiver.Open(datagram, now_s + 0.2).status != gateway::FrameStatus::kReplayed) std::abort();
  return 0;
}
