// The cure in a run (docs/architecture.md, "Curing"): the Simulation cures after every step with
// the light of the scene's cure events; a long cure advanced in large updates while the paste rests
// (CureSchedule) agrees with the same cure stepped at dt throughout; a live paste edit is kept by
// the cure; the CUDA backend's emulation cures as the CPU does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "dentsph/dental.hpp"
#include "dentsph/simulation.hpp"
#include "support/cure_scenes.hpp"

namespace dentsph::testing {
namespace {

constexpr real mm = 1e-3;
constexpr real kSpacing = 0.3 * mm;
constexpr real kSettle = 0.025;  // s of stepping before the light comes on

// Paste 1.8 mm deep in an open box (as PasteCuresWhileItIsStepped), no tool, the light on its top
// from kSettle for `light_s`, the run ending with the light.
Scene cure_box_scene(real light_s) {
  const real s = kSpacing;
  Scene sc;
  sc.name = "cure_box";
  sc.model = cure_model(s, {-2 * mm, -2 * mm, -2 * mm}, {5 * mm, 5 * mm, 6 * mm});
  const real wall_mass = lattice_particle_mass(kWall.rho0, s, sc.model.kernel);
  for (const Vec3& p : open_container({0, 0, 0}, s, 8, 8, 8, 2))
    sc.particles.push_back(make_particle(Role::boundary, p, wall_mass, kWall));
  const real paste_mass = lattice_particle_mass(kPaste.rho0, s, sc.model.kernel);
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 9; ++j)
      for (int i = 0; i < 9; ++i)
        sc.particles.push_back(
            make_particle(Role::material, {(i + 0.5) * s, (j + 0.5) * s, (k + 0.5) * s - 0.5 * s}, paste_mass, kPaste));
  sc.material_spacing = s;
  ProcedureEvent cure;
  cure.kind = ProcedureEvent::Kind::cure;
  cure.t = kSettle;
  cure.duration = light_s;
  cure.light = light_above({1.35 * mm, 1.35 * mm, 3 * mm});
  sc.events.push_back(cure);
  sc.duration = kSettle + light_s;
  intern_scene_materials(sc);
  return sc;
}

struct CureRun {
  State state;
  RunSummary summary;
};

// Runs `sc` to its end: every step at dt, or with the cure advanced at rest where it can be.
CureRun run_cure(const Scene& sc, bool large_updates, Backend backend = Backend::cpu, real update = 0.02) {
  SimulationOptions o;
  o.cure_schedule.update = update;
  o.backend = backend;
  o.thread_policy = ThreadPolicy::fixed;
  Simulation sim(sc, o);
  const real dt = sc.model.dt;
  while (sim.state().time + 0.5 * dt < sc.duration) {
    sim.apply_due_events();
    if (large_updates && sim.advance_cure_at_rest(sc.duration) > 0) continue;
    EXPECT_TRUE(sim.step(sim.keyframe_pose())) << sim.divergence();
    if (sim.diverged()) break;
  }
  CureRun r;
  r.summary = sim.summary();
  r.state = sim.synced();
  return r;
}

std::uint32_t count_rigid(const State& st) {
  std::uint32_t n = 0;
  for (std::uint32_t id = 0; id < st.cure.particles(); ++id) n += st.cure.rigid[id];
  return n;
}

TEST(CureInARun, TheSimulationCuresWithTheSceneLight) {
  const Scene sc = cure_box_scene(0.1);
  const CureRun r = run_cure(sc, false);
  EXPECT_TRUE(r.summary.curing);
  EXPECT_NEAR(r.summary.light_on_s, 0.1, 1e-3);
  EXPECT_EQ(r.summary.cure_updates_at_rest, 0u);
  EXPECT_GT(count_rigid(r.state), 2u * 81u) << "the top layers set within 0.1 s, as when cure_between_steps is called by hand";
  EXPECT_EQ(r.summary.material, 6u * 81u) << "set paste is still paste in the summary";
  // Without a cure event nothing cures and nothing is set.
  Scene dark = sc;
  dark.events.clear();
  SimulationOptions o;
  o.thread_policy = ThreadPolicy::fixed;
  Simulation sim(dark, o);
  EXPECT_FALSE(sim.curing());
  for (int k = 0; k < 100; ++k) sim.step(sim.keyframe_pose());
  EXPECT_EQ(count_rigid(sim.synced()), 0u);
  EXPECT_FALSE(sim.summary().curing);
}

// A scene named as filled with the `amalgam` preset cures by its cure (scene_paste_cure; the box's
// paste stays the paper's, whose flow does not matter here): the light does not cure it, and it sets
// by itself, light or none, once its age passes its gel point (346 s after mixing).
TEST(CureInARun, AnAmalgamIgnoresTheLightAndSetsByItself) {
  Scene sc = cure_box_scene(0.1);
  sc.paste_preset = "amalgam";
  const CureRun r = run_cure(sc, false);
  EXPECT_TRUE(r.summary.curing);
  EXPECT_EQ(count_rigid(r.state), 0u) << "an amalgam is not light-cured";
  Scene dark = sc;
  dark.events.clear();
  SimulationOptions o;
  o.thread_policy = ThreadPolicy::fixed;
  Simulation sim(dark, o);
  ASSERT_TRUE(sim.curing()) << "it sets with no light";
  EXPECT_EQ(sim.cure_model()->paste.name, "amalgam");
  for (int k = 0; k < 5; ++k) sim.step(sim.keyframe_pose());
  EXPECT_EQ(count_rigid(sim.synced()), 0u) << "within its working time";
  State& st = sim.edit();
  for (std::uint32_t id = 0; id < st.cure.particles(); ++id) st.cure.mixed_at[id] -= 400;  // mixed 400 s ago
  // Over a few of the cure's passes (CureModel::transition_interval apart).
  const int steps = int(std::ceil(3 * sim.cure_model()->transition_interval / dark.model.dt));
  for (int k = 0; k < steps; ++k) sim.step(sim.keyframe_pose());
  EXPECT_EQ(count_rigid(sim.synced()), 6u * 81u) << "past its gel point every paste particle has set";
}

// The rule (CureSchedule): while the light is on, nothing is due and the paste rests (under
// 0.5 mm/s), the cure goes on in updates of 20 ms of light with 10 steps of the paste after each.
// Over 0.5 s of light (the top 1.5 mm sets; the paste below stays paste) it agrees with the cure
// stepped at dt, in a quarter of the steps: measured, the dose within 1.0% in the inner columns and
// within 0.45% of the largest everywhere, the conversion within 0.0009, the same 450 particles set.
// (At a rest speed of 2 mm/s the updates began while the paste still settled: 2.2%, 2.6%, 0.0055
// and 8 particles fewer set; the update's length, 5 to 50 ms, changed little.)
// A paste particle flung away (here: one thrown up at 1 m/s from 20 mm above the box, outside the
// scene's domain) does not keep the cure stepping at dt: the paste where it is filled rests
// (Simulation::paste_at_rest). Before, the fastest particle anywhere decided: this run advanced
// 0.07 s of the 0.3 s of light at rest (4 updates, around the top of the particle's flight), now
// 0.21 s (11).
TEST(CureInARun, AParticleFlungAwayDoesNotKeepTheCureStepping) {
  Scene sc = cure_box_scene(0.3);
  ParticleInit far = sc.particles.back();
  far.pos = {1.35 * mm, 1.35 * mm, 20 * mm};
  far.vel = {0, 0, 1};
  sc.particles.push_back(far);
  intern_scene_materials(sc);
  const CureRun r = run_cure(sc, true);
  std::printf("%llu steps, %llu updates at rest (%.3f s of %.3f s of light)\n", (unsigned long long)r.summary.steps,
              (unsigned long long)r.summary.cure_updates_at_rest, r.summary.cure_at_rest_s, r.summary.light_on_s);
  EXPECT_GT(r.summary.cure_at_rest_s, 0.15) << "most of the light's time advanced at rest";
}

TEST(CureInARun, LargeUpdatesAtRestAgreeWithACureSteppedThroughout) {
  const Scene sc = cure_box_scene(0.5);
  const CureRun stepped = run_cure(sc, false);
  const CureRun fast = run_cure(sc, true, Backend::cpu, 0.02);
  ASSERT_EQ(stepped.state.cure.particles(), fast.state.cure.particles());
  const CureState& a = stepped.state.cure;
  const CureState& b = fast.state.cure;
  real max_dose = 0;
  for (std::uint32_t id = 0; id < a.particles(); ++id) max_dose = std::max(max_dose, a.dose[id]);
  // Dose: relative, in the paste's inner columns (the beam's grid interpolates the outer ones with
  // the box's walls, so that there a shift of a small fraction of a spacing changes the dose of
  // the dim base by more); against the largest dose everywhere.
  real worst_dose = 0, worst_dose_all = 0, worst_alpha = 0;
  std::uint32_t compared = 0;
  for (std::uint32_t id = 0; id < a.particles(); ++id) {
    if (!a.curable[id]) continue;
    worst_alpha = std::max(worst_alpha, std::abs(a.alpha[id] - b.alpha[id]));
    worst_dose_all = std::max(worst_dose_all, std::abs(a.dose[id] - b.dose[id]) / max_dose);
    const Vec3 p = stepped.state.pos[stepped.state.index_of_id[id]];
    const bool inner = p.x > 1.5 * kSpacing && p.x < 7.5 * kSpacing && p.y > 1.5 * kSpacing && p.y < 7.5 * kSpacing;
    if (!inner || a.dose[id] < 1e-3 * max_dose) continue;
    const real e = std::abs(a.dose[id] - b.dose[id]) / a.dose[id];
    worst_dose = std::max(worst_dose, e);
    ++compared;
  }
  const std::uint32_t set_a = count_rigid(stepped.state), set_b = count_rigid(fast.state);
  std::printf("stepped: %llu steps; at rest: %llu steps and %llu updates (%.3f s of %.3f s of light); dose within "
              "%.2f%% in %u inner particles, within %.2f%% of the largest everywhere; conversion within %.4f; set %u "
              "and %u of %u\n",
              (unsigned long long)stepped.summary.steps, (unsigned long long)fast.summary.steps,
              (unsigned long long)fast.summary.cure_updates_at_rest, fast.summary.cure_at_rest_s, fast.summary.light_on_s,
              100 * worst_dose, compared, 100 * worst_dose_all, worst_alpha, set_a, set_b, 6u * 81u);
  EXPECT_GT(compared, 200u);
  EXPECT_NEAR(fast.summary.light_on_s, 0.5, 1e-3);
  EXPECT_GT(fast.summary.cure_at_rest_s, 0.35) << "most of the light's time advanced at rest";
  EXPECT_LT(fast.summary.steps, stepped.summary.steps / 3) << "in far fewer steps";
  EXPECT_LT(worst_dose, 0.02);
  EXPECT_LT(worst_dose_all, 0.01);
  EXPECT_LT(worst_alpha, 0.003);
  EXPECT_LE(std::abs(int(set_a) - int(set_b)), 3);
  EXPECT_GT(set_a, 3u * 81u);
  EXPECT_LT(set_a, 6u * 81u);
}

// A paste edit (the viewer's material panel) becomes what the cure's mapping starts from: the
// conversion that rises afterwards stiffens the edited paste, not the one it was made with.
TEST(CureInARun, APasteEditIsKeptByTheCure) {
  const Scene sc = cure_box_scene(0.05);
  SimulationOptions o;
  o.thread_policy = ThreadPolicy::fixed;
  Simulation sim(sc, o);
  Material edited = kPaste;
  edited.mu = 0.5 * kPaste.mu;
  edited.Ka = 2 * kPaste.Ka;
  sim.set_paste(sc.model.adhesion, edited);
  while (sim.state().time + 0.5 * sc.model.dt < sc.duration) {
    sim.apply_due_events();
    ASSERT_TRUE(sim.step(sim.keyframe_pose()));
  }
  const State& st = sim.synced();
  const CureModel& cm = *sim.cure_model();
  int checked = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    const std::uint32_t id = st.id[i];
    if (st.role[i] != Role::material || !(st.cure.alpha[id] > 0)) continue;
    EXPECT_EQ(st.cure.mu0[id], edited.mu);
    EXPECT_EQ(st.cure.Ka0[id], edited.Ka);
    const Material p = cured_parameters(cm.paste, edited, st.cure.alpha[id], cm.viscosity_limit);
    EXPECT_NEAR(st.mu[i], p.mu, 1e-9 * p.mu) << "id " << id;
    EXPECT_NEAR(st.Ka[i], p.Ka, 1e-9 * p.Ka) << "id " << id;
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

// The CUDA backend's host emulation keeps the particles in its own memory: the Simulation downloads
// them for a cure pass and hands them back. Its cure matches the CPU's.
TEST(CureInARun, TheGpuEmulationCuresAsTheCpuDoes) {
  const Scene sc = cure_box_scene(0.1);
  const CureRun cpu = run_cure(sc, true);
  const CureRun gpu = run_cure(sc, true, Backend::cuda_emulation);
  EXPECT_EQ(gpu.summary.backend, "cuda-emulation");
  const std::uint32_t set_cpu = count_rigid(cpu.state), set_gpu = count_rigid(gpu.state);
  std::printf("set: cpu %u, cuda-emulation %u\n", set_cpu, set_gpu);
  EXPECT_GT(set_gpu, 2u * 81u);
  EXPECT_LE(std::abs(int(set_cpu) - int(set_gpu)), 5);
  real worst = 0;
  for (std::uint32_t id = 0; id < cpu.state.cure.particles(); ++id)
    if (cpu.state.cure.dose[id] > 100) worst = std::max(worst, std::abs(cpu.state.cure.dose[id] - gpu.state.cure.dose[id]) / cpu.state.cure.dose[id]);
  EXPECT_LT(worst, 0.02) << "dose, relative";
}

}  // namespace
}  // namespace dentsph::testing

