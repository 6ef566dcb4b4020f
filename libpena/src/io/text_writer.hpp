#pragma once
// Private: an output text file that reports failures with the path, shared by the writers.

#include <filesystem>
#include <fstream>
#include <string>

namespace pena::io::detail {

// Opens `path` for writing (truncating); Put appends text. Throws std::runtime_error naming the
// path when the file cannot be opened or a write fails (disk full, ...).
class TextWriter {
 public:
  explicit TextWriter(const std::filesystem::path& path);
  void Put(const std::string& text);
  // Flushes and checks; the destructor closes without being able to report.
  void Close();
  const std::filesystem::path& path() const { return path_; }

 private:
  void Check(const char* what);

  std::filesystem::path path_;
  std::ofstream stream_;
};

}  // namespace pena::io::detail
