#pragma once
// The link's security layer (docs/security.md): every datagram between two gateways is sealed
// with a per-link key by XChaCha20-Poly1305 (libsodium), its header authenticated as associated
// data, and checked against a replay window and the receiver's clock. Forged, modified, replayed,
// reflected and truncated datagrams come back as a FrameStatus with a message; opening never
// throws.
//
// Sealed datagram: key id (1 byte) | sender id (4, big endian) | counter (6, big endian) |
// ciphertext of the link frame | Poly1305 tag (16). The nonce is sender id | counter | zeros.

#include <array>
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <string_view>

#include "pena/gateway/frame.hpp"

namespace pena::gateway {

// Header (key id 1, sender id 4, counter 6) and tag sizes of a sealed datagram, in bytes.
inline constexpr std::size_t kSealHeaderBytes = 11;
inline constexpr std::size_t kSealTagBytes = 16;
inline constexpr std::size_t kSealOverheadBytes = kSealHeaderBytes + kSealTagBytes;
inline constexpr std::size_t kLinkKeyBytes = 32;

// A per-link key: 32 random bytes held by the two gateways of one link, and by no other link.
struct LinkKey {
  std::array<std::uint8_t, kLinkKeyBytes> bytes{};
  // The first 4 bytes of BLAKE2b(key) in hex: what operators compare to see both ends agree.
  std::string Fingerprint() const;
  // The fingerprint's first byte; every sealed datagram carries it, so a receiver can tell a
  // peer with another key from a forger.
  std::uint8_t id() const;
};

// Reads a key file: 64 hex digits (whitespace and '#' comments allowed) or 32 raw bytes.
// Throws std::runtime_error naming the file: missing, not a regular file, accessible to other
// users, unreadable, not hex, the wrong length, or all zeros.
LinkKey ReadLinkKey(const std::string& path);
// A new key from the system's random source (libsodium randombytes).
LinkKey GenerateLinkKey();
// Writes `key` in hex to a new file with mode 0600; never overwrites. Throws std::runtime_error
// naming the file.
void WriteLinkKey(const std::string& path, const LinkKey& key);

// Replay and freshness limits of the receiving side; validated by LinkSeal's constructor.
struct SealOptions {
  double max_clock_offset_s = 60.0;  // refuse counters further from this clock (0: no check)
  std::size_t replay_window = 1024;  // the most recent accepted counters remembered
  std::uint32_t sender_id = 0;       // this end's id in the header; 0: random
};

class LinkSeal {
 public:
  // Throws std::invalid_argument naming the field for a bad option, std::runtime_error if
  // libsodium cannot start.
  explicit LinkSeal(const LinkKey& key, SealOptions options = {});
  ~LinkSeal();
  LinkSeal(const LinkSeal&) = delete;
  LinkSeal& operator=(const LinkSeal&) = delete;

  // Seals one link frame. The counter is max(previous + 1, now_s in milliseconds): it never
  // repeats while the process runs, and a restarted sender starts above what it sent before
  // as long as its clock does not go back.
  std::string Seal(std::string_view frame, double now_s);
  // Opens one datagram received at now_s: kOk with the frame inside as `payload`, or why not
  // (kTruncated, kWrongKey, kUnauthenticated, kReflected, kStale, kReplayed). Only an
  // authentic, fresh, first-seen datagram moves the replay window.
  FrameResult Open(std::string_view datagram, double now_s);

  std::uint32_t sender_id() const { return sender_id_; }
  std::uint8_t key_id() const { return key_id_; }

 private:
  std::array<std::uint8_t, kLinkKeyBytes> key_{};
  std::uint8_t key_id_ = 0;
  std::uint32_t sender_id_ = 0;
  SealOptions options_;
  std::uint64_t last_sent_ = 0;
  std::set<std::uint64_t> recent_;  // accepted counters, at most replay_window of the newest
};

}  // namespace pena::gateway
