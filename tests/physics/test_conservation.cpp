// Internal forces conserve momentum (MODEL.md, "One step"): with no gravity, boundary or tool,
// total momentum stays constant to rounding over 1000 steps.
#include <gtest/gtest.h>

#include <random>

#include "dentsph/step.hpp"
#include "support/builders.hpp"

namespace dentsph {
namespace {

TEST(Conservation, MomentumOfFreeMaterialOver1000Steps) {
  constexpr real s = 0.01;
  Model model = make_model(testing::params_for_spacing(s, {-0.1, -0.1, -0.1}, {0.2, 0.2, 0.2}, 2e-4));
  const Material paste{0.5, 60, 1000, 400};
  const real m = lattice_particle_mass(1000, s, model.kernel);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<real> u(-1, 1);
  std::vector<ParticleInit> ps;
  for (Vec3 p : testing::lattice({0, 0, 0}, s, 7, 7, 7)) {
    p += Vec3{0.3 * s * u(rng), 0.3 * s * u(rng), 0.3 * s * u(rng)};
    ps.push_back(testing::particle(Role::material, p, m, paste, {0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng)}));
  }
  State st;
  st.add_particles(model, ps);
  const Vec3 p0 = testing::total_momentum(st);
  real scale = 0;  // sum m |v|: the size of the quantities whose rounding we allow
  for (std::uint32_t i = 0; i < st.size(); ++i) scale += st.mass[i] * norm(st.vel[i]);
  real max_force_impulse = 0;
  for (int k = 0; k < 1000; ++k) {
    step(model, st);
    ASSERT_EQ(st.diagnostics.non_finite, 0u);
    real impulse = 0;  // sum over particles of |m a dt|: what a violation would be measured against
    for (std::uint32_t i = 0; i < st.size(); ++i) impulse += st.mass[i] * norm(st.force[i]) / st.rho[i] * model.dt;
    max_force_impulse = std::max(max_force_impulse, impulse);
    const Vec3 dp = testing::total_momentum(st) - p0;
    ASSERT_LT(norm(dp), 1e-12 * scale) << "step " << k;
  }
  // The forces were not negligible: their impulses dwarf the drift allowed above.
  EXPECT_GT(max_force_impulse, 1e-6 * scale);
  EXPECT_GT(st.bonds.counters.formed, 0u);
}

}  // namespace
}  // namespace dentsph
