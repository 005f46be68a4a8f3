// The iisph solver holds a column of paste at rest at a time step 16 times the paper's step's
// acoustic limit: the pressure grows with depth as rho g d, and the paste is compressed by what its
// equation of state says (iisph.stiffness Kp = 0.5 Kp: rho g d / (0.5 Kp) is 0.8% at the lowest
// fitted layer), under 1%.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "dentsph/scene.hpp"
#include "dentsph/simulation.hpp"
#include "dentsph/step.hpp"
#include "solver/iisph.hpp"
#include "support/builders.hpp"

namespace dentsph {
namespace {

// The dental paste's scale and material (dental.hpp): spacing 0.3 mm, h = 0.6 mm, rho0 2000 kg/m^3,
// mu 1 Pa s, Kp 10 m^2/s^2 (walls 15), without adhesion.
constexpr real s = 3e-4, rho0 = 2000, g = 9.81;
constexpr int nx = 14, nz = 16;

struct Column {
  Model model;
  State state;
};

Column column(real dt, Solver solver = Solver::iisph) {
  ModelParams p = testing::params_for_spacing(s, Vec3{-5, -5, -5} * s, Vec3{nx + 5, nx + 5, nz + 8} * s, dt, {0, 0, -g});
  p.solver = solver;
  Column c{make_model(p), {}};
  const Material paste{1.0, 10, rho0, 0}, wall{1.0, 15, rho0, 0};
  c.state.add_particles(c.model, testing::column_in_container(c.model, s, nx, nz, paste, wall));
  return c;
}

// A least-squares line of the interior's pressure against depth below the free surface: layer means
// two columns from the walls, over the layers two from the floor to three from the surface (pairs
// of layers alternate about the line by a few percent, the line does not).
struct Fit {
  real slope = 0, intercept = 0, mean_depth = 0;  // Pa/m, Pa, m
  std::vector<real> layer_rho;                    // kg/m^3, the fitted layers' mean density
};

Fit fit_pressure(const State& st) {
  real top = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i)
    if (st.role[i] == Role::material) top = std::max(top, st.pos[i].z);
  std::vector<real> p_sum(nz + 2, 0), rho_sum(nz + 2, 0), count(nz + 2, 0), z_sum(nz + 2, 0);
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    const Vec3 x = st.pos[i];
    if (st.role[i] != Role::material || x.x < 2 * s || x.x > (nx - 3) * s || x.y < 2 * s || x.y > (nx - 3) * s) continue;
    const int layer = std::clamp(int(std::floor(x.z / s + 0.5)), 0, nz + 1);
    p_sum[layer] += st.pressure[i];
    rho_sum[layer] += st.rho[i];
    z_sum[layer] += x.z;
    count[layer] += 1;
  }
  Fit f;
  std::vector<real> d, p;
  for (int l = 2; l < nz - 3; ++l) {
    if (count[l] == 0) continue;
    d.push_back(top + 0.5 * s - z_sum[l] / count[l]);
    p.push_back(p_sum[l] / count[l]);
    f.layer_rho.push_back(rho_sum[l] / count[l]);
  }
  EXPECT_EQ(d.size(), std::size_t(nz - 5)) << "every interior layer holds particles";
  real md = 0, mp = 0;
  for (std::size_t k = 0; k < d.size(); ++k) md += d[k] / d.size(), mp += p[k] / p.size();
  real sdp = 0, sdd = 0;
  for (std::size_t k = 0; k < d.size(); ++k) sdp += (d[k] - md) * (p[k] - mp), sdd += (d[k] - md) * (d[k] - md);
  f.slope = sdp / sdd;
  f.intercept = mp - f.slope * md;
  f.mean_depth = md;
  return f;
}

