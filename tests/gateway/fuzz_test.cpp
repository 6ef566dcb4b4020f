// Fuzzing the link decoder in the test suite: 200,000 inputs (random, mutated, truncated,
// re-framed with a valid CRC). fuzz_link_frames runs a million the same way (docs/gateway.md).
#include <gtest/gtest.h>

#include "fuzz_inputs.hpp"

namespace pena::gateway {
namespace {

TEST(Fuzz, RandomMutatedAndTruncatedFramesNeverCrashTheDecoder) {
  constexpr std::size_t kInputs = 200'000;
  const testing::FuzzCounts counts = testing::RunFuzz(kInputs, 12345);
  testing::PrintFuzz(kInputs, counts);
  EXPECT_EQ(counts.silent_rejections, 0U);
  EXPECT_GT(counts.by_status[static_cast<std::size_t>(FrameStatus::kOk)], 0U);
  EXPECT_GT(counts.by_status[static_cast<std::size_t>(FrameStatus::kBadPayload)], 0U);
  EXPECT_GT(counts.by_status[static_cast<std::size_t>(FrameStatus::kBadCrc)], 0U);
  EXPECT_GT(counts.by_status[static_cast<std::size_t>(FrameStatus::kBadCompression)], 0U);
  EXPECT_TRUE(counts.still_accepts_valid);
  EXPECT_GT(counts.corpus_fragments, 0U) << "map pieces are fuzzed too";
}

}  // namespace
}  // namespace pena::gateway
