// The cure state in the State (kept by id through steps and removals) and the gel transition
// (src/cure/transition.cpp): a set particle becomes wall, its bonds as the step expects them.
#include <gtest/gtest.h>

#include <cmath>

#include "dentsph/assess.hpp"
#include "dentsph/cure.hpp"
#include "dentsph/dental.hpp"
#include "dentsph/dispense.hpp"
#include "dentsph/step.hpp"
#include "dentsph/tools.hpp"
#include "support/cure_scenes.hpp"

namespace dentsph::testing {
namespace {

constexpr real mm = 1e-3;

// Paste in an open box, settled for a few steps, with a ball tool resting in it.
struct Box {
  real s = 0.3 * mm;
  Model model = cure_model(s, {-2 * mm, -2 * mm, -2 * mm}, {4 * mm, 4 * mm, 4 * mm});
  State st;
  Box() {
    const real m = lattice_particle_mass(kWall.rho0, s, model.kernel);
    std::vector<ParticleInit> walls;
    for (const Vec3& p : open_container({0, 0, 0}, s, 6, 6, 6, 2)) walls.push_back(make_particle(Role::boundary, p, m, kWall));
    st.add_particles(model, walls);
    add_paste_layers(model, st, s, 6, 6, 0.5 * s, 4);
    st.tool_pose = st.tool_pose_applied = Pose{{0.9 * mm, 0.9 * mm, 1.0 * mm}, {}};
    st.add_particles(model, tool_particles(ball_burnisher(3.65 * s, s), m, kWall));
    for (int k = 0; k < 20; ++k) step(model, st);
  }
};

TEST(CureState, KeptByIdThroughStepsAndRemovals) {
  Box b;
  State& st = b.st;
  // Mark every particle's cure state with its id, then step (reordering) and switch the tool
  // (removing and renumbering particles).
  for (std::uint32_t id = 0; id < st.size(); ++id) st.cure.dose[id] = real(id);
  std::vector<Vec3> where(st.size());
  for (std::uint32_t i = 0; i < st.size(); ++i) where[st.id[i]] = st.pos[i];
  for (int k = 0; k < 5; ++k) step(b.model, st);
  for (std::uint32_t i = 0; i < st.size(); ++i) EXPECT_EQ(st.cure.dose[st.id[i]], real(st.id[i]));
  // Renumbering: a kept particle's dose still says its old id, whose position it had.
  std::vector<Vec3> before(st.size());
  for (std::uint32_t i = 0; i < st.size(); ++i) before[st.id[i]] = st.pos[i];
  switch_tool(st, b.model, flat_plugger(5 * b.s, 3 * b.s, b.s), st.mass[0], kWall);
  EXPECT_EQ(st.cure.particles(), st.size());
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    if (st.role[i] == Role::tool) {
      EXPECT_EQ(st.cure.curable[st.id[i]], 0);
      continue;
    }
    const auto old = std::uint32_t(st.cure.dose[st.id[i]]);
    EXPECT_EQ(norm(before[old] - st.pos[i]), 0) << "id " << st.id[i] << " was " << old;
  }
}

TEST(CureTransition, SetPasteBecomesWallAndKeepsItsBondsToMovingPaste) {
  Box b;
  State& st = b.st;
  const CureModel cm = make_cure_model(b.model, cure_material_preset("composite"), b.s, kPaste);
  // Set the paste particle bonded to the tool with the most bonds, by hand.
  std::uint32_t pick = ~0u;
  int most = -1;
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    if (st.role[i] != Role::material) continue;
    bool to_tool = false;
    for (int k = 0; k < st.bonds.count(st.id[i]); ++k)
      to_tool |= st.role[st.index_of_id[st.bonds.partner(st.id[i], k)]] == Role::tool;
    if (to_tool && st.bonds.count(st.id[i]) > most) most = st.bonds.count(st.id[i]), pick = i;
  }
  ASSERT_NE(pick, ~0u) << "the resting ball bonds to the paste";
  const std::uint32_t id = st.id[pick];
  std::vector<std::uint32_t> moving_partners, tool_partners;
  for (int k = 0; k < st.bonds.count(id); ++k) {
    const std::uint32_t other = st.bonds.partner(id, k);
    (st.role[st.index_of_id[other]] == Role::tool ? tool_partners : moving_partners).push_back(other);
  }
  ASSERT_FALSE(moving_partners.empty());
  st.cure.alpha[id] = cm.paste.alpha_gel;
  const Vec3 at = st.pos[pick];
  const CureUpdate up = apply_cure_transition(cm, st);
  EXPECT_EQ(up.set, 1u);
  EXPECT_EQ(st.role[pick], Role::boundary);
  EXPECT_EQ(norm(st.vel[pick]), 0);
  EXPECT_EQ(st.cure.rigid[id], 1);
  EXPECT_EQ(st.bonds.count(id), 0) << "walls keep no list";
  for (std::uint32_t other : moving_partners) EXPECT_TRUE(st.bonds.has(other, id)) << "moving paste keeps its bond";
  for (std::uint32_t other : tool_partners) EXPECT_FALSE(st.bonds.has(other, id)) << "the instrument never bonds to wall";
  EXPECT_FALSE(st.rho_static_valid);
  EXPECT_FALSE(st.grid.lists_valid);
  // The step takes it as wall: it stays put and has a static density.
  for (int k = 0; k < 20; ++k) step(b.model, st);
  const std::uint32_t now = st.index_of_id[id];
  EXPECT_EQ(norm(st.pos[now] - at), 0);
  EXPECT_GT(st.rho_static[id], 0);
  for (std::uint32_t other : moving_partners)
    if (st.bonds.has(other, id)) {
      EXPECT_LE(norm(st.pos[st.index_of_id[other]] - at), b.model.adhesion.B);
    }
}

