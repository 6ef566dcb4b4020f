// The daemons' text configs (services/common/config_loader, docs/services.md): loaded, turned
// into options and validated as pena-entity and pena-fusion do at start. The first byte picks
// the daemon. Accepted outcomes: options, InputError (syntax, key, value), invalid_argument
// (validation).
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "config_loader.hpp"
#include "entity_options.hpp"
#include "fusion_options.hpp"
#include "fuzz_file.hpp"

namespace services = pena::services;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static pena::fuzz::FuzzFile file("service.conf");
  if (size < 1) return -1;
  const auto& path = file.Write(data + 1, size - 1);
  try {
    if ((data[0] & 1) == 0) {
      const auto config = services::LoadTextConfig<services::config::EntityConfig>(path);
      services::ValidateEntityOptions(services::EntityOptionsFromConfig(config, path));
    } else {
      const auto config = services::LoadTextConfig<services::config::FusionConfig>(path);
      services::ValidateFusionServiceOptions(services::FusionOptionsFromConfig(config, path));
    }
  } catch (const pena::io::InputError&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
