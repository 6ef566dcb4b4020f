#pragma once
// Temporary directories for tests: each one fresh and private (mkdtemp under $TMPDIR, else /tmp),
// removed with everything in it when its owner ends, so tests neither collide nor leave files.

#include <errno.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace pena::testing {

// A new directory `pena-<tag>-XXXXXX` under the system temp dir, removed (recursively) on
// destruction by the process that made it.
class ScopedTempDir {
 public:
  explicit ScopedTempDir(const std::string& tag = "test") : owner_pid_(::getpid()) {
    std::string pattern =
        (std::filesystem::temp_directory_path() / ("pena-" + tag + "-XXXXXX")).string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      throw std::system_error(errno, std::generic_category(), "mkdtemp " + pattern);
    }
    path_ = pattern;
  }
  ~ScopedTempDir() {
    // A forked child that exits normally runs this destructor too: only the owner removes.
    if (::getpid() != owner_pid_) return;
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScopedTempDir(const ScopedTempDir&) = delete;
  ScopedTempDir& operator=(const ScopedTempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
  pid_t owner_pid_;
};

// This process's own temporary directory, made on first use and removed when the process exits.
// CTest runs each test case in a process of its own, so there it is one directory per test case.
inline const std::filesystem::path& ProcessTempDir() {
  static const ScopedTempDir dir(program_invocation_short_name);
  return dir.path();
}

// A fresh, empty directory `name` (may contain '/') inside ProcessTempDir().
inline std::filesystem::path FreshTempDir(const std::string& name) {
  const std::filesystem::path dir = ProcessTempDir() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace pena::testing
