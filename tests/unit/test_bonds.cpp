// The bond store: fixed capacity per particle, counted overflow, removal; and bonds in a State.
#include <gtest/gtest.h>

#include "dentsph/bonds.hpp"
#include "dentsph/step.hpp"
#include "support/builders.hpp"

namespace dentsph {
namespace {

TEST(BondStore, AddHasRemove) {
  BondStore b;
  b.resize(4, 3);
  EXPECT_TRUE(b.try_add(0, 1));
  EXPECT_TRUE(b.try_add(1, 0));
  EXPECT_TRUE(b.try_add(0, 2));
  EXPECT_TRUE(b.has(0, 1));
  EXPECT_TRUE(b.has(0, 2));
  EXPECT_FALSE(b.has(0, 3));
  EXPECT_FALSE(b.has(2, 0));
  EXPECT_EQ(b.count(0), 2);
  b.remove_at(0, 0);
  EXPECT_FALSE(b.has(0, 1));
  EXPECT_TRUE(b.has(0, 2));
  EXPECT_EQ(b.count(0), 1);
}

TEST(BondStore, AFullListRefuses) {
  BondStore b;
  b.resize(5, 2);
  EXPECT_TRUE(b.try_add(0, 1));
  EXPECT_TRUE(b.try_add(0, 2));
  EXPECT_FALSE(b.try_add(0, 3));
  EXPECT_FALSE(b.try_add(0, 4));
  EXPECT_EQ(b.count(0), 2);
  EXPECT_FALSE(b.has(0, 3));
}

TEST(BondStore, GrowingKeepsExistingLists) {
  BondStore b;
  b.resize(2, 2);
  b.try_add(0, 1);
  b.try_add(1, 0);
  b.resize(3, 4);
  EXPECT_TRUE(b.has(0, 1));
  EXPECT_TRUE(b.has(1, 0));
  EXPECT_EQ(b.count(2), 0);
  EXPECT_TRUE(b.try_add(2, 0));
  EXPECT_EQ(b.capacity(), 4);
}

}  // namespace
}  // namespace dentsph

// Bonds in a State: a bond to a wall lives in the moving particle's list only, and is counted once.
namespace dentsph {
namespace {

TEST(StateBonds, WallBondsLiveOnTheMovingSideAndCountOnce) {
  constexpr real s = 0.01;
  Model model = make_model(testing::params_for_spacing(s, {-0.05, -0.05, -0.05}, {0.05, 0.05, 0.05}, 1e-5));
  const Material paste{0, 60, 1000, 300}, wall{0, 200, 1000, 0};
  const real m = lattice_particle_mass(1000, s, model.kernel);
  State st;
  st.add_particles(model, {testing::particle(Role::material, {0, 0, 0}, m, paste),
                           testing::particle(Role::material, {s, 0, 0}, m, paste),
                           testing::particle(Role::boundary, {0, 0, -s}, m, wall),
                           testing::particle(Role::boundary, {s, 0, -s}, m, wall)});
  step(model, st);
  // Material 0 bonds to material 1 (r = s < A) and to the wall particle below it; material 1
  // likewise; the wall particles bond to each other never and keep no lists.
  EXPECT_EQ(st.bonds.count(0), 2);
  EXPECT_EQ(st.bonds.count(1), 2);
  EXPECT_EQ(st.bonds.count(2), 0);
  EXPECT_EQ(st.bonds.count(3), 0);
  EXPECT_EQ(st.bonded_pairs(), 3u);
  EXPECT_EQ(st.bonds.counters.formed, 3u);
}

TEST(StateBonds, TheStepCountsOverflowAndKeepsListsWithinCapacity) {
  // A tight cluster with room for 2 bonds per particle: every particle has more partners closer
  // than A than its list holds; the refusals are counted, never silent.
  constexpr real s = 0.01;
  ModelParams mp = testing::params_for_spacing(s, {-0.05, -0.05, -0.05}, {0.05, 0.05, 0.05}, 1e-5);
  mp.max_bonds_per_particle = 2;
  Model model = make_model(mp);
  const Material paste{0, 60, 1000, 300};
  const real m = lattice_particle_mass(1000, s, model.kernel);
  std::vector<ParticleInit> ps;
  for (Vec3 p : testing::lattice({0, 0, 0}, s, 3, 3, 3)) ps.push_back(testing::particle(Role::material, p, m, paste));
  State st;
  st.add_particles(model, ps);
  step(model, st, StepOptions{2, nullptr});
  for (std::uint32_t id = 0; id < st.size(); ++id) EXPECT_LE(st.bonds.count(id), 2);
  EXPECT_GT(st.bonds.counters.overflowed, 27u) << "the centre alone has 6 face neighbours closer than A";
  const std::uint64_t after_one = st.bonds.counters.overflowed;
  step(model, st);
  EXPECT_GT(st.bonds.counters.overflowed, after_one) << "refused again while still closer than A";
}

}  // namespace
}  // namespace dentsph