// A step whose fastest paste (the last step's) would cross more than cfl h in dt is taken as equal
// parts: the same, bit for bit, as that many steps of dt / n, counted as one step of dt. This kept
// the plugger's press on set paste from diverging at 2 ms (docs/model.md, "The iisph solver").
TEST(IisphStep, SplitsAStepWhoseFastestPasteWouldCrossMoreThanCflH) {
  const real dt = 2e-3;
  Column c = column(dt);
  for (int k = 0; k < 5; ++k) step(c.model, c.state, StepOptions{1, nullptr});
  ASSERT_EQ(c.state.diagnostics.substeps, 1) << "a column at rest takes whole steps";
  const real cfl_h = c.model.iisph.cfl * c.model.kernel.h;
  State a = c.state;
  a.diagnostics.max_speed = 2.5 * cfl_h / dt;
  EXPECT_EQ(iisph::substeps(c.model, a), 3);
  const std::uint64_t steps = a.steps;
  const real time = a.time;
  step(c.model, a, StepOptions{1, nullptr});
  EXPECT_EQ(a.diagnostics.substeps, 3);
  EXPECT_EQ(a.steps, steps + 1);
  EXPECT_EQ(a.time, time + dt);
  // The same three parts by hand.
  Model third = c.model;
  third.dt = dt / 3;
  State b = c.state;
  for (int k = 0; k < 3; ++k) {
    b.diagnostics.max_speed = 0;
    step(third, b, StepOptions{1, nullptr});
  }
  ASSERT_EQ(a.size(), b.size());
  for (std::uint32_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.pos[i], b.pos[i]) << i;
    ASSERT_EQ(a.vel[i], b.vel[i]) << i;
  }
  // Bounds: at most kMaxSubsteps, one for a non-finite or zero speed.
  a.diagnostics.max_speed = 1e9;
  EXPECT_EQ(iisph::substeps(c.model, a), iisph::kMaxSubsteps);
  a.diagnostics.max_speed = std::nan("");
  EXPECT_EQ(iisph::substeps(c.model, a), 1);
  a.diagnostics.max_speed = 0;
  EXPECT_EQ(iisph::substeps(c.model, a), 1);
}

// Model::hold_outside_domain (dental scenes): a drop of paste that falls out of the domain is held at
// rest where it was, inside it, counted, and out of the step's figures, so its speed neither splits
// steps nor reads as an explosion; without it, or on the paper's step, it falls on.
TEST(IisphStep, MaterialThatWouldLeaveTheDomainIsHeldAtRest) {
  const real dt = 1.5e-3;
  auto drop = [&](Solver solver, bool hold) {
    ModelParams p = testing::params_for_spacing(s, Vec3{-5, -5, -5} * s, Vec3{5, 5, 5} * s, solver == Solver::iisph ? dt : 5e-5,
                                                {0, 0, -g});
    p.solver = solver;
    p.hold_outside_domain = hold;
    Column c{make_model(p), {}};
    const real m = lattice_particle_mass(rho0, s, c.model.kernel);
    std::vector<ParticleInit> ps;
    for (Vec3 x : testing::lattice({0, 0, 0}, s, 2, 2, 2)) ps.push_back(testing::particle(Role::material, x, m, Material{1.0, 10, rho0, 0}));
    c.state.add_particles(c.model, ps);
    const real t_end = 0.5;  // free fall: 1.2 m below the start, 4.9 m/s
    while (c.state.time < t_end - 0.5 * c.model.dt) step(c.model, c.state, StepOptions{1, nullptr});
    return c;
  };
  const Column held = drop(Solver::iisph, true);
  EXPECT_EQ(held.state.diagnostics.held, 8u) << "the whole drop";
  EXPECT_EQ(held.state.diagnostics.max_speed, 0) << "held particles are out of the step's figures";
  EXPECT_EQ(held.state.diagnostics.substeps, 1);
  for (std::uint32_t i = 0; i < held.state.size(); ++i) {
    EXPECT_TRUE(inside(held.state.pos[i], held.model.domain_min, held.model.domain_max)) << i;
    EXPECT_LT(held.state.pos[i].z, held.model.domain_min.z + 0.2 * s) << "held where it would have left";
    EXPECT_EQ(held.state.vel[i], Vec3{}) << i;
  }
  // A run's summary counts what is held at its end.
  {
    ModelParams p = testing::params_for_spacing(s, Vec3{-5, -5, -5} * s, Vec3{5, 5, 5} * s, dt, {0, 0, -g});
    p.solver = Solver::iisph;
    p.hold_outside_domain = true;
    Scene scene;
    scene.params = p;
    scene.model = make_model(p);
    const real m = lattice_particle_mass(rho0, s, scene.model.kernel);
    scene.model.materials.add("paste", Material{1.0, 10, rho0, 0});
    for (Vec3 x : testing::lattice({0, 0, 0}, s, 2, 2, 2))
      scene.particles.push_back(testing::particle(Role::material, x, m, Material{1.0, 10, rho0, 0}));
    Simulation sim(scene, SimulationOptions{});
    for (int k = 0; k < 340; ++k) ASSERT_TRUE(sim.step(Pose{})) << "step " << k << ": " << sim.summary().message;
    EXPECT_EQ(sim.summary().solver_statistics.held_outside_domain, 8u);
  }
  // Without it the drop falls on, at g (no other force acts on it).
  const Column falling = drop(Solver::iisph, false);
  EXPECT_EQ(falling.state.diagnostics.held, 0u);
  EXPECT_NEAR(falling.state.diagnostics.max_speed, g * 0.5, 0.02 * g * 0.5) << "m/s";
  EXPECT_GT(falling.state.diagnostics.substeps, 1) << "a speed past cfl h / dt splits the step";
  // The paper's step ignores it (its step is the reference, unchanged).
  const Column paper = drop(Solver::paper, true);
  EXPECT_EQ(paper.state.diagnostics.held, 0u);
  EXPECT_NEAR(paper.state.diagnostics.max_speed, g * 0.5, 0.02 * g * 0.5) << "m/s";
}

