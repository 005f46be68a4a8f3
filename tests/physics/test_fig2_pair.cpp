// The paper's Fig. 2 as a two-particle test (docs/model.md, "Adhesion hysteresis"). A tool particle is
// pushed towards a material particle and pulled away again along x; the material particle is
// held at the origin (reset after every step), so the distance follows the script; the force on the tool shows the seven stages, and the loading
// and unloading force-distance curves differ (the area between them is positive).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "dentsph/step.hpp"
#include "physics/kernels.hpp"
#include "support/builders.hpp"

namespace dentsph {
namespace {

struct Sample {
  real r;       // distance during the step's force pass
  real fx;      // N, force on the tool along the separation axis (+: repulsion)
  int bonds;    // bonds of the tool particle
};

// On either solver: the iisph solver keeps the paper's bonds and adhesion on top of its pressure
// solve, so the same seven stages and the same hysteresis must hold.
class Fig2 : public ::testing::TestWithParam<Solver> {
 protected:
  static constexpr real s = 0.01;
  static Model model_of(Solver solver) {
    ModelParams p = testing::params_for_spacing(s, {-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1}, 1e-4);
    p.solver = solver;
    return make_model(p);
  }
  Model model = model_of(GetParam());
  // h = 2 s, A = 1.2 s, B = 3 s.
  real h = model.kernel.h, A = model.adhesion.A, B = model.adhesion.B;
  State st;

  void SetUp() override {
    const real m = 1e-3;
    // Rest density = the self contribution, so any neighbour inside h raises the pressure.
    const real rho0 = m * kernels::poly6(0, model.kernel);
    const Material tool{0, 50, rho0, 300};  // mu = 0: the loop comes from adhesion alone
    const Material paste{0, 50, rho0, 300};
    st.tool_pose.position = {1.2 * B, 0, 0};
    st.tool_pose_applied = st.tool_pose;
    st.add_particles(model, {testing::particle(Role::tool, {0, 0, 0}, m, tool),
                             testing::particle(Role::material, {0, 0, 0}, m, paste)});
  }

  // Moves the tool to x = r over `n` steps, recording each step.
  void move_to(real r, int n, std::vector<Sample>& out) {
    const real r0 = st.tool_pose.position.x;
    for (int k = 1; k <= n; ++k) {
      const real before = st.tool_pose_applied.position.x;  // distance used in this force pass
      st.tool_pose.position.x = r0 + (r - r0) * k / n;
      step(model, st);
      const std::uint32_t held = st.index_of_id[1];  // the material particle stays put
      st.pos[held] = {};
      st.vel[held] = {};
      out.push_back({before, st.tool_wrench.force.x, st.bonds.count(st.id[st.index_of_id[0]])});
    }
  }
};

TEST_P(Fig2, SevenStagesAndHysteresis) {
  std::vector<Sample> load, unload;
  move_to(0.7 * A, 400, load);   // stages 1-4: approach to well inside A
  move_to(0.5 * (A + h), 100, unload);  // stage 5: relax into [A, h]
  move_to(1.1 * B, 600, unload);  // stages 6-7: separate past B
  ASSERT_EQ(st.bonds.counters.formed, 1u);
  ASSERT_EQ(st.bonds.counters.broken, 1u);

  for (const Sample& x : load) {
    if (x.r > h) {  // 1. apart: nothing
      EXPECT_EQ(x.fx, 0) << "r=" << x.r;
      EXPECT_EQ(x.bonds, 0);
    } else if (x.r >= A) {  // 2. contact, not bonded: pressure only, repulsive
      EXPECT_EQ(x.bonds, 0) << "r=" << x.r;
      if (x.r < h) {
        EXPECT_GT(x.fx, 0) << "r=" << x.r;
      }
    } else {  // 3-4. below A: bonded, pressure dominates
      EXPECT_EQ(x.bonds, 1) << "r=" << x.r;
      EXPECT_GT(x.fx, 0);
    }
  }
  // Force grows as the particles close in (4).
  EXPECT_GT(load.back().fx, load[load.size() / 2].fx);

  real peak_attraction = 0, r_at_peak = 0;
  for (const Sample& x : unload) {
    if (x.r <= B) {
      EXPECT_EQ(x.bonds, 1) << "bond held up to B, r=" << x.r;
    }
    if (x.r > B) {
      EXPECT_EQ(x.bonds, 0) << "bond broken past B, r=" << x.r;
      EXPECT_EQ(x.fx, 0);
    }
    if (x.r > h && x.r <= B) {  // 6-7. adhesion alone: attraction
      EXPECT_LE(x.fx, 0) << "r=" << x.r;
      if (x.fx < peak_attraction) {
        peak_attraction = x.fx;
        r_at_peak = x.r;
      }
    }
  }
  // 6 then 7: attraction grows to a peak strictly inside (h, B), then decays to zero at B.
  EXPECT_LT(peak_attraction, 0);
  EXPECT_GT(r_at_peak, h);
  EXPECT_LT(r_at_peak, B);
  const Sample& near_B = *std::min_element(unload.begin(), unload.end(), [&](const Sample& a, const Sample& b) {
    return std::abs(a.r - B) < std::abs(b.r - B);
  });
  EXPECT_LT(std::abs(near_B.fx), 0.05 * std::abs(peak_attraction));

  // 5. In [A, h], bonded: pressure plus adhesion, less repulsive than the unbonded approach at the
  // same distance, and the blend is continuous (no jump larger than a step's change in pressure).
  bool saw_blend = false;
  for (const Sample& u : unload) {
    if (u.r < A + 0.3 * (h - A) || u.r > h || u.bonds != 1) continue;
    for (const Sample& l : load)
      if (std::abs(l.r - u.r) < 5e-3 * s && l.bonds == 0) {
        EXPECT_LT(u.fx, l.fx) << "r=" << u.r;
        saw_blend = true;
      }
  }
  EXPECT_TRUE(saw_blend);

  // Hysteresis: the area between loading and unloading curves over the common range [A, B] is
  // positive (work done on the way in exceeds the work returned on the way out).
  auto work = [&](const std::vector<Sample>& c, real lo, real hi) {
    real w = 0;
    for (std::size_t k = 1; k < c.size(); ++k) {
      const real a = std::clamp(c[k - 1].r, lo, hi), b = std::clamp(c[k].r, lo, hi);
      w += 0.5 * (c[k - 1].fx + c[k].fx) * std::abs(b - a);
    }
    return w;
  };
  const real w_load = work(load, A, B);
  const real w_unload = work(unload, A, B);
  EXPECT_GT(w_load - w_unload, 0.1 * std::abs(w_load)) << "load " << w_load << " unload " << w_unload;
}

INSTANTIATE_TEST_SUITE_P(Solvers, Fig2, ::testing::Values(Solver::paper, Solver::iisph),
                         [](const ::testing::TestParamInfo<Solver>& info) { return std::string(solver_name(info.param)); });

}  // namespace
}  // namespace dentsph
