#pragma once
// The one error type of every reader: names the input and the position in it.

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace pena::io {

// Thrown by readers on malformed input; what() reads "path:line: message" (line 0 = whole file).
class InputError : public std::runtime_error {
 public:
  InputError(const std::filesystem::path& path, std::size_t line, const std::string& message);
  const std::filesystem::path& path() const { return path_; }
  std::size_t line() const { return line_; }

 private:
  std::filesystem::path path_;
  std::size_t line_;
};

}  // namespace pena::io
