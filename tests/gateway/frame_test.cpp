// Link frames: every malformed input is rejected with a status and a message, never a crash.
#include <gtest/gtest.h>

#include "pena/gateway/frame.hpp"

namespace pena::gateway {
namespace {

std::string Valid() { return EncodeFrame("hello link", false); }

TEST(Frame, RejectsGarbage) {
  FrameResult result = DecodeFrame("this is not a frame at all");
  EXPECT_EQ(result.status, FrameStatus::kBadMagic);
  EXPECT_FALSE(result.message.empty());
}

TEST(Frame, RejectsTruncatedFramesAtEveryLength) {
  const std::string frame = Valid();
  for (std::size_t size = 0; size < frame.size(); ++size) {
    EXPECT_EQ(DecodeFrame(frame.substr(0, size)).status, FrameStatus::kTruncated) << size;
  }
}

TEST(Frame, RejectsUnknownVersionAndFlags) {
  std::string frame = Valid();
  frame[2] = 2;
  FrameResult result = DecodeFrame(frame);
  EXPECT_EQ(result.status, FrameStatus::kUnknownVersion);
  EXPECT_NE(result.message.find("version 2"), std::string::npos);
  frame = Valid();
  frame[3] = 0x40;
  EXPECT_EQ(DecodeFrame(frame).status, FrameStatus::kBadFlags);
}

TEST(Frame, RejectsOversizedBeforeReadingThePayload) {
  const std::string frame = EncodeFrame(std::string(2000, 'x'), false);
  FrameLimits limits;
  limits.max_payload_bytes = 1000;
  FrameResult result = DecodeFrame(frame, limits);
  EXPECT_EQ(result.status, FrameStatus::kOversized);
  EXPECT_NE(result.message.find("2000"), std::string::npos);
}

TEST(Frame, RejectsEverySingleBitFlip) {
  const std::string frame = Valid();
  for (std::size_t byte = 0; byte < frame.size(); ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      std::string damaged = frame;
      damaged[byte] = static_cast<char>(damaged[byte] ^ (1 << bit));
      EXPECT_FALSE(DecodeFrame(damaged).ok()) << "byte " << byte << " bit " << bit;
    }
  }
}

TEST(Frame, RejectsDecompressionBombs) {
  const std::string frame = EncodeFrame(std::string(60000, '\0'), true);
  ASSERT_TRUE(DecodeFrame(frame).ok());
  FrameLimits limits;
  limits.max_inflated_bytes = 1000;
  EXPECT_EQ(DecodeFrame(frame, limits).status, FrameStatus::kBadCompression);
}

TEST(FrameStream, ResynchronisesOnTheNextMagicAfterGarbage) {
  const std::string stream = "garbage P" + Valid() + "PL\x01junk" + Valid() + Valid();
  FrameStreamDecoder decoder;
  std::vector<FrameResult> frames;
  // One byte at a time: frames split across reads still come out whole.
  for (char byte : stream) {
    for (FrameResult& frame : decoder.Feed(std::string_view(&byte, 1))) frames.push_back(frame);
  }
  std::size_t ok = 0;
  for (const FrameResult& frame : frames) ok += frame.ok() ? 1 : 0;
  EXPECT_EQ(ok, 3U);
  EXPECT_GT(decoder.skipped_bytes(), 0U);
}

TEST(FrameStream, RecoversAfterACorruptedFrame) {
  std::string damaged = Valid();
  damaged[8] ^= 0x01;
  FrameStreamDecoder decoder;
  std::vector<FrameResult> frames = decoder.Feed(damaged + Valid());
  ASSERT_GE(frames.size(), 2U);
  EXPECT_EQ(frames.front().status, FrameStatus::kBadCrc);
  EXPECT_TRUE(frames.back().ok());
  EXPECT_EQ(frames.back().payload, "hello link");
}

}  // namespace
}  // namespace pena::gateway
