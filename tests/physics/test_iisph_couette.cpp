// Couette flow between parallel plates, as a parallel-plate rheometer shears a paste: a disc of
// liquid of radius R between a fixed plate (boundary particles) and a plate turning at Omega about
// the disc's axis (the tool), without gravity. At low Reynolds number (0.03 at 1 Pa s) the steady
// flow is azimuthal, v_theta(r, z) = Omega r z / H across a gap H: at each radius the velocity grows
// linearly from plate to plate, whatever the viscosity. On the iisph solver with the viscosity solved
// to a tolerance (iisph.viscosity_tolerance 1e-6) and the cg pressure solve, at 1, 1e3 and 1e5 Pa s,
// at the largest step the velocity limit allows (the turning plate's rim speed: 48 ms) and a quarter
// of it, the profile is within 2% of the rim's speed of the analytic one (measured: 1.25 to 1.31%).
//
// Where the plates are: the velocity reaches the plates' own at their first layer of particles (a
// line through the profile meets 0 and Omega r there, within a tenth of a spacing), so the gap is
// the distance between the plates' first layers, H = (nz + 1) s, half a spacing wider at each plate
// than the liquid's layers suggest: the boundary particles' no-slip plane. The disc is twice as wide
// as the gap and the profile is taken at 0.15 R to 0.5 R: its free rim, where the particles have
// neighbours on one side only, holds v_theta to its neighbours' average instead of to Omega r z / H,
// and at R = H it pulled the upper layers 14% behind.
//
// The torque the liquid puts on the turning plate, pi mu Omega R^4 / (2 H) for a Newtonian liquid (a
// rheometer's measure of mu), is printed with its ratio to that: measured 1.23 to 1.26 at every
// viscosity and step (the paper's viscosity term, the viscosity kernel's Laplacian, at this
// resolution and with the rim; docs/model.md).
//
// The setup: spacing s = 0.3 mm (h = 0.6 mm, the dental paste's), R = 20 s, 10 layers of liquid,
// rho0 = 2000 kg/m^3, Kp = 100 m^2/s^2, no adhesion; plates two layers deep and 3 s wider than the
// disc; the rim at 5 mm/s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "dentsph/step.hpp"
#include "support/builders.hpp"

