// A film of paste one particle thick sheared between a fixed plate (boundary particles) and a plate
// sliding over it (the tool), as paste caught between an instrument and a cavity's wall is. A
// particle's shear rate comes from its paste neighbours' velocities (src/solver/rheology.cpp); in a
// film one particle thick they all move together, so without more the film sat at its
// regularisation's cap (10^6 Pa s) and the sliding plate met 10^3 to 10^4 times the paste's flow
// stress. The instrument's slip rate (its motion across the line to a particle over their distance)
// is the film's shear rate: the plate meets the Bingham law's stress at U / H over the film's area.
// Measured: 1.279 times it (the film's rim and the plates beyond it, as the Couette tests' 1.11 to
// 1.13 and more for a film this thin); without the slip rate, 6,600 times it (245 N against 0.037).
//
// The setup: spacing s = 0.3 mm (h = 0.6 mm), a square film 20 s wide at z = s / 2, plates two layers
// deep and 3 s wider on each side, their first layers at -s / 2 and 3 s / 2: the gap H = 2 s between
// the no-slip planes (test_iisph_couette.cpp). A Bingham paste (100 Pa s, yield stress 200 Pa, cap
// 10^6 Pa s), no gravity, the plate at 5 mm/s.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "dentsph/step.hpp"
#include "support/builders.hpp"

namespace dentsph {
namespace {

constexpr real s = 3e-4, rho0 = 2000, Kp = 100, speed = 5e-3, dt = 2e-3;
constexpr int n = 20;  // the film's width in spacings

TEST(IisphFilm, AFilmOneParticleThickIsShearedAtTheInstrumentsSlipRate) {
  Material paste{100, Kp, rho0, 0};
  paste.yield_stress = 200;
  paste.max_viscosity = 1e6;
  ModelParams p = testing::params_for_spacing(s, Vec3{-n - 8, -n - 8, -6} * s, Vec3{n + 8, n + 8, 8} * s, dt);
  p.solver = Solver::iisph;
  p.iisph.pressure_solve = PressureSolve::cg;
  p.iisph.viscosity_tolerance = 1e-6;
  p.iisph.viscosity_iterations = 1000;
  p.iisph.max_iterations = 200;
  Model model = make_model(p);
  const real m = lattice_particle_mass(rho0, s, model.kernel);
  const Material plate{paste.mu, 1.5 * Kp, rho0, 0};
  std::vector<ParticleInit> ps;
  const int half = n / 2, reach = half + 3;
  for (int k = -2; k <= 2; ++k)
    for (int j = -reach; j < reach; ++j)
      for (int i = -reach; i < reach; ++i) {
        const Vec3 x{(i + 0.5) * s, (j + 0.5) * s, (k + 0.5) * s};
        if (k < 0) ps.push_back(testing::particle(Role::boundary, x, m, plate));
        else if (k > 0) ps.push_back(testing::particle(Role::tool, x, m, plate));
        else if (std::abs(i + 0.5) < half && std::abs(j + 0.5) < half) ps.push_back(testing::particle(Role::material, x, m, paste));
      }
  State state;
  state.add_particles(model, ps);
  real force = 0;
  int window = 0;
  const int steps = 20;
  for (int k = 1; k <= steps; ++k) {
    state.tool_pose = Pose{Vec3{speed * k * dt, 0, 0}, Quat{}};
    step(model, state, StepOptions{1, nullptr});
    ASSERT_EQ(state.diagnostics.non_finite, 0u);
    if (k > steps - 5) {
      force += -state.tool_wrench.force.x;  // the film's drag on the plate opposes its sliding
      ++window;
    }
  }
  force /= window;
  const real H = 2 * s, area = (n * s) * (n * s), rate = speed / H;
  const real law = (paste.yield_stress + paste.mu * rate) * area;
  std::printf("film: drag %.4g N, the Bingham law's %.4g N at %.2f /s over the film (ratio %.3f); the cap's %.4g N\n",
              force, law, rate, force / law, paste.max_viscosity * rate * area);
  EXPECT_GT(force / law, 0.7) << "the film resists the plate at its flow stress";
  EXPECT_LT(force / law, 1.5) << "not at its regularisation's cap (10^3 times more)";
}

}  // namespace
}  // namespace dentsph
