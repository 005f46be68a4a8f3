// The paper's explicit, weakly compressible step (docs/model.md, "One step"): its six stages on the grid
// (stages.hpp), and the solver object that runs it (paper_solver.cpp).
#pragma once

#include <memory>

#include "dentsph/model.hpp"
#include "dentsph/solver.hpp"
#include "dentsph/state.hpp"
#include "dentsph/step.hpp"

namespace dentsph::paper {

// The paper's solver object, the registry's factory (solver/registry.cpp).
std::unique_ptr<StepSolver> make_solver();

// The grid step (paper_step.cpp): cell keys, counting radix sort, reorder and cell ranges, density,
// pressure, forces over the neighbouring cells with the bond hysteresis of each moving particle,
// semi-implicit Euler; then the tool wrench. Its scratch is the State's own (GridIndex).
void step(const Model& model, State& state, const StepOptions& options);

}  // namespace dentsph::paper
