// Surface tension and wetting (docs/model.md, "Surface tension and wetting"): the iisph solver's
// Akinci, Akinci & Teschner 2013 forces against Laplace's law, and a drop on a wall.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "dentsph/solver.hpp"
#include "dentsph/step.hpp"
#include "solver/iisph.hpp"
#include "support/builders.hpp"

namespace dentsph {
namespace {

constexpr real s = 1e-4, rho0 = 2000, Kp = 16, mu = 2, sigma = 0.04;

struct Ball {
  Model model;
  State state;
  real radius = 0;  // m, the paste's: the lattice's points within R, and half a spacing beyond
};

// The iisph solver with the surface tension, its solves to tight tolerances (the pressures read are
// tens of pascals), without gravity.
ModelParams tension_params(Vec3 lo, Vec3 hi, real dt, real tension, real wetting = 0) {
  ModelParams p = testing::params_for_spacing(s, lo, hi, dt);
  p.solver = Solver::iisph;
  p.iisph.pressure_solve = PressureSolve::cg;
  p.iisph.max_iterations = 500;
  p.iisph.density_error = 1e-6;
  p.iisph.max_density_error = 1e-5;
  p.iisph.viscosity_tolerance = 1e-6;
  p.iisph.viscosity_iterations = 200;
  p.iisph.surface_tension = tension;
  p.iisph.wetting = wetting;
  return p;
}

// A ball of paste of lattice points within `r_spacings` spacings of the centre, without gravity.
Ball ball(real r_spacings, real tension, real dt, real viscosity = mu) {
  const real extent = (r_spacings + 6) * s;
  Ball b{make_model(tension_params(Vec3{-1, -1, -1} * extent, Vec3{1, 1, 1} * extent, dt, tension)), {}};
  const Material paste{viscosity, Kp, rho0, 0};
  const real m = lattice_particle_mass(rho0, s, b.model.kernel);
  const int n = int(std::ceil(r_spacings));
  std::vector<ParticleInit> ps;
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j)
      for (int k = -n; k <= n; ++k) {
        const Vec3 x{i * s, j * s, k * s};
        if (norm(x) <= r_spacings * s) ps.push_back(testing::particle(Role::material, x, m, paste));
      }
  b.state.add_particles(b.model, ps);
  // The ball's radius: the sphere of the particles' volume.
  b.radius = std::cbrt(3 * real(ps.size()) / (4 * std::numbers::pi)) * s;
  return b;
}

struct Pressures {
  real inside = 0;   // Pa, the mean over particles within half the radius
  real max_speed = 0;
};

Pressures settle(Ball& b, real seconds) {
  Pressures r;
  int samples = 0;
  while (b.state.time < seconds) {
    step(b.model, b.state, StepOptions{1, nullptr});
    if (b.state.time > 0.75 * seconds) {
      Vec3 c;
      for (std::uint32_t i = 0; i < b.state.size(); ++i) c += b.state.pos[i];
      c = c / real(b.state.size());
      real sum = 0;
      int count = 0;
      for (std::uint32_t i = 0; i < b.state.size(); ++i)
        if (norm(b.state.pos[i] - c) < 0.5 * b.radius) {
          sum += b.state.pressure[i];
          ++count;
        }
      r.inside += sum / std::max(1, count);
      ++samples;
    }
  }
  r.inside /= std::max(1, samples);
  for (const Vec3& v : b.state.vel) r.max_speed = std::max(r.max_speed, norm(v));
  return r;
}

// Laplace's law: a ball of paste of radius R without gravity holds 2 sigma / R inside. The scale of
// Akinci's coefficient (kSurfaceTensionScale, 14.7) is fitted to it: balls of 6, 8 and 10 spacings
// settled for 0.3 s read 0.93, 0.92 and 1.18 of their law (a mean of 1.01). Here, settled for 0.1 s,
// 0.80, 0.92 and 1.06 (mean 0.93). The law's 1 / R is followed only roughly (the pressure falls as
// R^-0.54 from 6 to 10 spacings): the balls' particles keep moving at 0.2 to 0.4 mm/s, the
// surface's packing rearranging (docs/model.md, "Surface tension and wetting"). Without tension,
// nothing inside.
TEST(SurfaceTension, ABallsPressureIsLaplaces) {
  real ratio_sum = 0;
  for (real rs : {6.0, 8.0, 10.0}) {
    Ball b = ball(rs, sigma, 5e-4);
    const Pressures with = settle(b, 0.1);
    const real laplace = 2 * sigma / b.radius, ratio = with.inside / laplace;
    std::printf("R %.1f s (%.3g mm, %u particles): inside %.2f Pa, Laplace %.2f Pa: ratio %.4f, max speed %.3g mm/s\n",
                rs, b.radius * 1e3, b.state.size(), with.inside, laplace, ratio, with.max_speed * 1e3);
    EXPECT_NEAR(ratio, 1.0, 0.25) << rs << " spacings";
    ratio_sum += ratio;
  }
  EXPECT_NEAR(ratio_sum / 3, 1.0, 0.1) << "the fitted scale";
  Ball b0 = ball(8, 0, 5e-4);
  EXPECT_LT(settle(b0, 0.02).inside, 0.01) << "Pa: no tension, no pressure";
}

// The forces are pairwise opposite (the cohesion's and, between particles of one mass, the
// curvature's): a free ball rounding itself keeps its momentum (zero).
TEST(SurfaceTension, ARoundingBallKeepsItsMomentum) {
  Ball b = ball(6, sigma, 5e-4);
  real speed = 0, mass = 0;
  for (int k = 0; k < 40; ++k) step(b.model, b.state, StepOptions{1, nullptr});
  for (std::uint32_t i = 0; i < b.state.size(); ++i) {
    speed = std::max(speed, norm(b.state.vel[i]));
    mass += b.state.mass[i];
  }
  ASSERT_GT(speed, 1e-6) << "m/s: the ball moves as it rounds";
  EXPECT_LT(norm(testing::total_momentum(b.state)), 1e-6 * mass * speed) << "kg m/s (the rows' single-precision gradients)";
}

// Wetting draws paste along a wall: a cube of paste set on a plate keeps more of it in contact with
// the wall's adhesion (wetting 1; measured 20 of its 36 bottom particles after 0.25 s) than with the
// surface tension alone, which rounds it and lifts it off the plate (4).
TEST(SurfaceTension, WettingDrawsThePasteAlongAWall) {
  auto spread = [](real wetting) {
    const int side = 6, plate = 22;
    Model model = make_model(tension_params(Vec3{-4, -4, -4} * s, Vec3{plate + 4, plate + 4, 14} * s, 5e-4, sigma, wetting));
    const Material paste{mu, Kp, rho0, 0}, wall{mu, 1.5 * Kp, rho0, 0};
    const real m = lattice_particle_mass(rho0, s, model.kernel);
    std::vector<ParticleInit> ps;
    const real off = (plate - side) / 2 * s;
    for (Vec3 x : testing::lattice({off, off, s}, s, side, side, side)) ps.push_back(testing::particle(Role::material, x, m, paste));
    for (Vec3 x : testing::lattice({0, 0, -s}, s, plate, plate, 2)) ps.push_back(testing::particle(Role::boundary, x, m, wall));
    State st;
    st.add_particles(model, ps);
    while (st.time < 0.25) step(model, st, StepOptions{1, nullptr});
    int on_plate = 0;
    for (std::uint32_t i = 0; i < st.size(); ++i)
      if (st.role[i] == Role::material && st.pos[i].z < 1.5 * s) ++on_plate;
    std::printf("wetting %.1f: %d paste particles in the layer on the plate (of %d)\n", wetting, on_plate, side * side * side);
    return on_plate;
  };
  const int dry = spread(0), wet = spread(1);
  EXPECT_GT(wet, dry + 6) << "paste particles in the layer on the plate";
}

// The forces are explicit: a step over the capillary limit is refused, naming it. Water's tension
// and viscosity at a spacing of 0.1 mm: sqrt(rho0 h^3 / (2 pi sigma)) = 0.13 ms binds (mu h / sigma
// is 2.8 us); the paste's 2 Pa s damps its surface: 5.6 ms.
TEST(SurfaceTension, AStepOverTheCapillaryLimitIsRefused) {
  const Ball water = ball(4, 0.072, 5e-4, 1e-3);
  const StabilityLimits l = stability_limits(water.model, water.state);
  EXPECT_NEAR(l.capillary, std::sqrt(rho0 * 8 * s * s * s / (2 * std::numbers::pi * 0.072)), 1e-9);
  const std::string problem = solver_properties(Solver::iisph).time_step_problem(water.model, l, 0);
  EXPECT_NE(problem.find("surface tension's limit"), std::string::npos) << problem;
  EXPECT_NE(problem.find("simulation.dt"), std::string::npos) << problem;
  const Ball paste = ball(4, sigma, 5e-4);
  const StabilityLimits lp = stability_limits(paste.model, paste.state);
  EXPECT_NEAR(lp.capillary, mu * 2 * s / sigma, 1e-12);
  EXPECT_EQ(solver_properties(Solver::iisph).time_step_problem(paste.model, lp, 0), "");
  const Ball none = ball(4, 0, 5e-4, 1e-3);
  EXPECT_TRUE(std::isinf(stability_limits(none.model, none.state).capillary));
}

// Out of their ranges: refused naming the field.
TEST(SurfaceTension, ParametersOutOfRangeAreRefused) {
  auto refused = [](real tension, real wetting, const std::string& words) {
    ModelParams p = testing::params_for_spacing(s, Vec3{-1, -1, -1} * s, Vec3{1, 1, 1} * s, 1e-4);
    p.solver = Solver::iisph;
    p.iisph.surface_tension = tension;
    p.iisph.wetting = wetting;
    try {
      (void)make_model(p);
      ADD_FAILURE() << "accepted " << tension << ", " << wetting;
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  refused(-0.01, 0, "iisph.surface_tension");
  refused(2, 0, "iisph.surface_tension");
  refused(0.04, 3, "iisph.wetting");
  refused(0, 1, "needs a surface tension");
}

}  // namespace
}  // namespace dentsph
