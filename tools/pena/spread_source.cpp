#include "spread_source.hpp"

#include <utility>

namespace pena::cli {
namespace {

class StrideSpreadingSource : public io::LogSource {
 public:
  StrideSpreadingSource(std::unique_ptr<io::LogSource> inner,
                        const dead_reckoning::StrideInterpolationOptions& options)
      : inner_(std::move(inner)), spread_(options) {}

  std::optional<sensors::SensorRecord> Next() override {
    while (true) {
      if (auto ready = spread_.Pop()) return ready;
      if (finished_) return std::nullopt;
      if (auto record = inner_->Next()) {
        spread_.Push(std::move(*record));
      } else {
        spread_.Finish();
        finished_ = true;
      }
    }
  }
  const io::LogDescription& description() const override { return inner_->description(); }
  std::size_t skipped() const override { return inner_->skipped(); }
  const dead_reckoning::StrideInterpolationCounts& counts() const { return spread_.counts(); }

 private:
  std::unique_ptr<io::LogSource> inner_;
  dead_reckoning::StrideInterpolator spread_;
  bool finished_ = false;
};

}  // namespace

std::unique_ptr<io::LogSource> OpenChainLog(
    const std::filesystem::path& path, const io::ReadOptions& read,
    const dead_reckoning::HumanDeadReckoningOptions& options) {
  std::unique_ptr<io::LogSource> source = io::OpenLog(path, read);
  if (!options.stride_interpolation.enabled ||
      source->description().kind != sensors::EntityKind::kHuman) {
    return source;
  }
  return std::make_unique<StrideSpreadingSource>(std::move(source),
                                                 dead_reckoning::SpreadOptionsOf(options));
}

const dead_reckoning::StrideInterpolationCounts* StrideSpreadingCounts(const io::LogSource& source) {
  const auto* spreading = dynamic_cast<const StrideSpreadingSource*>(&source);
  return spreading ? &spreading->counts() : nullptr;
}

}  // namespace pena::cli
