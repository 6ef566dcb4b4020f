#include "pena/gateway/map_fragments.hpp"

#include <algorithm>
#include <iterator>

namespace pena::gateway {
namespace {

constexpr std::size_t kRememberedGroups = 256;

bool Acked(const link::Ack& ack, std::uint64_t seq) {
  return seq != 0 && (seq <= ack.cumulative() ||
                      std::find(ack.selective().begin(), ack.selective().end(), seq) !=
                          ack.selective().end());
}

}  // namespace

OutgoingUpdate::OutgoingUpdate(const link::Item& item, std::uint64_t group)
    : item_(item), bytes_(item.SerializeAsString()), group_(group) {
  Restart(group);
}

std::vector<OutgoingUpdate::Piece> OutgoingUpdate::DuePieces(double now_s) const {
  std::vector<Piece> due;
  for (const Piece& piece : pieces_) {
    if (!piece.acked && piece.timer.Due(now_s)) due.push_back(piece);
  }
  return due;
}

ResendTimer OutgoingUpdate::MarkSent(std::uint32_t offset, std::uint32_t length, std::uint64_t seq,
                                     double now_s, double first_timeout_s, double max_timeout_s) {
  fragmented_ = true;
  auto it = std::find_if(pieces_.begin(), pieces_.end(),
                         [offset](const Piece& piece) { return piece.offset == offset; });
  if (it == pieces_.end() || length == 0 || length > it->length) return {};
  if (length < it->length) {  // the rest keeps its state
    Piece rest = *it;
    rest.offset = offset + length;
    rest.length = it->length - length;
    it->length = length;
    it = std::prev(pieces_.insert(std::next(it), rest));
  }
  const ResendTimer before = it->timer;
  ResendTimer& timer = it->timer;
  timer.timeout_s = timer.sends == 0 ? first_timeout_s
                                     : std::clamp(2.0 * timer.timeout_s, first_timeout_s, max_timeout_s);
  ++timer.sends;
  timer.last_sent_s = now_s;
  it->seq = seq;
  return before;
}

void OutgoingUpdate::Ack(const link::Ack& ack) {
  for (Piece& piece : pieces_) {
    if (!piece.acked && Acked(ack, piece.seq)) piece.acked = true;
  }
}

bool OutgoingUpdate::SentCompletely() const {
  if (whole_timer_.sends > 0) return true;
  return fragmented_ && std::all_of(pieces_.begin(), pieces_.end(),
                                    [](const Piece& piece) { return piece.timer.sends > 0; });
}

bool OutgoingUpdate::Stalled(double now_s, double stall_s) const {
  if (!fragmented_) return false;
  double last_s = 0.0;
  for (const Piece& piece : pieces_) {
    if (!piece.acked) return false;
    last_s = std::max(last_s, piece.timer.last_sent_s);
  }
  return now_s - last_s >= stall_s;
}

void OutgoingUpdate::Restart(std::uint64_t group) {
  group_ = group;
  fragmented_ = false;
  whole_timer_ = {};
  pieces_.assign(1, Piece{0, static_cast<std::uint32_t>(bytes_.size()), 0, false, {}});
}

void OutgoingUpdate::DueNow() {
  whole_timer_.timeout_s = 0.0;
  for (Piece& piece : pieces_) piece.timer.timeout_s = 0.0;
}

std::string CheckFragment(const link::Fragment& fragment, std::size_t max_update_bytes) {
  if (fragment.total_bytes() == 0 || fragment.total_bytes() > max_update_bytes) {
    return "fragment: total_bytes " + std::to_string(fragment.total_bytes()) + " not in [1, " +
           std::to_string(max_update_bytes) + "]";
  }
  if (fragment.data().empty()) return "fragment: empty data";
  if (static_cast<std::uint64_t>(fragment.offset()) + fragment.data().size() > fragment.total_bytes()) {
    return "fragment: offset " + std::to_string(fragment.offset()) + " + " +
           std::to_string(fragment.data().size()) + " bytes exceeds total_bytes " +
           std::to_string(fragment.total_bytes());
  }
  return {};
}

FragmentAssembler::FragmentAssembler(std::size_t max_buffered_bytes, std::size_t max_incomplete)
    : max_buffered_bytes_(max_buffered_bytes), max_incomplete_(std::max<std::size_t>(1, max_incomplete)) {}

std::optional<std::string> FragmentAssembler::Add(const link::Fragment& fragment) {
  const std::uint64_t group = fragment.group();
  if (done_.count(group) != 0) return std::nullopt;  // a late resend of a completed update
  auto [it, inserted] = partial_.try_emplace(group);
  Partial& partial = it->second;
  if (inserted) {
    partial.total_bytes = fragment.total_bytes();
    partial.created = next_created_++;
    by_age_.emplace(partial.created, group);
  } else if (partial.total_bytes != fragment.total_bytes()) {
    return std::nullopt;  // not the update this group started as: ignore the stray piece
  }
  Insert(partial, fragment.offset(), fragment.data());
  if (partial.held_bytes < partial.total_bytes) {
    Evict(group);
    return std::nullopt;
  }
  std::string whole;
  whole.reserve(partial.total_bytes);
  for (const auto& [offset, data] : partial.pieces) whole += data;
  Forget(group);
  done_.insert(group);
  done_order_.push_back(group);
  if (done_order_.size() > kRememberedGroups) {
    done_.erase(done_order_.front());
    done_order_.pop_front();
  }
  return whole;
}

// Stores the bytes of [offset, offset + size) not held yet (pieces of resends may overlap).
void FragmentAssembler::Insert(Partial& partial, std::uint32_t offset, std::string_view data) {
  std::uint32_t at = offset;
  const std::uint32_t end = offset + static_cast<std::uint32_t>(data.size());
  auto next = partial.pieces.upper_bound(at);
  if (next != partial.pieces.begin()) {
    const auto before = std::prev(next);
    at = std::max(at, before->first + static_cast<std::uint32_t>(before->second.size()));
  }
  while (at < end) {
    const std::uint32_t stop = next == partial.pieces.end() ? end : std::min(end, next->first);
    if (stop > at) {
      partial.pieces.emplace(at, std::string(data.substr(at - offset, stop - at)));
      partial.held_bytes += stop - at;
      buffered_bytes_ += stop - at;
    }
    if (next == partial.pieces.end()) break;
    at = std::max(at, next->first + static_cast<std::uint32_t>(next->second.size()));
    ++next;
  }
}

void FragmentAssembler::Evict(std::uint64_t keep_group) {
  auto oldest = by_age_.begin();
  while ((buffered_bytes_ > max_buffered_bytes_ || partial_.size() > max_incomplete_) &&
         oldest != by_age_.end()) {
    if (oldest->second == keep_group) {
      ++oldest;
      continue;
    }
    const std::uint64_t group = oldest->second;
    ++oldest;  // Forget erases the entry
    ++dropped_;
    Forget(group);
  }
}

void FragmentAssembler::Forget(std::uint64_t group) {
  const auto it = partial_.find(group);
  if (it == partial_.end()) return;
  buffered_bytes_ -= it->second.held_bytes;
  by_age_.erase(it->second.created);
  partial_.erase(it);
}

void FragmentAssembler::Clear() {
  partial_.clear();
  by_age_.clear();
  done_.clear();
  done_order_.clear();
  buffered_bytes_ = 0;
}

}  // namespace pena::gateway
