// The tooth frame: found axes against the reference axes of the real molars, the crown end of a
// tapered solid, and the frame's algebra.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_tooth_support.hpp"

namespace dentsph {
namespace {

using namespace dentsph::testing;
constexpr real mm = 1e-3;
constexpr real deg = 3.14159265358979323846 / 180;

real angle(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(dot(a, b) / (norm(a) * norm(b)), real(-1), real(1)));
}

// A square frustum, `base` wide at z = 0 and `top` wide at z = h (a crude tooth: long, one end
// wider), as a closed mesh.
TriMesh frustum(real base, real top, real h) {
  TriMesh m = box_mesh({-base / 2, -base / 2, 0}, {base / 2, base / 2, h});
  for (Vec3& v : m.vertices)
    if (v.z > 0) v.x *= top / base, v.y *= top / base;
  return m;
}

TEST(ToothFrame, FoundLongAxisMatchesTheReferenceAxesOfBothMolars) {
  DENTSPH_NEED_DATA();
  const auto axes = nlohmann::json::parse(std::ifstream(molar_axes));
  for (const auto& case_ : {std::pair{molar_36, "19"}, std::pair{molar_46, "30"}}) {
    const fs::path& file = case_.first;
    const char* id = case_.second;  // (clang 14 cannot capture structured bindings)
    SCOPED_TRACE(file.string());
    const auto point = [&](const char* k) {
      const auto& a = axes.at(id).at(k);
      return Vec3{a[0].get<real>(), a[1].get<real>(), a[2].get<real>()} * mm;
    };
    const Vec3 c = point("c");
    const ToothFrame f = find_tooth_frame(load_mesh(file).mesh);
    // The long axis, towards the biting surface (measured: 4.1 and 9.1 degrees).
    EXPECT_LT(angle(f.z, point("z") - c), 15 * deg);
    // The mesio-distal line, sign aside (measured: 7.8 and 15.1 degrees).
    const real md = angle(f.x, point("x") - c);
    EXPECT_LT(std::min(md, 180 * deg - md), 20 * deg);
    // The reference's crown centre lies near the found axis, crown-wards of the centroid.
    const Vec3 l = f.to_local(c);
    EXPECT_LT(std::hypot(l.x, l.y), 1.5 * mm);
    EXPECT_GT(l.z, 0);
    EXPECT_NEAR(norm(cross(f.x, f.y) - f.z), 0, 1e-12);
  }
}

TEST(ToothFrame, LongAxisPointsToTheWiderEnd) {
  const ToothFrame up = find_tooth_frame(repair_mesh(frustum(4 * mm, 8 * mm, 16 * mm), "up").mesh);
  EXPECT_LT(angle(up.z, {0, 0, 1}), 1e-6);
  const ToothFrame down =
      find_tooth_frame(repair_mesh(frustum(8 * mm, 4 * mm, 16 * mm), "down").mesh);
  EXPECT_LT(angle(down.z, {0, 0, -1}), 1e-6);
  // The centroid of a frustum sits nearer its wide end.
  EXPECT_GT(up.origin.z, 8 * mm);
  EXPECT_LT(down.origin.z, 8 * mm);
}

TEST(ToothFrame, GivenFrameIsOrthonormalRightHandedAndRoundTrips) {
  const ToothFrame f = make_tooth_frame({1 * mm, 2 * mm, 3 * mm}, {0, 1, 1}, {1, 1, 0});
  EXPECT_NEAR(norm(f.x), 1, 1e-15);
  EXPECT_NEAR(norm(f.y), 1, 1e-15);
  EXPECT_NEAR(norm(f.z), 1, 1e-15);
  EXPECT_NEAR(dot(f.x, f.z), 0, 1e-15);
  EXPECT_NEAR(norm(cross(f.z, f.x) - f.y), 0, 1e-15);
  const Vec3 p{4 * mm, -5 * mm, 6 * mm};
  EXPECT_NEAR(norm(f.to_world(f.to_local(p)) - p), 0, 1e-15);
  EXPECT_THROW(make_tooth_frame({}, {0, 0, 1}, {0, 0, 2}), std::invalid_argument);
}

}  // namespace
}  // namespace dentsph
