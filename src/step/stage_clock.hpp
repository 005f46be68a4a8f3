// Adds the wall time of each stage of a step to a StageTimes when one is given; costs nothing
// otherwise. Shared by the paper's step (paper_step.cpp) and the iisph solver (src/solver).
#pragma once

#include <chrono>

#include "dentsph/step.hpp"

namespace dentsph::stages {

class StageClock {
 public:
  explicit StageClock(StageTimes* t) : times_(t) {
    if (times_) last_ = std::chrono::steady_clock::now();
  }
  StageClock(const StageClock&) = delete;
  StageClock& operator=(const StageClock&) = delete;
  void lap(double StageTimes::*field) {
    if (!times_) return;
    const auto now = std::chrono::steady_clock::now();
    times_->*field += std::chrono::duration<double, std::micro>(now - last_).count();
    last_ = now;
  }
  ~StageClock() {
    if (times_) ++times_->steps;
  }

 private:
  StageTimes* times_;
  std::chrono::steady_clock::time_point last_;
};

}  // namespace dentsph::stages
