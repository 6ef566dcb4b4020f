#include "gz_line_reader.hpp"

#include <zlib.h>

#include <array>
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
  std::array<char, 8192> chunk;  // filled by gzgets before any read
  bool got_any = false;
  while (gzgets(AsGz(file_), chunk.data(), static_cast<int>(chunk.size())) != nullptr) {
    got_any = true;
    const std::size_t length = std::strlen(chunk.data());
    line.append(chunk.data(), length);
    if (length > 0 && chunk[length - 1] == '\n') break;
  }
  // gzgets stops early both at the clean end and when the deflate stream is cut: a line without
  // its newline may be the remains of a truncated file, so check before handing it out.
  const std::size_t reached = line_number_ + 1;
  if (line.empty() || line.back() != '\n') ThrowIfStreamError(reached);
  if (!got_any) return false;
  line_number_ = reached;
  if (line.back() == '\n') line.pop_back();
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return true;
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
