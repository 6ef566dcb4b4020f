#pragma once
// Link frames (docs/gateway.md): magic "PL", version, flags, big-endian payload length, payload,
// CRC32 of all before it. Decoding never throws: garbage, truncated, oversized, unknown-version
// and corrupted frames come back as a FrameStatus with a message for the caller to log.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace pena::gateway {

// The frame format version written, and the only one read.
inline constexpr std::uint8_t kFrameVersion = 1;
// Header (magic 2, version 1, flags 1, length 2) and trailer (CRC32 4) sizes in bytes.
inline constexpr std::size_t kFrameHeaderBytes = 6;
inline constexpr std::size_t kFrameTrailerBytes = 4;
// Flag bit: the payload is zlib-deflated.
inline constexpr std::uint8_t kFlagDeflated = 0x01;

// Why a frame was not accepted.
enum class FrameStatus {
  kOk,
  kTruncated,        // fewer bytes than the header or the length announce
  kBadMagic,         // does not start with "PL"
  kUnknownVersion,   // a frame version this gateway does not read
  kBadFlags,         // flag bits this gateway does not know
  kOversized,        // length (or inflated length) above the configured maximum
  kBadCrc,           // CRC32 mismatch: corrupted in transit
  kBadCompression,   // deflated payload that does not inflate
  kBadPayload,       // well-framed, but the envelope inside is malformed (set by the session)
  // Sealed datagrams (link_crypto.hpp; set by the session when the link has a key):
  kWrongKey,         // sealed under another key id, or an open frame at a sealed link
  kUnauthenticated,  // the tag does not verify: forged, or modified in transit
  kReflected,        // authentic, but sealed by this very end (sent back to it)
  kStale,            // authentic, but its counter is further from this clock than allowed
  kReplayed,         // authentic, but already received, or older than the replay window
};
// The number of FrameStatus values (counters are kept per status).
inline constexpr std::size_t kFrameStatusCount = 14;
static_assert(static_cast<std::size_t>(FrameStatus::kReplayed) + 1 == kFrameStatusCount);

// A short name for logs ("bad_crc").
const char* ToString(FrameStatus status);

// Limits of the decoder.
struct FrameLimits {
  std::size_t max_payload_bytes = 16384;   // on the wire, after compression
  std::size_t max_inflated_bytes = 65536;  // after inflating: no decompression bombs
};

// One decoded frame, or why not.
struct FrameResult {
  FrameStatus status = FrameStatus::kOk;
  std::string payload;       // inflated; set only when status == kOk
  std::size_t consumed = 0;  // bytes of the input this frame occupied (kOk only)
  std::string message;       // what was wrong, with offsets and values
  bool ok() const { return status == FrameStatus::kOk; }
};

// Frames `payload`; deflates it first if `try_compress` and that makes it smaller. Throws
// std::invalid_argument if the (possibly deflated) payload exceeds 65535 bytes.
std::string EncodeFrame(std::string_view payload, bool try_compress);

// Decodes the frame at the start of `bytes` (trailing bytes are left, see consumed).
FrameResult DecodeFrame(std::string_view bytes, const FrameLimits& limits = {});

// Splits a byte stream (TCP, serial) into frames: after a bad frame it skips to the next magic.
class FrameStreamDecoder {
 public:
  explicit FrameStreamDecoder(FrameLimits limits = {}) : limits_(limits) {}
  // Appends received bytes; returns the frames completed (ok or rejected, in order).
  std::vector<FrameResult> Feed(std::string_view bytes);
  // Bytes skipped while searching for a magic so far.
  std::size_t skipped_bytes() const { return skipped_; }

 private:
  FrameLimits limits_;
  std::string buffer_;
  std::size_t skipped_ = 0;
};

}  // namespace pena::gateway
