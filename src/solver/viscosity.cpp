// The iisph solver's viscosity: the paper's viscosity (eq. 4, the viscosity kernel's Laplacian)
// integrated backward in time after the pressure, v** - dt a_visc(v**) = v* + dt a_p. Multiplied by
// m_i it is the symmetric, positive definite system
//   m_i v_i + dt sum_j c_ij (v_i - v_j) = m_i v_i',   c_ij = (mu_i + mu_j)/2 m_i m_j lapW_visc(r) / (rho_i rho_j),
// with the boundary's (v = 0) and the tool's (its velocity) terms on the right-hand side, solved by
// conjugate gradients with the diagonal as preconditioner, model.iisph.viscosity_iterations iterations
// from v'. Backward Euler is stable for any dt (the explicit limit, 0.125 h^2 rho0 / mu, is 90 us
// for the dental paste), each iteration lowers the error's energy norm, and conjugate gradients
// reach the long wavelengths (the slumping of a heap of paste) that as many Jacobi sweeps leave
// undamped. After the pressure, so that the velocities the pressure gives are damped within the
// same step, as the paste's viscosity does over the step's millisecond (docs/model.md).
//
// The three components are three independent solves sharing each sweep. The sums over particles
// are taken in fixed blocks in a fixed order (block_sum.hpp), so every thread count gives the same
// result.
#include <algorithm>
#include <cmath>
#include <utility>

#include "solver/block_sum.hpp"
#include "solver/iisph.hpp"

