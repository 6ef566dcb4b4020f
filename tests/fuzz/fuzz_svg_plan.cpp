// SVG plans (docs/formats.md, "Plans"): ReadPlan segments or InputError.
#include <cstddef>
#include <cstdint>

#include "fuzz_file.hpp"
#include "pena/io/input_error.hpp"
#include "pena/io/plan_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static pena::fuzz::FuzzFile file("plan.svg");
  try {
    (void)pena::io::ReadPlan(file.Write(data, size));
  } catch (const pena::io::InputError&) {
  }
  return 0;
}
