// The iisph solver as an object (dentsph/solver.hpp): its scratch, sized for the State it steps,
// its step (iisph_step.cpp) and what it answers about itself: no acoustic or viscous limit (pressure
// and viscosity are implicit), the velocity CFL condition dt <= cfl h / max|v| instead, two layers of
// instrument particles, the wall field, and the pressure solve's figures over a run.
#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "solver/iisph.hpp"

namespace dentsph::iisph {

namespace {

constexpr real inf = std::numeric_limits<real>::infinity();

class IisphSolver final : public StepSolver {
 public:
  Solver key() const override { return Solver::iisph; }
  const char* name() const override { return "iisph"; }
  const char* description() const override { return "implicit pressure and viscosity; docs/model.md"; }

  void resize(const Model& model, const State& state) override {
    x_.resize(state, has_rheology(model), model.iisph.viscous_pressure > 0);
    list_material(state, x_);
    layout_ = state.layout_stamp;
    listed_ = state.order_stamp;
  }

  void step(const Model& model, State& state, const StepOptions& options) override {
    // Particles were added or removed since the scratch was sized (or this is another State): sized
    // again. The lists of material and tool particles follow the State's order: a State reordered
    // since they were made (another one, or a copy stepped meanwhile) is listed again.
    if (state.layout_stamp != layout_ || has_rheology(model) != x_.rheology ||
        (model.iisph.viscous_pressure > 0) != x_.with_viscous_pressure) {
      resize(model, state);
    } else if (state.order_stamp != listed_) {
      list_material(state, x_);
    }
    iisph::step(model, state, x_, options);
    listed_ = state.order_stamp;  // a rebuild listed them in the new order
  }

  std::size_t bytes() const override { return x_.bytes(); }

  real default_time_step() const override { return 1.5e-3; }

  void set_limits(const Model& model, real, StabilityLimits& l) const override {
    l.acoustic = inf;
    l.viscous = inf;
    l.sound_speed = model.kernel.h / model.dt;
  }
  real motion_limit(const Model& model, const StepDiagnostics& d) const override {
    return velocity_time_step_limit(model, d.max_speed);
  }
  const char* motion_limit_name() const override { return "velocity CFL"; }
  real tool_speed_limit(const Model& model, real tool_speed) const override {
    return velocity_time_step_limit(model, tool_speed);
  }

  std::string time_step_problem(const Model& model, const StabilityLimits& l, real v) const override {
    // The velocity CFL condition, against the fastest the scene's tool moves (the material moves
    // with it or slower; a device's hand is checked as it goes, by the force limit entry).
    const real dt = model.dt, limit = velocity_time_step_limit(model, v);
    if (dt > l.capillary)
      return fmt::format(
          "simulation.dt: {:.3g} s is over the surface tension's limit of {:.3g} s (iisph.surface_tension {:.3g} N/m: "
          "the larger of sqrt(rho0 h^3 / (2 pi sigma)) and the paste's viscosity times h / sigma); set simulation.dt "
          "to at most {:.3g}, lower iisph.surface_tension, or pass --allow-unstable to run anyway",
          dt, l.capillary, model.iisph.surface_tension, l.capillary);
    if (!(dt > limit)) return "";
    return fmt::format(
        "simulation.dt: {:.3g} s is over the iisph solver's velocity CFL limit of {:.3g} s (cfl {:.3g} * h {:.3g} m "
        "/ {:.3g} m/s, the tool's fastest speed between its keyframes); set simulation.dt to at most {:.3g}, slow "
        "the tool, or pass --allow-unstable to run anyway",
        dt, limit, model.iisph.cfl, model.kernel.h, v, limit);
  }
  std::string time_step_report(const Model& model, const StabilityLimits& l, real v) const override {
    return fmt::format("dt = {:.4g} s; limit: velocity CFL {:.4g} s = {:.2g} h / {:.4g} m/s (the tool's fastest); the "
                       "paper's step's acoustic {:.4g} s and viscous {:.4g} s do not bind it",
                       model.dt, velocity_time_step_limit(model, v), model.iisph.cfl, v, l.paper_acoustic,
                       l.paper_viscous);
  }

  int instrument_layers() const override { return 2; }
  bool uses_walls() const override { return true; }

  void record(SolverStatistics& s, const StepDiagnostics& d) const override {
    s.recorded = true;
    ++s.steps;
    s.iterations_sum += d.pressure_iterations;
    s.iterations_max = std::max(s.iterations_max, d.pressure_iterations);
    s.density_error_sum += d.density_error;
    s.density_error_max = std::max<double>(s.density_error_max, d.density_error);
    s.pressure_residual_max = std::max<double>(s.pressure_residual_max, d.pressure_residual);
    s.compression_sum += d.compression_mean;
    s.compression_mean_max = std::max<double>(s.compression_mean_max, d.compression_mean);
    s.compression_max = std::max<double>(s.compression_max, d.compression_max);
    s.viscous_pressure_max = std::max<double>(s.viscous_pressure_max, d.viscous_pressure_max);
    if (d.pressure_on_budget) {
      ++s.on_budget_steps;
      s.on_budget_residual_max = std::max<double>(s.on_budget_residual_max, d.pressure_residual);
    }
    s.pressure_max_error = std::max<double>(s.pressure_max_error, d.pressure_max_error);
    if (d.on_deadline) {
      ++s.on_deadline_steps;
      s.on_deadline_residual_max = std::max<double>(s.on_deadline_residual_max, d.pressure_residual);
    }
    s.viscosity_iterations_sum += d.viscosity_iterations;
    s.viscosity_iterations_max = std::max(s.viscosity_iterations_max, d.viscosity_iterations);
    s.viscosity_residual_sum += d.viscosity_residual;
    s.viscosity_residual_max = std::max<double>(s.viscosity_residual_max, d.viscosity_residual);
    if (d.rheology_iterations > 0) {
      s.viscosity_min = s.rheology_iterations_sum > 0 ? std::min<double>(s.viscosity_min, d.viscosity_min) : d.viscosity_min;
      s.viscosity_max = std::max<double>(s.viscosity_max, d.viscosity_max);
      s.rheology_iterations_sum += d.rheology_iterations;
      s.rheology_iterations_max = std::max(s.rheology_iterations_max, d.rheology_iterations);
    }
    s.wall_projections += d.wall_projections;
    s.wall_projection_steps += d.wall_projections > 0;
    s.substepped_steps += d.substeps > 1;
    s.substeps_max = std::max(s.substeps_max, d.substeps);
    s.held_outside_domain = d.held;
  }

 private:
  IisphScratch x_;
  std::uint64_t layout_ = 0, listed_ = 0;  // the State stamps the scratch was sized and listed for
};

}  // namespace

std::unique_ptr<StepSolver> make_solver() { return std::make_unique<IisphSolver>(); }

}  // namespace dentsph::iisph