namespace dentsph {
namespace {

constexpr real s = 3e-4, rho0 = 2000, Kp = 100, pi = 3.14159265358979323846;
constexpr int nr = 20, nz = 10;                 // the disc's radius and the gap, in spacings
constexpr real R = nr * s, H = (nz + 1) * s;    // m; H between the plates' first layers
constexpr real rim_speed = 5e-3;  // m/s

struct Rheometer {
  Model model;
  State state;
};

Rheometer rheometer(const Material& liquid, real dt) {
  ModelParams p = testing::params_for_spacing(s, Vec3{-nr - 8, -nr - 8, -6} * s, Vec3{nr + 8, nr + 8, nz + 6} * s, dt);
  p.solver = Solver::iisph;
  p.iisph.pressure_solve = PressureSolve::cg;
  p.iisph.viscosity_tolerance = 1e-6;
  p.iisph.viscosity_iterations = 1000;
  p.iisph.max_iterations = 200;
  Rheometer r{make_model(p), {}};
  const real m = lattice_particle_mass(rho0, s, r.model.kernel);
  const Material plate{liquid.mu, 1.5 * Kp, rho0, 0};
  std::vector<ParticleInit> ps;
  const int reach = nr + 3;
  for (int k = -2; k <= nz + 1; ++k)
    for (int j = -reach; j <= reach; ++j)
      for (int i = -reach; i <= reach; ++i) {
        const Vec3 x{i * s, j * s, (k + 0.5) * s};  // liquid layers at z = (k + 1/2) s, k = 0 .. nz - 1
        const real rr = std::hypot(x.x, x.y);
        if (k < 0) {
          if (rr <= reach * s) ps.push_back(testing::particle(Role::boundary, x, m, plate));
        } else if (k >= nz) {
          if (rr <= reach * s) ps.push_back(testing::particle(Role::tool, x, m, plate));
        } else if (rr < R) {
          ps.push_back(testing::particle(Role::material, x, m, liquid));
        }
      }
  r.state.add_particles(r.model, ps);
  return r;
}

struct Measured {
  real worst = 0;        // largest |layer mean of v_theta / (Omega r) - z / H| over the fitted layers
  real torque_ratio = 0;  // the plate's torque about the axis over pi mu Omega R^4 / (2 H)
  real torque = 0;        // N m, the liquid's on the turning plate
  int viscosity_iterations_max = 0;
  real viscosity_residual_max = 0;
};

// The largest step the velocity limit allows at the rim's speed.
real limit_step(real speed) { return IisphParams{}.cfl * 2 * s / speed; }

// The liquid sheared with the plate's rim at `speed` for at least `t_min`, stepped at `dt`; the
// profile of the last 5 steps, and the torque over them or, where `torque_from` > 0, from that time on.
// `set_factor` other than 1: every particle of the liquid as the cure leaves a setting paste
// (kCuredMaterial, its viscosity that factor times the liquid's: cured_parameters).
Measured shear(const Material& liquid, real speed, real dt, real t_min = 0, real torque_from = 0,
               real set_factor = 1) {
  const real omega = speed / R, mu = liquid.mu;
  Rheometer r = rheometer(liquid, dt);
  if (set_factor != 1)
    for (std::uint32_t i = 0; i < r.state.size(); ++i) {
      if (r.state.role[i] != Role::material) continue;
      Material m = liquid;
      m.mu *= set_factor;
      r.state.cure.set_cured(r.state.id[i], m);
      r.state.material[i] |= kCuredMaterial;
      r.state.mu[i] = m.mu;
    }
  // The steady state within 2% takes about rho H^2 / mu (18 ms at 1 Pa s); at least 20 steps.
  const real t_end = std::max({20 * dt, 5 * rho0 * H * H / mu, t_min});
  Measured out;
  std::vector<real> sum(nz, 0), count(nz, 0);
  real torque = 0, torque_long = 0;
  int window = 0, window_long = 0;
  while (r.state.time < t_end - 0.5 * dt) {
    r.state.tool_pose = Pose{{}, Quat::from_axis_angle({0, 0, 1}, omega * (r.state.time + dt))};
    step(r.model, r.state, StepOptions{1, nullptr});
    const StepDiagnostics& d = r.state.diagnostics;
    EXPECT_EQ(d.non_finite, 0u);
    out.viscosity_iterations_max = std::max(out.viscosity_iterations_max, d.viscosity_iterations);
    out.viscosity_residual_max = std::max(out.viscosity_residual_max, d.viscosity_residual);
    if (torque_from > 0 && r.state.time > torque_from - 1e-12) {
      torque_long += r.state.tool_wrench.torque.z;
      ++window_long;
    }
    if (r.state.time < t_end - 5 * dt - 1e-12) continue;  // the last 5 steps: the profile and the torque
    ++window;
    torque += r.state.tool_wrench.torque.z;
    for (std::uint32_t i = 0; i < r.state.size(); ++i) {
      if (r.state.role[i] != Role::material) continue;
      const Vec3 x = r.state.pos[i];
      const real rr = std::hypot(x.x, x.y);
      if (rr < 0.15 * R || rr > 0.5 * R) continue;  // away from the axis and the free rim
      const real v_theta = (x.x * r.state.vel[i].y - x.y * r.state.vel[i].x) / rr;
      const int layer = std::clamp(int(std::floor(x.z / s)), 0, nz - 1);
      sum[layer] += v_theta / (omega * rr);
      count[layer] += 1;
    }
  }
  for (int l = 0; l < nz; ++l) {
    const real expected = (l + 1) * s / H;  // the layer's height over the lower plate's first layer
    const real got = sum[l] / std::max<real>(count[l], 1);
    out.worst = std::max(out.worst, std::abs(got - expected));
    std::printf("  layer %d: v_theta / (Omega r) %.4f, analytic %.4f\n", l, got, expected);
  }
  const real analytic = pi * mu * omega * std::pow(R, 4) / (2 * H);
  // The liquid's torque on the plate opposes its turning: -torque.
  out.torque_ratio = -torque / std::max(window, 1) / analytic;
  out.torque = torque_from > 0 ? -torque_long / std::max(window_long, 1) : -torque / std::max(window, 1);
  std::printf("mu %.0e Pa s, dt %.3g ms: worst layer %.4f; torque %.3g of pi mu Omega R^4 / 2H; viscosity "
              "iterations at most %d, residual at most %.2g\n",
              mu, dt * 1e3, out.worst, out.torque_ratio, out.viscosity_iterations_max, out.viscosity_residual_max);
  return out;
}

struct Case {
  real mu, dt_factor;
};

class Couette : public ::testing::TestWithParam<Case> {};

TEST_P(Couette, TheVelocityIsLinearAcrossTheGap) {
  const Measured m = shear(Material{GetParam().mu, Kp, rho0, 0}, rim_speed, GetParam().dt_factor * limit_step(rim_speed));
  EXPECT_LT(m.worst, 0.02) << "every layer's v_theta / (Omega r) within 2% of the rim's of z / H";
  EXPECT_LE(m.viscosity_residual_max, 1e-6) << "every step's viscosity solve reached its tolerance";
  EXPECT_LE(m.viscosity_iterations_max, 64) << "as many at 1e5 Pa s as at 1 (measured 32 at each)";
  // The rheometer's torque: the measured excess (1.23 to 1.26) held, so that a change to the
  // viscosity's magnitude shows here.
  EXPECT_GT(m.torque_ratio, 1.0);
  EXPECT_LT(m.torque_ratio, 1.4);
}

INSTANTIATE_TEST_SUITE_P(Viscosities, Couette,
                         ::testing::Values(Case{1, 1}, Case{1, 0.25}, Case{1e3, 1}, Case{1e3, 0.25}, Case{1e5, 1},
                                           Case{1e5, 0.25}),
                         [](const auto& info) {
                           const Case& c = info.param;
                           return std::string(c.mu == 1 ? "Mu1" : c.mu == 1e3 ? "Mu1e3" : "Mu1e5") +
                                  (c.dt_factor == 1 ? "AtTheVelocityLimit" : "AtAQuarterOfIt");
                         });

}  // namespace
}  // namespace dentsph

