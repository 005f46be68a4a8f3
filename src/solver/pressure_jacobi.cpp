// The iisph solver's pressure: the paper's equation of state, P = max(0, k Kp (rho - rho0)) with
// k = model.iisph.stiffness (0.5: the paper's paste's stiffness, as its eq. 5 turns only half of a
// pressure gradient into force; model.hpp), taken at the end of the step (backward Euler) instead of
// its start, with every particle's density as in the paper (material, boundary and tool particles
// each have one, and a pressure). Below, Kp stands for k Kp. The pressures p >= 0
// are those for which the density predicted at the end of the step,
//   rho_pred,i = rho_i + dt sum_j m_j (v_i - v_j) . gradW_ij,   v = v* + dt a_p for material, given otherwise,
// satisfies p_i = Kp_i (rho_pred,i - rho0_i) where p_i > 0, and rho_pred,i <= rho0_i where p_i = 0.
// Only material moves, by the symmetric pressure acceleration
//   a_p,i = - sum_j m_j (p_i/rho_i^2 + p_j/rho_j^2) gradW_ij      (j over every neighbour)
// (gradW: the cubic spline's, kernels.hpp). Its power is -sum_i m_i p_i/rho_i^2 (d rho_i / dt): the
// pressure force is the adjoint of the density's rate, so the system below is symmetric (in
// m p / rho^2) and the pressure of the linearised step only takes kinetic energy out. For row i,
//   (A p)_i = dt^2 sum_j m_j (a_p,i - a_p,j) . gradW_ij        (a_p = 0 for boundary and tool)
//   (A p)_i - p_i / Kp_i = rho0_i - rho_adv_i,                   rho_adv from v* (no pressure)
// solved by relaxed Jacobi, p_i += omega r_i / a_ii, clamped at 0 (the paper's pressure only repels),
// from the last step's pressure times model.iisph.warm_start. The compliance 1 / Kp is what makes
// this cheap: at the dental paste's Kp and dt = 1 ms it outweighs the kernel part of the diagonal,
// and the pressure changes little from step to step, so two or three iterations from the last
// pressure reach 0.03% (docs/model.md). As Kp grows the solve becomes IISPH's (Ihmsen et al. 2014,
// "Implicit Incompressible SPH"). Each iteration is two sweeps over the pair rows; it stops after
// min_iterations once the mean error of the material rows is below density_error, and after
// max_iterations in any case.
#include <algorithm>

#include "solver/block_sum.hpp"
#include "solver/iisph.hpp"
#include "solver/pressure_terms.hpp"

namespace dentsph::iisph {

namespace {

// The start of row i: its right-hand side, and the last step's pressure times warm_start.
void start_row(const Model& model, State& s, IisphScratch& x, std::uint32_t i) {
  pressure_source(model, s, x, i);
  const real p = model.iisph.warm_start * s.pressure[i];
  s.pressure[i] = p;
  x.q[i] = p * x.inv_rho[i] * x.inv_rho[i];
}

}  // namespace

void solve_pressure_jacobi(const Model& model, State& s, IisphScratch& x, int threads, Deadline deadline) {
  const std::int64_t rows = x.active_count, n_material = std::int64_t(x.material.size());
  const real dt2 = model.dt * model.dt;
  const IisphParams& ip = model.iisph;
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t k = 0; k < rows; ++k) start_row(model, s, x, x.active[k]);
  int it = 0;
  real mean_error = 0, mean_compression = 0, last_error = -1;
  real omega = ip.omega;
  while (it < ip.max_iterations) {
    pressure_accelerations(x, x.q.data(), threads);
    // The update of every active row, and the sums of the material rows' error and compression
    // in the same pass (block_sum.hpp: the same sums, bit for bit, on every thread count).
    const Vec3 sums = for_rows_summed(rows, threads, x.partial.data(), [&](std::int64_t k) {
      const std::uint32_t i = x.active[k];
      const bool material = s.role[i] == Role::material;
      const real compliance = pressure_compliance(model, s, i);
      // rho0 - rho_predicted + p / (k Kp): zero where the equation of state holds at the end of the step
      const real residual = x.source[i] - pressure_density_change(x, i, material, dt2) + s.pressure[i] * compliance;
      // The solve's error: where the pressure pushes, the equation of state's; where it is 0, the
      // compression it leaves (expansion is free).
      Vec3 terms;
      if (material) {
        terms.x = (s.pressure[i] > 0 ? std::abs(residual) : std::max<real>(0, -residual)) / s.rho0[i];
        terms.y = std::max<real>(0, s.pressure[i] * compliance - residual) / s.rho0[i];
      }
      const real ir2 = x.inv_rho[i] * x.inv_rho[i];
      const real diag = -dt2 * ir2 * x.diag_x[i] - compliance;
      const real p = std::max<real>(0, s.pressure[i] + omega * residual / diag);
      s.pressure[i] = p;
      x.q[i] = p * ir2;
      return terms;
    });
    ++it;
    mean_error = n_material > 0 ? sums.x / real(n_material) : 0;
    mean_compression = n_material > 0 ? sums.y / real(n_material) : 0;
    if (it >= ip.min_iterations && mean_error <= ip.density_error) break;
    if (it >= ip.min_iterations && stops_at_deadline(mean_error, ip.density_error, deadline)) {
      s.diagnostics.on_deadline = true;
      break;
    }
    // Relaxed Jacobi converges for omega below 2 / (largest eigenvalue of diag^-1 A), which grows
    // with dt^2 / compliance: where the error grows, the relaxation halves (for the rest of the solve).
    if (last_error >= 0 && mean_error > 1.25 * last_error) omega *= 0.5;
    last_error = mean_error;
  }
  pressure_accelerations(x, x.q.data(), threads);  // of the pressures the solve ends with
  apply_pressure_accelerations(model, x, threads);
  s.diagnostics.pressure_iterations = it;
  s.diagnostics.pressure_on_budget = it >= ip.max_iterations && mean_error > ip.density_error;
  s.diagnostics.density_error = mean_compression;
  s.diagnostics.pressure_residual = mean_error;
  s.diagnostics.pressure_max_error = 0;
}

}  // namespace dentsph::iisph
