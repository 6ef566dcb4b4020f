// Native mission logs (docs/mission-log.md): the header and every record until the end or the
// first InputError, through OpenLog as the tools open them.
#include <cstddef>
#include <cstdint>

#include "fuzz_file.hpp"
#include "pena/io/input_error.hpp"
#include "pena/io/log_source.hpp"
#include "pena/io/mission_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static pena::fuzz::FuzzFile file("mission.penalog");
  const auto& path = file.Write(data, size);
  try {
    pena::io::MissionLogReader log(path);
    (void)log.header();
    while (log.Next()) {
    }
  } catch (const pena::io::InputError&) {
  }
  return 0;
}
