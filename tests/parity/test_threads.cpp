// The parallel step against the serial one: every thread count gives the same state, bit for
// bit, because each particle's sums are taken in the same order whichever thread takes them.
// The serial grid step is itself tested against the all-pairs reference (test_grid_vs_all_pairs),
// so this also holds the parallel step to the reference. Run under ThreadSanitizer (preset tsan).
#include <gtest/gtest.h>

#include <random>

#include "dentsph/step.hpp"
#include "dentsph/thread_governor.hpp"
#include "support/builders.hpp"

namespace dentsph {
namespace {

constexpr real s = 0.01;

State scene(Model& model) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<real> u(-1, 1);
  const Material paste{0.4, 60, 1000, 300}, wall{0.4, 200, 1000, 0};
  const real m = lattice_particle_mass(1000, s, model.kernel);
  std::vector<ParticleInit> ps;
  for (Vec3 p : testing::lattice({0.002, 0.001, 0.003}, s, 12, 12, 8)) {
    p += Vec3{0.2 * s * u(rng), 0.2 * s * u(rng), 0.2 * s * u(rng)};
    ps.push_back(testing::particle(Role::material, p, m, paste, {0.05 * u(rng), 0.05 * u(rng), 0}));
  }
  for (Vec3 p : testing::open_container({0, 0, 0}, s, 11, 11, 10, 2)) ps.push_back(testing::particle(Role::boundary, p, m, wall));
  for (Vec3 p : testing::lattice({-s, -s, -s}, s, 3, 3, 3)) ps.push_back(testing::particle(Role::tool, p, m, wall));
  State st;
  st.tool_pose.position = {0.06, 0.06, 0.09};
  st.tool_pose_applied = st.tool_pose;
  st.add_particles(model, ps);
  return st;
}

TEST(Threads, ParallelStepIsBitIdenticalToSerial) {
  Model model = make_model(testing::params_for_spacing(s, {-0.03, -0.03, -0.03}, {0.15, 0.15, 0.15}, 2e-4, {0, 0, -9.81}));
  State serial = scene(model), parallel = scene(model);
  StageTimes times;
  for (int k = 0; k < 100; ++k) {
    serial.tool_pose.position.z -= 0.0002;
    parallel.tool_pose.position.z -= 0.0002;
    step(model, serial);
    step(model, parallel, StepOptions{2, &times});
    for (std::uint32_t i = 0; i < serial.size(); ++i) {
      ASSERT_EQ(serial.id[i], parallel.id[i]) << "step " << k;
      ASSERT_EQ(serial.pos[i], parallel.pos[i]) << "step " << k << " index " << i;
      ASSERT_EQ(serial.vel[i], parallel.vel[i]) << "step " << k << " index " << i;
      ASSERT_EQ(serial.rho[i], parallel.rho[i]) << "step " << k << " index " << i;
      ASSERT_EQ(serial.bonds.count(serial.id[i]), parallel.bonds.count(parallel.id[i]));
    }
    ASSERT_EQ(serial.tool_wrench.force, parallel.tool_wrench.force);
    ASSERT_EQ(serial.diagnostics.max_accel, parallel.diagnostics.max_accel);
  }
  EXPECT_EQ(serial.bonds.counters.formed, parallel.bonds.counters.formed);
  EXPECT_EQ(serial.bonds.counters.broken, parallel.bonds.counters.broken);
  EXPECT_GT(serial.bonds.counters.formed, 0u);
  EXPECT_GT(norm(serial.tool_wrench.force), 0) << "the tool touched the material";
  // The stage clock saw every step and every stage.
  EXPECT_EQ(times.steps, 100u);
  EXPECT_GT(times.density_us, 0);
  EXPECT_GT(times.forces_us, 0);
  EXPECT_GE(times.total_us(), times.forces_us + times.density_us);
}

// The thread count may change from step to step (ThreadGovernor): a run whose count alternates
// 1, 2, 2, 1, ... ends bit for bit where the serial run does.
TEST(Threads, ChangingTheThreadCountBetweenStepsChangesNothing) {
  Model model = make_model(testing::params_for_spacing(s, {-0.03, -0.03, -0.03}, {0.15, 0.15, 0.15}, 2e-4, {0, 0, -9.81}));
  State serial = scene(model), mixed = scene(model);
  for (int k = 0; k < 60; ++k) {
    serial.tool_pose.position.z -= 0.0002;
    mixed.tool_pose.position.z -= 0.0002;
    step(model, serial);
    step(model, mixed, StepOptions{(k / 2) % 2 == 0 ? 1 : 2, nullptr});
  }
  for (std::uint32_t i = 0; i < serial.size(); ++i) {
    ASSERT_EQ(serial.pos[i], mixed.pos[i]) << "index " << i;
    ASSERT_EQ(serial.vel[i], mixed.vel[i]) << "index " << i;
  }
  EXPECT_EQ(serial.tool_wrench.force, mixed.tool_wrench.force);
}

// The iisph solver: the same, with its pressure iterations and their early exit (the mean error is
// summed in a fixed order, so every thread count stops after the same iteration).
TEST(Threads, ParallelIisphStepIsBitIdenticalToSerial) {
  ModelParams p = testing::params_for_spacing(s, {-0.03, -0.03, -0.03}, {0.15, 0.15, 0.15}, 2e-3, {0, 0, -9.81});
  p.solver = Solver::iisph;
  p.neighbour_skin = 0.1 * p.h;
  Model model = make_model(p);
  State serial = scene(model), parallel = scene(model);
  int iterations = 0;
  for (int k = 0; k < 60; ++k) {
    serial.tool_pose.position.z -= 0.001;
    parallel.tool_pose.position.z -= 0.001;
    step(model, serial);
    step(model, parallel, StepOptions{2, nullptr});
    for (std::uint32_t i = 0; i < serial.size(); ++i) {
      ASSERT_EQ(serial.id[i], parallel.id[i]) << "step " << k;
      ASSERT_EQ(serial.pos[i], parallel.pos[i]) << "step " << k << " index " << i;
      ASSERT_EQ(serial.vel[i], parallel.vel[i]) << "step " << k << " index " << i;
      ASSERT_EQ(serial.pressure[i], parallel.pressure[i]) << "step " << k << " index " << i;
      ASSERT_EQ(serial.bonds.count(serial.id[i]), parallel.bonds.count(parallel.id[i]));
    }
    ASSERT_EQ(serial.tool_wrench.force, parallel.tool_wrench.force);
    ASSERT_EQ(serial.diagnostics.pressure_iterations, parallel.diagnostics.pressure_iterations);
    ASSERT_EQ(serial.diagnostics.density_error, parallel.diagnostics.density_error);
    iterations += serial.diagnostics.pressure_iterations;
  }
  EXPECT_GT(serial.bonds.counters.formed, 0u);
  EXPECT_GT(norm(serial.tool_wrench.force), 0) << "the tool touched the material";
  EXPECT_GT(iterations, 60 * model.iisph.min_iterations) << "some steps iterated beyond the minimum";
}

}  // namespace
}  // namespace dentsph
