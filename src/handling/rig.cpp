// The handling tests' rigs (rig.hpp).
#include "handling/rig.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "dentsph/step.hpp"

namespace dentsph::handling {

ModelParams rig_params(real s, const Vec3& lo, const Vec3& hi, real dt, const Vec3& gravity) {
  ModelParams p;
  p.dt = dt;
  p.h = 2 * s;
  p.gravity = gravity;
  p.adhesion.A = 1.2 * s;
  p.adhesion.B = 3 * s;
  p.domain_min = lo;
  p.domain_max = hi;
  p.solver = Solver::iisph;
  p.iisph.pressure_solve = PressureSolve::cg;
  p.iisph.max_iterations = 200;
  p.iisph.viscosity_tolerance = 1e-4;
  p.iisph.viscosity_iterations = 500;
  return p;
}

Material wall_beside(const Material& paste) { return Material{paste.mu, 1.5 * paste.Kp, paste.rho0, 0}; }

void rig_step(const Model& model, State& state, const HandlingRunOptions& run, const std::string& test) {
  step(model, state, StepOptions{run.threads, nullptr});
  if (state.diagnostics.non_finite != 0)
    throw std::runtime_error(fmt::format("the {} test: {} particles' state is not finite at t = {:.3f} s", test,
                                         state.diagnostics.non_finite, state.time));
}

}  // namespace dentsph::handling
