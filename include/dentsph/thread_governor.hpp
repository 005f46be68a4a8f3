// How many threads the next step should use. Every thread count gives the same result bit for
// bit, so the count is free to change from step to step: the governor times the steps, keeps an
// estimate of the step's wall time for each candidate count, and uses the fastest, trying the
// others now and then. A core taken by another process (the viewer's software renderer, a
// browser, the haptic thread) makes the threads of a parallel loop wait at its barriers for the
// one that was descheduled, so that two threads can be slower than one: the governor then falls
// back to fewer threads, and goes back to more when the core is free again.
#pragma once

#include <cstdint>
#include <vector>

namespace dentsph {

struct ThreadGovernorParams {
  int window = 32;           // steps timed together before an estimate is updated
  int explore_every = 16;    // windows of the best count between two tries of another count
  double smoothing = 0.5;    // weight of the newest window in a count's estimate
};

class ThreadGovernor {
 public:
  // Candidates: 1, 2, 4, ... and max_threads itself. max_threads < 1 is taken as 1.
  explicit ThreadGovernor(int max_threads, ThreadGovernorParams params = {});

  // The thread count for the next step.
  int threads() const { return candidates_[current_]; }
  // The wall time in seconds of the step just taken with threads(). Non-finite or negative times
  // are ignored.
  void record(double seconds);

  int max_threads() const { return candidates_.back(); }
  const std::vector<int>& candidates() const { return candidates_; }
  // Estimated seconds per step of each candidate (0 where not yet measured).
  const std::vector<double>& estimates() const { return estimate_; }
  // Steps taken with each candidate so far.
  const std::vector<std::uint64_t>& steps_with() const { return steps_with_; }

 private:
  void finish_window();

  ThreadGovernorParams p_;
  std::vector<int> candidates_;
  std::vector<double> estimate_;
  std::vector<std::uint64_t> steps_with_;
  std::size_t current_ = 0;   // index into candidates_ of the count in use
  std::size_t best_ = 0;      // the count with the lowest estimate
  std::size_t next_try_ = 0;  // the next candidate to explore
  int in_window_ = 0;
  double window_sum_ = 0;
  int windows_since_try_ = 0;
  bool exploring_ = false;
};

}  // namespace dentsph
