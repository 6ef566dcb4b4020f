#include "text_writer.hpp"

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace pena::io::detail {

TextWriter::TextWriter(const std::filesystem::path& path) : path_(path) {
  errno = 0;
  stream_.open(path, std::ios::out | std::ios::trunc);
  Check("cannot open for writing");
}

void TextWriter::Put(const std::string& text) {
  errno = 0;  // so a failure reports its own cause, not an older one
  stream_ << text;
  Check("write failed");
}

void TextWriter::Close() {
  if (!stream_.is_open()) return;
  errno = 0;
  stream_.flush();
  Check("write failed");
  stream_.close();
  Check("close failed");
}

void TextWriter::Check(const char* what) {
  if (stream_.good()) return;
  const int saved = errno;
  throw std::runtime_error(path_.string() + ": " + what +
                           (saved != 0 ? std::string(": ") + std::strerror(saved) : ""));
}

}  // namespace pena::io::detail
