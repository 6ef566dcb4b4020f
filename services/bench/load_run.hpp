#pragma once
// pena-load's timed run: one participant publishes N entities' samples (precomputed source
// streams, replayed at mission speed, entity k shifted by k/N of a scan period) and listens for
// pena-fusion's corrections; latency = correction received - its reference scan sent (system
// clock, one machine). Reports per window so a growing backlog shows as growing latency.

#include <sys/types.h>

#include <atomic>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "dds_endpoints.hpp"
#include "load_streams.hpp"
#include "pena_dds/correctionPubSubTypes.h"
#include "pena_dds/entityPubSubTypes.h"
#include "pena_dds/global_mapPubSubTypes.h"
#include "pena_dds/line_mapPubSubTypes.h"
#include "pena_dds/scanPubSubTypes.h"
#include "work_queue.hpp"

namespace pena::services::bench {

struct LoadOptions {
  int entities = 50;
  double scan_period_s = 0.25;  // entities' phases are spread over one period (4 Hz)
  double spread_m = 0.0;        // copy r of a source is moved r * spread_m along x
  double window_s = 10.0;       // report period, wall seconds
  double drain_s = 10.0;        // wait for late corrections after the last sample
  pid_t fusion_pid = -1;        // for CPU and memory (/proc)
};

// One report window (or the whole run).
struct WindowFigures {
  double start_s = 0.0, end_s = 0.0;   // wall seconds since the replay started
  long reference_scans_sent = 0;
  std::vector<double> latencies_ms;    // corrections received in the window
  double fusion_cpu_s = 0.0;           // fusion CPU seconds in the window
  std::int64_t fusion_rss_kb = 0;      // at the window's end
};

class LoadRun {
 public:
  // Creates the participant and endpoints (DdsError).
  LoadRun(const DdsOptions& dds, std::vector<SourceStream> sources, LoadOptions options);

  // Waits until pena-fusion's readers matched; false after timeout_s.
  bool WaitForFusion(double timeout_s);
  // Replays every entity's stream once, printing a line per window; returns the windows.
  std::vector<WindowFigures> Replay();
  // Samples sent per topic, corrections unmatched (no reference scan known), global deltas.
  void PrintTotals() const;

 private:
  struct Event {
    double at_s;
    int entity;
    std::size_t scan;
  };
  struct Received {
    std::string entity_id;
    std::uint64_t reference_seq;
    std::int64_t at_ns;
  };
  std::vector<Event> Schedule() const;
  void Publish(const Event& event, WindowFigures& window);
  void SendStatus(pena_dds::EntityState state);
  void CollectCorrections(WindowFigures& window);
  void CloseWindow(WindowFigures& window, double now_s, std::vector<WindowFigures>& windows);

  std::vector<SourceStream> sources_;
  LoadOptions options_;
  std::vector<std::string> ids_;
  std::map<std::pair<std::string, std::uint64_t>, std::int64_t> sent_ns_;
  std::map<std::string, long> sent_samples_;
  long unmatched_ = 0;
  std::atomic<long> global_deltas_{0};
  double last_cpu_s_ = 0.0;

  WorkQueue<Received> corrections_;
  Participant participant_;
  Writer<pena_dds::EntityPosePubSubType> pose_writer_;
  Writer<pena_dds::EntityStatusPubSubType> status_writer_;
  Writer<pena_dds::LineMapDeltaPubSubType> delta_writer_;
  Writer<pena_dds::ReferenceScanPubSubType> scan_writer_;
  Reader<pena_dds::CorrectionPubSubType> correction_reader_;
  Reader<pena_dds::GlobalMapDeltaPubSubType> global_delta_reader_;
};

// Prints one window line (or the totals line when `label` is "all").
void PrintWindow(const std::string& label, const WindowFigures& window, int entities);

}  // namespace pena::services::bench
