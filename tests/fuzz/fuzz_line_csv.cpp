// Line CSV files (docs/formats.md): ReadLineCsv directly and as a plan through ReadPlan.
#include <cstddef>
#include <cstdint>

#include "fuzz_file.hpp"
#include "pena/io/input_error.hpp"
#include "pena/io/line_csv.hpp"
#include "pena/io/plan_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static pena::fuzz::FuzzFile file("lines.csv");
  const auto& path = file.Write(data, size);
  try {
    (void)pena::io::ReadLineCsv(path);
  } catch (const pena::io::InputError&) {
  }
  try {
    (void)pena::io::ReadPlan(path);
  } catch (const pena::io::InputError&) {
  }
  return 0;
}
