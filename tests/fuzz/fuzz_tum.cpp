// TUM trajectories (docs/formats.md): ReadTum or InputError.
#include <cstddef>
#include <cstdint>

#include "fuzz_file.hpp"
#include "pena/io/input_error.hpp"
#include "pena/io/trajectory_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static pena::fuzz::FuzzFile file("poses.tum");
  try {
    (void)pena::io::ReadTum(file.Write(data, size));
  } catch (const pena::io::InputError&) {
  }
  return 0;
}
