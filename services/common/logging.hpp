#pragma once
// spdlog setup shared by the daemons: "[time] [daemon/entity] [level] message" on stderr, and
// optionally a file.

#include <filesystem>
#include <string>

namespace pena::services {

// Sets the default logger. Throws std::invalid_argument for an unknown level name and
// std::runtime_error if the file cannot be opened.
void SetupLogging(const std::string& name, const std::string& level,
                  const std::filesystem::path& file = {});

}  // namespace pena::services
