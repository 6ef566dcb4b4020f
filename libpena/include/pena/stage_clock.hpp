#pragma once
// Where a chain's time goes: wall seconds and entries per named stage (an enum class whose last
// enumerator is kCount), measured with steady_clock at each change of stage. Exclusive time: a
// stage entered inside another counts its own time, and the outer one resumes after it, so every
// instant inside a call counts to exactly one stage and the stages sum to the calls' total.
// Cheap enough to stay on: one clock read per change of stage.

#include <array>
#include <chrono>
#include <cstddef>

namespace pena {

// Wall seconds spent in a stage and how often it was entered.
struct StageTime {
  double seconds = 0.0;
  long calls = 0;
};

// The stages' times of a chain; `total` is the time inside its calls (calls: the calls).
template <typename Stage>
struct StageTimes {
  static constexpr std::size_t kStages = static_cast<std::size_t>(Stage::kCount);
  StageTime total;
  std::array<StageTime, kStages> stages{};

  const StageTime& operator[](Stage stage) const { return stages[static_cast<std::size_t>(stage)]; }
  StageTime& operator[](Stage stage) { return stages[static_cast<std::size_t>(stage)]; }
  double StagesSeconds() const {
    double sum_s = 0.0;
    for (const StageTime& stage : stages) sum_s += stage.seconds;
    return sum_s;
  }
};

// Accumulates StageTimes. Call: one call of the chain (its time outside any stage counts to the
// `rest` stage); Scope: one stage, nested in a call or in another stage. Not thread-safe.
template <typename Stage>
class StageClock {
 public:
  using Clock = std::chrono::steady_clock;

  class [[nodiscard]] Scope {
   public:
    Scope(StageClock& clock, Stage stage) : clock_(clock), outer_(clock.current_) {
      clock_.SwitchTo(Index(stage));
      ++clock_.times_.stages[Index(stage)].calls;
    }
    ~Scope() { clock_.SwitchTo(outer_); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    StageClock& clock_;
    std::size_t outer_;
  };

  class [[nodiscard]] Call {
   public:
    Call(StageClock& clock, Stage rest) : clock_(clock), outer_(clock.current_) {
      started_ = clock_.SwitchTo(Index(rest));
      ++clock_.times_.total.calls;
      ++clock_.times_.stages[Index(rest)].calls;
    }
    ~Call() {
      const Clock::time_point now = clock_.SwitchTo(outer_);
      // A call inside a call (re-entry) counts once.
      if (outer_ == kOutside) clock_.times_.total.seconds += Seconds(now - started_);
    }
    Call(const Call&) = delete;
    Call& operator=(const Call&) = delete;

   private:
    StageClock& clock_;
    std::size_t outer_;
    Clock::time_point started_;
  };

  // `seconds` spent in the running stage (measured by a callee's own timer) moved to `to`, as
  // one call of it. Nothing outside a stage.
  void Move(Stage to, double seconds) {
    if (current_ == kOutside) return;
    times_.stages[current_].seconds -= seconds;
    times_[to].seconds += seconds;
    ++times_[to].calls;
  }

  const StageTimes<Stage>& times() const { return times_; }

 private:
  static constexpr std::size_t kOutside = StageTimes<Stage>::kStages;
  static std::size_t Index(Stage stage) { return static_cast<std::size_t>(stage); }
  static double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

  // Ends the running stage's stretch and starts `next`'s; returns the time of the switch.
  Clock::time_point SwitchTo(std::size_t next) {
    const Clock::time_point now = Clock::now();
    if (current_ != kOutside) times_.stages[current_].seconds += Seconds(now - since_);
    current_ = next;
    since_ = now;
    return now;
  }

  StageTimes<Stage> times_;
  std::size_t current_ = kOutside;
  Clock::time_point since_{};
};

}  // namespace pena
