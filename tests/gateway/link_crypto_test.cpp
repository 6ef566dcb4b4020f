// The link seal (link_crypto.hpp): only an authentic, fresh, first-seen datagram opens; every
// forged, modified, truncated, replayed, reflected or stale one is rejected with its status and a
// message. Key files: a bad one is refused with an error naming the file.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "link_pair.hpp"
#include "pena/gateway/link_crypto.hpp"

namespace pena::gateway {
namespace {

constexpr double kNowS = 1.7e9;  // a wall clock in seconds

LinkKey KeyOf(std::uint8_t fill) {
  LinkKey key;
  for (std::size_t i = 0; i < key.bytes.size(); ++i) key.bytes[i] = static_cast<std::uint8_t>(fill + 7 * i);
  return key;
}

SealOptions Sender(std::uint32_t id, std::size_t window = 1024) {
  SealOptions options;
  options.sender_id = id;
  options.replay_window = window;
  return options;
}

const std::string kFrame = EncodeFrame("an envelope of poses and walls", false);

TEST(LinkSeal, RoundTripsAFrame) {
  LinkSeal near(KeyOf(1), Sender(1));
  LinkSeal far(KeyOf(1), Sender(2));
  const std::string sealed = near.Seal(kFrame, kNowS);
  EXPECT_EQ(sealed.size(), kFrame.size() + kSealOverheadBytes);
  EXPECT_EQ(sealed.find("poses"), std::string::npos);  // encrypted, not only signed
  const FrameResult opened = far.Open(sealed, kNowS + 0.3);
  ASSERT_TRUE(opened.ok()) << opened.message;
  EXPECT_EQ(opened.payload, kFrame);
  // And the other way.
  const FrameResult back = near.Open(far.Seal("reply", kNowS), kNowS);
  ASSERT_TRUE(back.ok()) << back.message;
  EXPECT_EQ(back.payload, "reply");
}

TEST(LinkSeal, RejectsEverySingleBitFlip) {
  LinkSeal near(KeyOf(1), Sender(1));
  LinkSeal far(KeyOf(1), Sender(2));
  const std::string sealed = near.Seal(kFrame, kNowS);
  for (std::size_t byte = 0; byte < sealed.size(); ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      std::string damaged = sealed;
      damaged[byte] = static_cast<char>(damaged[byte] ^ (1 << bit));
      const FrameResult result = far.Open(damaged, kNowS);
      // The key id is checked first; everything else is covered by the tag.
      EXPECT_EQ(result.status, byte == 0 ? FrameStatus::kWrongKey : FrameStatus::kUnauthenticated)
          << "byte " << byte << " bit " << bit;
      EXPECT_FALSE(result.message.empty());
    }
  }
  // None of them moved the replay window: the original still opens, once.
  EXPECT_TRUE(far.Open(sealed, kNowS).ok());
  EXPECT_EQ(far.Open(sealed, kNowS).status, FrameStatus::kReplayed);
}

TEST(LinkSeal, RejectsTruncationAtEveryLengthAndExtension) {
  LinkSeal near(KeyOf(1), Sender(1));
  LinkSeal far(KeyOf(1), Sender(2));
  const std::string sealed = near.Seal(kFrame, kNowS);
  for (std::size_t size = 0; size < sealed.size(); ++size) {
    const FrameResult result = far.Open(sealed.substr(0, size), kNowS);
    EXPECT_EQ(result.status, size < kSealOverheadBytes ? FrameStatus::kTruncated : FrameStatus::kUnauthenticated)
        << size;
  }
  EXPECT_EQ(far.Open(sealed + "x", kNowS).status, FrameStatus::kUnauthenticated);
  EXPECT_TRUE(far.Open(sealed, kNowS).ok());
}

TEST(LinkSeal, RejectsAReplay) {
  LinkSeal near(KeyOf(1), Sender(1));
  LinkSeal far(KeyOf(1), Sender(2));
  const std::string sealed = near.Seal(kFrame, kNowS);
  ASSERT_TRUE(far.Open(sealed, kNowS).ok());
  const FrameResult again = far.Open(sealed, kNowS + 1.0);
  EXPECT_EQ(again.status, FrameStatus::kReplayed);
  EXPECT_NE(again.message.find("already received"), std::string::npos) << again.message;
}

TEST(LinkSeal, AcceptsOutOfOrderWithinTheWindowOnce) {
  LinkSeal near(KeyOf(1), Sender(1, 16));
  LinkSeal far(KeyOf(1), Sender(2, 16));
  std::vector<std::string> sealed;
  for (int i = 0; i < 12; ++i) sealed.push_back(near.Seal(kFrame, kNowS + 0.1 * i));
  for (int i = 0; i < 12; i += 2) EXPECT_TRUE(far.Open(sealed[static_cast<std::size_t>(i)], kNowS + 2).ok()) << i;
  for (int i = 11; i > 0; i -= 2) EXPECT_TRUE(far.Open(sealed[static_cast<std::size_t>(i)], kNowS + 2).ok()) << i;
  for (const std::string& datagram : sealed) EXPECT_EQ(far.Open(datagram, kNowS + 2).status, FrameStatus::kReplayed);
}

TEST(LinkSeal, RejectsOlderThanTheWindow) {
  LinkSeal near(KeyOf(1), Sender(1, 16));
  LinkSeal far(KeyOf(1), Sender(2, 16));
  std::vector<std::string> sealed;
  for (int i = 0; i < 40; ++i) sealed.push_back(near.Seal(kFrame, kNowS + 0.1 * i));
  for (int i = 20; i < 40; ++i) ASSERT_TRUE(far.Open(sealed[static_cast<std::size_t>(i)], kNowS + 4).ok());
  // Never received, but older than the 16 newest received: refused.
  for (int i : {0, 5, 19, 23}) {
    const FrameResult result = far.Open(sealed[static_cast<std::size_t>(i)], kNowS + 4);
    EXPECT_EQ(result.status, FrameStatus::kReplayed) << i;
    EXPECT_NE(result.message.find("older than the last 16"), std::string::npos) << result.message;
  }
  EXPECT_EQ(far.Open(sealed[24], kNowS + 4).status, FrameStatus::kReplayed);  // in the window, seen
}

TEST(LinkSeal, RejectsAnotherKey) {
  LinkSeal near(KeyOf(1), Sender(1));
  const std::string sealed = near.Seal(kFrame, kNowS);
  // Another key: another key id, told apart from a forgery.
  LinkKey other = KeyOf(2);
  ASSERT_NE(other.id(), KeyOf(1).id());
  LinkSeal stranger(other, Sender(2));
  const FrameResult result = stranger.Open(sealed, kNowS);
  EXPECT_EQ(result.status, FrameStatus::kWrongKey);
  EXPECT_NE(result.message.find("different link keys"), std::string::npos) << result.message;
  // Another key that happens to share the id byte: the tag fails.
  LinkKey twin = KeyOf(3);
  for (std::uint8_t fill = 3; twin.id() != KeyOf(1).id(); ++fill) twin = KeyOf(fill);
  LinkSeal impostor(twin, Sender(2));
  EXPECT_EQ(impostor.Open(sealed, kNowS).status, FrameStatus::kUnauthenticated);
}

TEST(LinkSeal, RejectsItsOwnDatagramsSentBack) {
  LinkSeal near(KeyOf(1), Sender(1));
  const FrameResult result = near.Open(near.Seal(kFrame, kNowS), kNowS);
  EXPECT_EQ(result.status, FrameStatus::kReflected);
}

TEST(LinkSeal, RejectsCountersFarFromItsClock) {
  LinkSeal near(KeyOf(1), Sender(1));
  LinkSeal far(KeyOf(1), Sender(2));
  const std::string old = near.Seal(kFrame, kNowS);
  FrameResult result = far.Open(old, kNowS + 61.0);
  EXPECT_EQ(result.status, FrameStatus::kStale);
  EXPECT_NE(result.message.find("61.0 s behind"), std::string::npos) << result.message;
  EXPECT_EQ(far.Open(near.Seal(kFrame, kNowS + 200.0), kNowS + 120.0).status, FrameStatus::kStale);
  // With the check off, only the replay window decides.
  SealOptions unchecked = Sender(3);
  unchecked.max_clock_offset_s = 0.0;
  LinkSeal lenient(KeyOf(1), unchecked);
  EXPECT_TRUE(lenient.Open(old, kNowS + 3600.0).ok());
}

TEST(LinkSeal, RestartedSenderIsHeardAndItsOldDatagramsAreNot) {
  LinkSeal far(KeyOf(1), Sender(2));
  std::string before;
  {
    LinkSeal first(KeyOf(1), Sender(1));
    before = first.Seal(kFrame, kNowS);
    ASSERT_TRUE(far.Open(before, kNowS).ok());
  }
  LinkSeal restarted(KeyOf(1));  // a new random sender id, counters from the clock
  EXPECT_NE(restarted.sender_id(), 0U);
  EXPECT_TRUE(far.Open(restarted.Seal(kFrame, kNowS + 5.0), kNowS + 5.0).ok());
  EXPECT_EQ(far.Open(before, kNowS + 5.0).status, FrameStatus::kReplayed);
}

TEST(LinkSeal, CountersIncreaseWhenTheClockGoesBack) {
  LinkSeal near(KeyOf(1), Sender(1));
  LinkSeal far(KeyOf(1), Sender(2));
  const std::string later = near.Seal(kFrame, kNowS + 10.0);
  const std::string earlier_clock = near.Seal(kFrame, kNowS);  // the clock stepped back
  EXPECT_TRUE(far.Open(later, kNowS + 10.0).ok());
  EXPECT_TRUE(far.Open(earlier_clock, kNowS + 10.0).ok());  // a new counter, not a replay
}

TEST(LinkSeal, RejectsBadOptions) {
  SealOptions options;
  options.replay_window = 0;
  EXPECT_THROW(LinkSeal(KeyOf(1), options), std::invalid_argument);
  options = {};
  options.max_clock_offset_s = -1.0;
  EXPECT_THROW(LinkSeal(KeyOf(1), options), std::invalid_argument);
}

// Key files, in a scratch directory of this test.
class LinkKeyFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("pena-link-key-test-" + std::to_string(getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& content, mode_t mode = 0600) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << content;
    chmod(path.c_str(), mode);
    return path;
  }
  // The message of ReadLinkKey's exception ("" if it did not throw).
  static std::string ErrorOf(const std::string& path) {
    try {
      ReadLinkKey(path);
    } catch (const std::runtime_error& error) {
      return error.what();
    }
    return "";
  }
  std::filesystem::path dir_;
};