namespace dentsph::testing {
namespace {

// A hand-held light over the cavity (the viewer's L key, the device's second button) cures the
// built-in dental scene's paste: after 0.1 s its top has converted, its base less.
TEST(CureInARun, AHandHeldLightOverTheCavityCuresTheDentalPaste) {
  const Scene sc = default_dental_scene();
  SimulationOptions o;
  o.thread_policy = ThreadPolicy::fixed;
  o.threads = 2;
  Simulation sim(sc, o);
  EXPECT_FALSE(sim.curing());
  sim.set_light(sim.light_over_cavity());
  EXPECT_TRUE(sim.curing());
  const ToothFrame& f = sc.tooth->frame();
  const real window = dot(sim.light()->tip - f.origin, f.z);
  EXPECT_GE(window, 1e-3 - 1e-12) << "1 mm above the occlusal reference, or above the paste's heap";
  for (int k = 0; k < 2000; ++k) ASSERT_TRUE(sim.step(sim.keyframe_pose()));
  const State& st = sim.synced();
  real top = -1, top_alpha = 0, low = 1, low_alpha = 0, max_alpha = 0;
  std::uint32_t lit = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    if (!st.is_paste(i)) continue;
    const real z = dot(st.pos[i] - f.origin, f.z), a = st.cure.alpha[st.id[i]];
    max_alpha = std::max(max_alpha, a);
    lit += st.cure.irradiance[st.id[i]] > 0;
    if (z > top) top = z, top_alpha = a;
    if (z < low) low = z, low_alpha = a;
  }
  std::printf("lit %u, max conversion %.4f, top (%.2f mm) %.4f, base (%.2f mm) %.4f, last update lit %u\n", lit,
              max_alpha, top / mm, top_alpha, low / mm, low_alpha, sim.last_cure().lit);
  std::uint32_t paste = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i) paste += st.is_paste(i);
  EXPECT_GT(lit, 9 * paste / 10) << "the window above the heap: nearly all the paste in the light";
  EXPECT_GT(max_alpha, 0.03);
  EXPECT_LT(low_alpha, max_alpha);
  sim.set_light(std::nullopt);
  EXPECT_FALSE(sim.light().has_value());
}

}  // namespace
}  // namespace dentsph::testing
