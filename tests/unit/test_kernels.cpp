// The smoothing kernels (docs/model.md, "Kernels"): normalisation by quadrature, derivatives against
// finite differences, and the adhesion kernel's zeros, sign and peak.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "dentsph/scene.hpp"
#include "physics/kernels.hpp"

namespace dentsph {
namespace {

constexpr real h = 0.02;

KernelCoeffs coeffs(real eps = 3, real zeta = 2) {
  AdhesionParams a;
  a.eps = eps;
  a.zeta = zeta;
  a.Cd = adhesion_normalisation(eps, zeta);
  return kernels::make_coeffs(h, a);
}

// 4 pi integral_0^h r^2 W(r) dr by composite Simpson (W may be singular like 1/r at 0, r^2 W not).
real volume_integral(const std::function<real(real)>& W) {
  const int n = 20000;
  const real dr = h / n;
  auto g = [&](real r) { return r == 0 ? 0 : r * r * W(r); };
  real s = g(0) + g(h);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4 : 2) * g(i * dr);
  return 4 * kernels::pi * s * dr / 3;
}

TEST(Kernels, ValueKernelsIntegrateToOne) {
  const KernelCoeffs k = coeffs();
  EXPECT_NEAR(volume_integral([&](real r) { return kernels::poly6(r * r, k); }), 1.0, 1e-3);
  EXPECT_NEAR(volume_integral([&](real r) { return kernels::spiky(r, k); }), 1.0, 1e-3);
  EXPECT_NEAR(volume_integral([&](real r) { return kernels::visc(r, k); }), 1.0, 1e-3);
}

TEST(Kernels, ZeroOutsideSupport) {
  const KernelCoeffs k = coeffs();
  EXPECT_EQ(kernels::poly6(h * h, k), 0);
  EXPECT_EQ(kernels::poly6(1.5 * h * h, k), 0);
  EXPECT_EQ(kernels::spiky_grad_radial(h, k), 0);
  EXPECT_EQ(kernels::visc_laplacian(1.1 * h, k), 0);
  EXPECT_GT(kernels::poly6(0, k), 0);
}

TEST(Kernels, SpikyGradientMatchesFiniteDifferenceIn3D) {
  const KernelCoeffs k = coeffs();
  const Vec3 dirs[] = {{1, 0, 0}, {0.3, -0.5, 0.8}, {-0.2, 0.1, -0.9}};
  for (const Vec3& dir0 : dirs) {
    const Vec3 dir = dir0 / norm(dir0);
    for (real r : {0.1 * h, 0.35 * h, 0.6 * h, 0.9 * h}) {
      const Vec3 x = dir * r;
      const real e = 1e-7 * h;
      const auto W = [&](Vec3 p) { return kernels::spiky(norm(p), k); };
      const Vec3 fd{(W(x + Vec3{e, 0, 0}) - W(x - Vec3{e, 0, 0})) / (2 * e),
                    (W(x + Vec3{0, e, 0}) - W(x - Vec3{0, e, 0})) / (2 * e),
                    (W(x + Vec3{0, 0, e}) - W(x - Vec3{0, 0, e})) / (2 * e)};
      const Vec3 grad = x * (kernels::spiky_grad_radial(r, k) / r);
      const real scale = std::abs(kernels::spiky_grad_radial(r, k));
      EXPECT_NEAR(grad.x, fd.x, 1e-5 * scale) << "r/h=" << r / h;
      EXPECT_NEAR(grad.y, fd.y, 1e-5 * scale);
      EXPECT_NEAR(grad.z, fd.z, 1e-5 * scale);
      EXPECT_LT(dot(grad, dir), 0) << "the spiky gradient points inwards";
    }
  }
}

// The discrete gradient sum_j V_j (f_j - f_i) gradW(r_i - r_j) of the linear field f = x at a
// particle inside a simple cubic lattice of spacing h / 2 whose particles have the poly6 lattice
// mass (V = m / rho0): the share of the true gradient (1) each iisph pressure gradient gives.
// fn(V, x_j) for the neighbours x_j within h of a particle at the origin of a simple cubic lattice
// of spacing h / 2 whose particles have the poly6 lattice mass (V = m / rho0); returns their sum.
real lattice_sum(const KernelCoeffs& k, const std::function<real(real, const Vec3&)>& fn) {
  const real spacing = k.h / 2;
  const real V = lattice_particle_mass(1000, spacing, k) / 1000;
  real sum = 0;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j)
      for (int l = -2; l <= 2; ++l) {
        const Vec3 xj{i * spacing, j * spacing, l * spacing};
        const real r = norm(xj);
        if (r > 0 && r < k.h) sum += fn(V, xj);
      }
  return sum;
}

real lattice_gradient(const KernelCoeffs& k, const std::function<real(real)>& radial) {
  return lattice_sum(k, [&](real V, const Vec3& xj) {
    const real x = xj.x, r = norm(xj);
    return V * x * radial(r) * (-x / r);  // f_j - f_i = x_j; d/dx of W at r_i - r_j = -x_j
  });
}