TEST_F(LinkKeyFile, WrittenKeyReadsBackAndIsNeverOverwritten) {
  const std::string path = (dir_ / "link.key").string();
  const LinkKey key = GenerateLinkKey();
  WriteLinkKey(path, key);
  struct stat status {};
  ASSERT_EQ(stat(path.c_str(), &status), 0);
  EXPECT_EQ(status.st_mode & 0777, 0600U);
  const LinkKey read = ReadLinkKey(path);
  EXPECT_EQ(read.bytes, key.bytes);
  EXPECT_EQ(read.Fingerprint(), key.Fingerprint());
  EXPECT_EQ(read.Fingerprint().size(), 8U);
  EXPECT_NE(GenerateLinkKey().bytes, key.bytes);
  EXPECT_THROW(WriteLinkKey(path, GenerateLinkKey()), std::runtime_error);
  EXPECT_EQ(ReadLinkKey(path).bytes, key.bytes);
}

TEST_F(LinkKeyFile, ReadsHexWithCommentsAndRawBytes) {
  const std::string hex = "# the ops room's key\n00112233445566778899aabbccddeeff\n"
                          "  00112233445566778899AABBCCDDEEFF  # second half\n";
  const LinkKey key = ReadLinkKey(Write("hex.key", hex));
  EXPECT_EQ(key.bytes[1], 0x11);
  EXPECT_EQ(key.bytes[31], 0xff);
  std::string raw(32, '\0');
  for (std::size_t i = 0; i < raw.size(); ++i) raw[i] = static_cast<char>(200 + i);
  EXPECT_EQ(ReadLinkKey(Write("raw.key", raw)).bytes[0], 200);
}

