// The iisph solver's pressure by projected conjugate gradients (iisph.pressure_solve "cg"; docs/model.md,
// "The pressure solve"). The equations are pressure_jacobi.cpp's: for every active row i,
//   r_i = rho0_i - rho_adv_i - (A q)_i + rho_i^2 q_i / (k Kp_i),   q = p / rho^2 >= 0,
// r_i = 0 where q_i > 0 and r_i >= 0 (no compression left) where q_i = 0. The pressure force is the
// adjoint of the density's rate (pressure_jacobi.cpp), so M A is symmetric and negative semi-definite (M: the
// particles' masses), and with H = M (-A + diag(rho^2 / (k Kp))) and b = -M (rho0 - rho_adv) the
// equations are the optimality conditions of the bound-constrained quadratic programme
//   minimise f(q) = 1/2 q.H q - b.q  subject to q >= 0,   its gradient H q - b = M r,
// with H symmetric positive definite. It is solved by MPRGP (modified proportioning with reduced
// gradient projections; Dostal & Schoberl 2005, "Minimizing quadratic functions subject to bound
// constraints with the rate of convergence and finite termination"), on the unknowns scaled by H's
// diagonal, y_i = sqrt(H_ii) q_i, so that the scaled matrix has a unit diagonal (diagonal
// preconditioning; the bound q >= 0 is y >= 0). Each iteration is one of
//   - a conjugate-gradient step on the rows with pressure (the free set), as long as it stays feasible;
//   - an expansion step: the feasible part of that step, then a projected gradient step of length
//     alpha_bar, which frees and binds many rows at once. MPRGP decreases the energy for alpha_bar up
//     to 2 / |H~| (H~ the scaled matrix, unit diagonal). |H~| is under 2 on an SPH paste's system,
//     but not where paste is pressed between the tool and set paste or overlapping walls: there,
//     with alpha_bar = 1 and a budget of 400 iterations, the solve diverged (a density error of
//     1e156 at 42.2 s of the cured built-in procedure on the universal preset). alpha_bar = 0.5
//     holds to |H~| <= 4, and took fewer iterations on the uncured procedure (9.4 a step against
//     10.5; docs/model.md, "The pressure solve");
//   - a proportioning step: where the rows held at q = 0 but compressed outweigh the free rows'
//     gradient, a step that lets them push.
// Conjugate gradients carry a correction across the paste in about sqrt(condition number)
// iterations, the number of particle layers, where relaxed Jacobi takes about its square (the deep
// column of tests/physics/test_iisph_column.cpp). Each iteration costs one product with H (the two
// sweeps over the pair rows a Jacobi iteration costs) and four light passes over the rows.
//
// It stops after min_iterations once the mean error of the material rows is at most density_error and
// their largest at most max_density_error (the error of a row: |r_i| / rho0_i where it has pressure,
// max(0, -r_i) / rho0_i where not: the compression it leaves; pressure_jacobi.cpp's), and after
// max_iterations in any case (state.diagnostics.pressure_on_budget). Every sum is taken in fixed
// blocks (block_sum.hpp) and every largest and smallest is exact, so every thread count gives the
// same result bit for bit.
#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/block_sum.hpp"
#include "solver/iisph.hpp"
#include "solver/pressure_terms.hpp"

namespace dentsph::iisph {

namespace {

constexpr real kGamma = 1;     // proportioning: a step for the bound rows when |beta|^2 > Gamma^2 phi~.phi
constexpr real kAlphaBar = 0.5;  // the expansion step's projected gradient step (scaled unknowns)

// The sums of a pass over the rows (PressureSums::sum's slots).
enum Slot { kBetaBeta, kPhiTildePhi, kPhiHp, kError, kCompression, kPhiPhi };

class PressureCg {
 public:
  PressureCg(const Model& model, State& s, IisphScratch& x, int threads, Deadline deadline)
      : model_(model), s_(s), x_(x), threads_(threads), deadline_(deadline), rows_(x.active_count),
        n_material_(std::int64_t(x.material.size())), dt2_(model.dt * model.dt) {}

