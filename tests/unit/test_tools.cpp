// Instruments, increments of material, and removing particles between steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "dentsph/step.hpp"
#include "dentsph/tools.hpp"
#include "support/builders.hpp"

namespace dentsph {
namespace {

constexpr real s = 0.3e-3;  // m

TEST(Tools, BallBurnisherIsThePapersFortyTwoParticlesOnASphere) {
  const ToolShape t = tool_by_name("ball_burnisher", s, Solver::paper);
  EXPECT_EQ(t.points.size(), 42u);
  const real R = 0.5 * 3.65 * s;
  real min_z = 1, min_gap = 1, max_gap = 0;
  for (const Vec3& p : t.points) {
    EXPECT_NEAR(norm(p - Vec3{0, 0, R}), R, 1e-12);
    min_z = std::min(min_z, p.z);
    real nearest = 1;
    for (const Vec3& q : t.points)
      if (&q != &p) nearest = std::min(nearest, norm(q - p));
    min_gap = std::min(min_gap, nearest);
    max_gap = std::max(max_gap, nearest);
  }
  EXPECT_GE(min_z, 0) << "the tip is the tool origin";
  EXPECT_LT(min_z, 0.05 * s);
  EXPECT_GT(min_gap, 0.6 * s) << "evenly spread";
  EXPECT_LT(max_gap, 1.3 * s);
}

// The iisph solver's walls need two layers: its ball is the paper's shell, a shell a spacing
// inside it and a particle at the centre; the plugger and the condenser are solid for both.
TEST(Tools, TheIisphSolversBallBurnisherHasTwoLayers) {
  const ToolShape paper = tool_by_name("ball_burnisher", s, Solver::paper);
  const ToolShape t = tool_by_name("ball_burnisher", s, Solver::iisph);
  ASSERT_EQ(t.points.size(), 52u);
  const real R = 0.5 * 3.65 * s;
  const Vec3 centre{0, 0, R};
  int outer = 0, inner = 0, middle = 0;
  for (std::size_t k = 0; k < t.points.size(); ++k) {
    const real r = norm(t.points[k] - centre);
    if (k < paper.points.size()) {
      EXPECT_EQ(t.points[k], paper.points[k]) << "the outer shell is the paper's ball";
    }
    outer += std::abs(r - R) < 1e-12;
    inner += std::abs(r - (R - s)) < 1e-12;
    middle += r < 1e-12;
  }
  EXPECT_EQ(outer, 42);
  EXPECT_EQ(inner, 9) << "one particle per spacing^2 of the inner sphere";
  EXPECT_EQ(middle, 1);
  EXPECT_EQ(instrument_layers(Solver::iisph), 2);
  EXPECT_EQ(instrument_layers(Solver::paper), 1);
  for (const char* name : {"flat_plugger", "condenser"}) {
    EXPECT_EQ(tool_by_name(name, s, Solver::iisph).points, tool_by_name(name, s, Solver::paper).points) << name;
  }
}

TEST(Tools, PluggerIsASolidCylinderAndTheCondenserFaceIsSerrated) {
  const ToolShape p = flat_plugger(5 * s, 3 * s, s), c = condenser(5 * s, 3 * s, s);
  ASSERT_EQ(p.points.size(), c.points.size());
  int face = 0, set_back = 0;
  for (std::size_t k = 0; k < p.points.size(); ++k) {
    EXPECT_LE(std::hypot(p.points[k].x, p.points[k].y), 2.5 * s + 1e-12);
    EXPECT_GE(p.points[k].z, 0);
    EXPECT_LE(p.points[k].z, 3 * s + 1e-12);
    face += p.points[k].z == 0;
    set_back += std::abs(c.points[k].z - s / 3) < 1e-12;
  }
  EXPECT_EQ(face, 21) << "lattice points in a disc of radius 2.5 spacings";
  EXPECT_GT(set_back, 5);
  EXPECT_LT(set_back, face);
  EXPECT_EQ(p.points.size(), 4u * 21u);
}

TEST(Tools, UnknownToolNamesTheKnownOnes) {
  try {
    tool_by_name("spatula", s, Solver::paper);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("ball_burnisher, flat_plugger, condenser"), std::string::npos);
  }
}

TEST(Tools, IncrementHasItsVolume) {
  const real volume = 8e-9;  // 8 mm^3
  const auto ps = material_increment({1e-3, 2e-3, 3e-3}, volume, s, 1e-7, Material{1, 10, 2000, 50});
  EXPECT_NEAR(real(ps.size()) * s * s * s, volume, 0.1 * volume);
  Vec3 c;
  for (const ParticleInit& p : ps) {
    c += p.pos;
    EXPECT_EQ(p.role, Role::material);
  }
  c = c / real(ps.size());
  EXPECT_LT(norm(c - Vec3{1e-3, 2e-3, 3e-3}), 1e-9);
}

// A small scene with bonds formed, for the removal tests.
struct Small {
  Model model = make_model(testing::params_for_spacing(0.01, {-0.05, -0.05, -0.05}, {0.1, 0.1, 0.1}, 2e-4, {0, 0, -9.81}));
  State st;
  Small() {
    const Material paste{0.5, 60, 1000, 300}, wall{0.5, 200, 1000, 0};
    const real m = lattice_particle_mass(1000, 0.01, model.kernel);
    std::vector<ParticleInit> ps;
    for (Vec3 p : testing::lattice({0, 0, 0.01}, 0.01, 4, 4, 3)) ps.push_back(testing::particle(Role::material, p, m, paste));
    for (Vec3 p : testing::lattice({-0.01, -0.01, 0}, 0.01, 6, 6, 1)) ps.push_back(testing::particle(Role::boundary, p, m, wall));
    for (Vec3 p : testing::lattice({0, 0, 0}, 0.01, 2, 2, 1)) ps.push_back(testing::particle(Role::tool, p, m, wall));
    st.tool_pose.position = {0.01, 0.01, 0.06};
    st.tool_pose_applied = st.tool_pose;
    st.add_particles(model, ps);
    for (int k = 0; k < 20; ++k) step(model, st);
  }
};

TEST(RemoveParticles, KeepsIdsDenseAndBondsBetweenKeptParticles) {
  Small sm;
  State& st = sm.st;
  // Remember each kept particle's bonded partners by position (positions identify them).
  std::vector<std::uint8_t> remove(st.size(), 0);
  for (std::uint32_t i = 0; i < st.size(); ++i) remove[i] = st.role[i] == Role::material && st.id[i] % 3 == 0;
  std::map<std::pair<real, real>, std::vector<Vec3>> partners;  // (x, z) -> partner positions kept
  auto key = [&](std::uint32_t i) { return std::make_pair(st.pos[i].x + 7 * st.pos[i].y, st.pos[i].z); };
  std::uint64_t bonds_before = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    bonds_before += st.bonds.count(st.id[i]);
    if (remove[i]) continue;
    for (int b = 0; b < st.bonds.count(st.id[i]); ++b) {
      const std::uint32_t j = st.index_of_id[st.bonds.partner(st.id[i], b)];
      if (!remove[j]) partners[key(i)].push_back(st.pos[j]);
    }
  }
  ASSERT_GT(bonds_before, 20u);
  const std::uint32_t n_before = st.size(), removed = std::uint32_t(std::count(remove.begin(), remove.end(), 1));
  st.remove_particles(sm.model, remove);
  ASSERT_EQ(st.size(), n_before - removed);
  std::vector<int> seen(st.size(), 0);
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    ASSERT_LT(st.id[i], st.size());
    ++seen[st.id[i]];
    EXPECT_EQ(st.index_of_id[st.id[i]], i);
    std::vector<Vec3> now;
    for (int b = 0; b < st.bonds.count(st.id[i]); ++b) {
      const std::uint32_t other = st.bonds.partner(st.id[i], b);
      ASSERT_LT(other, st.size());
      now.push_back(st.pos[st.index_of_id[other]]);
    }
    EXPECT_EQ(now.size(), partners[key(i)].size());
  }
  for (int c : seen) EXPECT_EQ(c, 1) << "every id once";
}