// A block of paste squeezed to 0.85 of its spacing reads its compression at its first step (the
// pressure solve's prediction, the density after its own correction, would not).
TEST(IisphStep, MeasuresTheCompressionThePasteHas) {
  ModelParams p = testing::params_for_spacing(s, Vec3{-8, -8, -8} * s, Vec3{8, 8, 8} * s, 1e-3, {0, 0, 0});
  p.solver = Solver::iisph;
  Column c{make_model(p), {}};
  const real m = lattice_particle_mass(rho0, s, c.model.kernel);
  std::vector<ParticleInit> ps;
  for (Vec3 x : testing::lattice({0, 0, 0}, 0.85 * s, 6, 6, 6)) ps.push_back(testing::particle(Role::material, x, m, Material{1.0, 10, rho0, 0}));
  c.state.add_particles(c.model, ps);
  State two = c.state;
  step(c.model, c.state, StepOptions{1, nullptr});
  // The interior at 1 / 0.85^3 = 1.63 of the rest density, the surface less.
  EXPECT_GT(c.state.diagnostics.compression_max, 0.5);
  EXPECT_GT(c.state.diagnostics.compression_mean, 0.1);
  EXPECT_LT(c.state.diagnostics.compression_mean, c.state.diagnostics.compression_max);
  // Summed in fixed blocks: the same on two threads, bit for bit.
  step(c.model, two, StepOptions{2, nullptr});
  EXPECT_EQ(two.diagnostics.compression_mean, c.state.diagnostics.compression_mean);
  EXPECT_EQ(two.diagnostics.compression_max, c.state.diagnostics.compression_max);
}

TEST(IisphHydrostatic, PressureIsRhoGDepthAndTheDensityHolds) {
  Column c = column(1e-3);
  State& st = c.state;
  const StabilityLimits paper_limits = stability_limits(c.model, st);
  EXPECT_GT(c.model.dt, 15 * paper_limits.paper_acoustic) << "far above the paper's step's acoustic limit";
  real density_error = 0;
  int max_iterations = 0;
  for (int k = 0; k < 300; ++k) {
    step(c.model, st);
    ASSERT_EQ(st.diagnostics.non_finite, 0u) << "step " << k;
    density_error = std::max(density_error, k > 100 ? st.diagnostics.density_error : 0);
    max_iterations = std::max(max_iterations, st.diagnostics.pressure_iterations);
  }
  EXPECT_LT(st.diagnostics.max_speed, 1e-3) << "m/s: the column is at rest";
  EXPECT_LT(density_error, 0.01) << "mean compression of the paste, every step after the first 0.1 s";
  EXPECT_LE(max_iterations, c.model.iisph.max_iterations);

  // The compression measured at the step's start is the pair pass's density's (not the solve's
  // prediction), and the settled column's is small.
  real sum = 0, most = 0;
  std::uint32_t materials = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i)
    if (st.role[i] == Role::material) {
      const real c = std::max<real>(0, st.rho[i] / st.rho0[i] - 1);
      sum += c;
      most = std::max(most, c);
      ++materials;
    }
  EXPECT_NEAR(st.diagnostics.compression_mean, sum / materials, 1e-12);
  EXPECT_NEAR(st.diagnostics.compression_max, most, 1e-12);
  EXPECT_LT(st.diagnostics.compression_mean, 0.01);

  const Fit f = fit_pressure(st);
  EXPECT_NEAR(f.slope / (rho0 * g), 1.0, 0.03) << "Pa/m: dp/dd against rho g";
  EXPECT_LT(std::abs(f.intercept), 0.03 * rho0 * g * f.mean_depth) << "Pa: the line goes through zero at the surface";
  for (std::size_t l = 0; l < f.layer_rho.size(); ++l) {
    EXPECT_LT(f.layer_rho[l], 1.01 * rho0) << "interior layer " << l;
    EXPECT_GT(f.layer_rho[l], 0.995 * rho0) << "interior layer " << l;
  }
}

