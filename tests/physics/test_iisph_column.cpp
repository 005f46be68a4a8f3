// A deep settled column (docs/model.md, "The pressure solve"): 30 layers of liquid in an open box, at
// the largest step the velocity limit allows and at a quarter of it. At rest the interior's pressure
// grows as rho g d with the depth d below the free surface. Relaxed Jacobi carries a correction
// about one layer an iteration, so while the column's pressure changes its default budget stops it
// far from its tolerance; the projected conjugate gradients (iisph.pressure_solve "cg") reach it
// within the budget at every step.
//
// The liquid: spacing s = 1 mm (h = 2 mm), rho0 = 1000 kg/m^3, Kp = 100 m^2/s^2 (a sound speed of
// 10 m/s: the column's bottom is compressed by rho g D / (0.5 Kp) = 0.6%), no adhesion, at 1 Pa s
// (water's viscosity settles only with the density and its rate of one kernel: the last test). The step: the velocity limit
// dt <= cfl h / v_max, with v_max = sqrt(2 g D) the speed of a fall through the column's whole depth
// D (the fastest any of its liquid can move, as when the column collapses): 1.04 ms, 13 times the
// paper's acoustic limit (80 us); and a quarter of it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "dentsph/step.hpp"
#include "support/builders.hpp"

namespace dentsph {
namespace {

constexpr real s = 1e-3, rho0 = 1000, g = 9.81, Kp = 100, mu = 1.0;
constexpr int nx = 10, nz = 30;

struct Column {
  Model model;
  State state;
};

real velocity_limited_step() {
  const real depth = nz * s, h = 2 * s, cfl = IisphParams{}.cfl;
  return cfl * h / std::sqrt(2 * g * depth);
}

// cubic: the density and the pressure's gradient of one kernel, the cubic spline (iisph.density_kernel
// "cubic"), at water's viscosity.
constexpr real water_mu = 1e-3;
Column column(real dt, PressureSolve solve, int max_iterations, bool cubic = false) {
  ModelParams p = testing::params_for_spacing(s, Vec3{-5, -5, -5} * s, Vec3{nx + 5, nx + 5, nz + 8} * s, dt, {0, 0, -g});
  p.solver = Solver::iisph;
  p.iisph.pressure_solve = solve;
  p.iisph.max_iterations = max_iterations;
  if (cubic) {
    p.iisph.gradient = PressureGradient::cubic;
    p.iisph.density_kernel = DensityKernel::cubic;
  }
  Column c{make_model(p), {}};
  const real viscosity = cubic ? water_mu : mu;
  const Material liquid{viscosity, Kp, rho0, 0}, wall{viscosity, 1.5 * Kp, rho0, 0};
  c.state.add_particles(c.model, testing::column_in_container(c.model, s, nx, nz, liquid, wall));
  return c;
}

// The interior's pressure against the depth below the free surface, averaged over the steps of a
// window: a least-squares line through the layer means two columns from the walls, from three layers
// above the floor to three below the surface.
class Profile {
 public:
  void add(const State& st) {
    real top = 0;
    for (std::uint32_t i = 0; i < st.size(); ++i)
      if (st.role[i] == Role::material) {
        top = std::max(top, st.pos[i].z);
        max_speed = std::max(max_speed, norm(st.vel[i]));
      }
    for (std::uint32_t i = 0; i < st.size(); ++i) {
      const Vec3 x = st.pos[i];
      if (st.role[i] != Role::material || x.x < 2 * s || x.x > (nx - 3) * s || x.y < 2 * s || x.y > (nx - 3) * s) continue;
      const int layer = std::clamp(int(std::floor(x.z / s + 0.5)), 0, nz + 1);
      p_sum_[layer] += st.pressure[i];
      d_sum_[layer] += top + 0.5 * s - x.z;
      count_[layer] += 1;
    }
  }
  // Fits the line; slope in Pa/m, worst_layer the largest |layer mean - line| / (rho0 g D).
  void fit() {
    std::vector<real> d, p;
    for (int l = 3; l < nz - 3; ++l) {
      if (count_[l] == 0) continue;
      d.push_back(d_sum_[l] / count_[l]);
      p.push_back(p_sum_[l] / count_[l]);
    }
    real md = 0, mp = 0;
    for (std::size_t k = 0; k < d.size(); ++k) md += d[k] / d.size(), mp += p[k] / p.size();
    real sdp = 0, sdd = 0;
    for (std::size_t k = 0; k < d.size(); ++k) sdp += (d[k] - md) * (p[k] - mp), sdd += (d[k] - md) * (d[k] - md);
    slope = sdp / sdd;
    intercept = mp - slope * md;
    worst_layer = 0;
    for (std::size_t k = 0; k < d.size(); ++k)
      worst_layer = std::max(worst_layer, std::abs(p[k] - (intercept + slope * d[k])) / (rho0 * g * nz * s));
  }
  real slope = 0, intercept = 0, worst_layer = 0;
  real max_speed = 0;  // m/s, of every material particle over the window

