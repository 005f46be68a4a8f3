// Dam break: a column of water, released at t = 0 against the left wall of a box on a dry floor,
// spreads along the floor; its surge front is compared with the experiment of J. C. Martin and
// W. J. Moyce (1952), "An experimental study of the collapse of liquid columns on a rigid
// horizontal plane", Phil. Trans. R. Soc. Lond. A 244, 312-324 (docs/model.md, "Measured").
//
// The experiment's data. Martin and Moyce write a column of width a and height n^2 a, the front's
// distance from the wall z, Z = z / a, and T = n t sqrt(g / a). The table below (their Table 2, as
// it is commonly reproduced) is the column of n^2 = 2 (height 2a) with a = 2.25 in, for which
// T = t sqrt(2 g / a): the same numbers, to 0.01, are pysph's pysph/examples/db_exp_data.py
// (mm_data_2, labelled "n^2=2 and a=2.25", z/a against t sqrt(2 g/a)) and Lethe's dam-break example
// (chaos-polymtl/lethe, examples/multiphysics/dam-break: a column 3.5 wide and 7 high). So the
// column here is twice as high as it is wide; a square column (n^2 = 1) is another curve of the
// paper, and the table does not describe it (measured: on a square column this solver's front
// falls 4 to 10% behind the table from T = 2.3 on, as it should, having less water behind it).
//
// The setup, in the experiment's units: a = 2.25 in = 57.15 mm, 20 particles across (spacing
// s = a / 20 = 2.86 mm, h = 2 s), 40 up, in a slab 4 particles deep between two walls (the
// references compare the table with two-dimensional flows); 3200 particles of water, two layers of
// boundary particles for the floor and the walls (three for the paper's step, below), the floor
// 5.5 a long. Water: rho0 = 1000 kg/m^3, mu = 1e-3 Pa s (water's), no adhesion (Ka = 0); the walls
// are of the same material (their friction is the water's viscosity against particles at rest).
// The front: the furthest particle with at least 4 others within h (a lone drop thrown ahead is
// not the front), at its far face x + s/2, from the wall's face at -s/2: Z = (x + s) / a.
//
// Measured, iisph (docs/model.md has the table), with its default gradient (the spiky kernel's,
// lattice-scaled): from T = 1.98 on the front is within 10% of the experiment (+8.9% at most, +2.6
// to +6.0% from T = 2.32 on). Before that it leads: +11.5, +15.2, +13.4, +10.5, +12.0% at T = 0.84
// to 1.83 (with the cubic spline's gradient, the default before: within 10% from T = 1.83, +14.5%
// at T = 1.19, +11.9, +10.2% at 1.43, 1.63; with the equation of state as written, iisph.stiffness
// 1: +16, +15, +14, +12% at 1.19 to 1.83). That lead is not the setup's: at T = 1.19 (cubic,
// stiffness 1) it is +13, +16 and +17% with 14, 20 and 30 particles across, +15% at dt = 0.25 ms,
// with a slab 6 deep and with Kp = 300, +16% with ten times the viscosity; the paper's step has it
// too (+13%). The simulated column is released at once, the experiment's by removing what held it,
// which takes time: the simulated front reaches the experiment's positions 0.17 to 0.25 earlier in
// T up to T = 1.83 (0.07 to 0.19 after). The test holds the 10% from T = 1.98 on and, before it, the lead
// to what was measured (ahead, by less than 20%).
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

constexpr real g = 9.81;
constexpr real a = 0.05715;  // m, the column's width: 2.25 in, the experiment's
// Martin and Moyce (1952), n^2 = 2: T = t sqrt(2 g / a), Z = front / a.
constexpr real table_T[] = {0.41, 0.84, 1.19, 1.43, 1.63, 1.83, 1.98, 2.20, 2.32, 2.51, 2.65, 2.83, 2.98, 3.11, 3.33};
constexpr real table_Z[] = {1.11, 1.22, 1.44, 1.67, 1.89, 2.11, 2.33, 2.56, 2.78, 3.00, 3.22, 3.44, 3.67, 3.89, 4.11};
constexpr int table_n = sizeof(table_T) / sizeof(table_T[0]);
// Held within 10% of the experiment from this T on; before it (from T = 1 on) within the lead measured.
constexpr real T_within_10_percent = 1.95;

constexpr int nw = 20, nh = 40, ny = 4;  // particles across, up and deep
constexpr int nbox = 110;                // lattice sites along the floor: 5.5 a
constexpr int min_neighbours = 4;

struct DamBreak {
  Model model;
  State state;
  real s = a / nw;
};

