// step(): a step of the model's solver for callers that hold no solver object of their own (tests,
// tools). Each thread keeps one object of each solver, which sizes its buffers for every State it
// is handed (StepSolver::step); a loop that steps one State holds its own (a Stepper).
#include <memory>
#include <vector>

#include "dentsph/solver.hpp"
#include "dentsph/step.hpp"

namespace dentsph {

void step(const Model& model, State& state, const StepOptions& opt) {
  thread_local std::vector<std::unique_ptr<StepSolver>> solvers;
  for (const std::unique_ptr<StepSolver>& s : solvers)
    if (s->key() == model.solver) return s->step(model, state, opt);
  solvers.push_back(make_solver(model.solver));
  solvers.back()->step(model, state, opt);
}

}  // namespace dentsph
