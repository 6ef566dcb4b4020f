#include "load_run.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

#include "proc_stats.hpp"
#include "to_dds.hpp"

namespace pena::services::bench {
namespace {

std::int64_t SecondsToNs(double seconds) { return static_cast<std::int64_t>(seconds * 1e9); }

}  // namespace

LoadRun::LoadRun(const DdsOptions& dds, std::vector<SourceStream> sources, LoadOptions options)
    : sources_(std::move(sources)),
      options_(options),
      participant_(dds, "pena-load"),
      pose_writer_(participant_, topics::kPose),
      status_writer_(participant_, topics::kStatus),
      delta_writer_(participant_, topics::kLineMapDelta),
      scan_writer_(participant_, topics::kReferenceScan),
      correction_reader_(participant_, topics::kCorrection,
                         [this](pena_dds::Correction&& c, const SampleMeta& meta) {
                           corrections_.Push(
                               {c.entity_id().to_string(), c.reference_seq(), meta.reception_time_ns});
                         }),
      global_delta_reader_(participant_, topics::kGlobalMapDelta,
                           [this](pena_dds::GlobalMapDelta&&, const SampleMeta&) {
                             ++global_deltas_;
                           }) {
  for (int k = 0; k < options_.entities; ++k) {
    char id[32];
    std::snprintf(id, sizeof id, "load%02d", k);
    ids_.emplace_back(id);
  }
}

bool LoadRun::WaitForFusion(double timeout_s) {
  const std::int64_t until_ns = NowNs() + SecondsToNs(timeout_s);
  while (NowNs() < until_ns) {
    if (delta_writer_.matched() > 0 && scan_writer_.matched() > 0 &&
        status_writer_.matched() > 0 && correction_reader_.matched() > 0) {
      return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

std::vector<LoadRun::Event> LoadRun::Schedule() const {
  std::vector<Event> events;
  const int count = options_.entities;
  for (int k = 0; k < count; ++k) {
    const SourceStream& source = sources_[static_cast<std::size_t>(k) % sources_.size()];
    const double phase_s = options_.scan_period_s * k / count;
    for (std::size_t i = 0; i < source.scans.size(); ++i) {
      events.push_back({phase_s + source.scans[i].offset_s, k, i});
    }
  }
  std::stable_sort(events.begin(), events.end(),
                   [](const Event& a, const Event& b) { return a.at_s < b.at_s; });
  return events;
}

void LoadRun::Publish(const Event& event, WindowFigures& window) {
  const std::size_t index = static_cast<std::size_t>(event.entity) % sources_.size();
  const long copy = event.entity / static_cast<long>(sources_.size());
  ScanSamples samples = sources_[index].scans[event.scan];
  const auto dx_mm = static_cast<long>(static_cast<double>(copy) * options_.spread_m * 1000.0);
  Relabel(samples, ids_[static_cast<std::size_t>(event.entity)], dx_mm, 0);
  pose_writer_.Write(samples.pose);
  ++sent_samples_["pose"];
  if (samples.delta) {
    delta_writer_.Write(*samples.delta);
    ++sent_samples_["line_map_delta"];
  }
  if (samples.reference_scan) {
    sent_ns_[{ids_[static_cast<std::size_t>(event.entity)], samples.reference_scan->seq()}] = NowNs();
    scan_writer_.Write(*samples.reference_scan);
    ++sent_samples_["reference_scan"];
    ++window.reference_scans_sent;
  }
}

void LoadRun::SendStatus(pena_dds::EntityState state) {
  for (std::size_t k = 0; k < ids_.size(); ++k) {
    pena_dds::EntityStatus status;
    SetBounded(status.entity_id(), ids_[k], "entity_id");
    status.schema_version(pena_dds::SCHEMA_VERSION);
    status.kind(sources_[k % sources_.size()].kind);
    status.state(state);
    status.mission("pena-load");
    status_writer_.Write(status);
    ++sent_samples_["status"];
  }
}

void LoadRun::CollectCorrections(WindowFigures& window) {
  while (std::optional<Received> received = corrections_.TryPop()) {
    const auto it = sent_ns_.find({received->entity_id, received->reference_seq});
    if (it == sent_ns_.end()) {
      ++unmatched_;
      continue;
    }
    window.latencies_ms.push_back(static_cast<double>(received->at_ns - it->second) * 1e-6);
  }
}

void LoadRun::CloseWindow(WindowFigures& window, double now_s,
                          std::vector<WindowFigures>& windows) {
  CollectCorrections(window);
  window.end_s = now_s;
  if (const std::optional<ProcSample> proc = ReadProc(options_.fusion_pid)) {
    window.fusion_cpu_s = proc->cpu_s - last_cpu_s_;
    window.fusion_rss_kb = proc->rss_kb;
    last_cpu_s_ = proc->cpu_s;
  }
  PrintWindow("window", window, options_.entities);
  windows.push_back(window);
  window = WindowFigures{};
  window.start_s = now_s;
}

std::vector<WindowFigures> LoadRun::Replay() {
  const std::vector<Event> events = Schedule();
  if (const std::optional<ProcSample> proc = ReadProc(options_.fusion_pid)) last_cpu_s_ = proc->cpu_s;
  std::vector<WindowFigures> windows;
  WindowFigures window;
  const std::int64_t start_ns = NowNs();
  const auto elapsed_s = [&] { return static_cast<double>(NowNs() - start_ns) * 1e-9; };
  double next_status_s = 0.0, next_window_s = options_.window_s;
  SendStatus(pena_dds::ENTITY_RUNNING);
  const double end_s = (events.empty() ? 0.0 : events.back().at_s) + options_.drain_s;
  std::size_t next = 0;
  while (elapsed_s() < end_s) {
    const double now_s = elapsed_s();
    while (next < events.size() && events[next].at_s <= now_s) Publish(events[next++], window);
    if (now_s >= next_status_s && next < events.size()) {
      SendStatus(pena_dds::ENTITY_RUNNING);
      next_status_s = now_s + 1.0;
    }
    if (now_s >= next_window_s) {
      CloseWindow(window, now_s, windows);
      next_window_s += options_.window_s;
    }
    CollectCorrections(window);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  CloseWindow(window, elapsed_s(), windows);
  SendStatus(pena_dds::ENTITY_FINISHED);
  return windows;
}

void LoadRun::PrintTotals() const {
  std::printf("sent:");
  for (const auto& [topic, count] : sent_samples_) std::printf(" %s %ld", topic.c_str(), count);
  std::printf("; corrections without a known reference scan: %ld; global map deltas "
              "received: %ld\n", unmatched_, global_deltas_.load());
}

void PrintWindow(const std::string& label, const WindowFigures& window, int entities) {
  const double span_s = window.end_s - window.start_s;
  std::printf("%-6s %6.1f-%6.1f s  refs sent %5ld  corrections %4zu  latency ms p50 %7.1f "
              "p99 %7.1f max %7.1f  fusion CPU %5.1f %%  RSS %6.1f MB  (%d entities)\n",
              label.c_str(), window.start_s, window.end_s, window.reference_scans_sent,
              window.latencies_ms.size(), Quantile(window.latencies_ms, 0.5),
              Quantile(window.latencies_ms, 0.99),
              window.latencies_ms.empty()
                  ? 0.0
                  : *std::max_element(window.latencies_ms.begin(), window.latencies_ms.end()),
              span_s > 0.0 ? 100.0 * window.fusion_cpu_s / span_s : 0.0,
              static_cast<double>(window.fusion_rss_kb) / 1024.0, entities);
  std::fflush(stdout);
}

}  // namespace pena::services::bench
