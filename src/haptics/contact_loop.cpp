#include "haptics/contact_loop.hpp"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>

#include "haptics/clock.hpp"

namespace dentsph::haptics {

void ContactLoop::run() {
  // The least urgent of the runtime's threads: a rebuild (milliseconds of work as paste sets) must
  // not take a core from the haptic loop or the simulation. Nice 10 (allowed without privileges);
  // where it cannot be set, the thread runs at the default priority.
  (void)setpriority(PRIO_PROCESS, id_t(syscall(SYS_gettid)), 10);
  constexpr std::int64_t kPollNs = 5'000'000;
  while (!shared_.stop.load(std::memory_order_relaxed)) {
    if (shared_.rigid.update()) {
      const RigidInput& in = shared_.rigid.front();
      const std::int64_t t0 = now_ns();
      // Built in the buffer's free slot: every slot holds the same grid (the runtime's initial
      // world), and set_particles fills all of it, so nothing is copied.
      ContactWorld& w = shared_.contact.back();
      w.field.set_particles(in.particles);
      w.shape = instrument_contact_shape(in.tool, in.tool_spacing);
      shared_.contact.publish();
      ++rebuilds_;
      build_max_ms_ = std::max(build_max_ms_, double(now_ns() - t0) * 1e-6);
    }
    sleep_until_ns(now_ns() + kPollNs, 0);
  }
}

}  // namespace dentsph::haptics
