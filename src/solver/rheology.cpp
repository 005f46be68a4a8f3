// A non-Newtonian material's viscosity in the iisph solver (docs/model.md, "Rheology"). Where the
// model has one, the pair pass leaves each row's viscosity weight without the viscosity (the unit
// weight of the projected form below, over rho_j; kept here the first time in a step: the advection
// pass's sums of the unit weights are replaced here), and each Picard iteration
// of the viscosity solve (viscosity.cpp) calls update_viscosity: every material particle's velocity
// gradient from its material neighbours, L_i = A_i M_i^-1 with A_i = sum_j (v_j - v_i) (x) V_j gradW_ij
// and M_i = sum_j (x_j - x_i) (x) V_j gradW_ij (the row's pressure gradient; the correction of Bonet &
// Lok 1999), exact for a linear field wherever the neighbours span space, at a wall and a free surface
// too (the boundary's particles, all at the wall's velocity, would bend a sheared layer's gradient
// there: measured 12% off the profile of a sheared power-law paste with them); its shear rate
// sqrt(2 D:D), raised to the instrument's slip rate where that is larger (below), its effective
// viscosity (physics/rheology.hpp; paste the cure has
// changed keeps its Newtonian viscosity), and then every row's weights c_ij = mu_ij times the unit
// weight, mu_ij = (mu_i + mu_j) / 2 between two material particles and mu_i against the boundary and
// the tool (the paste's own viscosity at the wall; a tool row weighs its material neighbour's).
//
// The viscous force of such a paste is the projected form (Morris, Fox & Zhu 1997; Monaghan 2005),
//   a_i = -1/rho_i sum_j mu_ij (m_j / rho_j) 2 (d + 2) ((v_i - v_j) . x_ij) / (r^2 + 0.01 h^2) |W'(r)| xhat_ij
//       = -1/rho_i sum_j c_ij ((v_i - v_j) . g_ij) g_ij,  g_ij = m_j gradW_ij (the row's gradient),
// not the paper's Laplacian: where the viscosity varies from particle to particle, the Laplacian's
// sum_j mu_ij (v_j - v_i) lapW also resists a rigid rotation (it diffuses the spin, not only the strain
// rate), and a shear-thinning paste between a turning and a fixed plate bent its profile 12% off the
// linear one. The projected form sees only the relative velocity along the pair's line, so a rigid
// motion costs nothing, and it conserves angular momentum.
#include <algorithm>
#include <cmath>
#include <limits>

#include "physics/rheology.hpp"
#include "solver/iisph.hpp"

namespace dentsph::iisph {

namespace {

// Adds a (x) w to L.
inline void add_outer(real L[3][3], const Vec3& a, const Vec3& w) {
  const real u[3] = {a.x, a.y, a.z}, b[3] = {w.x, w.y, w.z};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) L[r][c] += u[r] * b[c];
}

// L = A M^-1 where M is invertible enough (det M >= 0.1: a full neighbourhood's M is about the
// identity, a free surface's about 0.5 along its normal); A itself otherwise.
inline void corrected(const real A[3][3], const real M[3][3], real L[3][3]) {
  const real det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                   M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
  if (!(det >= 0.1)) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) L[r][c] = A[r][c];
    return;
  }
  real inv[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      // The cofactor of M[c][r] over det.
      const int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
      inv[r][c] = (M[r1][c1] * M[r2][c2] - M[r1][c2] * M[r2][c1]) / det;
    }
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) L[r][c] = A[r][0] * inv[0][c] + A[r][1] * inv[1][c] + A[r][2] * inv[2][c];
}

}  // namespace

// The setting's factor on a paste with a flow law raises its whole flow curve: a setting amalgam
// stiffens, and keeps its yield stress, until its gel point sets it (docs/model.md, "Presets").
real particle_viscosity(const Model& model, const State& s, std::uint32_t i, real gamma) {
  const MaterialIndex mat = s.material[i];
  if (!(mat & kCuredMaterial)) return rheology::effective_viscosity(model.materials[mat], gamma);
  const Material& base = model.materials[MaterialIndex(mat & ~kCuredMaterial)];
  if (newtonian(base) || !(base.mu > 0)) return s.mu[i];
  return s.mu[i] / base.mu * rheology::effective_viscosity(base, gamma);
}

