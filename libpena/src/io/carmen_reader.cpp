// CARMEN log reader: the line reader, the per-line parser and the time-order rule put together.
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "carmen_line_parser.hpp"
#include "gz_line_reader.hpp"
#include "pena/io/carmen.hpp"
#include "pena/io/input_error.hpp"
#include "text_fields.hpp"

namespace pena::io {
namespace {

// Scans may step back by up to this much within one message type (dropped and counted) before it
// is an error: the
// radish intel-corrected log has 4 scans up to 0.86 s early (docs/formats.md, "Timestamps").
constexpr double kScanStepBackTolerance_s = 1.0;

const ReadOptions& Validated(const ReadOptions& options) {
  if (!(options.carmen_max_range_m > 0.0) || !std::isfinite(options.carmen_max_range_m)) {
    throw std::invalid_argument("ReadOptions::carmen_max_range_m must be finite and > 0 m, got " +
                                std::to_string(options.carmen_max_range_m));
  }
  if (!(options.carmen_sweep_s >= 0.0 && options.carmen_sweep_s <= 1.0)) {
    throw std::invalid_argument("ReadOptions::carmen_sweep_s must be in [0, 1] s, got " +
                                std::to_string(options.carmen_sweep_s));
  }
  constexpr int kMaxInterlace = sensors::LaserGeometry::kMaxInterlace;
  if (!(options.carmen_interlace >= 0 && options.carmen_interlace <= kMaxInterlace)) {
    throw std::invalid_argument("ReadOptions::carmen_interlace must be in [0, " +
                                std::to_string(kMaxInterlace) + "], got " +
                                std::to_string(options.carmen_interlace));
  }
  return options;
}

class CarmenLogSource : public LogSource {
 public:
  CarmenLogSource(const std::filesystem::path& path, const ReadOptions& options)
      : options_(Validated(options)), reader_(path) {
    description_.path = path;
    description_.format = "carmen";
    description_.kind = sensors::EntityKind::kRobot;  // CARMEN is a robot framework
  }

  std::optional<sensors::SensorRecord> Next() override {
    while (reader_.ReadLine(line_)) {
      try {
        std::optional<detail::CarmenMessage> message = detail::ParseCarmenLine(line_, options_);
        if (message && Accept(*message)) return std::move(message->record);
      } catch (const detail::CarmenLineError& error) {
        if (!options_.skip_malformed) {
          throw InputError(reader_.path(), reader_.line_number(), error.what());
        }
        ++skipped_;
      }
    }
    return std::nullopt;
  }

  const LogDescription& description() const override { return description_; }
  std::size_t skipped() const override { return skipped_; }

 private:
  // The time-order rule; throws CarmenLineError for a scan too far back, drops stale ODOM.
  bool Accept(const detail::CarmenMessage& message) {
    const double stamp_s = sensors::StampOf(message.record);
    const auto last = last_stamp_s_.find(message.type);
    if (last != last_stamp_s_.end() && stamp_s < last->second) {
      // ODOM stamps in the radish logs are 0 after every scan or uninitialised memory (orebro):
      // odometry older than what was already returned is dropped, never returned out of order.
      if (message.type == "ODOM") return false;
      if (last->second - stamp_s > kScanStepBackTolerance_s) {
        throw detail::CarmenLineError("timestamp " + detail::FormatExact(stamp_s) +
                                      " is not after the previous " + message.type + " at " +
                                      detail::FormatExact(last->second) + " (more than " +
                                      detail::FormatExact(kScanStepBackTolerance_s) +
                                      " s back)");
      }
      // A small step back (clock jitter in the radish logs) drops the scan and counts it, so
      // every consumer still sees time in order.
      ++skipped_;
      return false;
    }
    last_stamp_s_[message.type] = stamp_s;
    return true;
  }

  ReadOptions options_;
  detail::GzLineReader reader_;
  LogDescription description_;
  std::string line_;
  std::map<std::string, double> last_stamp_s_;  // latest stamp per message type
  std::size_t skipped_ = 0;
};

}  // namespace

std::unique_ptr<LogSource> OpenCarmenLog(const std::filesystem::path& path,
                                         const ReadOptions& options) {
  return std::make_unique<CarmenLogSource>(path, options);
}

}  // namespace pena::io
