#pragma once
// Strict loading of the daemons' text-format configs (service_config.proto): unknown keys,
// syntax errors and bad values throw pena::io::InputError "path:line: what".

#include <filesystem>
#include <string>

#include <google/protobuf/message.h>

#include "pena/io/input_error.hpp"

namespace pena::services {

// Parses `path` into `message` (cleared first). Throws io::InputError naming file, line and
// column for an unreadable file, a syntax error or an unknown key.
void LoadTextConfigInto(const std::filesystem::path& path, google::protobuf::Message& message);

// The typed form: `auto config = LoadTextConfig<config::EntityConfig>(path);`.
template <class Config>
Config LoadTextConfig(const std::filesystem::path& path) {
  Config config;
  LoadTextConfigInto(path, config);
  return config;
}

// `relative` resolved against the directory of `config_path` (absolute paths unchanged; an
// empty config_path means the current directory).
std::filesystem::path ResolvePath(const std::filesystem::path& config_path,
                                  const std::string& relative);

}  // namespace pena::services
