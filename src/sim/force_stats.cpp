// ForceStats: the tool force over a procedure, step by step.
#include <algorithm>

#include "dentsph/force_stats.hpp"

namespace dentsph {

void ForceStats::add(const Vec3& force, real dt) {
  const real f = norm(force);
  elapsed_s += dt;
  if (!(f > 0)) return;  // no contact (or a non-finite force, which the run reports itself)
  peak_N = std::max(peak_N, f);
  impulse_Ns += f * dt;
  contact_s += dt;
}

}  // namespace dentsph
