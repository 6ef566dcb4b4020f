#include "pena/gateway/link_session.hpp"

#include <algorithm>
#include <random>
#include <stdexcept>

#include "pena/gateway/link_codec.hpp"

namespace pena::gateway {
namespace {

void Require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// Bytes every datagram adds around an envelope: frame header and CRC, the seal if any, and the
// configured overhead below (IP, UDP).
std::size_t DatagramOverhead(const LinkOptions& options) {
  return kFrameHeaderBytes + kFrameTrailerBytes + (options.key ? kSealOverheadBytes : 0) +
         options.overhead_bytes;
}

LinkOptions Validated(LinkOptions options) {
  const double frame_bits = 8.0 * static_cast<double>(options.packet_bytes + DatagramOverhead(options));
  Require(options.packet_bytes >= 64 && options.packet_bytes <= options.limits.max_payload_bytes,
          "link.packet_bytes must be in [64, limits.max_payload_bytes] bytes, got " +
              std::to_string(options.packet_bytes));
  Require(options.burst_bits >= frame_bits,
          "link.burst_bits must hold one full frame (" + std::to_string(frame_bits) +
              " bits), got " + std::to_string(options.burst_bits));
  Require(options.heartbeat_s > 0.0 && options.probe_interval_s > 0.0,
          "link.heartbeat_s and link.probe_interval_s must be > 0 s");
  Require(options.outage_timeout_s > options.heartbeat_s,
          "link.outage_timeout_s must exceed link.heartbeat_s (s), got " +
              std::to_string(options.outage_timeout_s));
  Require(options.min_packet_interval_s >= 0.0, "link.min_packet_interval_s must be >= 0 s");
  if (options.session == 0) {
    std::random_device random;
    options.session = (static_cast<std::uint64_t>(random()) << 32) | random() | 1U;
  }
  return options;
}

}  // namespace

LinkSession::LinkSession(LinkOptions options, DomainSide& domain)
    : options_(Validated(std::move(options))),
      domain_(domain),
      scheduler_(options_.scheduler),
      receiver_(options_.receiver),
      bucket_(options_.budget_bit_s, options_.burst_bits) {
  if (options_.key) seal_ = std::make_unique<LinkSeal>(*options_.key, options_.seal);
}

bool LinkSession::peer_alive(double now_s) const {
  return now_s - last_heard_s_ < options_.outage_timeout_s;
}

const LinkStats& LinkSession::stats() const {
  stats_.poses_replaced = scheduler_.replaced_poses();
  return stats_;
}

std::vector<std::string> LinkSession::Poll(double now_s) {
  for (DomainItem& item : domain_.Drain()) scheduler_.Offer(std::move(item));
  bucket_.Refill(now_s);
  std::vector<std::string> frames;
  while (std::optional<std::string> frame = BuildFrame(now_s)) frames.push_back(std::move(*frame));
  return frames;
}

// Control items: a resync request while the peer is silent or unconfirmed; this side's map
// versions when owed. Returns whether a request was added.
bool LinkSession::AddControl(link::Envelope* envelope, double now_s) const {
  if (receiver_.ack_owed()) *envelope->mutable_ack() = receiver_.MakeAck();
  if (receiver_.summary_owed()) {
    *envelope->add_items()->mutable_resync_summary() = receiver_.MakeSummary(options_.session);
  }
  const bool probe = (!peer_alive(now_s) || awaiting_resync_) && now_s >= next_probe_s_;
  if (probe) envelope->add_items()->mutable_resync_request()->set_session(options_.session);
  return probe;
}

std::optional<std::string> LinkSession::BuildFrame(double now_s) {
  const std::size_t frame_overhead = DatagramOverhead(options_);
  const double available_bytes = bucket_.tokens_bits() / 8.0 - static_cast<double>(frame_overhead);
  if (available_bytes < 24.0) return std::nullopt;  // not even a small envelope fits yet
  link::Envelope envelope;
  envelope.set_schema_version(kLinkSchemaVersion);
  envelope.set_packet_seq(next_packet_seq_);
  envelope.set_base_stamp_ms(StampMs(now_s));
  const bool probe = AddControl(&envelope, now_s);
  const std::size_t control_bytes = envelope.ByteSizeLong();
  const std::size_t max_bytes =
      std::min(options_.packet_bytes, static_cast<std::size_t>(available_bytes));
  Selection selection;
  if (peer_alive(now_s) && !awaiting_resync_) {
    selection = scheduler_.Fill(&envelope, max_bytes, bucket_.full(), now_s);
  }
  const bool has_data = selection.size() > 0;
  const bool urgent = probe || !selection.annotation_seqs.empty() ||
                      receiver_.FeedbackDue(now_s) ||
                      (peer_alive(now_s) && now_s - last_sent_s_ >= options_.heartbeat_s);
  const bool full = has_data && selection.full && max_bytes >= options_.packet_bytes;
  // While map data waits, a packet the budget cuts short waits for a full one: every packet
  // pays 38-52 bytes of headers and one round of poses, so fewer, fuller packets leave the map
  // class most of the budget (docs/gateway.md, "Scheduler policy").
  const bool cut_short = selection.map_waiting && max_bytes < options_.packet_bytes;
  const bool paced = has_data && !cut_short && now_s - last_sent_s_ >= options_.min_packet_interval_s;
  if (!urgent && !full && !paced) return std::nullopt;

  std::string frame = EncodeFrame(envelope.SerializeAsString(), options_.compress);
  if (seal_) {
    frame = seal_->Seal(frame, now_s);
    stats_.seal_bytes_sent += kSealOverheadBytes;
  }
  scheduler_.Commit(selection, now_s, &stats_);
  if (envelope.has_ack()) receiver_.ClearAck();
  receiver_.ClearSummary();
  if (probe) next_probe_s_ = now_s + options_.probe_interval_s;
  auto& control = stats_.sent[static_cast<std::size_t>(ItemClass::kControl)];
  ++control.items;
  control.bytes += control_bytes;
  ++next_packet_seq_;
  last_sent_s_ = now_s;
  ++stats_.frames_sent;
  stats_.frame_bytes_sent += frame.size();
  stats_.wire_bytes_sent += frame.size() + options_.overhead_bytes;
  bucket_.Consume(8.0 * static_cast<double>(frame.size() + options_.overhead_bytes));
  return frame;
}

FrameResult LinkSession::Reject(FrameStatus status, std::string message) {
  ++stats_.rejected[static_cast<std::size_t>(status)];
  FrameResult result;
  result.status = status;
  result.message = std::move(message);
  return result;
}

void LinkSession::OnPeerSession(std::uint64_t session, double now_s) {
  if (session == peer_session_) return;
  if (peer_session_ != 0) {
    receiver_.OnPeerRestart(now_s);
    scheduler_.OnPeerRestart();  // the pieces it acknowledged are gone with it
  }
  peer_session_ = session;
  awaiting_resync_ = true;  // a new peer: learn what it holds before sending more
}

// The domain items of an envelope (resync messages and fragments, checked here, are left to
// OnFrame); the first error if any.
std::string LinkSession::DecodeItems(const link::Envelope& envelope,
                                     std::vector<ReceivedItem>* items) const {
  for (int i = 0; i < envelope.items_size(); ++i) {
    const link::Item& item = envelope.items(i);
    if (item.has_resync_request() || item.has_resync_summary()) continue;
    if (item.has_fragment()) {
      const std::string error = CheckFragment(item.fragment(), receiver_.max_update_bytes());
      if (!error.empty()) return "item " + std::to_string(i) + ": " + error;
      continue;
    }
    std::string error;
    std::optional<DomainItem> decoded = FromProto(item, envelope.base_stamp_ms(), &error);
    if (!decoded) return "item " + std::to_string(i) + ": " + error;
    items->push_back({item.seq(), std::move(*decoded)});
  }
  return {};
}

FrameResult LinkSession::OnFrame(std::string_view bytes, double now_s) {
  // A sealed link opens (authenticates, checks replay) before it reads a byte of the frame.
  FrameResult opened;
  if (seal_) {
    opened = seal_->Open(bytes, now_s);
    if (!opened.ok()) return Reject(opened.status, opened.message);
    bytes = opened.payload;
  }
  FrameResult frame = DecodeFrame(bytes, options_.limits);
  if (!frame.ok()) return Reject(frame.status, frame.message);
  link::Envelope envelope;
  if (!envelope.ParseFromString(frame.payload)) {
    return Reject(FrameStatus::kBadPayload, "envelope does not parse");
  }
  if (envelope.schema_version() != kLinkSchemaVersion) {
    return Reject(FrameStatus::kUnknownVersion,
                  "schema_version " + std::to_string(envelope.schema_version()) + ", expected 1");
  }
  // Decode every item before acting on any: a bad frame changes nothing.
  std::vector<ReceivedItem> items;
  if (std::string error = DecodeItems(envelope, &items); !error.empty()) {
    return Reject(FrameStatus::kBadPayload, error);
  }
  if (!peer_alive(now_s)) awaiting_resync_ = true;  // back from silence: confirm before resending
  last_heard_s_ = now_s;
  ++stats_.frames_received;
  if (envelope.has_ack()) scheduler_.OnAck(envelope.ack());
  for (const link::Item& item : envelope.items()) {
    if (item.has_resync_request()) {
      OnPeerSession(item.resync_request().session(), now_s);
      receiver_.OweSummary(now_s - options_.receiver.ack_delay_s);  // answer at once
    } else if (item.has_resync_summary()) {
      OnPeerSession(item.resync_summary().session(), now_s);
      scheduler_.OnPeerSummary(item.resync_summary(), &stats_);
      if (awaiting_resync_) {
        scheduler_.ResendAllNow();  // what the summary did not confirm is missing: resend now
        awaiting_resync_ = false;
        ++stats_.resyncs;
      }
    }
  }
  AcceptFragments(envelope, &items, now_s);
  for (const DomainItem& item : receiver_.Accept(std::move(items), now_s)) domain_.Deliver(item);
  return frame;
}

// Map updates the envelope's fragments complete join the items. One that does not decode is
// dropped and counted (its pieces came in earlier frames, which were sound); the sender resends
// it when its version stays unconfirmed.
void LinkSession::AcceptFragments(const link::Envelope& envelope, std::vector<ReceivedItem>* items,
                                  double now_s) {
  for (const link::Item& item : envelope.items()) {
    if (!item.has_fragment()) continue;
    std::optional<std::string> whole = receiver_.AcceptFragment(item.seq(), item.fragment(), now_s);
    if (!whole) continue;
    ++stats_.updates_reassembled;
    link::Item update;
    std::optional<DomainItem> decoded;
    if (update.ParseFromString(*whole) && update.has_map()) decoded = FromProto(update, 0, nullptr);
    if (!decoded) {
      ++stats_.reassembled_invalid;
      continue;
    }
    items->push_back({0, std::move(*decoded)});
  }
}

}  // namespace pena::gateway