real update_viscosity(const Model& model, State& s, IisphScratch& x, int threads, const Vec3* v, bool first) {
  constexpr std::size_t stride = IisphScratch::kPairStride;
  const std::int64_t nm = std::int64_t(x.material.size());
  real change = 0, lo = std::numeric_limits<real>::infinity(), hi = 0;
  // Each material particle's effective viscosity at its shear rate.
#pragma omp parallel for num_threads(threads) schedule(static) reduction(max : change, hi) reduction(min : lo)
  for (std::int64_t m = 0; m < nm; ++m) {
    const std::uint32_t i = x.material[m];
    const SolverPair* row = x.pairs.data() + std::size_t(i) * stride;
    real A[3][3] = {}, M[3][3] = {}, L[3][3];
    const Vec3 vi = v[i], xi = s.pos[i];
    for (std::uint32_t q = 0; q < x.n_material[i]; ++q) {
      const std::uint32_t j = row[q].j;
      const Vec3 w = row[q].grad() * x.inv_rho[j];
      add_outer(A, v[j] - vi, w);
      add_outer(M, s.pos[j] - xi, w);
    }
    corrected(A, M, L);
    real gamma = rheology::shear_rate(L);
    // The instrument's slip: paste beside a moving instrument is sheared at least at the rate of
    // the instrument's slip past it: each of the instrument's particles around it moves relative to
    // it across their line, over their distance (at least h / 2); their mean by their gradient's
    // weight. Its material neighbours alone do not see that where the paste lay at rest, which then
    // kept the regularisation's cap against an instrument sweeping past (156 N in the universal
    // procedure with the viscous pressure), and a film one particle thick between the instrument
    // and a wall sat at the cap (docs/model.md, "Rheology"). Where the paste flows with the
    // instrument (a rheometer's plate) the mean is under the gradient's rate (the pairs along the
    // surface slip less than the one across it) and changes little. The instrument's particles are
    // left out of the gradient itself, as the walls' are: their second layer, moving as their
    // first, bends a sheared layer's gradient there.
    real slip = 0, weight = 0;
    for (std::size_t q = stride - x.n_other[i]; q < stride; ++q) {
      const std::uint32_t j = row[q].j;
      if (s.role[j] != Role::tool) continue;
      const Vec3 d = s.pos[j] - xi, u = s.vel[j] - vi;  // the tool's velocity this step
      const real r2 = dot(d, d);
      const Vec3 across = r2 > 0 ? u - d * (dot(u, d) / r2) : u;
      const real w = norm(row[q].grad());
      slip += w * norm(across) / std::max(std::sqrt(r2), 0.5 * model.kernel.h);
      weight += w;
    }
    if (weight > 0) gamma = std::max(gamma, slip / weight);
    const real mu = particle_viscosity(model, s, i, gamma);
    if (!first && x.mu_eff[i] > 0) change = std::max(change, std::abs(mu - x.mu_eff[i]) / x.mu_eff[i]);
    x.mu_eff[i] = mu;
    lo = std::min(lo, mu);
    hi = std::max(hi, mu);
  }
  // Every row's weights with them.
  const std::int64_t n = s.size();
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t k = 0; k < n; ++k) {
    const std::uint32_t i = std::uint32_t(k);
    if (s.role[i] == Role::boundary) continue;  // a boundary row's weights are never used
    SolverPair* row = x.pairs.data() + std::size_t(i) * stride;
    float* unit = x.visc_unit.data() + std::size_t(i) * stride;
    if (first) {
      for (std::uint32_t q = 0; q < x.n_material[i]; ++q) unit[q] = row[q].visc;
      for (std::size_t q = stride - x.n_other[i]; q < stride; ++q) unit[q] = row[q].visc;
    }
    if (s.role[i] == Role::tool) {
      for (std::uint32_t q = 0; q < x.n_material[i]; ++q) row[q].visc = float(unit[q] * x.mu_eff[row[q].j]);
      continue;
    }
    const real mu_i = x.mu_eff[i];
    Vec3 block, fixed;
    for (std::uint32_t q = 0; q < x.n_material[i]; ++q) {
      row[q].visc = float(unit[q] * 0.5 * (mu_i + x.mu_eff[row[q].j]));
      const Vec3 g = row[q].grad();
      block += Vec3{g.x * g.x, g.y * g.y, g.z * g.z} * real(row[q].visc);
    }
    for (std::size_t q = stride - x.n_other[i]; q < stride; ++q) {
      row[q].visc = float(unit[q] * mu_i);
      const Vec3 g = row[q].grad();
      block += Vec3{g.x * g.x, g.y * g.y, g.z * g.z} * real(row[q].visc);
      fixed += g * (row[q].visc * dot(s.vel[row[q].j], g));
    }
    x.visc_block[i] = block;
    x.visc_fixed[i] = fixed;
  }
  s.diagnostics.viscosity_min = nm > 0 ? lo : 0;
  s.diagnostics.viscosity_max = hi;
  return first ? std::numeric_limits<real>::infinity() : change;
}

}  // namespace dentsph::iisph
