#pragma once
// Fuzz inputs for the link decoder (tests/gateway/fuzz_test.cpp, fuzz_link_frames.cpp): random,
// mutated, truncated and re-framed (valid CRC, damaged payload or deflate stream) frames built
// from a real team's traffic, fed through LinkSession::OnFrame and the stream decoder.

#include <zlib.h>

#include <array>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "link_pair.hpp"
#include "pena/gateway/synthetic_team.hpp"

namespace pena::gateway::testing {

// Applies map changes like a real domain would, but keeps nothing else (a million inputs).
class CountingDomain : public DomainSide {
 public:
  std::vector<DomainItem> Drain() override { return {}; }
  void Deliver(const DomainItem& item) override {
    ++delivered;
    const auto* change = std::get_if<MapChange>(&item);
    if (change == nullptr) return;
    if (const auto* delta = std::get_if<line_map::MapDelta>(&change->change)) {
      maps[change->map_id].Apply(*delta);
    } else {
      maps[change->map_id] = line_map::LineMap::FromSnapshot(std::get<line_map::MapSnapshot>(change->change));
    }
  }
  std::size_t delivered = 0;
  std::map<std::string, line_map::LineMap> maps;
};

// Real frames: a team's traffic over a short run (poses, alarms, map deltas, control).
inline std::vector<std::string> Corpus() {
  LinkPair pair(Endpoint(1), Endpoint(2), IdealLink(),
                         IdealLink());
  SyntheticTeamOptions options;
  options.alarm_period_s = 5.0;
  SyntheticTeam team(options);
  // A map update far larger than a packet, so the corpus holds fragments too.
  line_map::LineMap global;
  std::vector<line_map::LineSegment> walls(150);
  for (std::size_t i = 0; i < walls.size(); ++i) {
    walls[i].segment.start_m = {4.0 * static_cast<double>(i % 30), 0.5 * static_cast<double>(i / 30)};
    walls[i].segment.end_m = walls[i].segment.start_m + Eigen::Vector2d(3.0, 0.0);
    walls[i].support_cells = 40;
    walls[i].observations = 5;
  }
  pair.near.Offer(MapChange{"global", global.Integrate(walls, "global"), false});
  while (pair.now_s < 30.0) {
    for (DomainItem& item : team.Advance(pair.now_s)) pair.near.Offer(std::move(item));
    pair.Step(0.01);
  }
  std::vector<std::string> corpus;
  for (auto& [t, frame] : pair.sent_forward) corpus.push_back(frame);
  return corpus;
}

inline std::string Mutate(std::string bytes, std::mt19937_64& random) {
  if (bytes.empty()) return bytes;
  const int flips = 1 + static_cast<int>(random() % 6);
  for (int i = 0; i < flips && !bytes.empty(); ++i) {
    const std::size_t at = random() % bytes.size();
    switch (random() % 4) {
      case 0: bytes[at] = static_cast<char>(random()); break;
      case 1: bytes[at] = static_cast<char>(bytes[at] ^ (1 << (random() % 8))); break;
      case 2: bytes.erase(at, 1 + random() % 4); break;
      default: bytes.insert(at, 1, static_cast<char>(random())); break;
    }
  }
  return bytes;
}

// A deflated frame whose compressed bytes are damaged, with the CRC made valid again.
inline std::string Redeflated(const std::string& payload, std::mt19937_64& random) {
  std::string frame = EncodeFrame(payload + payload, true);  // doubled: always compresses
  if ((frame[3] & kFlagDeflated) == 0) return frame;
  std::string body = Mutate(frame.substr(kFrameHeaderBytes, frame.size() - kFrameHeaderBytes - 4), random);
  if (body.size() > 0xFFFF) return frame;
  std::string out = frame.substr(0, 4);
  out.push_back(static_cast<char>(body.size() >> 8));
  out.push_back(static_cast<char>(body.size()));
  out += body;
  const auto crc = static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(out.data()), static_cast<uInt>(out.size())));
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>(crc >> shift));
  return out;
}

inline std::string Input(const std::vector<std::string>& corpus, std::mt19937_64& random) {
  const std::string& base = corpus[random() % corpus.size()];
  switch (random() % 6) {
    case 0: {  // random bytes, sometimes behind a valid magic and version
      std::string bytes(random() % 200, '\0');
      for (char& byte : bytes) byte = static_cast<char>(random());
      return random() % 2 ? bytes : std::string("PL\x01\x00", 4) + bytes;
    }
    case 1: return Mutate(base, random);                      // damaged in transit
    case 2: return base.substr(0, random() % base.size());    // truncated
    case 3: return Redeflated(DecodeFrame(base).payload, random);  // damaged deflate stream
    default: {  // damaged payload re-framed with a valid CRC: reaches the envelope parser
      const std::string payload = DecodeFrame(base).payload;
      return EncodeFrame(Mutate(payload, random), random() % 100 == 0);
    }
  }
}

// What a fuzz run saw: inputs per FrameStatus, items delivered, rejections without a message.
struct FuzzCounts {
  std::array<std::size_t, kFrameStatusCount> by_status{};
  std::size_t delivered = 0;
  std::size_t silent_rejections = 0;
  std::size_t corpus_fragments = 0;  // fragment items in the real frames mutated
  bool still_accepts_valid = false;
};

// Feeds `inputs` fuzz inputs (seeded) to one session; 1 in 16 also to a stream decoder.
inline FuzzCounts RunFuzz(std::size_t inputs, std::uint64_t seed) {
  const std::vector<std::string> corpus = Corpus();
  CountingDomain domain;
  LinkSession session(Endpoint(9), domain);
  FrameStreamDecoder stream;
  std::mt19937_64 random(seed);
  FuzzCounts counts;
  for (const std::string& frame : corpus) {
    link::Envelope envelope;
    if (!envelope.ParseFromString(DecodeFrame(frame).payload)) continue;
    for (const link::Item& item : envelope.items()) counts.corpus_fragments += item.has_fragment() ? 1 : 0;
  }
  for (std::size_t i = 0; i < inputs; ++i) {
    const std::string input = Input(corpus, random);
    const FrameResult result = session.OnFrame(input, 1.0 + 1e-3 * static_cast<double>(i));
    ++counts.by_status[static_cast<std::size_t>(result.status)];
    if (!result.ok() && result.message.empty()) ++counts.silent_rejections;
    if (i % 16 == 0) stream.Feed(input);
  }
  counts.delivered = domain.delivered;
  // The session still works: an untouched frame is accepted.
  counts.still_accepts_valid = session.OnFrame(corpus.back(), 2e6).ok();
  return counts;
}

// One line of figures: inputs and counts per status.
inline void PrintFuzz(std::size_t inputs, const FuzzCounts& counts) {
  std::printf("[figures] fuzz: %zu inputs:", inputs);
  for (std::size_t s = 0; s < counts.by_status.size(); ++s) {
    std::printf(" %s %zu", ToString(static_cast<FrameStatus>(s)), counts.by_status[s]);
  }
  std::printf("; %zu items delivered; %zu rejections without a message; %zu fragments in the "
              "corpus\n", counts.delivered, counts.silent_rejections, counts.corpus_fragments);
}

}  // namespace pena::gateway::testing
