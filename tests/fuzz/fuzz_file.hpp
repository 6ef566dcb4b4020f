#pragma once
// The fuzz targets of readers that take a path: the input goes into one file of a directory
// this process owns (under $TMPDIR), rewritten for every input and removed at exit.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace pena::fuzz {

class FuzzFile {
 public:
  // `name` gives the extension readers dispatch on ("plan.svg").
  explicit FuzzFile(const std::string& name) {
    dir_ = std::filesystem::temp_directory_path() /
           ("pena-fuzz-" + std::to_string(::getpid()) + "-" + name);
    std::filesystem::create_directories(dir_);
    path_ = dir_ / name;
  }
  ~FuzzFile() {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  FuzzFile(const FuzzFile&) = delete;
  FuzzFile& operator=(const FuzzFile&) = delete;

  // Writes `data` as the whole file and returns its path.
  const std::filesystem::path& Write(const std::uint8_t* data, std::size_t size) {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return path_;
  }

 private:
  std::filesystem::path dir_;
  std::filesystem::path path_;
};

inline std::string_view AsText(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

}  // namespace pena::fuzz
