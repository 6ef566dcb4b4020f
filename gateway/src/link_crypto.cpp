#include "pena/gateway/link_crypto.hpp"

#include <fcntl.h>
#include <sodium.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace pena::gateway {
namespace {

static_assert(kLinkKeyBytes == crypto_aead_xchacha20poly1305_ietf_KEYBYTES);
static_assert(kSealTagBytes == crypto_aead_xchacha20poly1305_ietf_ABYTES);

void StartSodium() {
  if (sodium_init() < 0) throw std::runtime_error("link seal: libsodium failed to initialise");
}

std::string Hex(const std::uint8_t* bytes, std::size_t size) {
  std::string text;
  char digits[3];
  for (std::size_t i = 0; i < size; ++i) {
    std::snprintf(digits, sizeof(digits), "%02x", bytes[i]);
    text += digits;
  }
  return text;
}

std::string Hex8(std::uint32_t value) {
  char text[9];
  std::snprintf(text, sizeof(text), "%08x", value);
  return text;
}

std::string Fixed(double value, int digits) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", digits, value);
  return text;
}

int HexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// A 32-byte file holding bytes that are not printable text is a raw key; anything else is text.
bool LooksRaw(const std::string& content) {
  if (content.size() != kLinkKeyBytes) return false;
  for (char c : content) {
    const auto byte = static_cast<unsigned char>(c);
    if ((byte < 0x20 || byte > 0x7e) && c != '\n' && c != '\r' && c != '\t') return true;
  }
  return false;
}

// 64 hex digits, whitespace and '#' comments to the end of the line.
LinkKey ParseHexKey(const std::string& path, const std::string& content) {
  LinkKey key;
  std::size_t digits = 0;
  std::size_t line = 1, column = 0;
  bool comment = false;
  for (char c : content) {
    ++column;
    if (c == '\n') {
      ++line;
      column = 0;
      comment = false;
      continue;
    }
    if (comment || c == ' ' || c == '\t' || c == '\r') continue;
    if (c == '#') {
      comment = true;
      continue;
    }
    const int value = HexValue(c);
    if (value < 0) {
      throw std::runtime_error("link key file " + path + ":" + std::to_string(line) + ":" +
                               std::to_string(column) + ": '" + std::string(1, c) +
                               "' is not a hex digit (a key is 64 hex digits or 32 raw bytes)");
    }
    if (digits < 2 * kLinkKeyBytes) {
      key.bytes[digits / 2] = static_cast<std::uint8_t>(key.bytes[digits / 2] << 4 | value);
    }
    ++digits;
  }
  if (digits != 2 * kLinkKeyBytes) {
    throw std::runtime_error("link key file " + path + ": " + std::to_string(digits) +
                             " hex digits, a key is 64 (32 bytes)");
  }
  return key;
}

// Counters are milliseconds of the clock, 48 bits: enough until the year 10889.
constexpr std::uint64_t kMaxCounter = (std::uint64_t{1} << 48) - 1;

std::uint64_t MillisOf(double now_s) {
  if (!(now_s > 0.0)) return 0;
  return std::min(kMaxCounter, static_cast<std::uint64_t>(std::llround(std::min(now_s, 1e13) * 1e3)));
}

void PutBigEndian(std::uint64_t value, int bytes, std::string* out) {
  for (int shift = 8 * (bytes - 1); shift >= 0; shift -= 8) out->push_back(static_cast<char>(value >> shift));
}

std::uint64_t GetBigEndian(std::string_view bytes, std::size_t offset, int count) {
  std::uint64_t value = 0;
  for (int i = 0; i < count; ++i) value = value << 8 | static_cast<std::uint8_t>(bytes[offset + i]);
  return value;
}

// sender id | counter | zeros: unique per key as long as (sender, counter) never repeats.
std::array<unsigned char, crypto_aead_xchacha20poly1305_ietf_NPUBBYTES> Nonce(std::string_view header) {
  std::array<unsigned char, crypto_aead_xchacha20poly1305_ietf_NPUBBYTES> nonce{};
  std::memcpy(nonce.data(), header.data() + 1, kSealHeaderBytes - 1);
  return nonce;
}

FrameResult Reject(FrameStatus status, std::string message) {
  FrameResult result;
  result.status = status;
  result.message = std::move(message);
  return result;
}

}  // namespace

