// The CPU's Stepper: the grid step (step.cpp) on the host State itself, so that syncing is nothing.
#include <fmt/format.h>

#include "dentsph/stepper.hpp"

namespace dentsph {

namespace {

class CpuStepper final : public Stepper {
 public:
  CpuStepper(const Model& model, int threads) : model_(model), threads_(threads) {}

  const char* name() const override { return "cpu"; }
  std::string device_name() const override {
    return fmt::format("{} CPU thread{}", threads_, threads_ == 1 ? "" : "s");
  }
  void step(State& host, const Pose& tool_pose) override {
    host.tool_pose = tool_pose;
    dentsph::step(model_, host, StepOptions{threads_, nullptr});
  }
  void step_timed(State& host, const Pose& tool_pose, StageTimes& times) override {
    host.tool_pose = tool_pose;
    dentsph::step(model_, host, StepOptions{threads_, &times});
  }
  void sync_to_host(State&) override {}
  void sync_from_host(const State&) override {}

 private:
  Model model_;
  int threads_;
};

}  // namespace

std::unique_ptr<Stepper> make_cpu_stepper(const Model& model, int threads) {
  return std::make_unique<CpuStepper>(model, threads);
}

}  // namespace dentsph
