// The GPU backend's algorithm, run on the CPU (make_emulated_gpu_stepper: the CUDA stage bodies
// looped over the particles), against the CPU reference: the all-pairs step and the grid step
// within 1e-4 relative over 100 steps, the Fig. 2 bond loop step for step, the bond overflow
// counted alike. tests/cuda runs the same checks on a device.
#include <gtest/gtest.h>

#include "support/gpu_parity.hpp"

namespace dentsph {
namespace {

using namespace testing;

const GpuFactory emulated = [](const Model& m, const State& s) { return make_emulated_gpu_stepper(m, s); };

class GpuEmulation : public ::testing::TestWithParam<GpuScene> {};

TEST_P(GpuEmulation, MatchesAllPairsOver100Steps) { gpu_parity_run(emulated, GetParam(), true, 1e-4); }

TEST_P(GpuEmulation, MatchesGridStepOver100Steps) { gpu_parity_run(emulated, GetParam(), false, 1e-4, 10); }

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
  const Model model = gpu_scene_model(scene);
  const State st = gpu_scene_state(model, scene);
  State back;
  make_emulated_gpu_stepper(model, st)->download(back);
  ASSERT_EQ(back.size(), st.size());
  for (std::uint32_t id = 0; id < st.size(); ++id) {
    EXPECT_EQ(back.pos[at(back, id)], st.pos[at(st, id)]);
    EXPECT_EQ(back.role[at(back, id)], st.role[at(st, id)]);
  }
  EXPECT_TRUE(back.rho_static_valid);
}

TEST(Backend, NamesParseAndUnknownNamesAreRefused) {
  EXPECT_EQ(parse_backend("cpu"), Backend::cpu);
  EXPECT_EQ(parse_backend("cuda"), Backend::cuda);
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
  const Model model = gpu_scene_model(scene);
  try {
    make_cuda_stepper(model, gpu_scene_state(model, scene));
    FAIL() << "make_cuda_stepper should throw without CUDA";
  } catch (const CudaUnavailable& e) {
    EXPECT_EQ(std::string(e.what()), st.reason);
  }
}

}  // namespace
}  // namespace dentsph