std::string LinkKey::Fingerprint() const {
  StartSodium();
  // Domain-separated, so the fingerprint reveals nothing usable about the key itself.
  static constexpr char kContext[] = "pena link key fingerprint";
  std::array<unsigned char, crypto_generichash_BYTES> digest{};
  crypto_generichash(digest.data(), digest.size(), bytes.data(), bytes.size(),
                     reinterpret_cast<const unsigned char*>(kContext), sizeof(kContext) - 1);
  return Hex(digest.data(), 4);
}

std::uint8_t LinkKey::id() const {
  const std::string fingerprint = Fingerprint();
  return static_cast<std::uint8_t>(HexValue(fingerprint[0]) << 4 | HexValue(fingerprint[1]));
}

LinkKey ReadLinkKey(const std::string& path) {
  StartSodium();
  struct stat status {};
  if (stat(path.c_str(), &status) != 0) {
    if (errno == ENOENT) {
      throw std::runtime_error("link key file " + path +
                               " does not exist (make one with: pena-gateway --generate-link-key " +
                               path + ")");
    }
    throw std::runtime_error("link key file " + path + ": " + std::strerror(errno));
  }
  if (!S_ISREG(status.st_mode)) throw std::runtime_error("link key file " + path + " is not a regular file");
  if ((status.st_mode & S_IRWXO) != 0) {
    char mode[8];
    std::snprintf(mode, sizeof(mode), "%04o", static_cast<unsigned>(status.st_mode & 07777));
    throw std::runtime_error("link key file " + path + " is accessible to other users (mode " + mode +
                             "): run chmod 600 " + path);
  }
  if (status.st_size > 4096) {
    throw std::runtime_error("link key file " + path + " is " + std::to_string(status.st_size) +
                             " bytes, too large for a key (64 hex digits or 32 raw bytes)");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("link key file " + path + ": cannot be read: " + std::strerror(errno));
  const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  LinkKey key;
  if (LooksRaw(content)) {
    std::memcpy(key.bytes.data(), content.data(), kLinkKeyBytes);
  } else {
    key = ParseHexKey(path, content);
  }
  if (sodium_is_zero(key.bytes.data(), key.bytes.size()) != 0) {
    throw std::runtime_error("link key file " + path + ": the key is all zeros");
  }
  return key;
}

LinkKey GenerateLinkKey() {
  StartSodium();
  LinkKey key;
  do {
    randombytes_buf(key.bytes.data(), key.bytes.size());
  } while (sodium_is_zero(key.bytes.data(), key.bytes.size()) != 0);
  return key;
}

void WriteLinkKey(const std::string& path, const LinkKey& key) {
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    if (errno == EEXIST) {
      throw std::runtime_error("link key file " + path +
                               " already exists; not overwritten (remove it first to replace the key)");
    }
    throw std::runtime_error("link key file " + path + ": " + std::strerror(errno));
  }
  const std::string text = "# pena-gateway link key, fingerprint " + key.Fingerprint() + "\n" +
                           Hex(key.bytes.data(), key.bytes.size()) + "\n";
  const bool written = write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size()) &&
                       fchmod(fd, 0600) == 0 && fsync(fd) == 0;
  const std::string why = std::strerror(errno);
  close(fd);
  if (!written) {
    unlink(path.c_str());
    throw std::runtime_error("link key file " + path + ": write failed: " + why);
  }
}

LinkSeal::LinkSeal(const LinkKey& key, SealOptions options)
    : key_(key.bytes), key_id_(key.id()), options_(options) {
  StartSodium();
  if (!(options_.max_clock_offset_s >= 0.0) || !std::isfinite(options_.max_clock_offset_s)) {
    throw std::invalid_argument("seal.max_clock_offset_s must be >= 0 s (0: no check), got " +
                                std::to_string(options_.max_clock_offset_s));
  }
  if (options_.replay_window == 0) throw std::invalid_argument("seal.replay_window must be >= 1 frames, got 0");
  sender_id_ = options_.sender_id;
  while (sender_id_ == 0) sender_id_ = randombytes_random();
}

LinkSeal::~LinkSeal() { sodium_memzero(key_.data(), key_.size()); }

