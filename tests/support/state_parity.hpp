// Two states compared particle by particle (by stable id): densities, pressures, forces,
// velocities and positions within a relative tolerance with floors set by each field's largest
// value, the same bonds, the same tool wrench and counters. Shared by the grid-against-all-pairs
// tests (tests/parity) and the GPU parity checks (support/gpu_parity.hpp), which differ only in
// their tolerances.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "support/builders.hpp"

namespace dentsph::testing {

// |a - b| <= rel * max(|b|, floor).
inline void expect_near_rel(real a, real b, real rel, real floor, const char* what, std::uint32_t id, int step) {
  ASSERT_LE(std::abs(a - b), rel * std::max(std::abs(b), floor))
      << what << " of id " << id << " at step " << step << ": " << a << " vs " << b;
}
inline void expect_near_rel(const Vec3& a, const Vec3& b, real rel, real floor, const char* what, std::uint32_t id,
                            int step) {
  for (int ax = 0; ax < 3; ++ax) expect_near_rel(a[ax], b[ax], rel, floor, what, id, step);
}

// How close two states must be: `rel` relative to each value, or to a floor where values are
// small: `share` of the field's largest magnitude in the reference plus an absolute floor.
struct StateTolerance {
  real rel = 1e-5;
  real share = 1e-6;            // of the largest pressure, force and speed
  real density_floor = 1.0;     // kg/m^3
  real pressure_floor = 1e-3;   // Pa (P = Kp (rho - rho0) cancels near rest)
  real motion_floor = 1e-12;    // N and m/s, added to the force and velocity floors
  real position_floor = 1e-3;   // m
  real tool_force_floor = 1e-9; // N
  real tool_torque_floor = 1e-11;  // N m
};

// g against the reference r after step `step`.
inline void compare_states(const State& g, const State& r, int step, const StateTolerance& t) {
  ASSERT_EQ(g.size(), r.size());
  real fmax = 0, vmax = 0, pmax = 0;
  for (std::uint32_t i = 0; i < r.size(); ++i) {
    fmax = std::max(fmax, norm(r.force[i]));
    vmax = std::max(vmax, norm(r.vel[i]));
    pmax = std::max(pmax, r.pressure[i]);
  }
  for (std::uint32_t id = 0; id < r.size(); ++id) {
    const std::uint32_t i = at(g, id), j = at(r, id);
    ASSERT_EQ(g.id[i], id);
    expect_near_rel(g.rho[i], r.rho[j], t.rel, t.density_floor, "density", id, step);
    expect_near_rel(g.pressure[i], r.pressure[j], t.rel, t.share * pmax + t.pressure_floor, "pressure", id, step);
    expect_near_rel(g.force[i], r.force[j], t.rel, t.share * fmax + t.motion_floor, "force", id, step);
    expect_near_rel(g.vel[i], r.vel[j], t.rel, t.share * vmax + t.motion_floor, "velocity", id, step);
    expect_near_rel(g.pos[i], r.pos[j], t.rel, t.position_floor, "position", id, step);
    ASSERT_EQ(g.bonds.count(id), r.bonds.count(id)) << "bond count of id " << id << " at step " << step;
    for (int b = 0; b < g.bonds.count(id); ++b) ASSERT_TRUE(r.bonds.has(id, g.bonds.partner(id, b)));
  }
  expect_near_rel(g.tool_wrench.force, r.tool_wrench.force, t.rel, t.tool_force_floor, "tool force", 0, step);
  expect_near_rel(g.tool_wrench.torque, r.tool_wrench.torque, t.rel, t.tool_torque_floor, "tool torque", 0, step);
  ASSERT_EQ(g.bonds.counters.formed, r.bonds.counters.formed) << "step " << step;
  ASSERT_EQ(g.bonds.counters.broken, r.bonds.counters.broken) << "step " << step;
  ASSERT_EQ(g.bonds.counters.overflowed, r.bonds.counters.overflowed) << "step " << step;
  ASSERT_EQ(g.steps, r.steps);
  ASSERT_EQ(g.diagnostics.non_finite, r.diagnostics.non_finite);
}

}  // namespace dentsph::testing
