#include "haptics/force_renderer.hpp"

#include "haptics/virtual_coupling.hpp"

namespace dentsph::haptics {

void ForceRenderer::add(const SimOutput& o, std::int64_t now_ns) {
  if (mode_ == ForceMode::direct) {
    force_.add(o.force_N, now_ns);
    return;
  }
  if (!started_) {  // the proxy's first position: no ramp from the origin
    proxy_x_.add(o.proxy_position, now_ns);
    proxy_v_.add(o.proxy_velocity, now_ns);
    started_ = true;
  }
  proxy_x_.add(o.proxy_position, now_ns);
  proxy_v_.add(o.proxy_velocity, now_ns);
}

Vec3 ForceRenderer::render(const Vec3& x, const Vec3& v, std::int64_t now_ns) const {
  if (mode_ == ForceMode::direct) return force_.at(now_ns);
  if (!started_) return {};
  return coupling_force(coupling_, proxy_x_.at(now_ns), proxy_v_.at(now_ns), x, v);
}

}  // namespace dentsph::haptics