namespace dentsph {
namespace {

// The flow curve of a generalised Newtonian paste (docs/model.md, "Rheology"), as a rheometer
// measures it: the torque at two speeds of the plate. Between parallel plates the shear rate at
// radius r is Omega r / H whatever the law (the profile stays linear across the gap), so a paste of
// stress tau(gammadot) puts a torque 2 pi int_0^R tau(Omega r / H) r^2 dr on the plate: for a
// power law K gammadot^n, 2 pi K (Omega / H)^n R^(n+3) / (n + 3), which doubles Omega to 2^n
// times; for a Bingham paste tau_y + mu_p gammadot, 2 pi tau_y R^3 / 3 + pi mu_p Omega R^4 / (2 H).
// The rim's excess (the Newtonian torque is 1.23 to 1.26 of its formula, above) is the same at
// both speeds, so the ratio of the torques is the law's.
// The torque wavers by some 10% as the plate's lattice of particles passes over the liquid's (a
// period of about 1.5 s at the rim's 5 mm/s): both speeds are averaged over the same turn of the
// plate, the second half of 1.5 s at 5 mm/s and of 3 s at 2.5 mm/s.
constexpr real turn = 1.5;  // s at the rim's speed

// The paste sheared at half the rim's speed and at it, each over the same turn of the plate.
std::pair<Measured, Measured> two_speeds(const Material& paste) {
  const real dt = limit_step(rim_speed);
  return {shear(paste, 0.5 * rim_speed, dt, 2 * turn, turn), shear(paste, rim_speed, dt, turn, 0.5 * turn)};
}

TEST(CouetteRheology, PowerLawTorqueGrowsAsTheSpeedToTheFlowIndex) {
  Material paste{1e3, Kp, rho0, 0};
  paste.flow_index = 0.5;
  paste.max_viscosity = 1e7;
  const auto [slow, fast] = two_speeds(paste);
  const real n = paste.flow_index;
  const real analytic = 2 * pi * paste.mu * std::pow(rim_speed / R / H, n) * std::pow(R, n + 3) / (n + 3);
  std::printf("power law n 0.5: torque ratio %.4f (analytic %.4f); fast torque %.4g of the law's\n",
              fast.torque / slow.torque, std::pow(2.0, n), fast.torque / analytic);
  EXPECT_LT(slow.worst, 0.02) << "linear across the gap at every radius, as for a Newtonian liquid";
  EXPECT_LT(fast.worst, 0.02);
  EXPECT_NEAR(fast.torque / slow.torque, std::pow(2.0, n), 0.01 * std::pow(2.0, n))
      << "the speed doubled, the torque 2^n times (measured 1.4177 for 1.4142); 2 for a Newtonian liquid";
  // The rim's excess, as the Newtonian liquid's below (1.11 to 1.12): measured 1.129.
  EXPECT_GT(fast.torque / analytic, 1.05);
  EXPECT_LT(fast.torque / analytic, 1.2);
}

TEST(CouetteRheology, BinghamTorque) {
  Material paste{100, Kp, rho0, 0};
  paste.yield_stress = 200;
  paste.max_viscosity = 1e6;
  const auto [slow, fast] = two_speeds(paste);
  auto law = [&](real speed) {
    return 2 * pi * paste.yield_stress * std::pow(R, 3) / 3 + pi * paste.mu * (speed / R) * std::pow(R, 4) / (2 * H);
  };
  std::printf("bingham: torque ratio %.4f (analytic %.4f); fast torque %.4g of the law's\n", fast.torque / slow.torque,
              law(rim_speed) / law(0.5 * rim_speed), fast.torque / law(rim_speed));
  // Within 3.5%, not 2%: the layer beside the turning plate takes the plate's slip rate where it
  // is over its gradient's (src/solver/rheology.cpp), and a paste whose stress is nearly all its
  // yield stress (200 Pa against 100 Pa s times 0.2 to 0.8 /s) moves its shear toward a layer
  // whose viscosity falls: the profile bows, measured 3.03% and 2.99% (0.31% and 0.57% without the
  // slip rate); the torque is unchanged (1.133 of the law against 1.132).
  EXPECT_LT(slow.worst, 0.035);
  EXPECT_LT(fast.worst, 0.035);
  const real expected = law(rim_speed) / law(0.5 * rim_speed);
  EXPECT_NEAR(fast.torque / slow.torque, expected, 0.01 * expected)
      << "the yield stress's share does not grow with the speed (measured 1.2234 for 1.2212; 2 without it)";
  EXPECT_GT(fast.torque / law(rim_speed), 1.05);  // the rim's excess: measured 1.132
  EXPECT_LT(fast.torque / law(rim_speed), 1.2);
}

// A paste that sets (an amalgam past its working time): the cure raises its viscosity by a factor
// (cured_parameters), and a paste with a flow law keeps its law, the whole flow curve raised by it
// (src/solver/rheology.cpp): the Bingham paste's torque three times at a factor of 3, yield stress
// and all (before, a setting particle took the factor times its consistency as a Newtonian
// viscosity and lost its yield stress).
TEST(CouetteRheology, ASettingPasteKeepsItsFlowLawRaisedByTheSetting) {
  Material paste{100, Kp, rho0, 0};
  paste.yield_stress = 200;
  paste.max_viscosity = 1e6;
  const real dt = limit_step(rim_speed);
  const Measured fresh = shear(paste, rim_speed, dt, turn, 0.5 * turn),
                 set = shear(paste, rim_speed, dt, turn, 0.5 * turn, 3);
  std::printf("setting paste: torque %.4g against %.4g fresh (%.4f times)\n", set.torque, fresh.torque,
              set.torque / fresh.torque);
  EXPECT_NEAR(set.torque / fresh.torque, 3, 0.03 * 3);
}

// The projected form with a Newtonian viscosity (a yield stress of 1e-9 Pa puts the liquid on the
// non-Newtonian path): the same linear profile, the torque twice at twice the speed, and its
// magnitude, the form's (divided by its lattice share, model.hpp) with the disc's rim: measured 1.11
// and 1.12 of pi mu Omega R^4 / (2 H) (the paper's Laplacian gives 1.23 to 1.26, above).
TEST(CouetteRheology, NewtonianOnTheProjectedForm) {
  Material liquid{1e3, Kp, rho0, 0};
  liquid.yield_stress = 1e-9;
  liquid.max_viscosity = 1e7;
  const auto [slow, fast] = two_speeds(liquid);
  const real analytic = pi * liquid.mu * (rim_speed / R) * std::pow(R, 4) / (2 * H);
  std::printf("newtonian, projected: torque ratio %.4f; fast torque %.4g of the formula\n", fast.torque / slow.torque,
              fast.torque / analytic);
  EXPECT_LT(slow.worst, 0.02);
  EXPECT_LT(fast.worst, 0.02);
  EXPECT_NEAR(fast.torque / slow.torque, 2.0, 0.02);
  EXPECT_GT(fast.torque / analytic, 1.0);
  EXPECT_LT(fast.torque / analytic, 1.2);
}

}  // namespace
}  // namespace dentsph
