#include "haptics/contact_loop.hpp"

#include <algorithm>

#include "haptics/clock.hpp"

namespace dentsph::haptics {

void ContactLoop::run() {
  constexpr std::int64_t kPollNs = 5'000'000;
  while (!shared_.stop.load(std::memory_order_relaxed)) {
    if (shared_.rigid.update()) {
      const RigidInput& in = shared_.rigid.front();
      const std::int64_t t0 = now_ns();
      world_.field.set_particles(in.particles);
      world_.shape = instrument_contact_shape(in.tool, in.tool_spacing);
      shared_.contact.back() = world_;
      shared_.contact.publish();
      ++rebuilds_;
      build_max_ms_ = std::max(build_max_ms_, double(now_ns() - t0) * 1e-6);
    }
    sleep_until_ns(now_ns() + kPollNs, 0);
  }
}

}  // namespace dentsph::haptics