TEST(Kernels, TheIisphGradientsAreExactOnTheRestLattice) {
  const KernelCoeffs k = coeffs();
  const real spiky = lattice_gradient(k, [&](real r) { return kernels::spiky_grad_radial(r, k); });
  EXPECT_NEAR(spiky, kSpikyLatticeGradient, 1e-12) << "the constant model.hpp divides by";
  const real scaled = lattice_gradient(k, [&](real r) { return -k.spiky_lattice * (k.h - r) * (k.h - r); });
  EXPECT_NEAR(scaled, 1.0, 1e-12) << "the iisph solver's spiky gradient";
  const real cubic = lattice_gradient(k, [&](real r) { return kernels::cubic_grad_radial(r, k); });
  EXPECT_NEAR(cubic, 1.0101671, 1e-6) << "the cubic spline's, 1% over";
}

// The projected viscosity 2 (d + 2) sum_j V_j ((v_i - v_j) . x_ij) / (r^2 + 0.01 h^2) gradW_ij of the
// shear flow v = (y^2, 0, 0) (Laplacian (2, 0, 0), divergence 0) at a particle inside the same
// lattice, over 2: the share of the viscous force a non-Newtonian paste's form gives with each
// iisph gradient (solver/rheology.cpp divides by it).
real projected_shear(const KernelCoeffs& k, const std::function<real(real)>& radial) {
  return lattice_sum(k, [&](real V, const Vec3& xj) {
           const real r = norm(xj);
           const Vec3 x_ij = -xj, v_ij{-xj.y * xj.y, 0, 0};  // v_i = 0 at the origin
           const Vec3 grad = x_ij * (radial(r) / r);
           return 10 * V * dot(v_ij, x_ij) / (r * r + 0.01 * k.h2) * grad.x;
         }) /
         2;
}

TEST(Kernels, TheProjectedViscosityIsItsLatticeShareOfTheLaplacian) {
  const KernelCoeffs k = coeffs();
  const real spiky = projected_shear(k, [&](real r) { return -k.spiky_lattice * (k.h - r) * (k.h - r); });
  EXPECT_NEAR(spiky, kProjectedShearSpiky, 1e-12) << "the constant model.hpp divides by (spiky gradient)";
  const real cubic = projected_shear(k, [&](real r) { return kernels::cubic_grad_radial(r, k); });
  EXPECT_NEAR(cubic, kProjectedShearCubic, 1e-12) << "the constant model.hpp divides by (cubic spline)";
}

TEST(Kernels, ViscosityLaplacianMatchesFiniteDifference) {
  const KernelCoeffs k = coeffs();
  for (real r : {0.2 * h, 0.5 * h, 0.8 * h}) {
    // Laplacian of a radial function: f'' + 2 f' / r.
    const real e = 1e-5 * h;
    const real f0 = kernels::visc(r, k), fp = kernels::visc(r + e, k), fm = kernels::visc(r - e, k);
    const real lap_fd = (fp - 2 * f0 + fm) / (e * e) + 2 * (fp - fm) / (2 * e) / r;
    EXPECT_NEAR(kernels::visc_laplacian(r, k), lap_fd, 1e-4 * kernels::visc_laplacian(r, k)) << "r/h=" << r / h;
    EXPECT_GT(kernels::visc_laplacian(r, k), 0);
  }
}

TEST(Kernels, Poly6DecreasesMonotonically) {
  const KernelCoeffs k = coeffs();
  real prev = kernels::poly6(0, k);
  for (int i = 1; i <= 100; ++i) {
    const real r = h * i / 100.0;
    const real w = kernels::poly6(r * r, k);
    EXPECT_LE(w, prev);
    prev = w;
  }
}

TEST(AdhesionKernel, NormalisationMatchesPaperForThreeAndTwo) {
  EXPECT_NEAR(adhesion_normalisation(3, 2), 27.0 / 4.0, 1e-12);
}

void check_adhesion_shape(real eps, real zeta) {
  const KernelCoeffs k = coeffs(eps, zeta);
  AdhesionParams a;
  a.A = 0.6 * h;
  a.B = 1.5 * h;
  a.eps = eps;
  a.zeta = zeta;
  a.Cd = adhesion_normalisation(eps, zeta);
  EXPECT_EQ(kernels::adhesion(a.A, a, k), 0);
  EXPECT_EQ(kernels::adhesion(a.B, a, k), 0);
  EXPECT_EQ(kernels::adhesion(0.5 * a.A, a, k), 0);
  EXPECT_EQ(kernels::adhesion(1.01 * a.B, a, k), 0);
  real peak = 0;
  for (int i = 1; i < 10000; ++i) {
    const real r = a.A + (a.B - a.A) * i / 10000.0;
    const real w = kernels::adhesion(r, a, k);
    ASSERT_LT(w, 0) << "negative (attractive) strictly inside [A, B]";
    peak = std::min(peak, w);
  }
  // Cd * bracket has peak magnitude 1, so W_adh = Cd/h^4 * bracket peaks at -1/h^4.
  EXPECT_NEAR(peak * std::pow(h, 4), -1.0, 1e-6);
}

TEST(AdhesionKernel, ZeroAtEndsNegativeBetweenUnitPeak) {
  check_adhesion_shape(3, 2);
  check_adhesion_shape(4, 1.5);
  check_adhesion_shape(2.5, 2);
}

}  // namespace
}  // namespace dentsph