namespace dentsph::iisph {

namespace {

// Component-wise product and quotient of Vec3 (the three solves side by side).
inline Vec3 mul(const Vec3& a, const Vec3& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline Vec3 quotient(const Vec3& a, const Vec3& b) {
  return {b.x != 0 ? a.x / b.x : 0, b.y != 0 ? a.y / b.y : 0, b.z != 0 ? a.z / b.z : 0};
}

// Projected: the rotation-invariant form of a non-Newtonian material (rheology.cpp), one system
// coupling the three components (one step length a direction); otherwise the paper's Laplacian,
// three independent systems.
template <bool Projected>
class ViscositySolve {
 public:
  ViscositySolve(const Model& model, State& s, IisphScratch& x, int threads)
      : s_(s), x_(x), dt_(model.dt), threads_(threads), n_(std::int64_t(x_.material.size())) {}

  // Conjugate gradients from the velocity in v_a (v', also the right-hand side's v_star), until
  // `iterations` of them or, where tolerance > 0, until the relative residual is at most tolerance.
  // Three parallel passes an iteration, each sum taken in the pass that computes its terms
  // (block_sum.hpp); z = D^-1 r is kept in cg_p's place only until the direction is updated. Returns
  // the relative residual left and the iterations taken. The residual is relative to the start's,
  // sqrt(r.D^-1 r / r0.D^-1 r0), for a fixed count (tolerance 0), and to the right-hand side's,
  // sqrt(r.D^-1 r / b.D^-1 b), for a tolerance (a warm start that is already close does not make it
  // harder to reach).
  std::pair<real, int> run(int iterations, real tolerance, Deadline deadline) {
    Vec3* v = x_.v_a.data();
    Vec3* p = x_.cg_p.data();
    Vec3* r = x_.cg_r.data();
    Vec3* ap = x_.cg_ap.data();
    real bb = 0;  // b.D^-1 b
    if (tolerance > 0) {
      // Warm: the better start of v' and the last step's velocity (state.vel: a slow, stiff flow's
      // velocity changes little from step to step, where v' has lost the viscous part of the last
      // step). Both residuals are kept (v''s in r, the last velocity's in ap, free until the
      // iterations), so the start's residual is not computed again.
      const Vec3 e = summed([&](std::uint32_t i) {
        const Vec3 b = rhs(i);
        r[i] = b - apply(v, i);
        ap[i] = b - apply(s_.vel.data(), i);
        if constexpr (Projected) {
          const Vec3 d = diagonal3(i);
          return Vec3{dot(b, quotient(b, d)), dot(r[i], quotient(r[i], d)), dot(ap[i], quotient(ap[i], d))};
        } else {
          const real d = diagonal(i);
          return Vec3{dot(b, b) / d, dot(r[i], r[i]) / d, dot(ap[i], ap[i]) / d};
        }
      });
      bb = e.x;
      if (e.z < e.y)
        each([&](std::uint32_t i) {
          v[i] = s_.vel[i];
          r[i] = ap[i];
        });
    }
    Vec3 rz = summed([&](std::uint32_t i) {
      if (!(tolerance > 0)) r[i] = rhs(i) - apply(v, i);  // a warm start has it already
      p[i] = precondition(r[i], i);
      return mul(r[i], p[i]);
    });
    const real rz0 = rz.x + rz.y + rz.z;
    const real reference = tolerance > 0 ? bb : rz0;
    real rz_end = rz0;
    int it = 0;
    auto relative = [&](real rz_now) { return reference > 0 ? std::sqrt(std::max<real>(0, rz_now) / reference) : 0; };
    while (it < iterations && !(tolerance > 0 && relative(rz_end) <= tolerance)) {
      const Vec3 pap = summed([&](std::uint32_t i) {
        ap[i] = apply(p, i);
        return mul(p[i], ap[i]);
      });
      const Vec3 alpha = step_length(rz, pap);
      const Vec3 rz_next = summed([&](std::uint32_t i) {
        v[i] += mul(alpha, p[i]);
        r[i] -= mul(alpha, ap[i]);
        return mul(r[i], precondition(r[i], i));
      });
      ++it;
      rz_end = rz_next.x + rz_next.y + rz_next.z;
      if (it == iterations || (tolerance > 0 && relative(rz_end) <= tolerance)) break;  // the last direction would not be used
      if (tolerance > 0 && stops_at_deadline(relative(rz_end), tolerance, deadline)) {  // a fixed count is its own budget
        s_.diagnostics.on_deadline = true;
        break;
      }
      const Vec3 beta = step_length(rz_next, rz);
      rz = rz_next;
      each([&](std::uint32_t i) { p[i] = precondition(r[i], i) + mul(beta, p[i]); });
    }
    return {relative(rz_end), it};
  }

 private:
  // The right-hand side of row i: m_i v'_i and the boundary's and the tool's terms.
  Vec3 rhs(std::uint32_t i) const {
    return x_.v_star[i] * s_.mass[i] + x_.visc_fixed[i] * (dt_ * s_.mass[i] * x_.inv_rho[i]);
  }
  // Row i (material) of the system times v.
  Vec3 apply(const Vec3* v, std::uint32_t i) const {
    const SolverPair* row = x_.pairs.data() + std::size_t(i) * IisphScratch::kPairStride;
    const real a = dt_ * s_.mass[i] * x_.inv_rho[i];
    if constexpr (Projected) {
      // m_i v_i + dt m_i / rho_i sum_j c_ij ((v_i - v_j) . g_ij) g_ij, v_j of the boundary and the tool
      // on the right-hand side (rheology.cpp).
      Vec3 sum;
      const Vec3 vi = v[i];
      for (std::uint32_t q = 0; q < x_.n_material[i]; ++q) {
        const Vec3 g = row[q].grad();
        sum += g * (row[q].visc * dot(vi - v[row[q].j], g));
      }
      for (std::uint32_t q = IisphScratch::kPairStride - x_.n_other[i]; q < IisphScratch::kPairStride; ++q) {
        const Vec3 g = row[q].grad();
        sum += g * (row[q].visc * dot(vi, g));
      }
      return vi * s_.mass[i] + sum * a;
    } else {
      // m_i v_i (1 + dt/rho_i sum_j visc_ij) - dt m_i/rho_i sum_{j material} visc_ij v_j,
      // visc_ij = (mu_i + mu_j)/2 m_j lapW / rho_j (advection.cpp).
      Vec3 neighbours;
      for (std::uint32_t q = 0; q < x_.n_material[i]; ++q) neighbours += v[row[q].j] * row[q].visc;
      return v[i] * (s_.mass[i] + a * x_.visc_diag[i]) - neighbours * a;
    }
  }
  real diagonal(std::uint32_t i) const { return s_.mass[i] * (1 + dt_ * x_.inv_rho[i] * x_.visc_diag[i]); }
  // The projected system's diagonal: m_i + dt m_i / rho_i sum_j c_ij g_ij,k^2 per component.
  Vec3 diagonal3(std::uint32_t i) const {
    return Vec3{1, 1, 1} * s_.mass[i] + x_.visc_block[i] * (dt_ * s_.mass[i] * x_.inv_rho[i]);
  }
  // D^-1 r.
  Vec3 precondition(const Vec3& r, std::uint32_t i) const {
    if constexpr (Projected)
      return quotient(r, diagonal3(i));
    else
      return r / diagonal(i);
  }
  // a / b: per component for three systems, the sums' for one.
  static Vec3 step_length(const Vec3& a, const Vec3& b) {
    if constexpr (Projected) {
      const real den = b.x + b.y + b.z;
      const real l = den != 0 ? (a.x + a.y + a.z) / den : 0;
      return {l, l, l};
    } else {
      return quotient(a, b);
    }
  }
  // fn(i) for every material particle, in parallel.
  template <class F>
  void each(F&& fn) const {
#pragma omp parallel for num_threads(threads_) schedule(static)
    for (std::int64_t m = 0; m < n_; ++m) fn(x_.material[m]);
  }
  // fn(i) for every material particle, in parallel, and the sum of what it returns (block_sum.hpp).
  template <class F>
  Vec3 summed(F&& fn) const {
    return for_rows_summed(n_, threads_, x_.partial.data(), [&](std::int64_t m) { return fn(x_.material[m]); });
  }

  State& s_;
  IisphScratch& x_;
  real dt_;
  int threads_;
  std::int64_t n_;
};

// Where the contact's strength is exceeded, its coupling weakened and the solve run again to
// `tolerance`, up to kInterfacePasses times (interface.cpp); the residual and iterations those solves
// leave. Returns the particles weakened (finish.cpp reads their factors where there are any).
template <class Solve>
std::uint32_t slip(const Model& model, State& s, IisphScratch& x, int threads, Solve& solve, real tolerance,
                   real& residual, int& iterations, Deadline deadline) {
  std::uint32_t weakened = 0;
  for (int pass = 0; pass < kInterfacePasses; ++pass) {
    const InterfacePass p = cap_tool_pull(model, s, x, threads, pass == 0);
    if (p.weakened == 0) break;
    weakened += p.first_time;
    const auto [r, it] = solve.run(model.iisph.viscosity_iterations, tolerance, deadline);
    residual = r;
    iterations += it;
    if (past(deadline)) break;
  }
  return weakened;
}

// A Picard iteration's solve's relative residual (IisphParams::rheology_forcing): the viscosity's
// tolerance, or with forcing the change of the viscosities that called for the solve times it, kept
// between that tolerance and kPicardLoosest times it; the first solve of a step at the loosest.
real picard_tolerance(const IisphParams& ip, int solves, real change) {
  if (!(ip.rheology_forcing > 0)) return ip.viscosity_tolerance;
  const real loosest = kPicardLoosest * ip.viscosity_tolerance;
  if (solves == 0) return loosest;
  return std::clamp(ip.rheology_forcing * change, ip.viscosity_tolerance, loosest);
}

}  // namespace

void implicit_viscosity(const Model& model, State& s, IisphScratch& x, int threads, Deadline deadline) {
  const IisphParams& ip = model.iisph;
  // Paste pulled from the instrument past its contact's strength slips (interface.cpp).
  const bool interface = model.materials.any_interface_strength();
  s.diagnostics.interface_capped = 0;
  if (!x.rheology) {
    ViscositySolve<false> solve(model, s, x, threads);
    auto [residual, iterations] = solve.run(ip.viscosity_iterations, ip.viscosity_tolerance, deadline);
    if (interface)
      s.diagnostics.interface_capped =
          slip(model, s, x, threads, solve, ip.viscosity_tolerance, residual, iterations, deadline);
    s.diagnostics.viscosity_iterations = iterations;
    s.diagnostics.viscosity_residual = residual;
    s.diagnostics.rheology_iterations = 0;
    s.diagnostics.rheology_change = 0;
    return;
  }
  // A non-Newtonian material: Picard iterations. The first takes the viscosities at the shear rates
  // of the last step's velocities; each later one those of the last solve's, and stops before
  // solving again once they changed by at most rheology_tolerance (that solve had them, within it).
  ViscositySolve<true> solve(model, s, x, threads);
  int solves = 0, iterations = 0;
  real residual = 0, change = 0, tolerance = ip.viscosity_tolerance;
  const int most = std::max(1, ip.rheology_iterations);
  for (;;) {
    change = update_viscosity(model, s, x, threads, solves == 0 ? s.vel.data() : x.v_a.data(), solves == 0);
    if (solves > 0 && change <= ip.rheology_tolerance) break;
    if (solves == most) break;  // the weights have the last solve's viscosities, the velocities the one before
    if (solves > 0 && stops_at_deadline(change, ip.rheology_tolerance, deadline)) {
      s.diagnostics.on_deadline = true;
      break;
    }
    tolerance = picard_tolerance(ip, solves, change);
    const auto [r, it] = solve.run(ip.viscosity_iterations, tolerance, deadline);
    residual = r;
    iterations += it;
    ++solves;
  }
  // The slip's solves to the last Picard solve's tolerance: they correct it, no more exactly than it was.
  if (interface) s.diagnostics.interface_capped = slip(model, s, x, threads, solve, tolerance, residual, iterations, deadline);
  s.diagnostics.viscosity_iterations = iterations;
  s.diagnostics.viscosity_residual = residual;
  s.diagnostics.rheology_iterations = solves;
  s.diagnostics.rheology_change = std::isfinite(change) ? change : 0;
}

}  // namespace dentsph::iisph
