#pragma once
// Where a wheelset evaluation spends its time (Wheelset::time_stages, WheelsetStageTimes;
// docs/WHEELSET.md §8 "Where a step's time goes"). The clock charges the wall-clock time since its
// last switch to the stage that was running, so that each interval counts in exactly one stage
// (the innermost one running) and the stages add up to the evaluation's time.
#include <chrono>

#include "railcontact/wheelset.hpp"

namespace railcontact::detail {

enum class WheelsetStage { search, area, normal, height, kinematics, tangential, assembly };

class StageClock {
 public:
  // Starts charging to the assembly stage (the evaluation's own work outside every other stage).
  explicit StageClock(WheelsetStageTimes& times) : times_(times), since_(Clock::now()) {}
  ~StageClock() {
    charge(Clock::now());
    ++times_.evaluations;
  }
  StageClock(const StageClock&) = delete;
  StageClock& operator=(const StageClock&) = delete;

  // A stage running from construction to destruction; the enclosing stage runs on afterwards. No
  // clock (nullptr): nothing is timed.
  class Scope {
   public:
    Scope(StageClock* clock, WheelsetStage stage) : clock_(clock) {
      if (clock_ != nullptr) enclosing_ = clock_->switch_to(stage);
    }
    ~Scope() {
      if (clock_ != nullptr) clock_->switch_to(enclosing_);
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    StageClock* clock_;
    WheelsetStage enclosing_ = WheelsetStage::assembly;
  };

 private:
  using Clock = std::chrono::steady_clock;
  // Charges the time since the last switch to the running stage, runs `stage`, returns the one before.
  WheelsetStage switch_to(WheelsetStage stage) {
    charge(Clock::now());
    const WheelsetStage before = running_;
    running_ = stage;
    return before;
  }
  void charge(Clock::time_point now) {
    const double seconds = std::chrono::duration<double>(now - since_).count();
    since_ = now;
    switch (running_) {
      case WheelsetStage::search: times_.search_s += seconds; break;
      case WheelsetStage::area: times_.area_s += seconds; break;
      case WheelsetStage::normal: times_.normal_s += seconds; break;
      case WheelsetStage::height: times_.height_s += seconds; break;
      case WheelsetStage::kinematics: times_.kinematics_s += seconds; break;
      case WheelsetStage::tangential: times_.tangential_s += seconds; break;
      case WheelsetStage::assembly: times_.assembly_s += seconds; break;
    }
  }

  WheelsetStageTimes& times_;
  Clock::time_point since_;
  WheelsetStage running_ = WheelsetStage::assembly;
};

}  // namespace railcontact::detail