  // Runs the solve; leaves the pressure in state.pressure and x.q, its diagnostics in state.
  void run() {
    start();
    const IisphParams& ip = model_.iisph;
    PressureSums st = gradient_and_stats();
    int it = 0;
    while (it < ip.max_iterations) {
      if (it >= ip.min_iterations && converged(st)) break;
      if (it >= ip.min_iterations && stops_at_deadline(mean(st.sum[kError]), ip.density_error, deadline_) &&
          st.max <= kDeadlineErrorFactor * ip.max_density_error) {
        s_.diagnostics.on_deadline = true;
        break;
      }
      const real bb = st.sum[kBetaBeta], phi_phi = st.sum[kPhiPhi];
      if (bb == 0 && phi_phi == 0) break;  // the solution, exactly
      ++it;
      if (bb <= kGamma * kGamma * st.sum[kPhiTildePhi] && phi_phi > 0) {
        // Along the free rows' direction (pc_dir): as far as conjugate gradients go, or to the bound.
        const PressureSums prod = product();  // pHp, gp, alpha_f
        const real php = prod.sum[0], gp = prod.sum[1], alpha_feasible = -prod.max;  // max of -y/p
        if (!(php > 0)) break;  // a direction with no curvature: nothing left to gain (never expected)
        const real alpha_cg = gp / php;
        if (alpha_cg <= alpha_feasible) {
          st = move(alpha_cg);
          const real gamma = st.sum[kPhiHp] / php;
          next_direction_conjugate(gamma);
        } else {
          move(alpha_feasible);
          project_gradient_step();
          st = gradient_and_stats();
        }
      } else {
        // Proportioning: the bound rows that are compressed push (pc_dir = beta).
        direction_from_beta();
        const PressureSums prod = product();
        const real php = prod.sum[0], gp = prod.sum[1];
        if (!(php > 0)) break;
        st = move(gp / php);
        direction_from_phi();
      }
    }
    finish(it, st);
  }

 private:
  bool converged(const PressureSums& st) const {
    return mean(st.sum[kError]) <= model_.iisph.density_error && st.max <= model_.iisph.max_density_error;
  }
  real mean(real sum) const { return n_material_ > 0 ? sum / real(n_material_) : 0; }
  bool material(std::uint32_t i) const { return s_.role[i] == Role::material; }

  // fn(i) for every active row in parallel, summed (block_sum.hpp).
  template <class F>
  PressureSums summed(F&& fn) {
    return for_rows_summed(rows_, threads_, x_.pc_partial.data(), [&](std::int64_t k) { return fn(x_.active[k]); });
  }
  template <class F>
  void each(F&& fn) {
#pragma omp parallel for num_threads(threads_) schedule(static)
    for (std::int64_t k = 0; k < rows_; ++k) fn(x_.active[k]);
  }

  // The right-hand sides, the scales and the start: the last step's pressure times warm_start.
  void start() {
    const std::int64_t n = s_.size();
    real* dir = x_.pc_dir.data();
#pragma omp parallel for num_threads(threads_) schedule(static)
    for (std::int64_t i = 0; i < n; ++i) dir[i] = 0;  // rows outside the solve stay 0
    each([&](std::uint32_t i) {
      pressure_source(model_, s_, x_, i);
      const real ir2 = x_.inv_rho[i] * x_.inv_rho[i];
      const real h_ii = s_.mass[i] * (dt2_ * x_.diag_x[i] + pressure_compliance(model_, s_, i) / ir2);
      x_.pc_scale[i] = std::sqrt(h_ii);
      const real q = std::max<real>(0, model_.iisph.warm_start * s_.pressure[i]) * ir2;
      x_.q[i] = q;
      x_.pc_y[i] = x_.pc_scale[i] * q;
    });
  }

  // (H u)_i for the q-field u (0 outside the solve): uses x.accel.
  real h_times(const real* u, std::uint32_t i) const {
    const real ir2 = x_.inv_rho[i] * x_.inv_rho[i];
    return s_.mass[i] * (-pressure_density_change(x_, i, material(i), dt2_) +
                         pressure_compliance(model_, s_, i) * u[i] / ir2);
  }

  // The gradient H q - b, scaled, from y afresh (the start, and after an expansion step); then the
  // statistics and the free rows' gradient as the next direction.
  PressureSums gradient_and_stats() {
    each([&](std::uint32_t i) { x_.q[i] = x_.pc_y[i] / x_.pc_scale[i]; });
    pressure_accelerations(x_, x_.q.data(), threads_);
    each([&](std::uint32_t i) {
      x_.pc_g[i] = (h_times(x_.q.data(), i) + s_.mass[i] * x_.source[i]) / x_.pc_scale[i];
    });
    const PressureSums st = stats();
    direction_from_phi();
    return st;
  }

  // H times the direction (scaled, into pc_hp): sum[0] p.Hp, sum[1] g.p, max the largest -y_i / p_i
  // over p_i > 0 (minus the longest feasible step; -inf where none bounds it).
  PressureSums product() {
    pressure_accelerations(x_, x_.pc_dir.data(), threads_);
    return summed([&](std::uint32_t i) {
      const real sc = x_.pc_scale[i];
      const real hp = h_times(x_.pc_dir.data(), i) / sc;
      x_.pc_hp[i] = hp;
      const real p = x_.pc_dir[i] * sc;
      PressureSums r;
      r.sum[0] = p * hp;
      r.sum[1] = x_.pc_g[i] * p;
      if (p > 0) r.max = -x_.pc_y[i] / p;
      return r;
    });
  }