std::string LinkSeal::Seal(std::string_view frame, double now_s) {
  // A repeated counter would repeat a nonce; 48 bits of milliseconds do not run out in practice.
  if (last_sent_ >= kMaxCounter) throw std::overflow_error("link seal: counter exhausted, use a new key");
  last_sent_ = std::max(last_sent_ + 1, MillisOf(now_s));
  std::string datagram(1, static_cast<char>(key_id_));
  PutBigEndian(sender_id_, 4, &datagram);
  PutBigEndian(last_sent_, 6, &datagram);
  const auto nonce = Nonce(datagram);
  datagram.resize(kSealHeaderBytes + frame.size() + kSealTagBytes);
  auto* out = reinterpret_cast<unsigned char*>(datagram.data());
  unsigned long long sealed_bytes = 0;
  crypto_aead_xchacha20poly1305_ietf_encrypt(
      out + kSealHeaderBytes, &sealed_bytes, reinterpret_cast<const unsigned char*>(frame.data()),
      frame.size(), out, kSealHeaderBytes, nullptr, nonce.data(), key_.data());
  return datagram;
}

FrameResult LinkSeal::Open(std::string_view datagram, double now_s) {
  // An open frame's magic and version, unless this key's id happens to be the magic's first byte.
  if (key_id_ != 'P' && datagram.size() >= 3 && datagram[0] == 'P' && datagram[1] == 'L' &&
      static_cast<std::uint8_t>(datagram[2]) == kFrameVersion) {
    return Reject(FrameStatus::kWrongKey, "an open frame (no seal): the peer runs with --insecure-link");
  }
  if (datagram.size() < kSealOverheadBytes) {
    return Reject(FrameStatus::kTruncated, std::to_string(datagram.size()) +
                                               " bytes, shorter than the 27-byte seal (header 11, tag 16)");
  }
  const auto key_id = static_cast<std::uint8_t>(datagram[0]);
  if (key_id != key_id_) {
    return Reject(FrameStatus::kWrongKey, "byte 0: key id " + Hex(&key_id, 1) + ", this link's key has " +
                                              Hex(&key_id_, 1) + ": the two ends hold different link keys");
  }
  const std::uint32_t sender = static_cast<std::uint32_t>(GetBigEndian(datagram, 1, 4));
  const std::uint64_t counter = GetBigEndian(datagram, 5, 6);
  const auto nonce = Nonce(datagram);
  FrameResult result;
  result.payload.resize(datagram.size() - kSealOverheadBytes);
  const auto* in = reinterpret_cast<const unsigned char*>(datagram.data());
  unsigned long long opened_bytes = 0;
  if (crypto_aead_xchacha20poly1305_ietf_decrypt(
          reinterpret_cast<unsigned char*>(result.payload.data()), &opened_bytes, nullptr,
          in + kSealHeaderBytes, datagram.size() - kSealHeaderBytes, in, kSealHeaderBytes,
          nonce.data(), key_.data()) != 0) {
    return Reject(FrameStatus::kUnauthenticated, "tag does not verify (sender " + Hex8(sender) +
                                                     ", counter " + std::to_string(counter) +
                                                     "): forged, or modified in transit");
  }
  if (sender == sender_id_) {
    return Reject(FrameStatus::kReflected,
                  "sealed by this end (sender " + Hex8(sender) + "): sent back to it");
  }
  const double offset_s = static_cast<double>(counter) * 1e-3 - now_s;
  if (options_.max_clock_offset_s > 0.0 && std::abs(offset_s) > options_.max_clock_offset_s) {
    return Reject(FrameStatus::kStale,
                  "counter " + std::to_string(counter) + " is " + Fixed(std::abs(offset_s), 1) + " s " +
                      (offset_s < 0.0 ? "behind" : "ahead of") + " this gateway's clock (limit " +
                      Fixed(options_.max_clock_offset_s, 1) +
                      " s): a replay, or the two gateways' clocks differ");
  }
  if (recent_.size() >= options_.replay_window && counter < *recent_.begin()) {
    return Reject(FrameStatus::kReplayed, "counter " + std::to_string(counter) + " is older than the last " +
                                              std::to_string(options_.replay_window) + " frames received");
  }
  if (!recent_.insert(counter).second) {
    return Reject(FrameStatus::kReplayed, "counter " + std::to_string(counter) + " already received");
  }
  if (recent_.size() > options_.replay_window) recent_.erase(recent_.begin());
  result.consumed = datagram.size();
  return result;
}

}  // namespace pena::gateway
