// Internal forces conserve momentum (docs/model.md, "One step"): with no gravity, boundary or tool,
// total momentum stays constant to rounding over 1000 steps.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "dentsph/step.hpp"
#include "support/builders.hpp"

namespace dentsph {
namespace {

constexpr real kSpacing = 0.01;

// A blob of 7^3 paste particles jittered off their lattice, with random velocities, free in space
// (no gravity, boundary or tool), stepped at `dt` on `solver`.
struct Blob {
  Model model;
  State state;
};

Blob free_blob(real dt, Solver solver) {
  ModelParams p = testing::params_for_spacing(kSpacing, {-0.1, -0.1, -0.1}, {0.2, 0.2, 0.2}, dt);
  p.solver = solver;
  Blob b{make_model(p), {}};
  const Material paste{0.5, 60, 1000, 400};
  const real s = kSpacing, m = lattice_particle_mass(1000, s, b.model.kernel);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<real> u(-1, 1);
  std::vector<ParticleInit> ps;
  for (Vec3 x : testing::lattice({0, 0, 0}, s, 7, 7, 7)) {
    x += Vec3{0.3 * s * u(rng), 0.3 * s * u(rng), 0.3 * s * u(rng)};
    ps.push_back(testing::particle(Role::material, x, m, paste, {0.2 * u(rng), 0.2 * u(rng), 0.2 * u(rng)}));
  }
  b.state.add_particles(b.model, ps);
  return b;
}

TEST(Conservation, MomentumOfFreeMaterialOver1000Steps) {
  Blob b = free_blob(2e-4, Solver::paper);
  const Model& model = b.model;
  State& st = b.state;
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

// The iisph solver on the same free blob at its own larger step: the pressure force is pairwise
// antisymmetric (m_i m_j (p_i / rho_i^2 + p_j / rho_j^2) gradW_ij) and so are the bonds' adhesion
// and the viscosity's system is symmetric; the viscosity's solve stopped after its fixed iterations
// and the single-precision pair rows could leave a drift, measured at 2.7e-10 of sum m |v| over
// 200 steps of 2 ms (docs/model.md, "Solvers").
TEST(Conservation, MomentumOfFreeMaterialOnTheIisphSolver) {
  Blob b = free_blob(2e-3, Solver::iisph);
  const Model& model = b.model;
  State& st = b.state;
  const Vec3 p0 = testing::total_momentum(st);
  real scale = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i) scale += st.mass[i] * norm(st.vel[i]);
  real worst = 0, moved = 0;
  for (int k = 0; k < 200; ++k) {
    real kinetic_before = 0;
    for (std::uint32_t i = 0; i < st.size(); ++i) kinetic_before += st.mass[i] * norm(st.vel[i]);
    step(model, st);
    ASSERT_EQ(st.diagnostics.non_finite, 0u);
    real kinetic_after = 0;
    for (std::uint32_t i = 0; i < st.size(); ++i) kinetic_after += st.mass[i] * norm(st.vel[i]);
    moved = std::max(moved, std::abs(kinetic_after - kinetic_before));
    worst = std::max(worst, norm(testing::total_momentum(st) - p0) / scale);
  }
  std::printf("iisph momentum drift: %.3g of sum m|v| over 200 steps (largest change of sum m|v| in a step %.3g of it)\n",
              worst, moved / scale);
  EXPECT_LT(worst, 1e-8) << "total momentum against sum m |v|";
  EXPECT_GT(moved / scale, 1e-3) << "the forces changed the velocities far more than the drift";
}

}  // namespace
}  // namespace dentsph
