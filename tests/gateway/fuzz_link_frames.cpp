// fuzz_link_frames: feeds N (default 1,000,000) random, mutated, truncated and re-framed inputs
// to the link decoder (LinkSession::OnFrame and the stream decoder). Exit status 1 if a rejection
// had no message or the session stopped accepting valid frames; a crash is a crash.
// usage: fuzz_link_frames [INPUTS] [SEED]
#include <cstdlib>

#include "fuzz_inputs.hpp"

int main(int argc, char** argv) {
  const std::size_t inputs = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1'000'000;
  const std::uint64_t seed = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 12345;
  const pena::gateway::testing::FuzzCounts counts = pena::gateway::testing::RunFuzz(inputs, seed);
  pena::gateway::testing::PrintFuzz(inputs, counts);
  return counts.silent_rejections == 0 && counts.still_accepts_valid ? 0 : 1;
}
