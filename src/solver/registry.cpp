// The solvers, listed in one place (dentsph/solver.hpp): each by its key, its name and its factory.
// Scene files' simulation.solver, --solver, the summary and the bench go by this list. Adding a
// solver: its folder (its step and its StepSolver), a key in the Solver enum (model.hpp) and a line
// here.
#include <array>
#include <stdexcept>

#include <fmt/format.h>

#include "dentsph/solver.hpp"
#include "solver/iisph.hpp"
#include "step/paper.hpp"

namespace dentsph {

namespace {

constexpr std::array kSolvers{
    SolverEntry{Solver::paper, "paper", &paper::make_solver},
    SolverEntry{Solver::iisph, "iisph", &iisph::make_solver},
};

const SolverEntry& entry(Solver key) {
  for (const SolverEntry& e : kSolvers)
    if (e.key == key) return e;
  throw std::invalid_argument(fmt::format("solver {}: not registered (src/solver/registry.cpp)", int(key)));
}

}  // namespace

std::span<const SolverEntry> registered_solvers() { return kSolvers; }

std::unique_ptr<StepSolver> make_solver(Solver key) { return entry(key).make(); }

const StepSolver& solver_properties(Solver key) {
  // One object of each, made on first use (never stepped: its buffers stay empty).
  static const std::array<std::unique_ptr<StepSolver>, kSolvers.size()> objects = [] {
    std::array<std::unique_ptr<StepSolver>, kSolvers.size()> made;
    for (std::size_t k = 0; k < kSolvers.size(); ++k) made[k] = kSolvers[k].make();
    return made;
  }();
  const SolverEntry& e = entry(key);  // throws for a key not registered
  return *objects[std::size_t(&e - kSolvers.data())];
}

const char* solver_name(Solver s) {
  for (const SolverEntry& e : kSolvers)
    if (e.key == s) return e.name;
  return "unknown";
}

std::optional<Solver> solver_from_name(std::string_view name) {
  for (const SolverEntry& e : kSolvers)
    if (name == e.name) return e.key;
  return std::nullopt;
}

std::string solver_choices() {
  std::string out;
  for (std::size_t k = 0; k < kSolvers.size(); ++k) {
    if (k > 0) out += k + 1 == kSolvers.size() ? " or " : ", ";
    out += kSolvers[k].name;
  }
  return out;
}

}  // namespace dentsph
