// The wall field (dentsph/wall_field.hpp): a sampled signed distance that keeps the iisph solver's
// paste out of the tooth at large steps. It interpolates a plane exactly, moves a particle inside
// or too close out to the clearance and takes away only its velocity into the wall; the dental
// scenes run by the iisph solver carry the prepared tooth's, and it stops a particle thrown at the
// cavity floor that passes through the lining without it. (The filling tests, test_filling, show
// it at work: nothing leaks at the iisph solver's dental step.)
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "dentsph/dental.hpp"
#include "dentsph/run.hpp"
#include "dentsph/step.hpp"
#include "dentsph/wall_field.hpp"

namespace dentsph {
namespace {

// A floor at z = 1 mm (the wall below it), sampled over a 4 mm box in cells of 0.15 mm.
WallField floor_field(real clearance = 0.075e-3) {
  return WallField([](const Vec3& p) { return p.z - 1e-3; }, Vec3{0, 0, 0}, Vec3{4e-3, 4e-3, 4e-3}, 0.15e-3,
                   clearance);
}

// Sampled coarse to fine, the field holds the exact distance at every corner within the clearance
// of the wall (of a sphere of 2 mm here), and beyond it the right side and more than the clearance,
// so that projections act exactly as over a field sampled everywhere; the distance is called for a
// share of the corners only.
TEST(WallField, CoarseToFineIsExactNearTheWalls) {
  const real radius = 2e-3, cell = 0.15e-3, clearance = 0.075e-3;
  std::atomic<std::int64_t> calls{0};
  const auto sphere = [&](const Vec3& p) {
    ++calls;
    return norm(p) - radius;
  };
  const Vec3 lo{-4e-3, -4e-3, -4e-3}, hi{4.1e-3, 4.1e-3, 4.1e-3};  // a last block shorter than the others
  const WallField f(sphere, lo, hi, cell, clearance);
  const int n = int(std::ceil((hi.x - lo.x) / cell)) + 1;
  ASSERT_EQ(f.nodes(), std::int64_t(n) * n * n);
  EXPECT_LT(calls.load(), f.nodes() / 2) << "most corners interpolated";
  int exact = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Vec3 p = lo + Vec3{i * cell, j * cell, k * cell};
        const real truth = norm(p) - radius;
        real d;
        Vec3 g;
        ASSERT_TRUE(f.sample(p, d, g));
        if (std::abs(truth) <= clearance) {
          ASSERT_NEAR(d, truth, 1e-9) << i << " " << j << " " << k;
          ++exact;
        } else {
          ASSERT_EQ(d > 0, truth > 0) << i << " " << j << " " << k;
          ASSERT_GT(std::abs(d), clearance) << i << " " << j << " " << k;
        }
      }
  EXPECT_GT(exact, 1000);  // the shell within the clearance
}

TEST(WallField, InterpolatesAPlaneExactly) {
  const WallField f = floor_field();
  EXPECT_EQ(f.nodes(), 28 * 28 * 28);  // ceil(4 / 0.15) + 1 corners a side
  std::mt19937 rng(3);
  std::uniform_real_distribution<real> u(0, 4e-3);
  for (int k = 0; k < 1000; ++k) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    real d;
    Vec3 g;
    ASSERT_TRUE(f.sample(p, d, g));
    EXPECT_NEAR(d, p.z - 1e-3, 1e-9);
    EXPECT_NEAR(g.x, 0, 1e-4);
    EXPECT_NEAR(g.y, 0, 1e-4);
    EXPECT_NEAR(g.z, 1, 1e-4);
  }
  real d;
  Vec3 g;
  EXPECT_FALSE(f.sample({5e-3, 1e-3, 1e-3}, d, g)) << "outside the box: no wall";
  EXPECT_FALSE(f.sample({std::nan(""), 1e-3, 1e-3}, d, g));
}

