// Cavities: volumes against the analytic volume of each box shape in a flat-topped block,
// Class I and II in the built-in crown and the real molars (volume checked by Monte Carlo), the
// inside-cavity predicate, and the refusals with their reasons.
#include <gtest/gtest.h>

#include <random>

#include "test_tooth_support.hpp"

namespace dentsph {
namespace {

using namespace dentsph::testing;
constexpr real mm = 1e-3, mm3 = mm * mm * mm;
constexpr real pi = 3.14159265358979323846;

// A flat-topped block 12 x 10 x 8 mm centred on the origin, z up: the occlusal reference is its
// top face, so each cavity's volume is known in closed form.
struct Block {
  MeshDistance tooth{
      repair_mesh(box_mesh({-6 * mm, -5 * mm, -4 * mm}, {6 * mm, 5 * mm, 4 * mm}), "block").mesh};
  ToothFrame frame = make_tooth_frame({0, 0, 0}, {0, 0, 1}, {1, 0, 0});
};

CavityParams plain(real w, real l, real d) {
  CavityParams p;
  p.width = w;
  p.length = l;
  p.depth = d;
  p.taper_deg = 0;
  p.rounding = 0;
  return p;
}

std::string refusal(const MeshDistance& tooth, const ToothFrame& f, const CavityParams& p) {
  try {
    carve_cavity(tooth, f, p);
  } catch (const CavityError& e) {
    return e.what();
  }
  return "(accepted)";
}

// Volume of {in_cavity} by uniform sampling of the cavity's bounds (independent of the octree).
real monte_carlo_volume(const PreparedTooth& t, int n, unsigned seed) {
  const Bounds b = t.cavity_bounds();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<real> u(0, 1);
  int hits = 0;
  for (int i = 0; i < n; ++i)
    hits +=
        t.in_cavity({b.min.x + u(rng) * (b.max.x - b.min.x), b.min.y + u(rng) * (b.max.y - b.min.y),
                     b.min.z + u(rng) * (b.max.z - b.min.z)});
  const Vec3 e = b.max - b.min;
  return e.x * e.y * e.z * hits / n;
}

TEST(ToothCavity, BoxVolumesMatchTheirClosedForms) {
  const Block block;
  // Square box: w l d.
  const PreparedTooth box = carve_cavity(block.tooth, block.frame, plain(3 * mm, 5 * mm, 2 * mm));
  EXPECT_NEAR(box.cavity_volume() / mm3, 30.0, 0.3);
  EXPECT_NEAR(box.report().occlusal_point.z, 4 * mm, 1e-12);  // the block's top face
  // Rounded edges and corners (radius r): the core's rounded rectangle above the floor's
  // quarter-round, plus the quarter-round's own volume.
  {
    CavityParams p = plain(3 * mm, 5 * mm, 2 * mm);
    p.rounding = 0.5 * mm;
    const real r = 0.5, a = 3 - 2 * r, b = 5 - 2 * r, d = 2;
    const real expect = (3 * 5 - (4 - pi) * r * r) * (d - r) + a * b * r +
                        (a + b) * pi * r * r / 2 + 2 * pi * r * r * r / 3;
    EXPECT_NEAR(carve_cavity(block.tooth, block.frame, p).cavity_volume() / mm3, expect,
                0.01 * expect);
  }
  // Tapered walls (8 degrees of occlusal divergence): a prismatoid, d / 6 (top + 4 mid + bottom).
  {
    CavityParams p = plain(3 * mm, 5 * mm, 2 * mm);
    p.taper_deg = 8;
    const real t = std::tan(8 * pi / 180), d = 2;
    auto area = [&](real depth) { return (3 - 2 * depth * t) * (5 - 2 * depth * t); };
    const real expect = d / 6 * (area(0) + 4 * area(d / 2) + area(d));
    EXPECT_NEAR(carve_cavity(block.tooth, block.frame, p).cavity_volume() / mm3, expect,
                0.01 * expect);
  }
  // Class II through the +x face: occlusal part to the face, plus the box, less their overlap.
  {
    CavityParams p = plain(3 * mm, 5 * mm, 2 * mm);
    p.kind = CavityClass::class_2;
    p.box_width = 4 * mm;
    p.box_depth = 3.5 * mm;
    p.box_axial_depth = 1.5 * mm;
    const real expect = (6 + 2.5) * 3 * 2 + 1.5 * 4 * 3.5 - 1.5 * 3 * 2;
    const PreparedTooth c2 = carve_cavity(block.tooth, block.frame, p);
    EXPECT_NEAR(c2.cavity_volume() / mm3, expect, 0.01 * expect);
    // Distal: the mirror image, same volume, reaching the -x face instead.
    p.side = ProximalSide::distal;
    const PreparedTooth d2 = carve_cavity(block.tooth, block.frame, p);
    EXPECT_NEAR(d2.cavity_volume() / mm3, expect, 0.01 * expect);
    EXPECT_TRUE(c2.in_cavity({5.9 * mm, 0, 1 * mm}));
    EXPECT_FALSE(d2.in_cavity({5.9 * mm, 0, 1 * mm}));
    EXPECT_TRUE(d2.in_cavity({-5.9 * mm, 0, 1 * mm}));
  }
}

TEST(ToothCavity, ClassOneAndTwoCarveIntoTheBuiltInCrown) {
  const MolarCrown crown = molar_crown();
  const MeshDistance tooth(crown.mesh);
  const PreparedTooth c1 = carve_cavity(tooth, crown.frame);  // the defaults: the built-in scene
  CavityParams p2;
  p2.kind = CavityClass::class_2;
  const PreparedTooth c2 = carve_cavity(tooth, crown.frame, p2);
  for (const PreparedTooth* t : {&c1, &c2}) {
    const CavityReport& r = t->report();
    SCOPED_TRACE(r.summary());
    // The fossa of the crown: on the axis, below the cusp tips (7 mm).
    EXPECT_NEAR(r.occlusal_point.x, 0, 1e-12);
    EXPECT_GT(r.occlusal_point.z, 4.5 * mm);
    EXPECT_LT(r.occlusal_point.z, 6.5 * mm);
    EXPECT_GE(r.min_wall, t->params().min_wall);
    EXPECT_GE(r.min_floor, t->params().min_floor);
    EXPECT_NEAR(monte_carlo_volume(*t, 20000, 5), t->cavity_volume(), 0.05 * t->cavity_volume());
    // In the cavity half-way down; not below its floor, nor above the tooth.
    const Vec3 top = r.occlusal_point;
    EXPECT_TRUE(t->in_cavity(top - Vec3{0, 0, 1 * mm}));
    EXPECT_FALSE(t->in_cavity(top - Vec3{0, 0, 2.5 * mm}));
    EXPECT_FALSE(t->in_cavity(top + Vec3{0, 0, 3 * mm}));
  }
  // Class I: at least its box below the reference (w l d less the rounding), plus the cusp
  // slopes above it; Class II adds the box and the marginal ridge.
  EXPECT_GT(c1.cavity_volume(), 25 * mm3);
  EXPECT_LT(c1.cavity_volume(), 45 * mm3);
  EXPECT_GT(c2.cavity_volume(), c1.cavity_volume() + 10 * mm3);
  // The Class II cavity opens on the mesial (+x) side: the crown's mesial surface at mid-box
  // height is gone.
  EXPECT_TRUE(c2.in_cavity({5.2 * mm, 0, c2.report().occlusal_point.z - 2.5 * mm}));
  EXPECT_FALSE(c1.in_cavity({5.2 * mm, 0, c2.report().occlusal_point.z - 2.5 * mm}));
}

TEST(ToothCavity, ClassOneAndTwoCarveIntoBothRealMolars) {
  DENTSPH_NEED_DATA();
  for (const fs::path& file : {molar_36, molar_46}) {
    const LoadedMesh m = load_mesh(file);
    const MeshDistance tooth(m.mesh);
    const ToothFrame f = find_tooth_frame(m.mesh);
    for (CavityClass kind : {CavityClass::class_1, CavityClass::class_2}) {
      CavityParams p;
      p.kind = kind;
      const PreparedTooth t = carve_cavity(tooth, f, p);
      SCOPED_TRACE(file.string() + ": " + t.report().summary());
      EXPECT_GE(t.report().min_wall, p.min_wall);
      EXPECT_GE(t.report().min_floor, p.min_floor);
      EXPECT_GT(t.cavity_volume(), (kind == CavityClass::class_1 ? 15 : 30) * mm3);
      EXPECT_LT(t.cavity_volume(), (kind == CavityClass::class_1 ? 50 : 80) * mm3);
      EXPECT_NEAR(monte_carlo_volume(t, 20000, 9), t.cavity_volume(), 0.06 * t.cavity_volume());
      // The occlusal reference is the top of the crown near the axis: on or just above the
      // surface where the axis meets it, high on the tooth.
      const real above = tooth.signed_distance(t.report().occlusal_point);
      EXPECT_GE(above, -1e-9);
      EXPECT_LT(above, 0.5 * mm);
      EXPECT_GT(f.to_local(t.report().occlusal_point).z, 5 * mm);
    }
  }
}

TEST(ToothCavity, TooDeepTooWideAndMisfitCavitiesAreRefusedWithTheReason) {
  const MolarCrown crown = molar_crown();
  const MeshDistance tooth(crown.mesh);
  CavityParams deep;
  deep.depth = 5 * mm;  // the fossa is ~5.4 mm above the base
  const std::string d = refusal(tooth, crown.frame, deep);
  EXPECT_NE(d.find("cavity does not fit: the pulpal floor leaves too little tooth"),
            std::string::npos)
      << d;
  EXPECT_NE(d.find("1.00 mm required (min_floor)"), std::string::npos) << d;
  EXPECT_NE(d.find("shallower"), std::string::npos) << d;

  CavityParams wide;
  wide.width = 9 * mm;  // the crown is 10 mm across
  const std::string w = refusal(tooth, crown.frame, wide);
  EXPECT_NE(w.find("side wall of the occlusal box"), std::string::npos) << w;
  EXPECT_NE(w.find("(min_wall)"), std::string::npos) << w;
  EXPECT_NE(w.find("narrower"), std::string::npos) << w;

  CavityParams off;
  off.length = 14 * mm;  // longer than the crown: the end walls are outside it
  const std::string o = refusal(tooth, crown.frame, off);
  EXPECT_NE(o.find("lies outside the tooth"), std::string::npos) << o;
  EXPECT_NE(o.find("runs off the crown"), std::string::npos) << o;

  CavityParams deep_box;
  deep_box.kind = CavityClass::class_2;
  deep_box.box_depth = 5.2 * mm;
  const std::string b = refusal(tooth, crown.frame, deep_box);
  EXPECT_NE(b.find("gingival floor"), std::string::npos) << b;

  // A frame whose axis misses the tooth.
  const ToothFrame beside = make_tooth_frame({20 * mm, 0, 0}, {0, 0, 1}, {1, 0, 0});
  EXPECT_NE(refusal(tooth, beside, {}).find("long axis does not meet"), std::string::npos);
}

TEST(ToothCavity, ParametersOutOfRangeAreRefusedByName) {
  const MolarCrown crown = molar_crown();
  const MeshDistance tooth(crown.mesh);
  CavityParams p;
  p.width = -1 * mm;
  EXPECT_NE(refusal(tooth, crown.frame, p).find("width = -1 mm: must be > 0"), std::string::npos);
  p = {};
  p.taper_deg = 45;
  EXPECT_NE(refusal(tooth, crown.frame, p).find("taper_deg = 45"), std::string::npos);
  p = {};
  p.rounding = 1.6 * mm;  // the 3 mm wide floor cannot hold it
  const std::string r = refusal(tooth, crown.frame, p);
  EXPECT_NE(r.find("occlusal box: the rounding radius 1.600 mm does not fit"), std::string::npos)
      << r;
  p = {};
  p.kind = CavityClass::class_2;
  p.box_depth = 1 * mm;  // shallower than the pulpal floor
  EXPECT_NE(refusal(tooth, crown.frame, p).find("box_depth = 1 mm"), std::string::npos);
  p.box_depth = 3.5 * mm;
  p.box_axial_depth = 8 * mm;  // past the axis
  EXPECT_NE(refusal(tooth, crown.frame, p).find("reaches past the long axis"), std::string::npos);
}

}  // namespace
}  // namespace dentsph