TEST(RemoveParticles, GridStepStillMatchesAllPairsAfterwards) {
  Small sm;
  std::vector<std::uint8_t> remove(sm.st.size(), 0);
  for (std::uint32_t i = 0; i < sm.st.size(); i += 4) remove[i] = 1;
  sm.st.remove_particles(sm.model, remove);
  State g = sm.st, r = sm.st;
  for (int k = 0; k < 30; ++k) {
    step(sm.model, g);
    step_all_pairs(sm.model, r);
  }
  for (std::uint32_t id = 0; id < g.size(); ++id) {
    const Vec3 a = g.pos[g.index_of_id[id]], b = r.pos[r.index_of_id[id]];
    EXPECT_LT(norm(a - b), 1e-9) << "id " << id;
  }
}

TEST(SwitchTool, ReplacesTheToolParticlesAtThePose) {
  Small sm;
  const std::uint32_t material = sm.st.count(Role::material), boundary = sm.st.count(Role::boundary);
  const ToolShape plugger = flat_plugger(0.03, 0.02, 0.01);
  const Material steel{0, 200, 1000, 0};
  EXPECT_THROW(switch_tool(sm.st, sm.model, plugger, 1e-3, steel), std::invalid_argument);  // not in the table
  EXPECT_EQ(sm.st.count(Role::tool), 4u);  // refused: the old tool stays
  const MaterialIndex index = sm.model.materials.add("plugger", steel);
  switch_tool(sm.st, sm.model, plugger, 1e-3, steel, index);
  EXPECT_EQ(sm.st.count(Role::tool), plugger.points.size());
  EXPECT_EQ(sm.st.count(Role::material), material);
  EXPECT_EQ(sm.st.count(Role::boundary), boundary);
  for (std::uint32_t i = 0; i < sm.st.size(); ++i) {
    if (sm.st.role[i] == Role::tool) {
      EXPECT_GE(sm.st.pos[i].z, sm.st.tool_pose.position.z - 1e-12);
    }
  }
  for (int k = 0; k < 10; ++k) step(sm.model, sm.st);
  EXPECT_EQ(sm.st.diagnostics.non_finite, 0u);
}

}  // namespace
}  // namespace dentsph
