// The iisph solver's viscous pressure (iisph.viscous_pressure; docs/model.md, "The viscous pressure"):
// the pressure a viscous paste needs to stay incompressible, which the step's pressure solve cannot
// give it. The step solves the pressure first (as if the paste had no viscosity), then the viscosity
// (backward Euler). Where the viscosity dominates (its weight dt mu / (rho h^2) is 10^4 for the universal
// preset at 10 /s and dt = 1.5 ms), the viscosity solve takes back almost all of the velocity by which the
// pressure undid a compression: the paste measured 1.7% (flowable) to 3.3% (universal) compressed on
// the built-in procedure, the predicted 0.05%. Solving the pressure after the viscosity instead leaves
// the pressure's velocities undamped, and the run diverged within 0.3 s on every preset.
//
// The viscous pressure p_v is the Uzawa iteration of the coupled (Stokes) problem, one iteration a
// step: after the viscosity, each material particle's density at the step's end is predicted from
// v**, and
//   p_v <- clamp(p_v + alpha mu_u (rho_end / rho0 - 1) / dt,  0,  k Kp max(0, rho_end - rho0))
// with alpha = iisph.viscous_pressure. mu (rho_end / rho0 - 1) / dt is the viscous stress of the flow
// that would undo the error within a step: Uzawa's step for a Stokes flow is the viscosity, as its
// pressure Schur complement is about the identity over mu. mu_u is the smaller of the particle's
// effective viscosity in this step's solve and the material's at the rate |rho_end / rho0 - 1| / dt
// (a paste held below its yield stress has its regularisation's cap, 10^6 Pa s: a step sized by that
// would throw it once it yields). The bound is the equation of state's pressure at the compression
// left: the paste is no stiffer than its Kp says, and a particle wedged where it cannot expand (between
// the instrument and set paste) holds a bounded pressure instead of a growing one. Its force, the
// symmetric pressure force of p_v on material and the instrument, joins the pressure's before the next
// step's viscosity solve (push_viscous_pressure), so that the viscosity, solved last, damps it.
//
// p_v is the State's, kept by particle id (State::viscous_pressure), so that the reorder does not move
// it: a copy of the State carries its own, and particles removed take theirs out
// (State::remove_particles); particles added start from zero.
#include <algorithm>
#include <cmath>

#include "physics/rheology.hpp"
#include "solver/iisph.hpp"
#include "solver/pressure_terms.hpp"

namespace dentsph::iisph {

void push_viscous_pressure(const Model& model, State& s, IisphScratch& x, int threads) {
  const std::int64_t n = s.size();
  // Made by the first step that solves it; add_particles and remove_particles keep it one by id.
  if (s.viscous_pressure.empty()) s.viscous_pressure.assign(s.size(), 0);
  const real* pv = s.viscous_pressure.data();
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
    x.q_viscous[i] = s.role[i] == Role::material ? pv[s.id[i]] * x.inv_rho[i] * x.inv_rho[i] : 0;
  // The pressure's own force and update (pressure_terms.hpp), with q = 0 for the walls and the
  // instrument: x.accel, read by nothing after the solve's, is free.
  pressure_accelerations(x, x.q_viscous.data(), threads);
  apply_pressure_accelerations(model, x, threads);
}

void update_viscous_pressure(const Model& model, State& s, IisphScratch& x, int threads) {
  const std::int64_t nm = std::int64_t(x.material.size());
  const real dt = model.dt, alpha = model.iisph.viscous_pressure, k = model.iisph.stiffness;
  real most = 0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(max : most)
  for (std::int64_t m = 0; m < nm; ++m) {
    const std::uint32_t i = x.material[m];
    const real rho_end = density_at_step_end(s, x, i, dt);  // from v**
    const real error = rho_end / s.rho0[i] - 1;
    real mu = particle_viscosity(model, s, i, std::abs(error) / dt);
    if (x.rheology) mu = std::min(mu, x.mu_eff[i]);
    const real bound = k * s.Kp[i] * std::max<real>(0, rho_end - s.rho0[i]);
    real& p = s.viscous_pressure[s.id[i]];
    p = std::clamp<real>(p + alpha * mu * error / dt, 0, bound);
    most = std::max(most, p);
  }
  s.diagnostics.viscous_pressure_max = most;
}

}  // namespace dentsph::iisph
