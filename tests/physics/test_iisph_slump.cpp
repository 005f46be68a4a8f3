// The cylindrical slump test of a yield-stress paste (docs/model.md, "Rheology"): a cylinder of
// Bingham paste, as tall as it is wide, released on a plate under gravity, slumps until the stress
// everywhere is under its yield stress, and stops. Pashias, Boger, Summers & Glenister (J. Rheol.
// 40, 1996) derived the final slump from the stress's balance in the cylinder and confirmed it with
// experiments on suspensions: with tau' = yield_stress / (rho g H0),
//   slump / H0 = 1 - 2 tau' (1 - ln(2 tau'))   (tau' < 1/2; no slump above).
//
// On the iisph solver, Bingham pastes of plastic viscosity 0.5 Pa s stop within 0.5 s, and a higher
// yield stress slumps less; a Newtonian paste of the same viscosity is still spreading. But they
// slump less than Pashias's formula: at tau' = 0.1, 0.319 of the height (0.326 and 0.335 with
// cylinders of 8 and 10 spacings' radius) where it gives 0.478; at tau' = 0.2, 0.005 where it gives
// 0.233; at 0.3 none (0.094). As if the yield stress were 1.5 times higher at 0.1 and more at 0.2:
// a departure (docs/model.md, "Rheology"), held here so that a change shows. Mostly the plate's
// friction: the formula's base carries no shear, and without the plate's viscous coupling the same
// pastes slump 0.537 and 0.020, on either side of it.
//
// The setup: spacing s = 0.25 mm (h = 0.5 mm), a cylinder of radius 6 s and height 12 s (3 mm),
// rho0 = 2000 kg/m^3, Kp = 50 m^2/s^2, no adhesion, a no-slip plate two layers deep; 1 ms steps for
// 0.6 s; the unyielded paste's viscosity 2e4 Pa s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "dentsph/step.hpp"
#include "support/builders.hpp"

namespace dentsph {
namespace {

constexpr real s = 2.5e-4, rho0 = 2000, Kp = 50, g = 9.81, mu_p = 0.5;
constexpr int nr = 6, nz = 12;           // the cylinder's radius and height, in spacings
constexpr real H0 = nz * s;              // m; the plate's surface half a spacing under the first layer
constexpr int plate = 3 * nr;            // the plate's radius, in spacings

struct Slump {
  real slump = 0;      // of H0: 1 - the paste's final height on the axis / H0
  real speed = 0;      // m/s, the fastest paste particle at the end
};

// A cylinder of paste of yield stress tau' rho g H0 (0: Newtonian) let go for t_end.
Slump slump(real tau_prime, real t_end = 0.6) {
  const real L = plate + 4;
  ModelParams p = testing::params_for_spacing(s, Vec3{-L, -L, -6} * s, Vec3{L, L, real(nz + 8)} * s, 1e-3, Vec3{0, 0, -g});
  p.solver = Solver::iisph;
  p.iisph.pressure_solve = PressureSolve::cg;
  p.iisph.viscosity_tolerance = 1e-4;
  p.iisph.viscosity_iterations = 500;
  p.iisph.max_iterations = 100;
  Model model = make_model(p);
  Material paste{mu_p, Kp, rho0, 0};
  paste.yield_stress = tau_prime * rho0 * g * H0;
  paste.max_viscosity = tau_prime > 0 ? 2e4 : 0;
  const Material wall{mu_p, 1.5 * Kp, rho0, 0};
  const real m = lattice_particle_mass(rho0, s, model.kernel);
  std::vector<ParticleInit> ps;
  for (int k = -2; k < nz; ++k)
    for (int j = -plate; j <= plate; ++j)
      for (int i = -plate; i <= plate; ++i) {
        const Vec3 x{i * s, j * s, (k + 0.5) * s};
        const real r = std::hypot(x.x, x.y);
        if (k < 0 && r <= plate * s) ps.push_back(testing::particle(Role::boundary, x, m, wall));
        if (k >= 0 && r < nr * s) ps.push_back(testing::particle(Role::material, x, m, paste));
      }
  State state;
  state.add_particles(model, ps);
  while (state.time < t_end - 0.5 * model.dt) {
    step(model, state, StepOptions{1, nullptr});
    EXPECT_EQ(state.diagnostics.non_finite, 0u);
  }
  // The height on the axis: the highest paste particle within 2 spacings of it, plus half a spacing
  // (its own share of the layer).
  real top = 0;
  for (std::uint32_t i = 0; i < state.size(); ++i)
    if (state.role[i] == Role::material && std::hypot(state.pos[i].x, state.pos[i].y) < 2 * s)
      top = std::max(top, state.pos[i].z);
  return {1 - (top + 0.5 * s) / H0, state.diagnostics.max_speed};
}

real pashias(real tau_prime) { return 1 - 2 * tau_prime * (1 - std::log(2 * tau_prime)); }

TEST(Slump, AYieldStressStopsTheSlumpAndAHigherOneSooner) {
  const Slump newtonian = slump(0), low = slump(0.1), high = slump(0.3);
  std::printf("Newtonian: slump %.3f, still at %.2g m/s; tau' 0.1: %.3f (Pashias %.3f), %.2g m/s; tau' 0.3: %.3f "
              "(Pashias %.3f), %.2g m/s\n",
              newtonian.slump, newtonian.speed, low.slump, pashias(0.1), low.speed, high.slump, pashias(0.3), high.speed);
  EXPECT_GT(newtonian.speed, 1e-3) << "a Newtonian paste keeps spreading";
  EXPECT_GT(newtonian.slump, low.slump + 0.1);
  EXPECT_LT(low.speed, 1e-4) << "the yield stress stops it";
  EXPECT_LT(high.speed, 1e-4);
  EXPECT_LT(high.slump, low.slump) << "a higher yield stress slumps less";
  // The departure from Pashias's 0.478, held: measured 0.319 (0.326, 0.335 finer).
  EXPECT_GT(low.slump, 0.25);
  EXPECT_LT(low.slump, 0.45);
}

}  // namespace
}  // namespace dentsph