TEST(CureTransition, NoLightNoWork) {
  Box b;
  State& st = b.st;
  const CureModel cm = make_cure_model(b.model, cure_material_preset("composite"), b.s, kPaste);
  const std::vector<real> mu = st.mu;
  CureUpdate up = cure_between_steps(cm, st, std::nullopt, b.model.dt);
  EXPECT_FALSE(up.changed());
  CuringLight off = light_above({0.9 * mm, 0.9 * mm, 3 * mm});
  off.on = false;
  up = cure_between_steps(cm, st, off, b.model.dt);
  EXPECT_FALSE(up.changed());
  EXPECT_EQ(up.lit, 0u);
  EXPECT_EQ(st.mu, mu);
  for (std::uint32_t id = 0; id < st.size(); ++id) EXPECT_EQ(st.cure.alpha[id], 0);
}

// Paste that has set is a boundary particle for the step, but still filling for the assessment
// and the pictures (State::is_paste).
TEST(CureTransition, SetPasteIsStillFillingForTheAssessment) {
  const Scene sc = default_dental_scene();
  State st = make_state(sc);
  const CavityAssessor assessor(*sc.tooth);
  const Assessment before = assessor.assess(st, sc.model);
  const CureModel cm = make_cure_model(sc.model, cure_material_preset("composite"), sc.material_spacing, scene_paste(sc).material);
  std::uint32_t paste = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i)
    if (st.role[i] == Role::material) st.cure.alpha[st.id[i]] = cm.paste.alpha_gel, ++paste;
  EXPECT_EQ(apply_cure_transition(cm, st).set, paste);
  EXPECT_EQ(st.count(Role::material), 0u);
  for (std::uint32_t i = 0; i < st.size(); ++i) EXPECT_EQ(st.is_paste(i), st.cure.curable[st.id[i]] == 1);
  const Assessment after = assessor.assess(st, sc.model);
  EXPECT_EQ(after.material_particles, before.material_particles);
  EXPECT_EQ(after.fill_fraction, before.fill_fraction);
}

// Removing particles renumbers ids: a light on at the time keeps adding dose to the right
// particles (the next call lists the lit paste anew).
TEST(CureState, ALitCureSurvivesAToolSwitch) {
  Box b;
  State& st = b.st;
  const CureModel cm = make_cure_model(b.model, cure_material_preset("composite"), b.s, kPaste);
  const CuringLight light = light_above({0.9 * mm, 0.9 * mm, 4 * mm});
  st.time += b.model.dt;
  cure_between_steps(cm, st, light, b.model.dt);
  switch_tool(st, b.model, flat_plugger(5 * b.s, 3 * b.s, b.s), st.mass[0], kWall);  // ids renumbered
  st.time += b.model.dt;
  const CureUpdate up = cure_between_steps(cm, st, light, b.model.dt);
  EXPECT_GT(up.lit, 0u);
  for (std::uint32_t id : st.cure.lit_ids) EXPECT_EQ(st.cure.curable[id], 1) << id;
  for (std::uint32_t id = 0; id < st.size(); ++id) {
    if (!st.cure.curable[id]) {
      EXPECT_EQ(st.cure.dose[id], 0) << "no dose on the instrument or the walls";
    }
  }
}

}  // namespace
}  // namespace dentsph::testing
