// CARMEN logs (docs/formats.md): every record until the end or the first InputError, strict and
// skipping. The first byte picks the read options; the rest is the file.
#include <cstddef>
#include <cstdint>

#include "fuzz_file.hpp"
#include "pena/io/carmen.hpp"
#include "pena/io/input_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static pena::fuzz::FuzzFile file("log.clf");
  if (size < 1) return -1;
  pena::io::ReadOptions options;
  options.skip_malformed = (data[0] & 1) != 0;
  options.carmen_180_beams_span_180_deg = (data[0] & 2) != 0;
  options.carmen_interlace = (data[0] >> 2) & 3;
  const auto& path = file.Write(data + 1, size - 1);
  try {
    const auto log = pena::io::OpenCarmenLog(path, options);
    while (log->Next()) {
    }
  } catch (const pena::io::InputError&) {
  }
  return 0;
}
