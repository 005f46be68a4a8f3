// The grid step against the all-pairs reference: same densities, forces, bonds and trajectories
// (within 1e-5 relative over 100 steps) for several particle counts and random configurations,
// including particles exactly on cell borders and far outside the grid's domain.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "dentsph/step.hpp"
#include "support/builders.hpp"
#include "support/state_parity.hpp"

namespace dentsph {
namespace {

using testing::at;

constexpr real s = 0.01;  // m, spacing

struct Config {
  int n_side;          // material lattice of n_side^3
  real jitter;         // fraction of s
  bool on_borders;     // lattice aligned with the grid cells (coordinates on cell faces)
  bool far_outliers;   // a second cluster far outside the domain
  bool with_tool;
  unsigned seed;
  int reach = 2;       // grid cells of h / reach
  real skin = 0;       // neighbour-list skin, in h
};

State build(Model& model, const Config& c) {
  std::mt19937_64 rng(c.seed);
  std::uniform_real_distribution<real> u(-1, 1);
  const Material paste{0.4, 60, 1000, 300};
  const Material wall{0.4, 200, 1000, 0};
  const real m = lattice_particle_mass(1000, s, model.kernel);
  std::vector<ParticleInit> ps;
  // On borders: the origin and spacing are multiples of the cell size (h / reach, h = 2 s), so
  // lattice planes lie exactly on cell faces.
  const Vec3 lo = c.on_borders ? Vec3{0, 0, 0} : Vec3{0.0031, 0.0017, 0.0043};
  for (Vec3 p : testing::lattice(lo + Vec3{2 * s, 2 * s, 2 * s}, s, c.n_side, c.n_side, c.n_side)) {
    const real j = c.jitter * s;
    p += Vec3{j * u(rng), j * u(rng), j * u(rng)};
    ps.push_back(testing::particle(Role::material, p, m, paste, Vec3{0.05 * u(rng), 0.05 * u(rng), 0.05 * u(rng)}));
  }
  // A floor of boundary particles below.
  for (Vec3 p : testing::lattice(lo + Vec3{0, 0, 0}, s, c.n_side + 4, c.n_side + 4, 2))
    ps.push_back(testing::particle(Role::boundary, p, m, wall));
  if (c.far_outliers) {
    // A small cluster 1 km away (and one at negative coordinates): aliases into wrapped cells.
    for (Vec3 p : testing::lattice({1000.0, -2000.0, 3000.0}, s, 3, 3, 3))
      ps.push_back(testing::particle(Role::material, p, m, paste, Vec3{0.01, 0, 0}));
    for (Vec3 p : testing::lattice({-1e4 + 0.001, 5.0, -77.0}, s, 2, 2, 2))
      ps.push_back(testing::particle(Role::material, p, m, paste));
  }
  if (c.with_tool) {
    for (Vec3 p : testing::lattice({-s, -s, -s}, s, 3, 3, 3)) ps.push_back(testing::particle(Role::tool, p, m, wall));
  }
  State st;
  st.tool_pose.position = lo + Vec3{(c.n_side / 2.0 + 2) * s, (c.n_side / 2.0 + 2) * s, (c.n_side + 3.5) * s};
  st.tool_pose_applied = st.tool_pose;
  st.add_particles(model, ps);
  return st;
}

// Within 1e-5 relative; floors a millionth of each field's largest value. P = Kp (rho - rho0)
// cancels near rest: the rounding of rho (Kp rho0 1e-16) is allowed by a 1e-3 Pa floor, far
// below any pressure that moves material (Kp rho0 ~ 1e5 Pa).
void compare(const State& g, const State& r, int step) { testing::compare_states(g, r, step, testing::StateTolerance{}); }

void PrintTo(const Config& c, std::ostream* os) {
  *os << "material" << c.n_side << "cubed_jitter" << int(c.jitter * 100) << "pct" << (c.on_borders ? "_on_cell_borders" : "")
      << (c.far_outliers ? "_far_outliers" : "") << (c.with_tool ? "_tool" : "") << "_reach" << c.reach
      << "_skin" << int(c.skin * 100) << "pct";
}

class GridParity : public ::testing::TestWithParam<Config> {};

TEST_P(GridParity, MatchesAllPairsOver100Steps) {
  const Config c = GetParam();
  const real ext = (c.n_side + 6) * s;
  ModelParams mp = testing::params_for_spacing(s, {0, 0, 0}, {ext, ext, ext}, 2e-4, {0, 0, -9.81});
  mp.grid_reach = c.reach;
  mp.neighbour_skin = c.skin * mp.h;
  Model model = make_model(mp);
  State g = build(model, c), r = build(model, c);
  for (int k = 0; k < 100; ++k) {
    // The tool presses down and sideways so that bonds form and break.
    const Vec3 move{0.02 * s * (k % 7 == 0 ? 1 : 0), 0, -0.03 * s};
    g.tool_pose.position += move;
    r.tool_pose.position += move;
    step(model, g);
    step_all_pairs(model, r);
    compare(g, r, k);
    if (HasFatalFailure()) return;
  }
  // The comparison is not vacuous: bonds formed and forces acted.
  EXPECT_GT(g.bonds.counters.formed, 0u);
  EXPECT_EQ(g.bonds.counters.formed, r.bonds.counters.formed);
  EXPECT_EQ(g.bonds.counters.broken, r.bonds.counters.broken);
  EXPECT_EQ(g.diagnostics.non_finite, 0u);
}

TEST(GridParity, SkinSkipsRebuildsAndStillMatchesAllPairs) {
  ModelParams mp = testing::params_for_spacing(s, {0, 0, 0}, {0.15, 0.15, 0.15}, 2e-4, {0, 0, -9.81});
  mp.neighbour_skin = 0.2 * mp.h;
  Model model = make_model(mp);
  const Config c{6, 0.2, false, false, true, 12};
  State g = build(model, c), r = build(model, c);
  int rebuilds = 0;
  for (int k = 0; k < 100; ++k) {
    g.tool_pose.position.z -= 0.03 * s;
    r.tool_pose.position.z -= 0.03 * s;
    step(model, g, StepOptions{2, nullptr});
    step_all_pairs(model, r);
    rebuilds += g.diagnostics.rebuilt;
    compare(g, r, k);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(rebuilds, 1) << "the tool's motion forces rebuilds";
  EXPECT_LT(rebuilds, 50) << "most steps reuse the lists";
}

INSTANTIATE_TEST_SUITE_P(Configs, GridParity,
                         ::testing::Values(Config{3, 0.2, false, false, false, 1},
                                           Config{5, 0.25, true, false, true, 2},
                                           Config{6, 0.0, true, true, true, 3},
                                           Config{8, 0.3, false, true, true, 4},
                                           Config{5, 0.25, true, false, true, 5, 1},
                                           Config{6, 0.2, false, true, true, 6, 1},
                                           Config{5, 0.2, true, true, true, 7, 3},
                                           Config{6, 0.25, true, true, true, 8, 1, 0.1},
                                           Config{7, 0.3, false, false, true, 9, 1, 0.3},
                                           Config{5, 0.2, true, false, true, 10, 2, 0.2}));

// A 5^3 block of paste on a lattice of dyadic spacing (every coordinate and difference exact,
// pairs two spacings apart exactly h apart), with a neighbour skin of `skin` h.
struct DyadicBlock {
  Model model;
  std::vector<ParticleInit> particles;
};
DyadicBlock dyadic_block(real skin) {
  const real d = 1.0 / 128;
  ModelParams mp = testing::params_for_spacing(d, {0, 0, 0}, {0.25, 0.25, 0.25}, 1e-4);
  mp.neighbour_skin = skin * mp.h;
  DyadicBlock b{make_model(mp), {}};
  const Material paste{0.4, 60, 1000, 300};
  const real m = lattice_particle_mass(1000, d, b.model.kernel);
  for (Vec3 p : testing::lattice({8 * d, 8 * d, 8 * d}, d, 5, 5, 5))
    b.particles.push_back(testing::particle(Role::material, p, m, paste));
  return b;
}

TEST(GridParity, PairsExactlyOnTheSupportWithASkin) {
  // A lattice of dyadic spacing (every coordinate and difference exact): pairs two spacings
  // apart are exactly h apart, r^2 == h^2, inside the list's skin but not within h. The density
  // pass must leave them out of the force pass's pairs, as the all-pairs kernels give them 0.
  DyadicBlock block = dyadic_block(0.1);
  Model& model = block.model;
  const std::vector<ParticleInit>& ps = block.particles;
  State g, r;
  g.add_particles(model, ps);
  r.add_particles(model, ps);
  step(model, g, StepOptions{2, nullptr});
  step_all_pairs(model, r);
  compare(g, r, 0);
  // Not vacuous: listed pairs at exactly h exist and none of them was kept.
  std::uint64_t on_support = 0, kept_on_support = 0;
  for (std::uint32_t i = 0; i < g.size(); ++i) {
    const std::uint32_t* list = g.grid.neighbours.data() + std::size_t(i) * GridIndex::kNeighbourStride;
    const std::uint32_t* within = g.grid.within.data() + std::size_t(i) * GridIndex::kNeighbourStride;
    for (std::uint32_t q = 0; q < g.grid.neighbour_count[i]; ++q)
      on_support += norm2(g.grid.pos_at_build[i] - g.grid.pos_at_build[list[q]]) == model.kernel.h2;
    for (std::uint32_t q = 0; q < g.grid.within_count[i]; ++q)
      kept_on_support += norm2(g.grid.pos_at_build[i] - g.grid.pos_at_build[within[q]]) >= model.kernel.h2;
  }
  EXPECT_GT(on_support, 100u);
  EXPECT_EQ(kept_on_support, 0u);
  for (int k = 1; k < 20; ++k) {
    step(model, g, StepOptions{2, nullptr});
    step_all_pairs(model, r);
    compare(g, r, k);
    if (HasFatalFailure()) return;
  }
}

TEST(GridParity, WithinListsAndBuildPositionsOnlyWithASkin) {
  // Without a skin every list is rebuilt each step and holds exactly the pairs within h: the
  // within-h copy and the build positions are not allocated, and the step still matches.
  auto run = [&](real skin) {
    DyadicBlock block = dyadic_block(skin);
    Model& model = block.model;
    const std::vector<ParticleInit>& ps = block.particles;
    State g, r;
    g.add_particles(model, ps);
    r.add_particles(model, ps);
    for (int k = 0; k < 5; ++k) {
      step(model, g, StepOptions{2, nullptr});
      step_all_pairs(model, r);
      compare(g, r, k);
    }
    return g;
  };
  const State without = run(0), with = run(0.1);
  EXPECT_FALSE(without.grid.keep_lists);
  EXPECT_EQ(without.grid.within.capacity(), 0u);
  EXPECT_EQ(without.grid.pos_at_build.capacity(), 0u);
  EXPECT_TRUE(with.grid.keep_lists);
  EXPECT_EQ(with.grid.within.size(), std::size_t(with.size()) * GridIndex::kNeighbourStride);
  // The within-h lists (4 bytes a slot) and the build positions are the difference per particle.
  EXPECT_GE(with.bytes_per_particle(),
            without.bytes_per_particle() + std::size_t(4 * GridIndex::kNeighbourStride + sizeof(Vec3)));
}

TEST(GridParity, BondsBreakBeyondBInBothPaths) {
  // Two material particles pulled apart by their initial velocities: the bond formed at r < A
  // breaks past B in both paths; the grid reaches the partner beyond h through the bond list.
  Model model = make_model(testing::params_for_spacing(s, {0, 0, 0}, {0.2, 0.2, 0.2}, 1e-4));
  const Material paste{0, 60, 1000, 300};
  const real m = lattice_particle_mass(1000, s, model.kernel);
  std::vector<ParticleInit> ps = {testing::particle(Role::material, {0.1, 0.1, 0.1}, m, paste, {-1.0, 0, 0}),
                                  testing::particle(Role::material, {0.1 + 0.5 * s, 0.1, 0.1}, m, paste, {1.0, 0, 0})};
  State g, r;
  g.add_particles(model, ps);
  r.add_particles(model, ps);
  for (int k = 0; k < 2000 && r.bonds.counters.broken == 0; ++k) {
    step(model, g);
    step_all_pairs(model, r);
    compare(g, r, k);
    if (HasFatalFailure()) return;
  }
  EXPECT_EQ(r.bonds.counters.formed, 1u);
  EXPECT_EQ(r.bonds.counters.broken, 1u);
  EXPECT_EQ(g.bonds.counters.broken, 1u);
}

TEST(GridParity, OverfullNeighbourListsFallBackToTheGridSearch) {
  // Material packed at 0.45 spacings: about 360 neighbours within h, far over the list capacity
  // of the density pass, so the force pass searches the grid for these particles.
  // Bond lists large enough for every pair closer than A (about 80): a full list would make
  // which bonds form depend on the visiting order, which is all that differs between the paths.
  ModelParams mp = testing::params_for_spacing(s, {0, 0, 0}, {0.2, 0.2, 0.2}, 1e-5);
  mp.max_bonds_per_particle = 256;
  Model model = make_model(mp);
  const Material paste{0.1, 1, 1000, 100};
  const real m = lattice_particle_mass(1000, s, model.kernel);
  std::vector<ParticleInit> ps;
  for (Vec3 p : testing::lattice({0.05, 0.05, 0.05}, 0.45 * s, 12, 12, 12)) ps.push_back(testing::particle(Role::material, p, m, paste));
  State g, r;
  g.add_particles(model, ps);
  r.add_particles(model, ps);
  for (int k = 0; k < 10; ++k) {
    step(model, g);
    step_all_pairs(model, r);
    compare(g, r, k);
    if (HasFatalFailure()) return;
  }
  int overfull = 0;
  for (std::uint32_t i = 0; i < g.size(); ++i) overfull += g.grid.neighbour_count[i] > GridIndex::kNeighbourCapacity;
  EXPECT_GT(overfull, 100) << "the fallback path was taken";
  EXPECT_GT(g.bonds.counters.formed, 1000u);
  EXPECT_EQ(g.bonds.counters.overflowed, 0u);
}

}  // namespace
}  // namespace dentsph
