// HandPath (hand_path.hpp). With H(s) = omega^2 / (s + omega)^2, the response to a ramp of unit
// slope starting at 0 is R(u) = u - 2/omega + exp(-omega u) (2/omega + u) for u > 0. The keyframes'
// path is x(t) = x_0 + sum_k dv_k (t - t_k)+, so the filtered path is y(t) = x_0 + sum_k dv_k R(t - t_k).
// Splitting R, the terms u - 2/omega of the corners older than the lag sum to x(t - lag), and the
// exponential terms of corners older than 40 / omega are below 1e-16 of their size:
//   y(t) = x(t - lag) + sum_{t - lag <= t_k < t} dv_k (t - t_k - lag)
//                     + sum_{t - 40/omega < t_k < t} dv_k exp(-omega (t - t_k)) (lag + t - t_k).
#include "haptics/hand_path.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dentsph::haptics {

HandPath::HandPath(const ToolTrajectory& trajectory, double bandwidth_hz)
    : trajectory_(trajectory), omega_(2.0 * M_PI * bandwidth_hz) {
  if (!(bandwidth_hz > 0) || !std::isfinite(bandwidth_hz))
    throw std::invalid_argument("HandPath: the hand's bandwidth must be a positive number of Hz");
  const std::vector<ToolKeyframe>& kf = trajectory.keyframes;
  Vec3 before;  // the velocity before the keyframe: at rest before the first
  for (std::size_t k = 0; k < kf.size(); ++k) {
    const Vec3 after = k + 1 < kf.size()
                           ? (kf[k + 1].pose.position - kf[k].pose.position) / (kf[k + 1].t - kf[k].t)
                           : Vec3{};  // held after the last
    corners_.push_back({double(kf[k].t), after - before});
    before = after;
  }
}

Pose HandPath::at(double t) const {
  if (corners_.empty()) return Pose{};
  const double lag = lag_s();
  Pose p = trajectory_.at(real(t - lag));
  const double horizon = 40.0 / omega_;
  // Corners with t_k in (t - horizon, t), newest last.
  const auto first = std::upper_bound(corners_.begin(), corners_.end(), t - horizon,
                                      [](double time, const Corner& c) { return time < c.t; });
  Vec3 y = p.position;
  for (auto c = first; c != corners_.end() && c->t < t; ++c) {
    const double u = t - c->t;
    double w = std::exp(-omega_ * u) * (lag + u);
    if (u <= lag) w += u - lag;
    y += c->dv * real(w);
  }
  p.position = y;
  return p;
}

}  // namespace dentsph::haptics
