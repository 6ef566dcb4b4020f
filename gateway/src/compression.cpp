#include "pena/gateway/compression.hpp"

#include <zlib.h>

#include <algorithm>

namespace pena::gateway {
namespace {

// Raw deflate: negative window bits drop the zlib header and Adler-32 (6 bytes per frame).
constexpr int kRawWindowBits = -15;

}  // namespace

std::string Deflate(std::string_view bytes) {
  z_stream stream{};
  deflateInit2(&stream, Z_BEST_COMPRESSION, Z_DEFLATED, kRawWindowBits, 9, Z_DEFAULT_STRATEGY);
  std::string out(deflateBound(&stream, static_cast<uLong>(bytes.size())), '\0');
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  stream.avail_in = static_cast<uInt>(bytes.size());
  stream.next_out = reinterpret_cast<Bytef*>(out.data());
  stream.avail_out = static_cast<uInt>(out.size());
  deflate(&stream, Z_FINISH);
  out.resize(stream.total_out);
  deflateEnd(&stream);
  return out;
}

std::optional<std::string> Inflate(std::string_view bytes, std::size_t max_bytes) {
  z_stream stream{};
  if (inflateInit2(&stream, kRawWindowBits) != Z_OK) return std::nullopt;
  // Grow on demand up to one byte past the limit (that byte detects "more than max_bytes"):
  // a frame is small, and a bomb must not cost a full-size buffer per attempt.
  std::string out(std::min(max_bytes + 1, 4 * bytes.size() + 256), '\0');
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  stream.avail_in = static_cast<uInt>(bytes.size());
  int status = Z_OK;
  while (status == Z_OK) {
    stream.next_out = reinterpret_cast<Bytef*>(out.data() + stream.total_out);
    stream.avail_out = static_cast<uInt>(out.size() - stream.total_out);
    status = inflate(&stream, Z_FINISH);
    const bool needs_room = status == Z_BUF_ERROR && stream.avail_out == 0 && out.size() <= max_bytes;
    if (needs_room) {
      out.resize(std::min(max_bytes + 1, 2 * out.size()));
      status = Z_OK;
    }
  }
  const bool complete = status == Z_STREAM_END && stream.avail_in == 0;
  out.resize(stream.total_out);
  inflateEnd(&stream);
  if (!complete || out.size() > max_bytes) return std::nullopt;
  return out;
}

}  // namespace pena::gateway
