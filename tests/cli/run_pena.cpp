#include "run_pena.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace pena::testing {

PenaRun RunPena(const std::string& args) {
  // Runs in this test's own temporary directory, so that even a relative --out stays in it.
  static int run_count = 0;
  const std::string tag = std::to_string(++run_count);
  const std::filesystem::path dir = ProcessTempDir();
  const auto out_path = dir / ("pena_stdout_" + tag + ".txt");
  const auto err_path = dir / ("pena_stderr_" + tag + ".txt");
  const std::string command = "cd '" + dir.string() + "' && " + std::string(PENA_BINARY) + " " +
                              args + " >" + out_path.string() + " 2>" + err_path.string();
  const int status = std::system(command.c_str());
  PenaRun run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = ReadBytes(out_path);
  run.err = ReadBytes(err_path);
  std::filesystem::remove(out_path);
  std::filesystem::remove(err_path);
  return run;
}

std::filesystem::path FreshDir(const std::string& name) { return FreshTempDir(name); }

std::string ReadBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

double JsonNumber(const std::string& json, const std::string& key) {
  const std::size_t at = json.find("\"" + key + "\": ");
  if (at == std::string::npos) return std::nan("");
  return std::stod(json.substr(at + key.size() + 4));
}

}  // namespace pena::testing
