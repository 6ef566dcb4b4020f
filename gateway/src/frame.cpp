#include "pena/gateway/frame.hpp"

#include <zlib.h>

#include <stdexcept>

#include "pena/gateway/compression.hpp"

namespace pena::gateway {
namespace {

constexpr char kMagic0 = 'P';
constexpr char kMagic1 = 'L';

std::uint32_t Crc32(std::string_view bytes) {
  return static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size())));
}

std::uint32_t ByteAt(std::string_view bytes, std::size_t index) {
  return static_cast<std::uint8_t>(bytes[index]);
}

FrameResult Reject(FrameStatus status, std::string message) {
  FrameResult result;
  result.status = status;
  result.message = std::move(message);
  return result;
}

}  // namespace

const char* ToString(FrameStatus status) {
  switch (status) {
    case FrameStatus::kOk: return "ok";
    case FrameStatus::kTruncated: return "truncated";
    case FrameStatus::kBadMagic: return "bad_magic";
    case FrameStatus::kUnknownVersion: return "unknown_version";
    case FrameStatus::kBadFlags: return "bad_flags";
    case FrameStatus::kOversized: return "oversized";
    case FrameStatus::kBadCrc: return "bad_crc";
    case FrameStatus::kBadCompression: return "bad_compression";
    case FrameStatus::kBadPayload: return "bad_payload";
    case FrameStatus::kWrongKey: return "wrong_key";
    case FrameStatus::kUnauthenticated: return "unauthenticated";
    case FrameStatus::kReflected: return "reflected";
    case FrameStatus::kStale: return "stale";
    case FrameStatus::kReplayed: return "replayed";
  }
  return "unknown";
}

std::string EncodeFrame(std::string_view payload, bool try_compress) {
  std::uint8_t flags = 0;
  std::string deflated;
  if (try_compress) {
    deflated = Deflate(payload);
    if (deflated.size() < payload.size()) {
      flags |= kFlagDeflated;
      payload = deflated;
    }
  }
  if (payload.size() > 0xFFFFU) {
    throw std::invalid_argument("link frame: payload of " + std::to_string(payload.size()) +
                                " bytes exceeds 65535");
  }
  std::string frame{kMagic0, kMagic1, static_cast<char>(kFrameVersion), static_cast<char>(flags),
                    static_cast<char>(payload.size() >> 8), static_cast<char>(payload.size())};
  frame.append(payload);
  const std::uint32_t crc = Crc32(frame);
  for (int shift = 24; shift >= 0; shift -= 8) frame.push_back(static_cast<char>(crc >> shift));
  return frame;
}

// Checks the fixed header; kOk (with nothing else set) if the frame may follow.
static FrameResult CheckHeader(std::string_view bytes, const FrameLimits& limits) {
  if (bytes.size() < kFrameHeaderBytes) {
    return Reject(FrameStatus::kTruncated,
                  std::to_string(bytes.size()) + " bytes, shorter than the 6-byte header");
  }
  if (bytes[0] != kMagic0 || bytes[1] != kMagic1) {
    return Reject(FrameStatus::kBadMagic, "byte 0: no \"PL\" magic");
  }
  if (ByteAt(bytes, 2) != kFrameVersion) {
    return Reject(FrameStatus::kUnknownVersion,
                  "byte 2: frame version " + std::to_string(ByteAt(bytes, 2)) + ", expected 1");
  }
  const std::uint32_t flags = ByteAt(bytes, 3);
  if ((flags & ~static_cast<std::uint32_t>(kFlagDeflated)) != 0) {
    return Reject(FrameStatus::kBadFlags, "byte 3: unknown flags " + std::to_string(flags));
  }
  const std::size_t length = (ByteAt(bytes, 4) << 8) | ByteAt(bytes, 5);
  if (length > limits.max_payload_bytes) {
    return Reject(FrameStatus::kOversized, "byte 4: payload length " + std::to_string(length) +
                                               " > " + std::to_string(limits.max_payload_bytes));
  }
  return {};
}

FrameResult DecodeFrame(std::string_view bytes, const FrameLimits& limits) {
  if (FrameResult header = CheckHeader(bytes, limits); !header.ok()) return header;
  const std::uint32_t flags = ByteAt(bytes, 3);
  const std::size_t length = (ByteAt(bytes, 4) << 8) | ByteAt(bytes, 5);
  const std::size_t total = kFrameHeaderBytes + length + kFrameTrailerBytes;
  if (bytes.size() < total) {
    return Reject(FrameStatus::kTruncated, std::to_string(bytes.size()) + " bytes, frame needs " +
                                               std::to_string(total));
  }
  std::uint32_t crc = 0;
  for (std::size_t i = total - kFrameTrailerBytes; i < total; ++i) crc = (crc << 8) | ByteAt(bytes, i);
  if (crc != Crc32(bytes.substr(0, total - kFrameTrailerBytes))) {
    return Reject(FrameStatus::kBadCrc, "byte " + std::to_string(total - 4) + ": CRC32 mismatch");
  }
  FrameResult result;
  result.consumed = total;
  const std::string_view payload = bytes.substr(kFrameHeaderBytes, length);
  if ((flags & kFlagDeflated) == 0) {
    result.payload.assign(payload);
    return result;
  }
  std::optional<std::string> inflated = Inflate(payload, limits.max_inflated_bytes);
  if (!inflated) {
    return Reject(FrameStatus::kBadCompression,
                  "payload does not inflate within " + std::to_string(limits.max_inflated_bytes) +
                      " bytes");
  }
  result.payload = std::move(*inflated);
  return result;
}

std::vector<FrameResult> FrameStreamDecoder::Feed(std::string_view bytes) {
  buffer_.append(bytes);
  std::vector<FrameResult> frames;
  std::size_t start = 0;
  while (true) {
    // Resynchronise: the next frame can only start at a magic.
    const std::size_t magic = buffer_.find(std::string_view("PL", 2), start);
    const std::size_t found = magic == std::string::npos ? buffer_.size() : magic;
    // Keep a trailing 'P': it may be the first half of a magic split across reads.
    const std::size_t keep = (magic == std::string::npos && found > start &&
                              buffer_.back() == kMagic0) ? 1 : 0;
    skipped_ += found - start - keep;
    start = found - keep;
    if (magic == std::string::npos) break;
    FrameResult frame = DecodeFrame(std::string_view(buffer_).substr(start), limits_);
    if (frame.status == FrameStatus::kTruncated) break;  // wait for more bytes
    if (frame.ok()) {
      start += frame.consumed;
    } else {
      start += 1;  // a false magic or a damaged frame: look for the next magic after it
    }
    frames.push_back(std::move(frame));
  }
  buffer_.erase(0, start);
  return frames;
}

}  // namespace pena::gateway
