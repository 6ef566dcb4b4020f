#include "pena/io/input_error.hpp"

namespace pena::io {
namespace {

// "path:line: message", the form compilers use, so editors and grep can jump to the line.
std::string Describe(const std::filesystem::path& path, std::size_t line, const std::string& message) {
  return path.string() + ":" + std::to_string(line) + ": " + message;
}

}  // namespace

InputError::InputError(const std::filesystem::path& path, std::size_t line,
                       const std::string& message)
    : std::runtime_error(Describe(path, line, message)), path_(path), line_(line) {}

}  // namespace pena::io
