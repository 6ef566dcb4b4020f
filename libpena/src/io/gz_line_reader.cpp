#include "gz_line_reader.hpp"

#include <zlib.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "pena/io/input_error.hpp"

namespace pena::io::detail {
namespace {

gzFile AsGz(void* file) { return static_cast<gzFile>(file); }

}  // namespace

GzLineReader::GzLineReader(const std::filesystem::path& path) : path_(path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) throw InputError(path, 0, "no such file");
  if (std::filesystem::is_directory(path, error)) throw InputError(path, 0, "is a directory");
  errno = 0;
  gzFile file = gzopen(path.c_str(), "rb");
  if (file == nullptr) {
    const int saved = errno;
    throw InputError(path, 0, std::string("cannot open: ") +
                                  (saved != 0 ? std::strerror(saved) : "out of memory"));
  }
  // Lines of 361-beam scans are ~3 kB; a large buffer keeps inflate calls few.
  gzbuffer(file, 1 << 18);
  file_ = file;
}

GzLineReader::~GzLineReader() {
  if (file_ != nullptr) gzclose(AsGz(file_));
}

bool GzLineReader::ReadLine(std::string& line) {
  line.clear();
  // Split on '\n' ourselves (not gzgets, whose C string loses everything after a NUL byte): a
  // line keeps any byte it holds, and the parsers name what is wrong with it.
  while (true) {
    const std::size_t newline = buffer_.find('\n', next_);
    if (newline != std::string::npos) {
      line.append(buffer_, next_, newline - next_);
      next_ = newline + 1;
      break;
    }
    line.append(buffer_, next_, std::string::npos);
    if (!Fill()) {
      // The data ran out: cleanly, or a truncated or corrupt gzip stream (checked first, so a
      // cut line is not handed out as if whole).
      ThrowIfStreamError(line_number_ + 1);
      if (line.empty()) return false;
      break;
    }
  }
  ++line_number_;
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return true;
}

bool GzLineReader::Fill() {
  constexpr std::size_t kChunkBytes = 1 << 16;
  buffer_.resize(kChunkBytes);
  next_ = 0;
  const int count = gzread(AsGz(file_), buffer_.data(), static_cast<unsigned>(kChunkBytes));
  buffer_.resize(count > 0 ? static_cast<std::size_t>(count) : 0);
  return count > 0;
}

void GzLineReader::ThrowIfStreamError(std::size_t line) const {
  int error_number = Z_OK;
  const char* message = gzerror(AsGz(file_), &error_number);
  if (error_number == Z_OK) return;
  // Z_BUF_ERROR is zlib's "unexpected end of file": the gzip stream stops mid-way.
  const std::string what = error_number == Z_BUF_ERROR
                               ? "gzip data ends unexpectedly (truncated file?): "
                               : "cannot decompress: ";
  std::string detail = message != nullptr ? message : "unknown zlib error";
  // zlib prefixes its message with the path, which InputError already gives.
  const std::string prefix = path_.string() + ": ";
  if (detail.rfind(prefix, 0) == 0) detail.erase(0, prefix.size());
  throw InputError(path_, line, what + detail);
}

std::string ReadHead(const std::filesystem::path& path, std::size_t max_bytes) {
  gzFile file = gzopen(path.c_str(), "rb");
  if (file == nullptr) return {};
  std::string head(max_bytes, '\0');
  const int count = gzread(file, head.data(), static_cast<unsigned>(max_bytes));
  gzclose(file);
  head.resize(count > 0 ? static_cast<std::size_t>(count) : 0);
  return head;
}

}  // namespace pena::io::detail
