#pragma once
// Runs the pena binary as a user would and captures what it prints.

#include <filesystem>
#include <string>

#include "scoped_temp_dir.hpp"
#include "test_data.hpp"

namespace pena::testing {

// Exit status and output of one pena run.
struct PenaRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// Runs `pena <args>` (args are passed through a shell: quote paths with spaces).
PenaRun RunPena(const std::string& args);

// A fresh empty directory in this test's own temporary directory (removed when the test ends).
std::filesystem::path FreshDir(const std::string& name);

// Whole file contents as bytes.
std::string ReadBytes(const std::filesystem::path& path);

// The number after `"key": ` in a JSON text (the first such key); NaN when absent.
double JsonNumber(const std::string& json, const std::string& key);

}  // namespace pena::testing