  // y -= alpha p, g -= alpha Hp (y kept >= 0 against rounding); the statistics of the new point.
  PressureSums move(real alpha) {
    return summed([&](std::uint32_t i) {
      x_.pc_y[i] = std::max<real>(0, x_.pc_y[i] - alpha * x_.pc_dir[i] * x_.pc_scale[i]);
      x_.pc_g[i] -= alpha * x_.pc_hp[i];
      return row_stats(i);
    });
  }

  // y = max(0, y - alpha_bar phi(y)).
  void project_gradient_step() {
    each([&](std::uint32_t i) {
      const real y = x_.pc_y[i];
      if (y > 0) x_.pc_y[i] = std::max<real>(0, y - kAlphaBar * x_.pc_g[i]);
    });
  }

  PressureSums stats() {
    return summed([&](std::uint32_t i) { return row_stats(i); });
  }

  // One row's terms: beta.beta, phi~.phi, phi.Hp, its error and compression (material rows), phi.phi.
  PressureSums row_stats(std::uint32_t i) const {
    PressureSums r;
    const real y = x_.pc_y[i], g = x_.pc_g[i];
    if (y > 0) {
      const real phi_tilde = g > 0 ? std::min(y / kAlphaBar, g) : g;
      r.sum[kPhiTildePhi] = phi_tilde * g;
      r.sum[kPhiHp] = g * x_.pc_hp[i];
      r.sum[kPhiPhi] = g * g;
    } else if (g < 0) {
      r.sum[kBetaBeta] = g * g;
    }
    if (material(i)) {
      // r_i in density units: the gradient is M r, scaled by 1 / sqrt(H_ii).
      const real res = g * x_.pc_scale[i] / s_.mass[i];
      const real inv_rho0 = 1 / s_.rho0[i];
      const real err = (y > 0 ? std::abs(res) : std::max<real>(0, -res)) * inv_rho0;
      r.sum[kError] = err;
      r.max = err;
      const real p_compliance = y / x_.pc_scale[i] / (x_.inv_rho[i] * x_.inv_rho[i]) * pressure_compliance(model_, s_, i);
      r.sum[kCompression] = std::max<real>(0, p_compliance - res) * inv_rho0;
    }
    return r;
  }

  // The next direction: the free rows' gradient (after an expansion or a proportioning step).
  void direction_from_phi() {
    each([&](std::uint32_t i) { x_.pc_dir[i] = x_.pc_y[i] > 0 ? x_.pc_g[i] / x_.pc_scale[i] : 0; });
  }
  // phi - gamma p, conjugate to the last direction.
  void next_direction_conjugate(real gamma) {
    each([&](std::uint32_t i) {
      const real phi = x_.pc_y[i] > 0 ? x_.pc_g[i] : 0;
      x_.pc_dir[i] = phi / x_.pc_scale[i] - gamma * x_.pc_dir[i];
    });
  }
  // The bound rows' chopped gradient beta = min(g, 0) where y = 0.
  void direction_from_beta() {
    each([&](std::uint32_t i) {
      x_.pc_dir[i] = x_.pc_y[i] > 0 ? 0 : std::min<real>(0, x_.pc_g[i]) / x_.pc_scale[i];
    });
  }

  // The pressures, their accelerations and v* + dt a_p; the diagnostics.
  void finish(int it, const PressureSums& st) {
    each([&](std::uint32_t i) {
      const real q = x_.pc_y[i] / x_.pc_scale[i];
      x_.q[i] = q;
      s_.pressure[i] = q * s_.rho[i] * s_.rho[i];
    });
    pressure_accelerations(x_, x_.q.data(), threads_);
    apply_pressure_accelerations(model_, x_, threads_);
    StepDiagnostics& d = s_.diagnostics;
    d.pressure_iterations = it;
    d.pressure_on_budget = it >= model_.iisph.max_iterations && !converged(st);
    d.density_error = mean(st.sum[kCompression]);
    d.pressure_residual = mean(st.sum[kError]);
    d.pressure_max_error = std::max<real>(0, st.max);
  }

  const Model& model_;
  State& s_;
  IisphScratch& x_;
  int threads_;
  Deadline deadline_;
  std::int64_t rows_, n_material_;
  real dt2_;
};

}  // namespace

void solve_pressure_cg(const Model& model, State& s, IisphScratch& x, int threads, Deadline deadline) {
  PressureCg(model, s, x, threads, deadline).run();
}

}  // namespace dentsph::iisph
