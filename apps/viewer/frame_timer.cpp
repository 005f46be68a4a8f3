// The viewer's frame statistics (frame_timer.hpp).
#include "frame_timer.hpp"

#include <algorithm>

#include "viewer_app.hpp"

namespace dentsph::viewer {

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const std::size_t k = std::min(v.size() - 1, std::size_t(q * double(v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

const FrameStats& FrameTimer::frame_done(clock::time_point now) {
  ++stats_.frames;
  frame_ms_.push_back(std::chrono::duration<double, std::milli>(now - frame_).count());
  frame_ = now;
  ++frames_this_second_;
  if (now - second_ >= std::chrono::seconds(1)) {
    stats_.fps = double(frames_this_second_) / std::chrono::duration<double>(now - second_).count();
    fps_samples_.push_back(stats_.fps);
    const std::size_t keep = std::min<std::size_t>(frame_ms_.size(), 600);
    const std::vector<double> recent(frame_ms_.end() - std::ptrdiff_t(keep), frame_ms_.end());
    stats_.frame_p50_ms = percentile(recent, 0.5);
    stats_.frame_p99_ms = percentile(recent, 0.99);
    frames_this_second_ = 0;
    second_ = now;
  }
  if (fps_samples_.empty() && frame_ms_.size() >= 2) {
    // Before the first full second: the mean so far.
    stats_.fps = double(stats_.frames) / std::max(1e-9, seconds_since_start(now));
    stats_.frame_p50_ms = percentile(frame_ms_, 0.5);
    stats_.frame_p99_ms = percentile(frame_ms_, 0.99);
  }
  return stats_;
}

void FrameTimer::finish(ViewerResult& result) const {
  result.frames = stats_.frames;
  result.fps_median = percentile(fps_samples_, 0.5);
  if (fps_samples_.empty() && !frame_ms_.empty()) {
    const double total = seconds_since_start(clock::now());
    result.fps_median = total > 0 ? double(stats_.frames) / total : 0;
  }
  result.frame_p50_ms = percentile(frame_ms_, 0.5);
  result.frame_p99_ms = percentile(frame_ms_, 0.99);
}

}  // namespace dentsph::viewer