 private:
  std::vector<real> p_sum_ = std::vector<real>(nz + 2, 0), d_sum_ = std::vector<real>(nz + 2, 0),
                    count_ = std::vector<real>(nz + 2, 0);
};

// The column run for `seconds`, its pressure averaged over the last 0.25 s. With the poly6 density at
// water's viscosity (1e-3 Pa s) it does not come to rest on any solve: its particles move at 0.14
// and 0.37 m/s after 1.5 s (1 ms and 0.26 ms steps, cg at a mean density error of 1e-4), and 0.3 to
// 0.4 m/s at 13 us (docs/model.md, "One kernel for the density and its rate").
struct Settled {
  Profile window;
  real iterations_mean = 0;
  int iterations_max = 0;
  int on_budget = 0;
  real max_error = 0;  // the largest StepDiagnostics::pressure_max_error after the first step
};

// Steps `c` at `dt` until `seconds`; the window is the last 0.25 s.
Settled settle(Column& c, real dt, real seconds) {
  c.model.dt = dt;
  Settled r;
  int steps = 0;
  while (c.state.time < seconds - 0.5 * dt) {
    step(c.model, c.state, StepOptions{1, nullptr});
    const StepDiagnostics& d = c.state.diagnostics;
    r.iterations_mean += d.pressure_iterations;
    r.iterations_max = std::max(r.iterations_max, d.pressure_iterations);
    r.on_budget += d.pressure_on_budget;
    if (c.state.steps > 1) r.max_error = std::max(r.max_error, d.pressure_max_error);
    ++steps;
    if (c.state.time > seconds - 0.25) r.window.add(c.state);
  }
  r.iterations_mean /= std::max(1, steps);
  r.window.fit();
  std::printf("dt %.3g ms, %s, budget %d, to %.2f s: slope %.4f rho g, intercept %.1f Pa, worst layer %.4f, max speed "
              "%.3g mm/s; iterations mean %.2f max %d, on budget %d of %d steps, largest error %.5f\n",
              dt * 1e3, pressure_solve_name(c.model.iisph.pressure_solve), c.model.iisph.max_iterations, seconds,
              r.window.slope / (rho0 * g), r.window.intercept, r.window.worst_layer, r.window.max_speed * 1e3,
              r.iterations_mean, r.iterations_max, r.on_budget, steps, r.max_error);
  return r;
}

// A new column stepped at `dt` until `seconds`, its solve's targets 1e-4 (mean) and 1e-3 (largest):
// rho0 Kp / 2 times the mean error is 5 Pa, 2% of rho g D (the default 0.002 is a third of it).
Settled settle(real dt, PressureSolve solve, int max_iterations, real seconds) {
  Column c = column(dt, solve, max_iterations);
  c.model.iisph.density_error = 1e-4;
  c.model.iisph.max_density_error = 1e-3;
  return settle(c, dt, seconds);
}

// At the velocity limit and a quarter of it, every step's solve reaches its tolerance (mean and
// largest density error) within its budget, and the settled column's pressure is the same at both
// steps: the column settles from the lattice at the velocity limit for 1.25 s, then goes on to 1.5 s
// at that step and, from the same state, at a quarter of it. Measured: dp/dd = 1.034 and 1.034
// rho g (1.037 and 1.035 with the cg solve's expansion step at 1; each settled from the lattice at
// its own step: 1.037 and 1.049; 1.028 and 1.045 with the cubic spline's gradient), the line through
// zero within 3 Pa, the layers about it within 9.3% of rho g D (6% with the step at 1: pairs of
// layers alternate about it, a mode the tolerance leaves free: a largest density error of 1e-3 is
// 50 Pa, 17% of rho g D), the fastest particle at 1.8 and 2.5 mm/s (the packing still creeps at
// 1.5 s). The 3.5 to 4.9% over rho g is the discretisation's (the SPH gradient of a linear pressure on this
// packing; the 16-layer paste column of test_iisph_hydrostatic.cpp reads within 3%), not the solve's:
// it does not move with the tolerance or the step.
TEST(DeepColumn, TheSolveConvergesAndThePressureIsTheSameAtEveryStep) {
  const real dt = velocity_limited_step();
  Column c = column(dt, PressureSolve::cg, 200);
  c.model.iisph.density_error = 1e-4;
  c.model.iisph.max_density_error = 1e-3;
  const Settled first = settle(c, dt, 1.25);  // from the lattice, at the velocity limit
  Column q = c;                               // the same column, on at a quarter of the step
  const Settled large = settle(c, dt, 1.5), quarter = settle(q, dt / 4, 1.5);
  EXPECT_EQ(first.on_budget, 0) << "every step's solve reached its tolerance while the column settled";
  EXPECT_LE(first.max_error, 1e-3 * (1 + 1e-9));
  for (const Settled* r : {&large, &quarter}) {
    EXPECT_EQ(r->on_budget, 0) << "every step's solve reached its tolerance";
    EXPECT_LE(r->max_error, 1e-3 * (1 + 1e-9)) << "no particle's density error over max_density_error";
    EXPECT_NEAR(r->window.slope / (rho0 * g), 1.0, 0.06) << "dp/dd against rho g";
    EXPECT_LT(std::abs(r->window.intercept), 0.03 * rho0 * g * nz * s) << "Pa: through zero at the surface";
    EXPECT_LT(r->window.worst_layer, 0.12) << "the layers about the line, in rho g D";
    EXPECT_LT(r->window.max_speed, 3e-3) << "m/s: at rest";
  }
  EXPECT_NEAR(large.window.slope, quarter.window.slope, 0.02 * rho0 * g) << "the same pressure at both steps";
}

// The first 0.5 s from the lattice, at the velocity limit, where the pressure changes from step to
// step: relaxed Jacobi with the default budget of 12 stops on it (measured: 55 of 480 steps, a mean
// error up to 0.00175, 17 times the target) and needs up to 77 iterations given 200; the conjugate
// gradients need at most 21 (32 with the expansion step at 1; mean 3.4 against 5.3).
TEST(DeepColumn, ConjugateGradientsNeedFewerIterationsThanJacobiWhileItSettles) {
  const real dt = velocity_limited_step();
  const Settled jacobi_12 = settle(dt, PressureSolve::jacobi, 12, 0.5);
  const Settled jacobi = settle(dt, PressureSolve::jacobi, 200, 0.5);
  const Settled cg = settle(dt, PressureSolve::cg, 200, 0.5);
  EXPECT_GT(jacobi_12.on_budget, 10) << "Jacobi stops on its budget of 12";
  EXPECT_EQ(jacobi.on_budget, 0);
  EXPECT_EQ(cg.on_budget, 0);
  EXPECT_LT(cg.iterations_max, 0.6 * jacobi.iterations_max);
  EXPECT_LT(cg.iterations_mean, 0.8 * jacobi.iterations_mean);
}



// At water's viscosity, the density and its rate of one kernel (iisph.density_kernel "cubic",
// docs/model.md, "One kernel for the density and its rate"). With the paper's poly6 density and
// either gradient, the same column relaxed the same way heats up once it is released (measured, with
// the targets 1e-4 and 1e-3: 0.5 s after, a kinetic energy of 1.8 uJ, 35 mm/s rms, the fastest
// particle at 99 mm/s; at a quarter of the step 13 uJ, 94 mm/s rms, 263 mm/s): the solve predicts
// the density's change with one kernel's gradient, the next step sums the density with another and
// corrects the difference within its step, so the smaller the step the faster the heating. With one
// kernel the prediction is the density's own rate (at the targets 1e-4 and 1e-3: 0.002 uJ, 1.2 mm/s
// rms). The start: 0.5 s from the lattice at the velocity limit with the velocities damped by 0.9 a
// step (a relaxed packing: the liquid's rest, not its dynamics), then free at that step to 3.5 s, and
// from there at that step and at a quarter of it to 3.75 s, the solve's targets 1e-6 (mean) and 1e-5
// (largest). Measured over the last 0.25 s: dp/dd 1.0157 rho g at both steps, 0.043 and 0.041 mm/s
// rms, the fastest particle at 0.44 and 0.45 mm/s. Released from the damped packing the lattice
// rearranges (the free surface's layer slides sideways at up to 5 to 9 mm/s at 0.6 to 1.2 s) and the
// water's viscosity takes about 2.5 s to calm it. The targets are the surface's: a largest density
// error of 1e-4 is about 5 Pa of pressure, half of what holds up a surface particle (rho g s, 9.8 Pa),
// and with 1e-5 and 1e-4 the fastest particle stays at 1.0 to 1.5 mm/s out to 4.5 s.
TEST(DeepColumn, AtWatersViscosityOneKernelForTheDensityKeepsItAtRest) {
  const real dt = velocity_limited_step();
  Column c = column(dt, PressureSolve::cg, 200, /*cubic=*/true);
  c.model.iisph.density_error = 1e-6;
  c.model.iisph.max_density_error = 1e-5;
  while (c.state.time < 0.5) {
    step(c.model, c.state, StepOptions{1, nullptr});
    for (Vec3& v : c.state.vel) v *= 0.9;
  }
  settle(c, dt, 3.5);
  Column q = c;
  const Settled large = settle(c, dt, 3.75), quarter = settle(q, dt / 4, 3.75);
  for (const Column* col : {&c, &q}) {
    real ke = 0, m = 0;
    for (std::uint32_t i = 0; i < col->state.size(); ++i)
      if (col->state.role[i] == Role::material) {
        ke += col->state.mass[i] * dot(col->state.vel[i], col->state.vel[i]);
        m += col->state.mass[i];
      }
    const real rms = std::sqrt(ke / m);
    std::printf("rms speed %.3g mm/s\n", rms * 1e3);
    EXPECT_LT(rms, 1e-3) << "m/s: the liquid at rest on the whole";
  }
  for (const Settled* r : {&large, &quarter}) {
    EXPECT_EQ(r->on_budget, 0) << "every step's solve reached its tolerance";
    EXPECT_NEAR(r->window.slope / (rho0 * g), 1.0, 0.02) << "dp/dd against rho g";
    EXPECT_LT(std::abs(r->window.intercept), 0.03 * rho0 * g * nz * s) << "Pa: through zero at the surface";
    EXPECT_LT(r->window.max_speed, 1e-3) << "m/s: every particle at rest";
  }
  EXPECT_NEAR(large.window.slope, quarter.window.slope, 0.01 * rho0 * g) << "the same pressure at both steps";
}

}  // namespace
}  // namespace dentsph
