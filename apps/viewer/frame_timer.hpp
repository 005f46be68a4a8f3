// The viewer's frame statistics: frames a second (each whole second's count) and the frame time's
// percentiles over the last 600 frames, shown in the panels while the loop runs and given in the
// ViewerResult (and --summary) at its end.
#pragma once

#include <chrono>
#include <cstdint>
#include <vector>

#include "panels.hpp"

namespace dentsph::viewer {

struct ViewerResult;

class FrameTimer {
 public:
  using clock = std::chrono::steady_clock;

  FrameTimer() : start_(clock::now()), second_(start_), frame_(start_) {}

  // A frame ended at `now`; returns the statistics so far.
  const FrameStats& frame_done(clock::time_point now);
  double seconds_since_start(clock::time_point now) const {
    return std::chrono::duration<double>(now - start_).count();
  }
  // The whole run's: the median of the per-second counts (the mean where the run was shorter than
  // a second) and the frame time's percentiles.
  void finish(ViewerResult& result) const;

 private:
  clock::time_point start_, second_, frame_;
  std::uint64_t frames_this_second_ = 0;
  std::vector<double> frame_ms_, fps_samples_;
  FrameStats stats_;
};

// The `q` quantile (0 to 1) of `v`, the nearest rank; 0 for none.
double percentile(std::vector<double> v, double q);

}  // namespace dentsph::viewer
