// Signed distance, inside test and rays: exact answers for a cube, the faceting bound for a
// sphere, and brute force over every triangle (distance) and ray parity (inside) for a crown.
#include <gtest/gtest.h>

#include <random>

#include "test_tooth_support.hpp"

namespace dentsph {
namespace {

using namespace dentsph::testing;
constexpr real mm = 1e-3;

// Signed distance to the box [0, a]^3, exactly.
real cube_sdf(const Vec3& p, real a) {
  const Vec3 q{std::fabs(p.x - a / 2) - a / 2, std::fabs(p.y - a / 2) - a / 2,
               std::fabs(p.z - a / 2) - a / 2};
  const Vec3 outside{std::max(q.x, 0.0), std::max(q.y, 0.0), std::max(q.z, 0.0)};
  return norm(outside) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0);
}

TEST(ToothDistance, CubeDistancesAreExactInsideOutsideAndAtCornersAndEdges) {
  const real a = 10 * mm;
  const MeshDistance d(cube_mesh(a));
  EXPECT_NEAR(d.signed_distance({5 * mm, 5 * mm, 5 * mm}), -5 * mm, 1e-15);
  EXPECT_NEAR(d.signed_distance({13 * mm, 5 * mm, 5 * mm}), 3 * mm, 1e-15);
  EXPECT_NEAR(d.signed_distance({-1 * mm, -1 * mm, -1 * mm}), std::sqrt(3.0) * mm, 1e-15);
  EXPECT_NEAR(d.signed_distance({-1 * mm, 11 * mm, 5 * mm}), std::sqrt(2.0) * mm, 1e-15);
  // The point just inside a corner is where face normals alone give the wrong sign.
  EXPECT_LT(d.signed_distance({0.1 * mm, 0.1 * mm, 0.1 * mm}), 0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<real> u(-3 * mm, 13 * mm);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    const SurfacePoint s = d.query(p);
    ASSERT_NEAR(s.distance, cube_sdf(p, a), 1e-15) << p.x << ' ' << p.y << ' ' << p.z;
    ASSERT_EQ(d.inside(p), cube_sdf(p, a) < 0);
    ASSERT_NEAR(norm(s.normal), 1, 1e-12);
    ASSERT_NEAR(norm(p - s.closest), std::fabs(s.distance), 1e-15);
  }
  // A ray from the centre leaves through the face 5 mm away; from outside it meets the cube.
  EXPECT_NEAR(*d.ray({5 * mm, 5 * mm, 5 * mm}, {1, 0, 0}), 5 * mm, 1e-15);
  EXPECT_NEAR(*d.ray({5 * mm, 5 * mm, 20 * mm}, {0, 0, -1}), 10 * mm, 1e-15);
  EXPECT_FALSE(d.ray({5 * mm, 5 * mm, 20 * mm}, {0, 0, 1}).has_value());
}

TEST(ToothDistance, SphereDistanceIsWithinTheFacetingOfTheExactOne) {
  const real r = 5 * mm;
  const LoadedMesh sphere = repair_mesh(icosphere(r, 4), "icosphere");  // 5120 triangles
  EXPECT_FALSE(sphere.report.repaired()) << sphere.report.summary();
  const MeshDistance d(sphere.mesh);
  // The chord of the finest level lies at most r (1 - cos(edge / 2r)) inside the sphere.
  const real sag = 0.02 * mm;
  std::mt19937 rng(3);
  std::uniform_real_distribution<real> u(-8 * mm, 8 * mm);
  for (int i = 0; i < 3000; ++i) {
    const Vec3 p{u(rng), u(rng), u(rng)};
    const real exact = norm(p) - r;
    ASSERT_NEAR(d.signed_distance(p), exact, sag) << norm(p);
    if (std::fabs(exact) > sag) {
      ASSERT_EQ(d.inside(p), exact < 0) << norm(p);
    }
  }
  EXPECT_NEAR(sphere.report.volume, 4.0 / 3 * 3.14159265358979 * r * r * r,
              0.01 * sphere.report.volume);
}

TEST(ToothDistance, CrownDistanceMatchesBruteForceAndInsideMatchesRayParity) {
  const MolarCrown crown = molar_crown();
  const MeshDistance d(crown.mesh);
  const Bounds b = crown.mesh.bounds();
  std::mt19937 rng(11);
  std::uniform_real_distribution<real> u(0, 1);
  for (int i = 0; i < 150; ++i) {
    // Half anywhere around the crown, half near its surface.
    Vec3 p{b.min.x - mm + u(rng) * (b.max.x - b.min.x + 2 * mm),
           b.min.y - mm + u(rng) * (b.max.y - b.min.y + 2 * mm),
           b.min.z - mm + u(rng) * (b.max.z - b.min.z + 2 * mm)};
    if (i % 2) {
      const auto& t = crown.mesh.triangles[std::size_t(u(rng) * crown.mesh.triangles.size())];
      p = crown.mesh.vertices[t[0]] + Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5} * (0.2 * mm);
    }
    const real sd = d.signed_distance(p);
    ASSERT_NEAR(std::fabs(sd), brute_distance(crown.mesh, p), 1e-15);
    if (std::fabs(sd) > 1e-9) {
      ASSERT_EQ(sd < 0, parity_inside(crown.mesh, p)) << i;
    }
  }
}

}  // namespace
}  // namespace dentsph
