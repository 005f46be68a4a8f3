// The CPU's Stepper: the grid step (step.cpp) on the host State itself, so that syncing is nothing.
#include <chrono>
#include <optional>

#include <fmt/format.h>

#include "dentsph/stepper.hpp"
#include "dentsph/thread_governor.hpp"

namespace dentsph {

namespace {

class CpuStepper final : public Stepper {
 public:
  CpuStepper(const Model& model, int threads, ThreadPolicy policy) : model_(model), threads_(threads) {
    if (policy == ThreadPolicy::governed && threads > 1) governor_.emplace(threads);
  }

  const char* name() const override { return "cpu"; }
  std::string device_name() const override {
    if (governor_) return fmt::format("up to {} CPU threads (the fastest count, timed)", threads_);
    return fmt::format("{} CPU thread{}", threads_, threads_ == 1 ? "" : "s");
  }
  void step(State& host, const Pose& tool_pose) override {
    host.tool_pose = tool_pose;
    if (!governor_) {
      dentsph::step(model_, host, StepOptions{threads_, nullptr});
      return;
    }
    using clock = std::chrono::steady_clock;
    const auto t0 = clock::now();
    dentsph::step(model_, host, StepOptions{governor_->threads(), nullptr});
    governor_->record(std::chrono::duration<double>(clock::now() - t0).count());
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
  std::optional<ThreadGovernor> governor_;
};

}  // namespace

std::unique_ptr<Stepper> make_cpu_stepper(const Model& model, int threads, ThreadPolicy policy) {
  return std::make_unique<CpuStepper>(model, threads, policy);
}

}  // namespace dentsph
