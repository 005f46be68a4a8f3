#include "dentsph/thread_governor.hpp"

#include <algorithm>
#include <cmath>

namespace dentsph {

ThreadGovernor::ThreadGovernor(int max_threads, ThreadGovernorParams params) : p_(params) {
  max_threads = std::max(1, max_threads);
  p_.window = std::max(1, p_.window);
  p_.explore_every = std::max(1, p_.explore_every);
  p_.smoothing = std::clamp(p_.smoothing, 0.01, 1.0);
  for (int t = 1; t < max_threads; t *= 2) candidates_.push_back(t);
  candidates_.push_back(max_threads);
  estimate_.assign(candidates_.size(), 0.0);
  steps_with_.assign(candidates_.size(), 0);
  // Start with every thread (what an idle machine wants); the others are tried in turn.
  current_ = best_ = candidates_.size() - 1;
}

void ThreadGovernor::record(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return;
  window_sum_ += seconds;
  ++steps_with_[current_];
  if (++in_window_ >= p_.window) finish_window();
}

void ThreadGovernor::finish_window() {
  const double mean = window_sum_ / in_window_;
  double& e = estimate_[current_];
  e = e == 0 ? mean : (1 - p_.smoothing) * e + p_.smoothing * mean;
  in_window_ = 0;
  window_sum_ = 0;
  // The best measured count; a count never measured is tried before any comparison counts.
  best_ = current_;
  for (std::size_t k = 0; k < estimate_.size(); ++k)
    if (estimate_[k] > 0 && estimate_[k] < estimate_[best_]) best_ = k;
  if (candidates_.size() == 1) return;
  if (exploring_) {
    exploring_ = false;
    current_ = best_;
    return;
  }
  const bool unmeasured = std::any_of(estimate_.begin(), estimate_.end(), [](double v) { return v == 0; });
  if (unmeasured || ++windows_since_try_ >= p_.explore_every) {
    windows_since_try_ = 0;
    // Try the next candidate other than the best, round robin.
    do next_try_ = (next_try_ + 1) % candidates_.size();
    while (next_try_ == best_);
    current_ = next_try_;
    exploring_ = true;
    return;
  }
  current_ = best_;
}

}  // namespace dentsph