// The paper's step on the same column, settled within its acoustic limit: its `pressure`, Kp (rho -
// rho0), grows with depth at about twice rho g. Its pressure force (eq. 5, -(P_i + P_j)/2 m_j/rho_j
// gradW) turns only about half of a pressure gradient into force, so the paste compresses until the
// written pressure's gradient is twice what holds it up. The factor is what docs/outputs.md and
// docs/model.md tell a user reading the paper step's pressure; the iisph solver writes the mechanical
// pressure (the test above).
TEST(PaperPressure, ASettledColumnsPressureIsAboutTwiceRhoGDepth) {
  Column c = column(5e-5, Solver::paper);
  State& st = c.state;
  ASSERT_LT(c.model.dt, stability_limits(c.model, st).acoustic);
  for (int k = 0; k < 4000; ++k) {  // 0.2 s
    step(c.model, st);
    ASSERT_EQ(st.diagnostics.non_finite, 0u) << "step " << k;
  }
  EXPECT_LT(st.diagnostics.max_speed, 5e-3) << "m/s: the column has settled";
  const Fit f = fit_pressure(st);
  const real factor = f.slope / (rho0 * g);
  std::printf("the paper's step: dp/dd = %.3f rho g (intercept %.1f Pa)\n", factor, f.intercept);
  EXPECT_GT(factor, 1.7) << "the written pressure's gradient, in units of rho g";
  EXPECT_LT(factor, 2.5) << "the written pressure's gradient, in units of rho g";
}


// A block of viscous paste (1700 Pa s, the flowable's plateau; Kp 1e4) squeezed to 0.9 of its spacing
// in a container, at the dental presets' step (1.5 ms) and solve: the viscosity, solved after the
// pressure, takes back the velocity by which the pressure would expand it, so without the viscous
// pressure the paste stays compressed; with it (docs/model.md, "The viscous pressure") it expands to
// within its equation of state's compression under its own weight.
struct Squeezed {
  real compression_mean = 0, compression_max = 0, viscous_pressure_max = 0, max_speed = 0;
};

Squeezed squeezed_block(real viscous_pressure) {
  constexpr int n = 8;
  ModelParams p = testing::params_for_spacing(s, Vec3{-5, -5, -5} * s, Vec3{n + 5, n + 5, n + 12} * s, 1.5e-3, {0, 0, -g});
  p.solver = Solver::iisph;
  p.iisph.pressure_solve = PressureSolve::cg;
  p.iisph.max_iterations = 50;
  p.iisph.viscosity_tolerance = 1e-3;
  p.iisph.viscosity_iterations = 100;
  p.iisph.wall_rest_density = true;
  p.iisph.viscous_pressure = viscous_pressure;
  Column c{make_model(p), {}};
  const Material paste{1700, 1e4, rho0, 0}, wall{1700, 1.5e4, rho0, 0};
  std::vector<ParticleInit> ps = testing::column_in_container(c.model, s, n, n, paste, wall);
  for (ParticleInit& q : ps)
    if (q.role == Role::material) q.pos = q.pos * 0.9;
  c.state.add_particles(c.model, ps);
  Squeezed out;
  for (int k = 0; k < 200; ++k) {
    step(c.model, c.state, StepOptions{1, nullptr});
    EXPECT_EQ(c.state.diagnostics.non_finite, 0u);
    out.viscous_pressure_max = std::max(out.viscous_pressure_max, real(c.state.diagnostics.viscous_pressure_max));
  }
  out.compression_mean = c.state.diagnostics.compression_mean;
  out.compression_max = c.state.diagnostics.compression_max;
  out.max_speed = c.state.diagnostics.max_speed;
  return out;
}

TEST(IisphViscousPressure, AViscousPasteSqueezedInAContainerExpandsToItsVolume) {
  const Squeezed without = squeezed_block(0), with = squeezed_block(0.5);
  std::printf("after 0.3 s: compression without the viscous pressure %.3g%% (particle max %.3g%%), with it %.3g%% "
              "(%.3g%%); largest viscous pressure %.3g Pa\n",
              100 * without.compression_mean, 100 * without.compression_max, 100 * with.compression_mean,
              100 * with.compression_max, with.viscous_pressure_max);
  // Squeezed to 0.9: 1 / 0.9^3 = 1.37 of the rest density inside.
  EXPECT_GT(without.compression_mean, 0.05) << "the viscosity holds the compression";
  EXPECT_EQ(without.viscous_pressure_max, 0);
  // rho g d / (0.5 Kp) at the floor, 2.4 mm down: 0.5%; the mean is under half of it.
  EXPECT_LT(with.compression_mean, 0.003);
  EXPECT_LT(with.compression_mean, 0.05 * without.compression_mean);
  EXPECT_GT(with.viscous_pressure_max, 0);
  EXPECT_LT(with.max_speed, 0.05) << "m/s: expanded, not thrown";
}

}  // namespace
}  // namespace dentsph