TEST_F(LinkKeyFile, RefusesBadFilesNamingThem) {
  const std::string missing = (dir_ / "missing.key").string();
  std::string error = ErrorOf(missing);
  EXPECT_NE(error.find(missing), std::string::npos) << error;
  EXPECT_NE(error.find("does not exist"), std::string::npos) << error;
  EXPECT_NE(error.find("--generate-link-key"), std::string::npos) << error;

  const std::string open = Write("open.key", std::string(64, 'a'), 0644);
  error = ErrorOf(open);
  EXPECT_NE(error.find("accessible to other users (mode 0644)"), std::string::npos) << error;
  EXPECT_NE(error.find("chmod 600 " + open), std::string::npos) << error;

  const std::string short_key = Write("short.key", std::string(62, 'a') + "\n");
  error = ErrorOf(short_key);
  EXPECT_NE(error.find(short_key + ": 62 hex digits"), std::string::npos) << error;

  const std::string bad = Write("bad.key", "0011\nzz" + std::string(60, 'a'));
  error = ErrorOf(bad);
  EXPECT_NE(error.find(bad + ":2:1: 'z' is not a hex digit"), std::string::npos) << error;

  error = ErrorOf(Write("zero.key", std::string(64, '0')));
  EXPECT_NE(error.find("all zeros"), std::string::npos) << error;
  error = ErrorOf(Write("empty.key", ""));
  EXPECT_NE(error.find("0 hex digits"), std::string::npos) << error;
  error = ErrorOf(dir_.string());
  EXPECT_NE(error.find("not a regular file"), std::string::npos) << error;
}

