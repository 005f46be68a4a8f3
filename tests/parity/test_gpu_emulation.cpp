// The GPU backend's algorithm, run on the CPU (make_emulated_gpu_stepper: the CUDA stage bodies
// looped over the particles), against the CPU reference: the all-pairs step and the grid step
// within kBackendParityTolerance (1e-4) relative over 100 steps, the Fig. 2 bond loop step for
// step, the bond overflow counted alike, edits between steps. tests/cuda runs the same checks on
// a device.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "dentsph/bench.hpp"
#include "dentsph/run.hpp"
#include "support/gpu_parity.hpp"

namespace dentsph {
namespace {

using namespace testing;

const GpuFactory emulated = [](const Model& m, const State& s) { return make_emulated_gpu_stepper(m, s); };

class GpuEmulation : public ::testing::TestWithParam<GpuScene> {};

TEST_P(GpuEmulation, MatchesAllPairsOver100Steps) {
  gpu_parity_run(emulated, GetParam(), true, kBackendParityTolerance);
}

TEST_P(GpuEmulation, MatchesGridStepOver100Steps) {
  gpu_parity_run(emulated, GetParam(), false, kBackendParityTolerance, 10);
}

INSTANTIATE_TEST_SUITE_P(Scenes, GpuEmulation,
                         ::testing::Values(GpuScene{4, 0.2, 1, false, 1}, GpuScene{5, 0.25, 2, true, 2},
                                           GpuScene{6, 0.0, 1, true, 3}, GpuScene{5, 0.3, 3, false, 4}),
                         [](const auto& info) {
                           const GpuScene& c = info.param;
                           return "side" + std::to_string(c.side) + "_reach" + std::to_string(c.reach) +
                                  (c.far_cluster ? "_far" : "") + "_seed" + std::to_string(c.seed);
                         });

TEST(GpuEmulation, Fig2BondLoopStepForStep) { gpu_fig2_loop(emulated); }

TEST(GpuEmulation, BondOverflowCountedAsOnTheCpu) { gpu_overflow_counted(emulated); }

TEST(GpuEmulation, DownloadBeforeAnyStepKeepsTheParticles) {
  const GpuScene scene;
  Model model = gpu_scene_model(scene);
  const State st = gpu_scene_state(model, scene);
  State back;
  make_emulated_gpu_stepper(model, st)->sync_to_host(back);
  ASSERT_EQ(back.size(), st.size());
  for (std::uint32_t id = 0; id < st.size(); ++id) {
    EXPECT_EQ(back.pos[at(back, id)], st.pos[at(st, id)]);
    EXPECT_EQ(back.role[at(back, id)], st.role[at(st, id)]);
  }
  EXPECT_TRUE(back.rho_static_valid);
}

// An edit between steps through the Stepper (sync to the host, change, sync back): material added
// mid-run goes into a new engine (the count changed), then a velocity kick into the same memory;
// the run goes on as the CPU's with the same edits, within the parity tolerance.
TEST(GpuEmulation, EditsBetweenStepsMatchTheCpu) {
  const GpuScene scene{5, 0.2, 1, false, 7};
  Model model = gpu_scene_model(scene);
  State ref = gpu_scene_state(model, scene), g = gpu_scene_state(model, scene);
  const std::unique_ptr<Stepper> gpu = make_emulated_gpu_stepper(model, g);
  const Pose start = ref.tool_pose;
  const real s = kGpuSpacing, m = lattice_particle_mass(1000, s, model.kernel);
  std::vector<ParticleInit> more;
  for (Vec3 p : lattice({0.03, 0.03, 0.1}, s, 3, 3, 2)) more.push_back(particle(Role::material, p, m, {0.4, 60, 1000, 300}));
  auto kick = [](State& st) {
    for (std::uint32_t i = 0; i < st.size(); ++i)
      if (st.role[i] == Role::material) st.vel[i].z -= 0.05;
  };
  for (int k = 0; k < 60; ++k) {
    if (k == 20) {
      ref.add_particles(model, more);
      gpu->sync_to_host(g);
      g.add_particles(model, more);
      gpu->sync_from_host(g);
    }
    if (k == 40) {
      kick(ref);
      gpu->sync_to_host(g);
      kick(g);
      gpu->sync_from_host(g);
    }
    step_both(model, ref, *gpu, g, gpu_scene_pose(start, k));
  }
  gpu->sync_to_host(g);
  ASSERT_EQ(g.size(), ref.size());
  compare_states(g, ref, 60, kBackendParityTolerance);
  EXPECT_EQ(g.steps, 60u);
  EXPECT_EQ(g.bonds.counters.formed, ref.bonds.counters.formed);
}

// The CPU's Stepper is the grid step itself: bit for bit, and its syncs change nothing.
TEST(Backend, CpuStepperIsTheGridStepBitForBit) {
  const GpuScene scene{5, 0.2, 1, false, 3};
  Model model = gpu_scene_model(scene);
  State ref = gpu_scene_state(model, scene), st = gpu_scene_state(model, scene);
  const std::unique_ptr<Stepper> cpu = make_stepper(Backend::cpu, model, st, 1);
  EXPECT_STREQ(cpu->name(), "cpu");
  for (int k = 0; k < 40; ++k) {
    step_both(model, ref, *cpu, st, gpu_scene_pose(ref.tool_pose, k));
    cpu->sync_to_host(st);
    cpu->sync_from_host(st);
  }
  EXPECT_EQ(st.pos, ref.pos);
  EXPECT_EQ(st.vel, ref.vel);
  EXPECT_EQ(st.tool_wrench.force, ref.tool_wrench.force);
  EXPECT_EQ(st.steps, ref.steps);
  EXPECT_STREQ(make_stepper(Backend::cuda_emulation, model, st, 1)->name(), "cuda-emulation");
}

// The GPU backends run the paper's step only: a model of another solver is refused by name.
TEST(Backend, AGpuBackendRefusesAnotherSolverByName) {
  const GpuScene scene{5, 0.2, 1, false, 3};
  Model model = gpu_scene_model(scene);
  const State st = gpu_scene_state(model, scene);
  model.solver = Solver::iisph;
  try {
    make_stepper(Backend::cuda_emulation, model, st, 1);
    ADD_FAILURE() << "the emulation took the iisph solver";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("iisph solver has no cuda-emulation backend"), std::string::npos) << e.what();
  }
  EXPECT_STREQ(make_stepper(Backend::cpu, model, st, 1)->name(), "cpu");
}

TEST(Backend, NamesParseAndUnknownNamesAreRefused) {
  EXPECT_EQ(parse_backend("cpu"), Backend::cpu);
  EXPECT_EQ(parse_backend("cuda"), Backend::cuda);
  EXPECT_EQ(parse_backend("cuda-emulation"), Backend::cuda_emulation);
  EXPECT_STREQ(backend_name(Backend::cuda), "cuda");
  EXPECT_THROW(parse_backend("opencl"), std::invalid_argument);
}

TEST(Backend, CudaUnavailableSaysWhy) {
  const CudaStatus st = cuda_status();
  if (st.available) GTEST_SKIP() << "a CUDA device is present: " << st.device;
  EXPECT_FALSE(st.reason.empty());
  const std::string expected = cuda_built() ? "no CUDA device" : "this build has no CUDA backend";
  EXPECT_EQ(st.reason.rfind(expected, 0), 0u) << st.reason;
  const GpuScene scene;
  Model model = gpu_scene_model(scene);
  try {
    make_cuda_stepper(model, gpu_scene_state(model, scene));
    FAIL() << "make_cuda_stepper should throw without CUDA";
  } catch (const CudaUnavailable& e) {
    EXPECT_EQ(std::string(e.what()), st.reason);
  }
  // The run and the benchmark refuse the same way (the CLI prints it and exits non-zero).
  RunOptions ro;
  ro.steps = 1;
  ro.backend = Backend::cuda;
  EXPECT_THROW(run_offline(load_scene("scenes/tool_press.json"), ro), CudaUnavailable);
  BenchOptions bo;
  bo.backend = Backend::cuda;
  EXPECT_THROW(run_benchmarks(bo, [](const std::string&) {}), CudaUnavailable);
}

// The run loop's GPU path (the particles downloaded only for snapshots, events and the end):
// a scene with a dispense event gives the CPU run's summary.
TEST(GpuEmulation, RunLoopMatchesTheCpuRun) {
  Scene sc = load_scene("scenes/tool_press.json");
  ProcedureEvent more;
  more.t = 0.01;
  more.kind = ProcedureEvent::Kind::dispense;
  for (Vec3 p : lattice({-0.02, -0.02, 0.075}, 0.01, 3, 3, 2))
    more.particles.push_back(make_particle(Role::material, p, 1e-3, {0.5, 60, 1000, 200}));
  sc.events.push_back(more);
  const auto dir = std::filesystem::temp_directory_path() / ("dentsph_gpu_run_" + std::to_string(::getpid()));
  RunOptions opt;
  opt.steps = 60;
  opt.out_dir = dir / "cpu";
  const RunSummary cpu = run_offline(sc, opt);
  opt.out_dir = dir / "gpu";
  opt.backend = Backend::cuda_emulation;
  const RunSummary gpu = run_offline(sc, opt);
  EXPECT_EQ(gpu.events_applied, 1u);
  EXPECT_EQ(gpu.material, cpu.material);
  EXPECT_EQ(gpu.steps, cpu.steps);
  EXPECT_EQ(gpu.snapshots, cpu.snapshots);
  EXPECT_EQ(gpu.bonds.formed, cpu.bonds.formed);
  EXPECT_EQ(gpu.bonds_current, cpu.bonds_current);
  EXPECT_GT(cpu.peak_tool_force_N, 0);
  EXPECT_NEAR(gpu.peak_tool_force_N, cpu.peak_tool_force_N, kBackendParityTolerance * cpu.peak_tool_force_N);
  EXPECT_EQ(gpu.status, "completed");
  std::filesystem::remove_all(dir);
}

TEST(GpuEmulation, BenchmarkReportsTheBackendAndItsSweep) {
  BenchOptions opt;
  opt.backend = Backend::cuda_emulation;
  opt.cuda_sweep_sides = {4, 6};
  opt.repeats = 1;
  opt.seconds_per_run = 0.01;
  const auto j = nlohmann::json::parse(bench_json(run_benchmarks(opt, [](const std::string&) {})));
  EXPECT_EQ(j["backend"], "cuda-emulation");
  EXPECT_GT(j["default_scene"]["steps_per_second"]["1"].get<double>(), 0);
  EXPECT_GT(j["default_scene"]["stage_us"]["1"]["forces"].get<double>(), 0);
  ASSERT_EQ(j["sweep"].size(), 2u);
  for (const auto& row : j["sweep"]) {
    EXPECT_EQ(row["method"], "cuda-emulation");
    EXPECT_GT(row["steps_per_second"].get<double>(), 0);
    EXPECT_GT(row["stage_us"]["density"].get<double>(), 0);
  }
}

}  // namespace
}  // namespace dentsph