DamBreak dam_break(Solver solver, real dt, const Material& water, int L = 2) {
  DamBreak d;
  const real s = d.s;
  ModelParams p = testing::params_for_spacing(s, Vec3{-4, -4, -4} * s, Vec3{nbox + 4.0, ny + 4.0, nh + 8.0} * s, dt,
                                              {0, 0, -g});
  p.solver = solver;
  d.model = make_model(p);
  const MaterialIndex iw = d.model.materials.add("water", water);
  const MaterialIndex ib = d.model.materials.add("wall", water);
  const real m = lattice_particle_mass(water.rho0, s, d.model.kernel);
  std::vector<ParticleInit> ps;
  for (Vec3 x : testing::lattice({0, 0, 0}, s, nw, ny, nh)) ps.push_back(make_particle(Role::material, x, m, water, {}, iw));
  // The box's inner sites are 0 <= i < nbox, 0 <= j < ny, k >= 0; its walls two sites thick. The
  // side walls stand 2a + 2s high beside the column and 1.2 a beyond it (where the water is lower
  // than a), the far wall a high.
  for (int i = -L; i < nbox + L; ++i)
    for (int j = -L; j < ny + L; ++j) {
      const int top = i < nw ? nh + 2 : (i >= nbox ? nw : nw + 4);
      for (int k = -L; k <= top; ++k) {
        const bool inside = i >= 0 && i < nbox && j >= 0 && j < ny && k >= 0;
        if (!inside) ps.push_back(make_particle(Role::boundary, Vec3{i * s, j * s, k * s}, m, water, {}, ib));
      }
    }
  d.state.add_particles(d.model, ps);
  return d;
}

// Z of the front: the furthest material particle with at least min_neighbours material
// neighbours within h, at its far face, from the left wall's face.
real front(const DamBreak& d) {
  const State& st = d.state;
  const real h2 = d.model.kernel.h2;
  std::vector<std::pair<real, std::uint32_t>> xs;
  for (std::uint32_t i = 0; i < st.size(); ++i)
    if (st.role[i] == Role::material) xs.push_back({st.pos[i].x, i});
  std::sort(xs.rbegin(), xs.rend());
  for (const auto& [x, i] : xs) {
    int n = 0;
    for (const auto& [xj, j] : xs) n += j != i && norm2(st.pos[j] - st.pos[i]) < h2;
    if (n >= min_neighbours) return (x + d.s) / a;
  }
  return 0;
}

struct FrontRun {
  std::vector<real> Z;           // the front at table_T
  std::vector<real> lead_T;      // how much earlier than the experiment the front reached table_Z
  real density_error = 0;        // the largest mean compression of the water over the steps
  int max_iterations = 0;        // iisph: the pressure solve's most iterations in a step
  std::uint64_t non_finite = 0;  // summed over the steps
  int outside = 0;               // water particles outside the box at the end
  real max_speed = 0;            // m/s
};

// Steps to T = 3.38, the front every step.
FrontRun run(DamBreak& d) {
  State& st = d.state;
  const Model& model = d.model;
  const real s = d.s;
  const real Tscale = std::sqrt(2 * g / a);
  const int steps = int(std::ceil((table_T[table_n - 1] + 0.05) / Tscale / model.dt));
  FrontRun r;
  std::vector<real> T{0}, Z{front(d)};
  for (int k = 0; k < steps; ++k) {
    step(model, st);
    r.non_finite += st.diagnostics.non_finite;
    r.max_iterations = std::max(r.max_iterations, st.diagnostics.pressure_iterations);
    r.max_speed = std::max(r.max_speed, st.diagnostics.max_speed);
    // The mean compression (iisph: the solve's own figure at the end of the step; the paper's step:
    // of the density it computed, that of the step's start).
    real compression = st.diagnostics.density_error;
    if (model.solver == Solver::paper) {
      real sum = 0;
      int n = 0;
      for (std::uint32_t i = 0; i < st.size(); ++i)
        if (st.role[i] == Role::material) sum += std::max<real>(0, st.rho[i] / st.rho0[i] - 1), ++n;
      compression = sum / n;
    }
    r.density_error = std::max(r.density_error, compression);
    T.push_back(st.time * Tscale);
    Z.push_back(front(d));
  }
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    if (st.role[i] != Role::material) continue;
    const Vec3 x = st.pos[i];  // not past the first layer of a wall or the floor
    if (x.x < -s || x.x > nbox * s || x.y < -s || x.y > ny * s || x.z < -s) ++r.outside;
  }
  for (int q = 0; q < table_n; ++q) {
    std::size_t k = 1;
    while (k + 1 < T.size() && T[k] < table_T[q]) ++k;
    r.Z.push_back(Z[k - 1] + (Z[k] - Z[k - 1]) * (table_T[q] - T[k - 1]) / (T[k] - T[k - 1]));
    std::size_t e = 0;
    while (e + 1 < Z.size() && Z[e] < table_Z[q]) ++e;
    r.lead_T.push_back(table_T[q] - T[e]);
  }
  return r;
}

