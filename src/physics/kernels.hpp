// SPH smoothing kernels (docs/model.md, "Kernels"): pure functions of their arguments, host and device.
// Mueller et al. 2003 for poly6, spiky and viscosity; the paper's eq. 12 for adhesion.
#pragma once

#include <cmath>

#include "dentsph/model.hpp"

namespace dentsph::kernels {

inline constexpr real pi = 3.14159265358979323846;

// Normalisation constants for support h.
DENTSPH_HD inline KernelCoeffs make_coeffs(real h, const AdhesionParams& a) {
  KernelCoeffs k;
  k.h = h;
  k.h2 = h * h;
  const real h3 = h * h * h;
  const real h6 = h3 * h3;
  k.poly6 = 315.0 / (64.0 * pi * h6 * h3);
  k.spiky_grad = 45.0 / (pi * h6);
  k.visc_lap = 45.0 / (pi * h6);
  k.adh_scale = a.Cd / (h * h * h * h);
  k.cubic = 8.0 / (pi * h3);
  k.spiky_lattice = k.spiky_grad / kSpikyLatticeGradient;
  return k;
}

// One neighbour's term of a density sum before the poly6 constant: m_j w^3, w = h^2 - r^2 >= 0
// (each density pass clamps or tests w its own way and applies k.poly6 once to its sum). Written
// once for the paper's density pass (step/density.cpp), its CUDA stage body
// (backend/cuda/density.hpp) and the iisph solver's pair pass (solver/pairs.cpp).
DENTSPH_HD inline real poly6_mass_term(real m, real w) { return m * w * w * w; }

// Density kernel W_poly6 from the squared distance, 1/m^3. Integrates to 1.
DENTSPH_HD inline real poly6(real r2, const KernelCoeffs& k) {
  if (r2 >= k.h2) return 0;
  const real d = k.h2 - r2;
  return k.poly6 * d * d * d;
}

// Spiky value kernel 15/(pi h^6) (h - r)^3, 1/m^3 (for tests; the step uses its gradient).
DENTSPH_HD inline real spiky(real r, const KernelCoeffs& k) {
  if (r >= k.h) return 0;
  const real d = k.h - r;
  return k.spiky_grad / 3.0 * d * d * d;
}

// Radial derivative of the spiky kernel, 1/m^4: gradW_spiky(r_ij) = spiky_grad_radial(r) * rhat.
DENTSPH_HD inline real spiky_grad_radial(real r, const KernelCoeffs& k) {
  if (r >= k.h) return 0;
  const real d = k.h - r;
  return -k.spiky_grad * d * d;
}

// Viscosity value kernel 15/(2 pi h^3) (-r^3/(2h^3) + r^2/h^2 + h/(2r) - 1), 1/m^3 (for tests).
DENTSPH_HD inline real visc(real r, const KernelCoeffs& k) {
  if (r >= k.h) return 0;
  const real h = k.h;
  const real q = r / h;
  return 15.0 / (2.0 * pi * h * h * h) * (-0.5 * q * q * q + q * q + 0.5 / q - 1.0);
}

// Laplacian of the viscosity kernel, 1/m^5.
DENTSPH_HD inline real visc_laplacian(real r, const KernelCoeffs& k) {
  if (r >= k.h) return 0;
  return k.visc_lap * (k.h - r);
}

// The cubic spline (Monaghan's M4) of support h, 1/m^3: with q = r / h,
// 8/(pi h^3) (6 (q^3 - q^2) + 1) for q <= 1/2, 8/(pi h^3) 2 (1 - q)^3 for q <= 1. Integrates to 1.
// The iisph solver's pressure gradient: on a cubic lattice of spacing h / 2 with the poly6 lattice
// mass, the discrete gradient of a linear field is 1.010 of the true one (spiky: 0.947, poly6's
// own gradient: 1.055; docs/model.md), so its pressure is the mechanical one.
DENTSPH_HD inline real cubic(real r, const KernelCoeffs& k) {
  const real q = r / k.h;
  if (q >= 1) return 0;
  if (q <= 0.5) return k.cubic * (6 * (q * q * q - q * q) + 1);
  const real d = 1 - q;
  return k.cubic * 2 * d * d * d;
}

// Radial derivative of the cubic spline, 1/m^4 (non-positive): gradW(r_ij) = cubic_grad_radial(r) rhat.
DENTSPH_HD inline real cubic_grad_radial(real r, const KernelCoeffs& k) {
  const real q = r / k.h;
  if (q >= 1) return 0;
  if (q <= 0.5) return k.cubic / k.h * 6 * q * (3 * q - 2);
  const real d = 1 - q;
  return -k.cubic / k.h * 6 * d * d;
}

// The bracket x^eps - x^zeta of eq. 12, x in [0, 1]; integer exponents take the fast path.
DENTSPH_HD inline real adhesion_bracket(real x, real eps, real zeta) {
  if (eps == 3 && zeta == 2) return x * x * (x - 1);
  return std::pow(x, eps) - std::pow(x, zeta);
}

// Adhesion kernel W_adh(r), 1/m^4: Cd/h^4 (x^eps - x^zeta), x = (r - A)/(B - A), on [A, B];
// zero elsewhere. Non-positive, so W_adh * rhat (rhat from j to i) points from i to j: attraction.
DENTSPH_HD inline real adhesion(real r, const AdhesionParams& a, const KernelCoeffs& k) {
  if (r < a.A || r > a.B) return 0;
  const real x = (r - a.A) / (a.B - a.A);
  return k.adh_scale * adhesion_bracket(x, a.eps, a.zeta);
}

// Akinci, Akinci & Teschner 2013 ("Versatile surface tension and adhesion for SPH fluids", ACM TOG
// 32(6) 182), support h, each the product of its normalisation (once a step) and its shape (a pair).
// Their cohesion spline C(r) = cohesion_scale(h) cohesion(r, h), 1/m^3: attracts beyond h / 2,
// repels a little closer (so that cohesion alone does not cluster particles).
DENTSPH_HD inline real cohesion_scale(real h) { return real(32) / (pi * h * h * h * h * h * h * h * h * h); }
DENTSPH_HD inline real cohesion(real r, real h) {
  if (!(r > 0) || r > h) return 0;
  const real h3 = h * h * h;
  const real a = (h - r) * (h - r) * (h - r) * r * r * r;
  return 2 * r > h ? a : 2 * a - h3 * h3 / 64;
}
// Their adhesion spline A(r) = wall_adhesion_scale(h) wall_adhesion(r, h) of a fluid particle to a
// wall particle, 1/m^3.25: only beyond h / 2.
DENTSPH_HD inline real wall_adhesion_scale(real h) { return real(0.007) / std::pow(h, real(3.25)); }
DENTSPH_HD inline real wall_adhesion(real r, real h) {
  if (2 * r <= h || r > h) return 0;
  const real v = -4 * r * r / h + 6 * r - 2 * h;
  return std::pow(v > 0 ? v : 0, real(0.25));
}

}  // namespace dentsph::kernels
