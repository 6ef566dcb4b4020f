// The live input's account of samples that never arrived (seq_gaps): a whole stream, a late
// joiner, a lost sample, topics arriving out of order, a repeat, and the bound on what is held.
#include <gtest/gtest.h>

#include <stdexcept>

#include "seq_gaps.hpp"

namespace pena::services {
namespace {

TEST(SeqGaps, AWholeStreamMissesNothing) {
  SeqGaps gaps;
  for (std::uint64_t seq = 1; seq <= 100; ++seq) gaps.Saw(seq);
  const SeqGapCounts counts = gaps.Counts();
  EXPECT_EQ(counts.missed_at_start, 0u);
  EXPECT_EQ(counts.missed, 0u);
  EXPECT_EQ(counts.repeated_or_late, 0u);
  EXPECT_EQ(gaps.highest(), 100u);
}

TEST(SeqGaps, ALateJoinerMissedTheStart) {
  SeqGaps gaps;
  for (std::uint64_t seq = 41; seq <= 60; ++seq) gaps.Saw(seq);
  EXPECT_EQ(gaps.Counts().missed_at_start, 40u);
  EXPECT_EQ(gaps.Counts().missed, 0u);
}

TEST(SeqGaps, TopicsOutOfOrderBetweenEachOtherAreNotLosses) {
  SeqGaps gaps;
  // Scans (odd numbers) arrive a few numbers ahead of the gyro (even numbers).
  for (std::uint64_t seq : {1u, 3u, 5u, 2u, 7u, 4u, 6u, 9u, 8u, 10u}) gaps.Saw(seq);
  EXPECT_EQ(gaps.Counts().missed_at_start, 0u);
  EXPECT_EQ(gaps.Counts().missed, 0u);
}

TEST(SeqGaps, AnEarlierNumberArrivingSecondStillCountsAsStart) {
  SeqGaps gaps;
  gaps.Saw(12);
  gaps.Saw(11);  // another topic's sample, older, arrived after
  EXPECT_EQ(gaps.Counts().missed_at_start, 10u);
  EXPECT_EQ(gaps.Counts().repeated_or_late, 0u);
}

TEST(SeqGaps, ALostSampleIsMissedOpenOrGivenUp) {
  SeqGaps open;
  for (std::uint64_t seq = 1; seq <= 20; ++seq) {
    if (seq != 7) open.Saw(seq);
  }
  EXPECT_EQ(open.Counts().missed, 1u);  // still open: counted at the end of the stream

  SeqGaps bounded(SeqGapsOptions{4});
  for (std::uint64_t seq = 1; seq <= 20; ++seq) {
    if (seq != 7 && seq != 8) bounded.Saw(seq);
  }
  EXPECT_EQ(bounded.Counts().missed, 2u);  // given up after 5 later numbers
  bounded.Saw(7);  // too late: its hole was given up
  EXPECT_EQ(bounded.Counts().missed, 2u);
  EXPECT_EQ(bounded.Counts().repeated_or_late, 1u);
}

TEST(SeqGaps, ARepeatIsCountedNotLost) {
  SeqGaps gaps;
  for (std::uint64_t seq : {1u, 2u, 3u, 2u, 4u}) gaps.Saw(seq);
  EXPECT_EQ(gaps.Counts().repeated_or_late, 1u);
  EXPECT_EQ(gaps.Counts().missed, 0u);
}

TEST(SeqGaps, UnnumberedSamplesAreIgnored) {
  SeqGaps gaps;
  gaps.Saw(0);
  EXPECT_EQ(gaps.highest(), 0u);
  EXPECT_EQ(gaps.Counts().missed_at_start, 0u);
}

TEST(SeqGaps, RefusesAnEmptyWindow) {
  EXPECT_THROW(SeqGaps(SeqGapsOptions{0}), std::invalid_argument);
}

}  // namespace
}  // namespace pena::services
