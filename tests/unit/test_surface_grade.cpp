// The restoration's surface graded (dentsph/surface_grade.hpp) on constructed cases with known
// answers: a flat-topped tooth (a 10 x 10 x 7 mm box) with the default Class I cavity, whose
// occlusal outline is the CavityParams' rounded rectangle (3 x 5 mm, corners of 0.5 mm: 15.14 mm
// round), filled with particles on a lattice 0.1 mm apart whose surface (OpenVDB, surface.hpp)
// lies half a spacing outside the outer particles: exactly to the intact surface (and kept a
// particle's standoff off the walls), 0.3 mm short
// over the mesial end, 0.5 mm heaped over the distal end's margin, or not at all.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "dentsph/surface.hpp"
#include "dentsph/surface_grade.hpp"
#include "dentsph/tooth.hpp"

namespace dentsph {
namespace {

constexpr real s = 0.1e-3;  // m, the lattice's spacing

// A box tooth, its top at z = 7 mm, the long axis +z, mesial +x.
PreparedTooth box_tooth(CavityClass kind = CavityClass::class_1) {
  const real a = 5e-3, h = 7e-3;
  TriMesh m;
  for (int c = 0; c < 8; ++c) m.vertices.push_back({(c & 1) ? a : -a, (c & 2) ? a : -a, (c & 4) ? h : 0});
  // Each face as two triangles, wound outward.
  const std::uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    m.triangles.push_back({f[0], f[1], f[2]});
    m.triangles.push_back({f[0], f[2], f[3]});
  }
  const LoadedMesh box = repair_mesh(m, "box");
  CavityParams c;
  c.kind = kind;
  return carve_cavity(MeshDistance(box.mesh), make_tooth_frame({0, 0, 0}, {0, 0, 1}, {1, 0, 0}), c);
}

// Lattice points (tooth frame, the top layer half a spacing under z = 0) kept where `keep` says.
std::vector<Vec3> lattice(const PreparedTooth& t, real z_top, const std::function<bool(const Vec3&)>& keep) {
  std::vector<Vec3> p;
  for (real x = -5.5e-3 + s / 2; x < 5.5e-3; x += s)
    for (real y = -2.5e-3 + s / 2; y < 2.5e-3; y += s)
      for (real z = z_top - s / 2; z > -4e-3; z -= s) {
        const Vec3 local{x, y, z};
        if (keep(local)) p.push_back(t.frame().to_world(local));
      }
  return p;
}

// Distance in the occlusal plane to the outline's rounded rectangle (negative inside).
real outline_distance(real x, real y) {
  const real qx = std::abs(x) - 2.0e-3, qy = std::abs(y) - 1.0e-3;
  return std::hypot(std::max<real>(qx, 0), std::max<real>(qy, 0)) + std::min<real>(std::max(qx, qy), 0) - 0.5e-3;
}

// The outline's length beyond |x| = 1.5 mm at one end: two straight 0.5 mm sides, two quarter
// circles of 0.5 mm, the 2 mm end.
constexpr real kEndLength_mm = 2 * 0.5 + std::numbers::pi * 0.5 + 2.0;
constexpr real kOutline_mm = 2 * (3.0 + 5.0) - 8 * 0.5 + 2 * std::numbers::pi * 0.5;

GradeParams fine() {
  GradeParams p;
  p.spacing = s;
  p.column = 0.05e-3;
  return p;
}

TEST(SurfaceGrade, ARestorationOfTheIntactSurfaceIsAlphaWithASoundMargin) {
  const PreparedTooth t = box_tooth();
  const auto p = lattice(t, 0, [&](const Vec3& l) { return t.in_cavity(t.frame().to_world(l)); });
  const SurfaceGrade g = grade_surface(t, particle_surface(p, s), fine());
  ASSERT_TRUE(g.anatomic.measured) << g.anatomic.why_not;
  EXPECT_LT(g.anatomic.rms_mm, s / 3 * 1e3);  // within a voxel of the surface
  EXPECT_EQ(g.anatomic.band, 'A');
  // The opening's area: the rounded rectangle's 15 - (4 - pi) 0.25 mm^2.
  EXPECT_NEAR(g.anatomic.columns * 0.05 * 0.05, 15 - (4 - std::numbers::pi) * 0.25, 0.2);
  ASSERT_TRUE(g.margin.measured) << g.margin.why_not;
  EXPECT_NEAR(g.margin.length_mm, kOutline_mm, 0.01 * kOutline_mm);
  EXPECT_EQ(g.margin.open_samples, 0);
  EXPECT_TRUE(g.margin.defects.empty());
  EXPECT_NEAR(g.margin.gap_length_mm + g.margin.excess_length_mm, 0, 0.05);
  EXPECT_TRUE(g.margin.passes);

  // The same paste kept 0.12 mm off the walls and the floor, as the SPH paste keeps a particle's
  // standoff: the crevice between its surface and the walls (0.07 to 0.17 mm) is not a gap.
  const auto standoff = lattice(t, 0, [&](const Vec3& l) {
    const Vec3 w = t.frame().to_world(l);
    return t.in_cavity(w) && t.distance(w).distance > 0.12e-3;
  });
  const SurfaceGrade kept_off = grade_surface(t, particle_surface(standoff, s), fine());
  EXPECT_EQ(kept_off.anatomic.band, 'A');
  EXPECT_TRUE(kept_off.margin.defects.empty());
  EXPECT_NEAR(kept_off.margin.gap_length_mm, 0, 0.05);
  GradeParams narrow = fine();
  narrow.bridge = 0.01e-3;  // read down the crevice, half a spacing inside the margin: a gap all round
  narrow.probe = 0.05e-3;
  EXPECT_GT(grade_surface(t, particle_surface(standoff, s), narrow).margin.gap_length_mm, 0.9 * kOutline_mm);
}

TEST(SurfaceGrade, AnUnderContourAndAnExcessAreFoundOverTheirMarginsLength) {
  const PreparedTooth t = box_tooth();
  // 0.3 mm short beyond x = 1.5 mm (mesial).
  const auto short_end = lattice(t, 0, [&](const Vec3& l) {
    return t.in_cavity(t.frame().to_world(l)) && !(l.x > 1.5e-3 && l.z > -0.3e-3);
  });
  SurfaceGrade g = grade_surface(t, particle_surface(short_end, s), fine());
  ASSERT_TRUE(g.margin.measured);
  ASSERT_EQ(g.margin.defects.size(), 1u);
  EXPECT_EQ(g.margin.defects[0].kind, "gap");
  EXPECT_NEAR(g.margin.defects[0].length_mm, kEndLength_mm, 0.1 * kEndLength_mm);
  EXPECT_NEAR(g.margin.defects[0].largest_step_mm, 0.3, 0.06);
  EXPECT_GT(g.margin.defects[0].centre_mm.x, 1.5);
  EXPECT_NEAR(g.margin.excess_length_mm, 0, 0.05);
  EXPECT_FALSE(g.margin.passes);  // a site over 1 mm
  // The 95th percentile of the under-contour: a fifth of the opening lies 0.3 mm short. (Its
  // deepest column lies deeper: where the paste's surface curls down into the corner between two
  // walls, a reconstruction's edge.)
  EXPECT_NEAR(g.anatomic.p95_under_mm, 0.3, 0.06);
  EXPECT_GE(g.anatomic.max_under_mm, 0.3 - 0.06);
  EXPECT_EQ(g.anatomic.band, 'B');

  // 0.5 mm of paste heaped over the distal end, reaching 0.6 mm beyond its margin.
  auto heaped = lattice(t, 0, [&](const Vec3& l) { return t.in_cavity(t.frame().to_world(l)); });
  for (const Vec3& q : lattice(t, 0.5e-3, [](const Vec3& l) {
         return l.z > 0 && l.x < -1.5e-3 && outline_distance(l.x, l.y) <= 0.6e-3;
       }))
    heaped.push_back(q);
  g = grade_surface(t, particle_surface(heaped, s), fine());
  ASSERT_EQ(g.margin.defects.size(), 1u);
  EXPECT_EQ(g.margin.defects[0].kind, "excess");
  EXPECT_NEAR(g.margin.defects[0].length_mm, kEndLength_mm, 0.1 * kEndLength_mm);
  EXPECT_NEAR(g.margin.defects[0].largest_step_mm, 0.5, 0.06);
  EXPECT_LT(g.margin.defects[0].centre_mm.x, -1.5);
  EXPECT_NEAR(g.margin.gap_length_mm, 0, 0.05);
  EXPECT_NEAR(g.anatomic.max_over_mm, 0.5, 0.06);
  EXPECT_EQ(g.anatomic.band, 'B');
}

// Voids open to the surface: a pit 0.6 mm across and 0.4 mm deep in the middle of a restoration
// filled to the intact surface is one, of the particles' volume it lacks within 15% (0.113 mm^3;
// measured 0.123, the rim's rounding included), apart from the enclosed voids; the restoration
// without it has none, and a dip that reaches the margin (the under-contoured end) is the margin's
// gap, not a surface void.
TEST(SurfaceGrade, APitOpenToTheSurfaceIsASurfaceVoidAndADipAtTheMarginIsNot) {
  const PreparedTooth t = box_tooth();
  const auto pitted = lattice(t, 0, [&](const Vec3& l) {
    return t.in_cavity(t.frame().to_world(l)) && !(std::hypot(l.x, l.y) < 0.3e-3 && l.z > -0.4e-3);
  });
  const SurfaceGrade g = grade_surface(t, particle_surface(pitted, s), fine());
  ASSERT_TRUE(g.voids.measured) << g.voids.why_not;
  ASSERT_EQ(g.voids.count, 1);
  EXPECT_NEAR(g.voids.pits[0].depth_mm, 0.40, 0.06);
  const real removed = std::numbers::pi * 0.3 * 0.3 * 0.4;  // mm^3, the particles' place
  EXPECT_NEAR(g.voids.pits[0].volume_mm3, removed, 0.15 * removed);
  EXPECT_NEAR(g.voids.pits[0].centre_mm.x, 0, 0.05);
  EXPECT_NEAR(g.voids.pits[0].centre_mm.y, 0, 0.05);
  EXPECT_TRUE(g.margin.defects.empty());

  const auto whole = lattice(t, 0, [&](const Vec3& l) { return t.in_cavity(t.frame().to_world(l)); });
  EXPECT_EQ(grade_surface(t, particle_surface(whole, s), fine()).voids.count, 0);
  const auto short_end = lattice(t, 0, [&](const Vec3& l) {
    return t.in_cavity(t.frame().to_world(l)) && !(l.x > 1.5e-3 && l.z > -0.3e-3);
  });
  const SurfaceGrade dip = grade_surface(t, particle_surface(short_end, s), fine());
  EXPECT_EQ(dip.voids.count, 0);
  EXPECT_EQ(dip.margin.defects.size(), 1u);
}

TEST(SurfaceGrade, AnEmptyCavityIsUnderContouredToItsFloorAndAllGap) {
  const PreparedTooth t = box_tooth();
  const SurfaceGrade g = grade_surface(t, SurfaceMesh{}, fine());
  ASSERT_TRUE(g.anatomic.measured);
  EXPECT_NEAR(g.anatomic.max_under_mm, 2.0, 0.02);  // the default cavity's 2 mm depth
  EXPECT_EQ(g.anatomic.band, 'C');
  ASSERT_EQ(g.margin.defects.size(), 1u);
  EXPECT_EQ(g.margin.defects[0].kind, "gap");
  EXPECT_NEAR(g.margin.gap_length_mm, kOutline_mm, 0.01 * kOutline_mm);
}

TEST(SurfaceGrade, AClassIIsProximalOpeningIsNotGradedAsAMargin) {
  const PreparedTooth t = box_tooth(CavityClass::class_2);
  const auto p = lattice(t, 0, [&](const Vec3& l) { return t.in_cavity(t.frame().to_world(l)); });
  const SurfaceGrade g = grade_surface(t, particle_surface(p, s), fine());
  ASSERT_TRUE(g.margin.measured);
  EXPECT_GT(g.margin.open_samples, 0);
  EXPECT_LT(g.margin.open_samples, 360);  // the box's side only
  EXPECT_EQ(g.anatomic.band, 'A');
}

// A Class II's proximal surface against the intact tooth's (the box tooth's mesial face, x = 5 mm,
// where the neighbour is taken to stand): its box filled to the face, a tight contact and no
// overhang; 0.1 mm short, light; 0.4 mm short, open; 0.4 mm of paste beyond the face over the
// box's lowest 0.5 mm, an overhang of 0.4 mm (and a tight contact: it reaches the neighbour). A
// Class I has none.
TEST(SurfaceGrade, AClassIIsContactAndOverhangAreReadAgainstTheIntactContour) {
  const PreparedTooth t = box_tooth(CavityClass::class_2);
  auto filled_to = [&](real x_max) {
    return grade_surface(t, particle_surface(lattice(t, 0, [&](const Vec3& l) {
                                               return t.in_cavity(t.frame().to_world(l)) && l.x < x_max;
                                             }),
                                             s),
                         fine())
        .proximal;
  };
  const ProximalGrade full = filled_to(1);
  ASSERT_TRUE(full.measured) << full.why_not;
  EXPECT_EQ(full.side, "mesial");
  EXPECT_NEAR(full.contact_mm.x, 5.0, 1e-6);
  EXPECT_NEAR(full.gap_mm, 0, 0.03);
  EXPECT_EQ(full.contact, "tight");
  EXPECT_LT(full.overhang_mm, 0.05);
  EXPECT_EQ(full.overhang_area_mm2, 0);
  const ProximalGrade light = filled_to(4.9e-3);
  EXPECT_NEAR(light.gap_mm, 0.1, 0.03);
  EXPECT_EQ(light.contact, "light");
  const ProximalGrade open = filled_to(4.6e-3);
  EXPECT_NEAR(open.gap_mm, 0.4, 0.03);
  EXPECT_EQ(open.contact, "open");

  auto over = lattice(t, 0, [&](const Vec3& l) { return t.in_cavity(t.frame().to_world(l)); });
  for (const Vec3& q : lattice(t, 0, [](const Vec3& l) {
         return l.x > 5e-3 && l.x < 5.4e-3 && l.z > -3.5e-3 && l.z < -3.0e-3 && std::abs(l.y) < 1.5e-3;
       }))
    over.push_back(q);
  const ProximalGrade hang = grade_surface(t, particle_surface(over, s), fine()).proximal;
  EXPECT_NEAR(hang.overhang_mm, 0.4, 0.03);
  EXPECT_NEAR(hang.overhang_area_mm2, 3.0 * 0.5, 0.5);
  EXPECT_EQ(hang.contact, "tight");

  const ProximalGrade none = grade_surface(box_tooth(), SurfaceMesh{}, fine()).proximal;
  EXPECT_FALSE(none.measured);
  EXPECT_NE(none.why_not.find("Class I"), std::string::npos);
}

TEST(SurfaceGrade, ParametersOutOfRangeAreRefusedNamingTheField) {
  const PreparedTooth t = box_tooth();
  GradeParams p;
  p.spacing = 0;
  try {
    grade_surface(t, SurfaceMesh{}, p);
    ADD_FAILURE() << "a spacing of 0 was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("spacing"), std::string::npos) << e.what();
  }
  p = GradeParams{};
  p.margin_samples = 3;
  EXPECT_THROW(grade_surface(t, SurfaceMesh{}, p), std::invalid_argument);
  p = GradeParams{};
  p.step_threshold = std::nan("");
  EXPECT_THROW(grade_surface(t, SurfaceMesh{}, p), std::invalid_argument);
}

}  // namespace
}  // namespace dentsph
