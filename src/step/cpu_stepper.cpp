// The CPU's Stepper: the model's solver object (dentsph/solver.hpp) stepping the host State itself,
// so that syncing is nothing; it sizes the solver's buffers for the State it starts from and after
// every edit (sync_from_host), so that a step allocates nothing.
#include <chrono>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "dentsph/solver.hpp"
#include "dentsph/stepper.hpp"
#include "dentsph/thread_governor.hpp"

namespace dentsph {

namespace {

class CpuStepper final : public Stepper {
 public:
  CpuStepper(const Model& model, const State& state, int threads, ThreadPolicy policy)
      : model_(model), solver_(make_solver(model.solver)), threads_(threads) {
    if (policy == ThreadPolicy::governed && threads > 1) governor_.emplace(threads);
    solver_->resize(model_, state);
  }

  const char* name() const override { return "cpu"; }
  std::string device_name() const override {
    if (governor_) return fmt::format("up to {} CPU threads (the fastest count, timed)", threads_);
    return fmt::format("{} CPU thread{}", threads_, threads_ == 1 ? "" : "s");
  }
  void step(State& host, const Pose& tool_pose) override {
    host.tool_pose = tool_pose;
    using clock = std::chrono::steady_clock;
    const auto t0 = budget_.count() > 0 || governor_ ? clock::now() : clock::time_point{};
    StepOptions opt{governor_ ? governor_->threads() : threads_, nullptr};
    if (budget_.count() > 0) opt.deadline = t0 + std::chrono::duration_cast<clock::duration>(budget_);
    solver_->step(model_, host, opt);
    if (governor_) governor_->record(std::chrono::duration<double>(clock::now() - t0).count());
  }
  void set_solve_budget(double seconds) override {
    budget_ = std::chrono::duration<double>(seconds > 0 && std::isfinite(seconds) ? seconds : 0);
  }
  void step_timed(State& host, const Pose& tool_pose, StageTimes& times) override {
    host.tool_pose = tool_pose;
    solver_->step(model_, host, StepOptions{threads_, &times});
  }
  void sync_to_host(State&) override {}
  void sync_from_host(const State& host) override { solver_->resize(model_, host); }
  std::size_t solver_bytes() const override { return solver_->bytes(); }

 private:
  const Model& model_;  // the caller's (a Simulation's): it outlives the stepper
  std::unique_ptr<StepSolver> solver_;
  int threads_;
  std::optional<ThreadGovernor> governor_;
  std::chrono::duration<double> budget_{0};
};

}  // namespace

std::unique_ptr<Stepper> make_cpu_stepper(const Model& model, const State& state, int threads, ThreadPolicy policy) {
  return std::make_unique<CpuStepper>(model, state, threads, policy);
}

}  // namespace dentsph
