// A gateway's receiving side (LinkSession::OnFrame, docs/gateway.md): envelopes, link items
// (link_codec FromProto), map fragments and resync, delivered to a domain that applies map
// changes. The input is a sequence of datagram payloads, each a 2-byte big-endian length and
// that many bytes, framed with a valid CRC (so the fuzzer reaches the envelope parser) and fed
// to a fresh open session, one every 10 ms. A rejection must say why.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "fuzz_file.hpp"
#include "pena/gateway/domain_side.hpp"
#include "pena/gateway/frame.hpp"
#include "pena/gateway/link_session.hpp"
#include "pena/line_map/line_map.hpp"

namespace gateway = pena::gateway;

namespace {

// Applies map changes as a real domain would and drops the rest.
class ApplyingDomain : public gateway::DomainSide {
 public:
  std::vector<gateway::DomainItem> Drain() override { return {}; }
  void Deliver(const gateway::DomainItem& item) override {
    const auto* change = std::get_if<gateway::MapChange>(&item);
    if (change == nullptr) return;
    if (const auto* delta = std::get_if<pena::line_map::MapDelta>(&change->change)) {
      maps_[change->map_id].Apply(*delta);
    } else {
      maps_[change->map_id] =
          pena::line_map::LineMap::FromSnapshot(std::get<pena::line_map::MapSnapshot>(change->change));
    }
  }

 private:
  std::map<std::string, pena::line_map::LineMap> maps_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ApplyingDomain domain;
  gateway::LinkOptions options;
  options.session = 9;
  gateway::LinkSession session(options, domain);
  double now_s = 1.0;
  std::size_t at = 0;
  while (at + 2 <= size) {
    const std::size_t length = std::size_t{data[at]} << 8 | data[at + 1];
    at += 2;
    const std::size_t take = length < size - at ? length : size - at;
    const std::string frame = gateway::EncodeFrame(pena::fuzz::AsText(data + at, take), false);
    at += take;
    const gateway::FrameResult result = session.OnFrame(frame, now_s);
    if (!result.ok() && result.message.empty()) std::abort();
    (void)session.Poll(now_s);
    now_s += 0.01;
  }
  return 0;
}
