// Parity checks of a GPU backend's Stepper (the CUDA backend, or its host emulation) against the CPU
// reference: the all-pairs step and the grid step. Shared by tests/parity/test_gpu_emulation.cpp,
// which runs everywhere, and tests/cuda/test_cuda_parity.cpp, which needs a device.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <ostream>
#include <memory>
#include <random>

#include "dentsph/backend.hpp"
#include "physics/kernels.hpp"
#include "support/builders.hpp"
#include "support/state_parity.hpp"

namespace dentsph::testing {

using GpuFactory = std::function<std::unique_ptr<Stepper>(const Model&, const State&)>;

constexpr real kGpuSpacing = 0.01;  // m

// A jittered block of moving paste over a wall floor, with a 27-particle tool above it pressing
// down: bonds form between paste, wall and tool, and some break again.
struct GpuScene {
  int side = 5;          // material block of side^3
  real jitter = 0.2;     // fraction of the spacing
  int reach = 1;         // grid cells of h / reach
  bool far_cluster = false;  // a few particles 1 km away (wrapped cells)
  unsigned seed = 1;
};

inline void PrintTo(const GpuScene& c, std::ostream* os) {
  *os << "side " << c.side << ", jitter " << c.jitter << ", reach " << c.reach << (c.far_cluster ? ", far cluster" : "")
      << ", seed " << c.seed;
}

inline Model gpu_scene_model(const GpuScene& c, int bond_capacity = 64) {
  const real s = kGpuSpacing, ext = (c.side + 6) * s;
  ModelParams mp = params_for_spacing(s, {0, 0, 0}, {ext, ext, ext}, 2e-4, {0, 0, -9.81});
  mp.grid_reach = c.reach;
  mp.max_bonds_per_particle = bond_capacity;
  return make_model(mp);
}

inline State gpu_scene_state(Model& model, const GpuScene& c) {
  const real s = kGpuSpacing;
  std::mt19937_64 rng(c.seed);
  std::uniform_real_distribution<real> u(-1, 1);
  const Material paste{0.4, 60, 1000, 300}, wall{0.4, 200, 1000, 0};
  const real m = lattice_particle_mass(1000, s, model.kernel);
  std::vector<ParticleInit> ps;
  const Vec3 lo{0.0021, 0.0037, 0.0013};
  for (Vec3 p : lattice(lo + Vec3{2 * s, 2 * s, 2 * s}, s, c.side, c.side, c.side)) {
    p += Vec3{u(rng), u(rng), u(rng)} * (c.jitter * s);
    ps.push_back(particle(Role::material, p, m, paste, Vec3{u(rng), u(rng), u(rng)} * 0.05));
  }
  for (Vec3 p : lattice(lo, s, c.side + 4, c.side + 4, 2)) ps.push_back(particle(Role::boundary, p, m, wall));
  if (c.far_cluster)
    for (Vec3 p : lattice({1000.0, -2000.0, 3000.0}, s, 3, 3, 3)) ps.push_back(particle(Role::material, p, m, paste));
  for (Vec3 p : lattice({-s, -s, -s}, s, 3, 3, 3)) ps.push_back(particle(Role::tool, p, m, wall));
  State st;
  const real mid = (c.side / 2.0 + 2) * s;
  st.tool_pose.position = lo + Vec3{mid, mid, (c.side + 3.5) * s};
  st.tool_pose.orientation = Quat::from_axis_angle({0, 0, 1}, 0.3);
  st.tool_pose_applied = st.tool_pose;
  st.add_particles(model, ps);
  return st;
}

// The tool's pose at step k: down, sideways now and then, turning.
inline Pose gpu_scene_pose(const Pose& start, int k) {
  const real s = kGpuSpacing;
  Pose p = start;
  p.position += Vec3{0.02 * s * ((k + 1) / 7), 0, -0.03 * s * (k + 1)};
  p.orientation = Quat::from_axis_angle({0, 0, 1}, 0.3 + 0.01 * (k + 1));
  return p;
}

// One step of the reference `ref` (the CPU grid step) and of `g` through `stepper`, the tool to `pose`.
inline void step_both(const Model& model, State& ref, Stepper& stepper, State& g, const Pose& pose) {
  ref.tool_pose = pose;
  step(model, ref);
  stepper.step(g, pose);
}

// g (from the GPU) against r (the reference) by stable id, within `tol` relative (floors from
// each field's largest value: a tenth of it), the same bonds, the same wrench and counters.
inline void compare_states(const State& g, const State& r, int step, real tol) {
  StateTolerance t;
  t.rel = tol;
  t.share = 0.1;
  t.pressure_floor = 1.0;
  t.motion_floor = 1e-9;
  t.position_floor = 0.01;
  t.tool_force_floor = 1e-6;
  t.tool_torque_floor = 1e-8;
  compare_states(g, r, step, t);
}

// 100 steps of `scene` on the GPU stepper and on the reference (all-pairs or grid step), compared
// after every step (`check_every`: sync the particles to the host and compare every that many
// steps). The tool pose goes in, the wrench comes out each step; the particles come down only for
// the comparison.
inline void gpu_parity_run(const GpuFactory& make, const GpuScene& scene, bool all_pairs, real tol,
                           int check_every = 1, int steps = 100) {
  Model model = gpu_scene_model(scene);
  State ref = gpu_scene_state(model, scene), g = gpu_scene_state(model, scene);
  const Pose start = ref.tool_pose;
  std::unique_ptr<Stepper> gpu = make(model, g);
  const std::vector<Vec3> stale = g.pos;  // the host's particles before the steps
  for (int k = 0; k < steps; ++k) {
    const Pose pose = gpu_scene_pose(start, k);
    ref.tool_pose = pose;
    all_pairs ? step_all_pairs(model, ref) : step(model, ref);
    gpu->step(g, pose);
    // The small results come every step without a sync; the particles stay where they were.
    expect_near_rel(g.tool_wrench.force, ref.tool_wrench.force, tol, 1e-6, "tool force (no sync)", 0, k);
    if (::testing::Test::HasFatalFailure()) return;
    ASSERT_EQ(g.bonds.counters.formed, ref.bonds.counters.formed) << "step " << k;
    ASSERT_EQ(g.steps, ref.steps);
    ASSERT_EQ(g.time, ref.time);
    ASSERT_EQ(g.tool_pose_applied.position, pose.position);
    if (k == 0) {
      ASSERT_EQ(g.pos, stale) << "step() alone moves no host particle";
    }
    if ((k + 1) % check_every == 0 || k + 1 == steps) {
      gpu->sync_to_host(g);
      compare_states(g, ref, k, tol);
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
  EXPECT_GT(ref.bonds.counters.formed, 0u) << "bonds formed: the comparison covers adhesion";
  EXPECT_GT(norm(ref.tool_wrench.force), 0) << "the tool touched the material";
  EXPECT_EQ(g.steps, std::uint64_t(steps));
}

// The paper's Fig. 2 with a GPU stepper: a tool particle pushed into a material particle held at
// the origin and pulled away again. The holding needs the particles on the host every step, so
// each step syncs them to the host, holds the particle there and syncs the State back (into the
// same memory: the particle count is unchanged), which tests both. Every step's force and bond
// count must equal the CPU grid step's, and the bond must form once and break once.
inline void gpu_fig2_loop(const GpuFactory& make) {
  const real s = kGpuSpacing;
  Model model = make_model(params_for_spacing(s, {-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1}, 1e-4));
  const real m = 1e-3, rho0 = m * kernels::poly6(0, model.kernel);
  const Material mat{0, 50, rho0, 300};
  State ref;
  ref.tool_pose.position = {1.2 * model.adhesion.B, 0, 0};
  ref.tool_pose_applied = ref.tool_pose;
  ref.add_particles(model, {particle(Role::tool, {0, 0, 0}, m, mat), particle(Role::material, {0, 0, 0}, m, mat)});
  State g = ref;
  auto hold = [](State& st) {
    const std::uint32_t i = st.index_of_id[1];
    st.pos[i] = {};
    st.vel[i] = {};
  };
  std::vector<std::pair<real, int>> path = {{0.7 * model.adhesion.A, 400},
                                            {0.5 * (model.adhesion.A + model.kernel.h), 100},
                                            {1.1 * model.adhesion.B, 600}};
  int step_no = 0, bonded_steps = 0;
  std::unique_ptr<Stepper> gpu = make(model, g);
  for (const auto& [r, n] : path) {
    const real r0 = ref.tool_pose.position.x;
    for (int k = 1; k <= n; ++k, ++step_no) {
      ref.tool_pose.position.x = r0 + (r - r0) * k / n;
      step(model, ref);
      hold(ref);
      gpu->step(g, ref.tool_pose);
      gpu->sync_to_host(g);
      hold(g);
      gpu->sync_from_host(g);
      ASSERT_EQ(g.bonds.count(0), ref.bonds.count(0)) << "step " << step_no;
      bonded_steps += ref.bonds.count(0);
      expect_near_rel(g.tool_wrench.force, ref.tool_wrench.force, 1e-9, 1e-12, "tool force", 0, step_no);
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
  EXPECT_EQ(g.bonds.counters.formed, 1u);
  EXPECT_EQ(g.bonds.counters.broken, 1u);
  EXPECT_EQ(ref.bonds.counters.formed, 1u);
  EXPECT_EQ(ref.bonds.counters.broken, 1u);
  EXPECT_GT(bonded_steps, 100);
  EXPECT_EQ(g.steps, ref.steps);
}

// Bond lists too small for a packed block: the GPU refuses the same partners and counts the same
// overflows as the CPU grid step (both visit the cells in the same order).
inline void gpu_overflow_counted(const GpuFactory& make) {
  const GpuScene scene{5, 0.1, 1, false, 21};
  Model model = gpu_scene_model(scene, 4);
  State ref = gpu_scene_state(model, scene), g = gpu_scene_state(model, scene);
  std::unique_ptr<Stepper> gpu = make(model, g);
  for (int k = 0; k < 20; ++k) step_both(model, ref, *gpu, g, gpu_scene_pose(ref.tool_pose, k));
  gpu->sync_to_host(g);
  compare_states(g, ref, 20, 1e-6);
  EXPECT_GT(g.bonds.counters.overflowed, 100u) << "the lists overflowed";
}

}  // namespace dentsph::testing