void print(const char* name, const FrontRun& r) {
  std::printf("%s: largest mean compression %.4f, pressure iterations <= %d, max speed %.2f m/s\n", name,
              r.density_error, r.max_iterations, r.max_speed);
  std::printf("   T   Z exp.  Z sim.  diff.  lead in T\n");
  for (int q = 0; q < table_n; ++q)
    std::printf("%5.2f  %5.2f  %5.2f  %+5.1f%%  %5.2f\n", table_T[q], table_Z[q], r.Z[q], 100 * (r.Z[q] / table_Z[q] - 1),
                r.lead_T[q]);
}

void expect_front_follows_the_experiment(const FrontRun& r) {
  for (int q = 0; q < table_n; ++q) {
    if (table_T[q] < 1) continue;  // the first points depend on how the column was released
    const real diff = r.Z[q] / table_Z[q] - 1;
    if (table_T[q] >= T_within_10_percent) {
      EXPECT_LT(std::abs(diff), 0.10) << "T = " << table_T[q] << ": Z " << r.Z[q] << ", the experiment's " << table_Z[q];
    } else {
      // The measured lead of the early spreading (the file's comment): ahead, by less than 20%.
      EXPECT_GT(diff, 0) << "T = " << table_T[q] << ": Z " << r.Z[q] << ", the experiment's " << table_Z[q];
      EXPECT_LT(diff, 0.20) << "T = " << table_T[q] << ": Z " << r.Z[q] << ", the experiment's " << table_Z[q];
    }
  }
}

void expect_sane(const DamBreak& d, const FrontRun& r) {
  EXPECT_EQ(r.non_finite, 0u);
  EXPECT_EQ(r.outside, 0) << "water particles that left the box";
  EXPECT_LT(r.Z.back(), nbox / real(nw) - 0.5) << "the front stayed clear of the far wall";
  EXPECT_LT(r.max_speed, 4 * std::sqrt(g * 2 * a)) << "m/s: nothing twice as fast as the shallow-water front, 2 sqrt(g H)";
  EXPECT_EQ(d.state.diagnostics.pair_overflow, 0u);
}

// The iisph solver, water's viscosity, Kp = 1000 m^2/s^2: sqrt(Kp) = 32 m/s is 20 times the fastest
// water (1.6 m/s), so the equation of state lets it compress by rho g 2a / (Kp rho0) = 0.11% at the
// floor at rest (twice that at the paper paste's stiffness, iisph.stiffness 0.5); the solve keeps its
// mean compression under 0.5% (measured 0.23%, 0.15% with the cubic spline's gradient) in at most 3
// iterations. dt = 0.5 ms: max|v| dt / h = 0.16, well within the velocity CFL condition (0.4); at
// 1 ms (0.3) the front moves by 2% at most but the solve needs its whole budget of 12 iterations.
TEST(DamBreak, IisphSurgeFrontFollowsMartinAndMoyce) {
  DamBreak d = dam_break(Solver::iisph, 5e-4, Material{1e-3, 1000, 1000, 0});
  const FrontRun r = run(d);
  print("iisph", r);
  expect_sane(d, r);
  EXPECT_LT(r.max_speed * d.model.dt, d.model.iisph.cfl * d.model.kernel.h) << "the velocity CFL condition held";
  EXPECT_LT(r.density_error, 0.005) << "the water's mean compression, every step";
  EXPECT_LE(r.max_iterations, d.model.iisph.max_iterations);
  expect_front_follows_the_experiment(r);
}

// The paper's explicit step on the same column, in its weakly compressible reading: Kp = 250
// m^2/s^2, sqrt(Kp) = 16 m/s, ten times the fastest water (the usual rule for a weakly compressible
// liquid), at dt = 0.12 ms, within its acoustic limit 0.4 h / sqrt(Kp) = 0.145 ms. Its viscosity is
// its only damping: with water's (1e-3 Pa s) the pressure's noise throws particles ahead of the
// front and the front itself runs 11 to 18% ahead from T = 1.98 on (Kp = 1000: 23 to 38%), so here
// mu = 0.05 Pa s, about what Monaghan's artificial viscosity with alpha = 0.01 amounts to at this h
// and sound speed (nu = alpha h c / 10 in 3D); the flow stays inertial (Re = sqrt(g a) a / nu = 850).
// Its walls are three layers thick: with two, a particle went through the floor (and the repulsive
// pressure of stiffer walls, Kp = 500 or 1000, threw more particles out, through the floor and over
// the side walls, than it held).
TEST(DamBreak, PaperStepSurgeFrontFollowsMartinAndMoyce) {
  DamBreak d = dam_break(Solver::paper, 1.2e-4, Material{0.05, 250, 1000, 0}, 3);
  const StabilityLimits limits = stability_limits(d.model, d.state);
  ASSERT_LT(d.model.dt, limits.acoustic);
  ASSERT_LT(d.model.dt, limits.viscous);
  const FrontRun r = run(d);
  print("paper", r);
  expect_sane(d, r);
  EXPECT_LT(r.density_error, 0.01) << "the water's mean compression, every step";
  expect_front_follows_the_experiment(r);
}

}  // namespace
}  // namespace dentsph
