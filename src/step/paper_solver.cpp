// The paper's step as a solver object (dentsph/solver.hpp). Its scratch is the State's (the grid's
// buffers, sized with the particles), so it has none of its own; it is explicit in pressure,
// viscosity and adhesion, so the acoustic, viscous and force limits bind it (docs/model.md, "Stability").
#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "dentsph/limits.hpp"
#include "step/paper.hpp"

namespace dentsph::paper {

namespace {

constexpr real inf = std::numeric_limits<real>::infinity();

class PaperSolver final : public StepSolver {
 public:
  Solver key() const override { return Solver::paper; }
  const char* name() const override { return "paper"; }
  const char* description() const override { return "the paper's explicit step"; }

  void resize(const Model&, const State&) override {}
  void step(const Model& model, State& state, const StepOptions& options) override {
    paper::step(model, state, options);
  }
  std::size_t bytes() const override { return 0; }

  real default_time_step() const override { return 5e-5; }

  void set_limits(const Model&, real kp_max, StabilityLimits& l) const override {
    l.acoustic = l.paper_acoustic;
    l.viscous = l.paper_viscous;
    l.sound_speed = std::sqrt(kp_max);
  }
  real motion_limit(const Model& model, const StepDiagnostics& d) const override {
    return d.max_accel > 0 ? 0.25 * std::sqrt(model.kernel.h / d.max_accel) : inf;
  }
  const char* motion_limit_name() const override { return "force"; }
  real tool_speed_limit(const Model&, real) const override { return inf; }

  std::string time_step_problem(const Model& model, const StabilityLimits& l, real) const override {
    const std::string excess = time_step_excess(model.dt, l);
    if (excess.empty()) return "";
    const real limit = std::min(l.acoustic, l.viscous);
    if (limit < limits::min_dt)
      return fmt::format("{}; no time step the program takes (at least {:.0e} s) is under it: lower the stiffest "
                         "material's stiffness or viscosity, raise its rest density, or choose the iisph solver "
                         "(simulation.solver, --solver iisph)",
                         excess, limits::min_dt);
    return fmt::format("{}; set simulation.dt to at most {:.3g}, lower the stiffest material's stiffness or viscosity, "
                       "choose the iisph solver (simulation.solver, --solver iisph), or pass --allow-unstable to run "
                       "anyway",
                       excess, std::min(l.acoustic, l.viscous));
  }
  std::string time_step_report(const Model& model, const StabilityLimits& l, real) const override {
    return fmt::format("dt = {:.4g} s; limits: acoustic {:.4g} s, viscous {:.4g} s", model.dt, l.acoustic, l.viscous);
  }

  int instrument_layers() const override { return 1; }
  bool uses_walls() const override { return false; }
};

}  // namespace

std::unique_ptr<StepSolver> make_solver() { return std::make_unique<PaperSolver>(); }

}  // namespace dentsph::paper