// Sessions: a sealed pair keeps its picture; an open peer and a sealed one do not talk.
TEST(LinkSealSession, SealedPairDeliversAndOpenFramesAreRefused) {
  LinkOptions near = testing::Endpoint(1);
  LinkOptions far = testing::Endpoint(2);
  near.key = far.key = KeyOf(1);
  testing::LinkPair pair(near, far, testing::IdealLink(), testing::IdealLink());
  pair.near.Offer(Annotation{.alarm = true, .entity = "ff1", .id = 1, .x_m = 3.0, .y_m = 4.0,
                             .stamp_s = 0.0, .text = "victim"});
  pair.RunUntil(2.0);
  ASSERT_EQ(pair.far.delivered().size(), 1U);
  EXPECT_TRUE(pair.near_session.sealed());
  const LinkStats& stats = pair.near_session.stats();
  EXPECT_EQ(stats.seal_bytes_sent, stats.frames_sent * kSealOverheadBytes);
  EXPECT_EQ(pair.far_session.stats().rejected_total(), 0U);

  // An open frame at the sealed end, and a sealed one at an open end.
  const FrameResult open = pair.far_session.OnFrame(EncodeFrame("x", false), pair.now_s);
  EXPECT_EQ(open.status, FrameStatus::kWrongKey);
  EXPECT_NE(open.message.find("--insecure-link"), std::string::npos) << open.message;
  EXPECT_EQ(pair.far_session.stats().rejected[static_cast<std::size_t>(FrameStatus::kWrongKey)], 1U);
  InMemoryDomain domain;
  LinkSession unsealed(testing::Endpoint(3), domain);
  EXPECT_FALSE(unsealed.OnFrame(pair.sent_forward.back().second, pair.now_s).ok());
}

}  // namespace
}  // namespace pena::gateway
