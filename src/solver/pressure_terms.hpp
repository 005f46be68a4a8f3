// The pressure solve's terms shared by its two methods (pressure_jacobi.cpp: relaxed Jacobi; pressure_cg.cpp:
// projected conjugate gradients): the pressure accelerations of a field q = p / rho^2, the density
// change they make over the step, and each row's right-hand side. pressure_jacobi.cpp's header comment
// derives the system.
#pragma once

#include <algorithm>

#include <cstdint>

#include "dentsph/model.hpp"
#include "dentsph/state.hpp"
#include "solver/scratch.hpp"

namespace dentsph::iisph {

inline const SolverPair* pressure_row(const IisphScratch& x, std::uint32_t i) {
  return x.pairs.data() + std::size_t(i) * IisphScratch::kPairStride;
}

// The pressure acceleration of every material particle, into x.accel, from q[] (p / rho^2; 0 for rows
// outside the solve).
inline void pressure_accelerations(IisphScratch& x, const real* q, int threads) {
  const std::int64_t n = std::int64_t(x.material.size());
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t m = 0; m < n; ++m) {
    const std::uint32_t i = x.material[m];
    const SolverPair* row = pressure_row(x, i);
    Vec3 a = x.grad_sum[i] * q[i];
    for (std::uint32_t e = 0; e < x.n_material[i]; ++e) a += row[e].grad() * q[row[e].j];
    for (std::uint32_t e = IisphScratch::kPairStride - x.n_other[i]; e < IisphScratch::kPairStride; ++e)
      a += row[e].grad() * q[row[e].j];
    x.accel[i] = -a;
  }
}

// The density change x.accel makes over the step at row i, dt^2 sum_j m_j (a_i - a_j) . gradW_ij.
inline real pressure_density_change(const IisphScratch& x, std::uint32_t i, bool material, real dt2) {
  const SolverPair* row = pressure_row(x, i);
  real ap = material ? dot(x.accel[i], x.grad_sum[i]) : 0;
  for (std::uint32_t e = 0; e < x.n_material[i]; ++e) ap -= dot(x.accel[row[e].j], row[e].grad());
  return ap * dt2;
}

// Row i's density at the end of the step were the particles to move at x.v_a (boundary, tool: their
// velocity), rho_i + dt sum_j m_j (v_i - v_j) . gradW_ij: material over every neighbour; boundary
// and tool, the material neighbours' motion alone (what a solve can change).
inline real density_at_step_end(const State& s, const IisphScratch& x, std::uint32_t i, real dt) {
  const Vec3* v = x.v_a.data();
  const SolverPair* row = pressure_row(x, i);
  const bool material = s.role[i] == Role::material;
  real div = material ? dot(v[i], x.grad_sum[i]) - x.div_fixed[i] : 0;
  for (std::uint32_t e = 0; e < x.n_material[i]; ++e) div += dot((material ? Vec3{} : v[i]) - v[row[e].j], row[e].grad());
  return s.rho[i] + dt * div;
}

// The p / rho^2 the pressure force between particles i and j carries (its symmetric form's q_i + q_j):
// the solve's, and the viscous pressure's where it runs (material's alone: 0 for walls and the tool;
// viscous_pressure.cpp). The tool's wrench and the contact's strength read it (finish.cpp,
// interface.cpp).
inline real pair_q(const IisphScratch& x, std::uint32_t i, std::uint32_t j) {
  const real q = x.q[i] + x.q[j];
  return x.with_viscous_pressure ? q + x.q_viscous[i] + x.q_viscous[j] : q;
}

// Row i's right-hand side, rho0 - rho_adv (rho_adv: the density at the end of the step without
// pressure, from v* in x.v_a), into x.source. With iisph.wall_rest_density, a boundary particle's
// target is the larger of rho0 and its walls' own density (rho_static): where walls overlap (paste
// that set against the tooth's lining) the walls alone are denser than rho0, which no motion of the
// paste can undo, and a stiff paste's solve pushes it away with the whole excess's pressure (Kp 1e4:
// megapascals; docs/model.md, "Presets").
inline void pressure_source(const Model& model, const State& s, IisphScratch& x, std::uint32_t i) {
  const real target = s.role[i] == Role::boundary && model.iisph.wall_rest_density
                          ? std::max(s.rho0[i], s.rho_static[s.id[i]])
                          : s.rho0[i];
  x.source[i] = target - density_at_step_end(s, x, i, model.dt);  // from v* in x.v_a
}

// 1 / (stiffness Kp_i): kg/m^3 per Pa, rho - rho0 = p / (stiffness Kp).
inline real pressure_compliance(const Model& model, const State& s, std::uint32_t i) {
  return 1 / (model.iisph.stiffness * s.Kp[i]);
}

// v* + dt a_p of every material particle (x.accel from the solve's pressures): the viscosity's start
// and right-hand side.
inline void apply_pressure_accelerations(const Model& model, IisphScratch& x, int threads) {
  const std::int64_t n = std::int64_t(x.material.size());
  const real dt = model.dt;
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t m = 0; m < n; ++m) {
    const std::uint32_t i = x.material[m];
    x.v_star[i] += x.accel[i] * dt;
    x.v_a[i] = x.v_star[i];
  }
}

}  // namespace dentsph::iisph
