#pragma once
// The real logs the tests read: the repository's data/ folder (data/README.md), or the folder
// given to CMake as PENA_DATA_DIR.

#include <filesystem>
#include <string>

namespace pena::testing {

// Path of `relative` ("freiburg/intel.clf.gz", "radish-corrected/aces-corrected.log.gz") in data/.
inline std::filesystem::path DataPath(const std::string& relative) {
  return std::filesystem::path(PENA_DATA_DIR) / relative;
}

}  // namespace pena::testing
