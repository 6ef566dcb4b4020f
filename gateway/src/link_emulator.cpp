#include "pena/gateway/link_emulator.hpp"

#include <algorithm>
#include <stdexcept>

namespace pena::gateway {

EmulatedLink::EmulatedLink(EmulatedLinkOptions options)
    : options_(std::move(options)), random_(options_.seed) {
  if (!(options_.rate_bit_s >= 0.0)) {
    throw std::invalid_argument("emulated_link.rate_bit_s must be >= 0 bit/s");
  }
  if (!(options_.delay_s >= 0.0)) throw std::invalid_argument("emulated_link.delay_s must be >= 0 s");
  if (!(options_.loss >= 0.0 && options_.loss < 1.0)) {
    throw std::invalid_argument("emulated_link.loss must be in [0, 1), got " +
                                std::to_string(options_.loss));
  }
  for (const auto& [start, end] : options_.outages) {
    if (!(end > start)) throw std::invalid_argument("emulated_link.outages: end must be > start (s)");
  }
}

bool EmulatedLink::InOutage(double now_s) const {
  return std::any_of(options_.outages.begin(), options_.outages.end(),
                     [now_s](const auto& w) { return now_s >= w.first && now_s < w.second; });
}

void EmulatedLink::Send(std::string frame, double now_s) {
  Advance(now_s);
  const std::size_t bytes = frame.size() + options_.overhead_bytes;
  ++stats_.frames_in;
  stats_.bytes_in += bytes;
  if (options_.rate_bit_s > 0.0 && queued_bytes_ + bytes > options_.queue_limit_bytes) {
    ++stats_.dropped_queue;
    return;
  }
  const double serialise_s =
      options_.rate_bit_s > 0.0 ? 8.0 * static_cast<double>(bytes) / options_.rate_bit_s : 0.0;
  busy_until_s_ = std::max(busy_until_s_, now_s) + serialise_s;
  queue_.push_back({busy_until_s_, bytes, std::move(frame)});
  queued_bytes_ += bytes;
  Advance(now_s);
}

void EmulatedLink::Advance(double now_s) {
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  while (!queue_.empty() && queue_.front().departure_s <= now_s) {
    Queued done = std::move(queue_.front());
    queue_.pop_front();
    queued_bytes_ -= done.bytes;
    if (InOutage(done.departure_s)) {
      ++stats_.dropped_outage;
    } else if (options_.loss > 0.0 && uniform(random_) < options_.loss) {
      ++stats_.dropped_loss;
    } else {
      in_flight_.push_back({done.departure_s + options_.delay_s, std::move(done.frame)});
    }
  }
}

std::vector<std::string> EmulatedLink::Receive(double now_s) {
  Advance(now_s);
  std::vector<std::string> arrived;
  while (!in_flight_.empty() && in_flight_.front().arrival_s <= now_s) {
    arrived.push_back(std::move(in_flight_.front().frame));
    in_flight_.pop_front();
  }
  stats_.frames_out += arrived.size();
  return arrived;
}

}  // namespace pena::gateway
