#pragma once
// Private: reads a text file line by line through zlib, so plain and gzip files read the same.

#include <cstddef>
#include <filesystem>
#include <string>

namespace pena::io::detail {

// Line-numbered reader over gzopen/gzread. Throws InputError on a missing file (line 0) and on
// truncated or corrupt gzip data (at the line being read when the data ran out).
class GzLineReader {
 public:
  explicit GzLineReader(const std::filesystem::path& path);
  ~GzLineReader();
  GzLineReader(const GzLineReader&) = delete;
  GzLineReader& operator=(const GzLineReader&) = delete;

  // The next line without its line break; false at the clean end of the file.
  bool ReadLine(std::string& line);
  // 1-based number of the line last returned (0 before the first).
  std::size_t line_number() const { return line_number_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  // Throws if zlib reports an error; `line` is the line being read when it happened.
  void ThrowIfStreamError(std::size_t line) const;
  // Reads the next chunk of the (decompressed) file into buffer_; false at the end or an error.
  bool Fill();

  std::filesystem::path path_;
  void* file_ = nullptr;  // gzFile, kept opaque so zlib.h stays out of the other sources
  std::size_t line_number_ = 0;
  std::string buffer_;     // decompressed bytes not yet handed out start at next_
  std::size_t next_ = 0;
};

// Up to `max_bytes` of the file's (decompressed) start; empty if it cannot be read.
std::string ReadHead(const std::filesystem::path& path, std::size_t max_bytes);

}  // namespace pena::io::detail