TEST(WallField, MovesOutToTheClearanceAndStopsOnlyTheMotionIntoTheWall) {
  const WallField f = floor_field(0.075e-3);
  Vec3 pos{2e-3, 2e-3, 0.9e-3}, vel{1, 2, -3};
  ASSERT_TRUE(f.project(pos, vel));
  EXPECT_NEAR(pos.x, 2e-3, 1e-12);
  EXPECT_NEAR(pos.y, 2e-3, 1e-12);
  EXPECT_NEAR(pos.z, 1.075e-3, 1e-9);
  EXPECT_EQ(vel, (Vec3{1, 2, 0}));
  // Inside but already leaving: moved out, its velocity kept.
  pos = {2e-3, 2e-3, 1.05e-3};
  vel = {0, 0, 3};
  ASSERT_TRUE(f.project(pos, vel));
  EXPECT_NEAR(pos.z, 1.075e-3, 1e-9);
  EXPECT_EQ(vel, (Vec3{0, 0, 3}));
  // Beyond the clearance, outside the box, or not a number: untouched.
  for (const Vec3 start : {Vec3{2e-3, 2e-3, 1.08e-3}, Vec3{5e-3, 2e-3, 0.5e-3}, Vec3{2e-3, std::nan(""), 0.5e-3}}) {
    pos = start;
    vel = {0, 0, -1};
    EXPECT_FALSE(f.project(pos, vel));
    EXPECT_EQ(vel, (Vec3{0, 0, -1}));
  }
}

TEST(WallField, RefusesAnEmptyBoxABadCellOrTooManyCorners) {
  const auto plane = [](const Vec3& p) { return p.z; };
  EXPECT_THROW(WallField(plane, {0, 0, 0}, {0, 1, 1}, 0.1, 0), std::invalid_argument);
  EXPECT_THROW(WallField(plane, {0, 0, 0}, {1, 1, 1}, 0, 0), std::invalid_argument);
  EXPECT_THROW(WallField(plane, {0, 0, 0}, {1, 1, 1}, std::nan(""), 0), std::invalid_argument);
  EXPECT_THROW(WallField(plane, {0, 0, 0}, {1, 1, 1}, 0.1, -1), std::invalid_argument);
  EXPECT_THROW(WallField(plane, {0, 0, 0}, {1, 1, 1}, 1e-3, 0, 1'000'000), std::invalid_argument);
}

// The paste particle nearest the cavity floor's centre, thrown at the floor at `speed`, one step.
real thrown_at_the_floor(const Scene& sc, real speed, std::uint64_t* projections) {
  State st = make_state(sc);
  const PreparedTooth& tooth = *sc.tooth;
  const Vec3 down = -tooth.frame().z;
  std::uint32_t pick = 0;
  real lowest = std::numeric_limits<real>::infinity();
  for (std::uint32_t i = 0; i < st.size(); ++i)
    if (st.role[i] == Role::material) {
      const real d = tooth.distance(st.pos[i]).distance;
      const real off_axis = norm(cross(st.pos[i] - tooth.frame().origin, down));
      if (d + off_axis < lowest) lowest = d + off_axis, pick = st.id[i];
    }
  for (std::uint32_t i = 0; i < st.size(); ++i)
    if (st.id[i] == pick) st.vel[i] = down * speed;
  st.tool_pose = sc.tool.at(sc.model.dt);
  step(sc.model, st, StepOptions{1, nullptr});
  if (projections) *projections = st.diagnostics.wall_projections;
  for (std::uint32_t i = 0; i < st.size(); ++i)
    if (st.id[i] == pick) return tooth.distance(st.pos[i]).distance;
  return std::numeric_limits<real>::quiet_NaN();
}

TEST(WallField, TheIisphDentalScenesKeepAParticleThrownAtTheFloorOutOfTheTooth) {
  DentalSceneParams dp;
  dp.solver = Solver::iisph;
  Scene sc = default_dental_scene(dp);
  ASSERT_TRUE(sc.model.walls) << "the iisph dental scene carries the tooth's wall field";
  const real s = sc.material_spacing;
  EXPECT_NEAR(sc.model.walls->clearance(), 0.25 * s, 1e-12);
  // The pressure solve alone stops a particle thrown at the floor at 20 m/s within half a spacing
  // of it (measured: 0.05 mm in); at 50 m/s it passes through the lining into the tooth.
  const real kSpeed = 50;
  std::uint64_t projections = 0;
  const real with = thrown_at_the_floor(sc, kSpeed, &projections);
  EXPECT_GE(with, 0.2 * s) << "kept out, about a quarter spacing from the floor";
  EXPECT_GE(projections, 1u);
  Scene bare = sc;
  bare.model.walls.reset();
  EXPECT_LT(thrown_at_the_floor(bare, kSpeed, nullptr), -0.5 * s) << "without the field it passes into the tooth";
  // The paper's step never reads one, and choosing it drops it.
  select_solver(sc, Solver::paper);
  EXPECT_FALSE(sc.model.walls);
  select_solver(sc, Solver::iisph);
  EXPECT_TRUE(sc.model.walls);
}

}  // namespace
}  // namespace dentsph
