#include "haptics/force_renderer.hpp"

#include <algorithm>

#include "haptics/virtual_coupling.hpp"

namespace dentsph::haptics {

void ForceRenderer::add(const SimOutput& o, std::int64_t now_ns) {
  if (mode_ == ForceMode::direct) {
    force_.add(o.force_N, now_ns);
    return;
  }
  const bool entering = free_ && !o.free;
  free_ = o.free;
  if (entering) entered_ns_ = now_ns;
  const double stamp_s = double(o.command_stamp_ns - (started_ ? base_ns_ : now_ns)) * 1e-9;
  if (!started_) {  // the proxy's first position: no ramp from the origin
    base_ns_ = now_ns;
    proxy_x_.add(o.proxy_position, now_ns);
    stamp_.add({stamp_s, 0, 0}, now_ns);
    last_x_ = o.proxy_position;
    last_stamp_s_ = stamp_s;
    started_ = true;
  }
  // The proxy's motion per second of the device's clock: what carries it forward and what the
  // damper compares with the device's velocity (its own velocity is per simulated second, which a
  // simulation slower than real time makes larger: at a twentieth of real time the damper rendered
  // 2.4 N against a hand moving with the proxy at 62.5 mm/s).
  if (entering) {  // the motion of the free moves is not the proxy's now
    motion_ = {};
    last_x_ = o.proxy_position;
    last_stamp_s_ = stamp_s;
    proxy_x_ = proxy_w_ = ForceInterpolator{};
    proxy_x_.add(o.proxy_position, now_ns);  // no ramp from the free moves' last place
  } else if (stamp_s - last_stamp_s_ >= kMinStampStep) {
    motion_ = (o.proxy_position - last_x_) / (stamp_s - last_stamp_s_);
    last_x_ = o.proxy_position;
    last_stamp_s_ = stamp_s;
  }
  proxy_x_.add(o.proxy_position, now_ns);
  proxy_w_.add(motion_, now_ns);
  stamp_.add({stamp_s, 0, 0}, now_ns);
}

Vec3 ForceRenderer::proxy_now(std::int64_t now_ns) const {
  const double lead = std::clamp(double(now_ns - base_ns_) * 1e-9 - stamp_.at(now_ns).x, 0.0, kMaxLead);
  return proxy_x_.at(now_ns) + proxy_w_.at(now_ns) * lead;
}

Vec3 ForceRenderer::render(const Vec3& x, const Vec3& v, std::int64_t now_ns) const {
  if (mode_ == ForceMode::direct) return force_.at(now_ns);
  if (!started_ || free_) return {};
  const Vec3 f = coupling_force(coupling_, proxy_now(now_ns), proxy_w_.at(now_ns), x, v);
  if (entered_ns_ < 0) return f;
  const double ramp = double(now_ns - entered_ns_) * 1e-9 / kEntryRamp;
  return ramp >= 1 ? f : f * std::max(0.0, ramp);
}

}  // namespace dentsph::haptics
