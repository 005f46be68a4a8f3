// The physics of light curing that teaches the rule of 2 mm increments (docs/model.md, "Curing"):
// two 2 mm increments cured 20 s each are adequately cured throughout, one 4 mm increment is not;
// more dose or a clearer paste cures deeper; a shadowed region cures less; shrinkage keeps the mass
// and takes the volume down by the set fraction; a cured increment resists the ball burnisher; the
// paste cures while it is stepped; the ISO 4049 depth of cure matches the published value.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "dentsph/cure_assessment.hpp"
#include "dentsph/depth_of_cure.hpp"
#include "dentsph/step.hpp"
#include "dentsph/tools.hpp"
#include "support/cure_scenes.hpp"

namespace dentsph::testing {
namespace {

constexpr real mm = 1e-3;
const Vec3 kUp{0, 0, 1};

// A slab 4 x 4 mm of paste at 0.2 mm on a floor of tooth, built in increments of `layers` each,
// each cured for `seconds` with the light's window on its top.
struct Slab {
  real s = 0.2 * mm;
  int n = 20;
  Model model = cure_model(s, {-1 * mm, -1 * mm, -1 * mm}, {5 * mm, 5 * mm, 8 * mm});
  CureModel cure;
  State st;
  real top = 0;
  explicit Slab(const CureMaterial& m = cure_material_preset("composite")) {
    cure = make_cure_model(model, m, s, kPaste);
    add_floor(model, st, s, n, n, 0, 3);
  }
  void add_increment(int layers) {
    add_paste_layers(model, st, s, n, n, top, layers);
    top += layers * s;
  }
  void cure_top(real seconds, real irradiance_mw = 1000) {
    cure_at_rest(cure, st, light_above({2 * mm, 2 * mm, top}, irradiance_mw), seconds);
  }
  CureAssessment assess() const { return assess_cure(cure, st, kUp); }
};

void print(const CureAssessment& a) {
  std::printf("%s", cure_assessment_report(a).c_str());
}

TEST(CurePhysics, TwoIncrementsOfTwoMillimetresCureThroughoutOneOfFourDoesNot) {
  Slab two;
  two.add_increment(10);
  two.cure_top(20);
  two.add_increment(10);
  two.cure_top(20);
  const CureAssessment a = two.assess();
  print(a);
  ASSERT_EQ(a.increments.size(), 2u);
  for (const IncrementCure& c : a.increments) {
    EXPECT_NEAR(c.thickness, 2 * mm, 0.02 * mm) << "2 mm, less its shrinkage";
    EXPECT_GE(c.base_alpha / c.top_alpha, 0.8) << c.message;
    EXPECT_EQ(c.adequate_fraction, 1.0) << c.message;
  }
  EXPECT_EQ(a.under_cured_volume, 0);

  Slab one;
  one.add_increment(20);
  one.cure_top(20);
  const CureAssessment b = one.assess();
  print(b);
  ASSERT_EQ(b.increments.size(), 1u);
  const IncrementCure& c = b.increments[0];
  EXPECT_NEAR(c.thickness, 4 * mm, 0.04 * mm);
  EXPECT_LT(c.base_alpha / c.top_alpha, 0.5) << c.message;
  EXPECT_LT(c.base_dose, 0.5e4) << "under 0.5 J/cm2 at the base";
  EXPECT_LT(c.adequate_fraction, 0.7) << c.message;
  EXPECT_GT(c.adequate_fraction, 0.5) << "the top 2 mm or so are cured";
  EXPECT_GT(c.under_cured_from, 2 * mm);
  EXPECT_LT(c.under_cured_from, 3 * mm);
  EXPECT_NEAR(b.under_cured_volume, (1 - c.adequate_fraction) * b.paste_volume, 0.01 * b.under_cured_volume);
  EXPECT_NE(c.message.find("% of it is under-cured"), std::string::npos) << c.message;
}

// The adequately cured depth of a 4 mm increment (its adequately cured share times its thickness).
real cured_depth(const CureMaterial& m, real seconds, real irradiance_mw) {
  Slab slab(m);
  slab.add_increment(20);
  slab.cure_top(seconds, irradiance_mw);
  const IncrementCure c = slab.assess().increments.at(0);
  std::printf("  %s\n", c.message.c_str());
  return c.adequate_fraction * c.thickness;
}

TEST(CurePhysics, MoreDoseOrAClearerPasteCuresDeeper) {
  const CureMaterial composite = cure_material_preset("composite");
  CureMaterial clear = composite;  // a translucent (bulk-fill like) paste
  clear.attenuation_uncured = 600, clear.attenuation_cured = 500;
  const real base = cured_depth(composite, 20, 1000);
  const real longer = cured_depth(composite, 40, 1000);
  const real brighter = cured_depth(composite, 20, 2000);
  const real clearer = cured_depth(clear, 20, 1000);
  std::printf("adequately cured depth of a 4 mm increment: 20 s at 1000 mW/cm2 %.2f mm, 40 s %.2f mm, "
              "2000 mW/cm2 %.2f mm, clearer paste %.2f mm\n",
              base / mm, longer / mm, brighter / mm, clearer / mm);
  EXPECT_GT(base, 2 * mm);
  EXPECT_LT(base, 3 * mm);
  EXPECT_GE(longer, base + 0.4 * mm) << "twice the dose: ln 2 / 1.15 per mm deeper, about 0.6 mm";
  EXPECT_NEAR(brighter, longer, 0.2 * mm + 1e-12) << "the same dose: the law is of the dose";
  EXPECT_GT(clearer, 3.9 * mm) << "a clearer paste cures the whole 4 mm (less its shrinkage)";
}

TEST(CurePhysics, AShadowedRegionCuresLess) {
  Slab slab;
  slab.add_increment(10);  // 2 mm
  // A ledge of tooth 0.6 mm thick over the half x < 2 mm, 1 mm above the paste (an overhanging wall).
  std::vector<ParticleInit> ledge;
  const real m = lattice_particle_mass(kWall.rho0, slab.s, slab.model.kernel);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < slab.n; ++j)
      for (int i = 0; i < slab.n / 2; ++i)
        ledge.push_back(make_particle(Role::boundary, {(i + 0.5) * slab.s, (j + 0.5) * slab.s, 3 * mm + (k + 0.5) * slab.s}, m, kWall));
  slab.st.add_particles(slab.model, ledge);
  cure_at_rest(slab.cure, slab.st, light_above({2 * mm, 2 * mm, 4 * mm}), 20);
  real shaded = 0, lit = 0;
  int ns = 0, nl = 0;
  for (std::uint32_t i = 0; i < slab.st.size(); ++i) {
    const Vec3 p = slab.st.cure.gel_pos[slab.st.id[i]];
    if (!slab.st.cure.curable[slab.st.id[i]] || p.z > 0.2 * mm) continue;  // the base layer
    if (p.x < 1.6 * mm) shaded += slab.st.cure.alpha[slab.st.id[i]], ++ns;
    if (p.x > 2.4 * mm) lit += slab.st.cure.alpha[slab.st.id[i]], ++nl;
  }
  shaded /= ns, lit /= nl;
  const CureAssessment a = slab.assess();
  print(a);
  std::printf("base conversion: shaded %.3f, lit %.3f\n", shaded, lit);
  EXPECT_LT(shaded, 0.6 * lit);
  EXPECT_GT(lit, 0.8 * slab.cure.paste.alpha_max);
  EXPECT_LT(a.increments.at(0).adequate_fraction, 0.9) << "the shadowed base is under-cured";
}

// Mass-weighted covariance of positions: its determinant's square root scales as a volume.
real volume_measure(const State& st) {
  Vec3 c;
  real m = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i)
    if (st.cure.curable[st.id[i]]) c += st.mass[i] * st.pos[i], m += st.mass[i];
  c = c / m;
  real C[3][3] = {};
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    if (!st.cure.curable[st.id[i]]) continue;
    const Vec3 d = st.pos[i] - c;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) C[a][b] += st.mass[i] * d[a] * d[b] / m;
  }
  const real det = C[0][0] * (C[1][1] * C[2][2] - C[1][2] * C[2][1]) - C[0][1] * (C[1][0] * C[2][2] - C[1][2] * C[2][0]) +
                   C[0][2] * (C[1][0] * C[2][1] - C[1][1] * C[2][0]);
  return std::sqrt(det);
}

TEST(CurePhysics, ShrinkageKeepsTheMassAndTakesTheVolumeDownByTheSetFraction) {
  Slab slab;
  slab.add_increment(5);  // 1 mm: cured to its maximum throughout in 60 s
  auto totals = [&] {
    real mass = 0, rest_volume = 0;
    for (std::uint32_t i = 0; i < slab.st.size(); ++i)
      if (slab.st.cure.curable[slab.st.id[i]]) mass += slab.st.mass[i], rest_volume += slab.st.mass[i] / slab.st.rho0[i];
    return std::pair{mass, rest_volume};
  };
  const auto [mass0, rest0] = totals();
  const real v0 = volume_measure(slab.st);
  slab.cure_top(60);
  const auto [mass1, rest1] = totals();
  const real v1 = volume_measure(slab.st);
  const CureMaterial& m = slab.cure.paste;
  for (std::uint32_t id = 0; id < slab.st.size(); ++id)
    if (slab.st.cure.curable[id]) {
      ASSERT_GT(slab.st.cure.alpha[id], 0.999 * m.alpha_max);
      ASSERT_EQ(slab.st.cure.rigid[id], 1);
    }
  EXPECT_EQ(mass1, mass0);
  // The set part's geometry: from the gel point on, (1 - S) / (1 - S alpha_gel / alpha_max).
  const real shrunk = 1 - v1 / v0;
  std::printf("volume shrinkage: geometric %.4f, rest volume %.4f, set %.4f\n", shrunk, 1 - rest1 / rest0, m.shrinkage);
  EXPECT_NEAR(shrunk, m.shrinkage, 0.1 * m.shrinkage);
  EXPECT_NEAR(1 - rest1 / rest0, m.shrinkage, 0.001 * m.shrinkage);
}

// The ball burnisher pressed 0.2 mm into paste: set paste pushes back at least ten times harder.
real press_force(bool cured) {
  const real s = 0.3 * mm, dt = 5e-5;
  Model model = cure_model(s, {-2 * mm, -2 * mm, -2 * mm}, {5 * mm, 5 * mm, 6 * mm}, dt);
  State st;
  const real wall_mass = lattice_particle_mass(kWall.rho0, s, model.kernel);
  std::vector<ParticleInit> walls;
  for (const Vec3& p : open_container({0, 0, 0}, s, 10, 10, 8, 2)) walls.push_back(make_particle(Role::boundary, p, wall_mass, kWall));
  st.add_particles(model, walls);
  add_paste_layers(model, st, s, 11, 11, -0.5 * s, 5);  // 3.3 x 3.3 x 1.5 mm
  const Vec3 centre{1.65 * mm, 1.65 * mm, 0};
  st.tool_pose = st.tool_pose_applied = Pose{centre + Vec3{0, 0, 3 * mm}, {}};
  st.add_particles(model, tool_particles(ball_burnisher(3.65 * s, s), wall_mass, kWall));
  const CureModel cm = make_cure_model(model, cure_material_preset("composite"), s, kPaste);
  for (int k = 0; k < 2000; ++k) step(model, st);  // settle 0.1 s
  if (cured) cure_at_rest(cm, st, light_above(centre + Vec3{0, 0, 2 * mm}), 20);
  real surface = -1;
  for (std::uint32_t i = 0; i < st.size(); ++i)
    if (st.cure.curable[st.id[i]]) surface = std::max(surface, st.pos[i].z + 0.5 * s);
  // Down at 10 mm/s from 0.3 mm above the surface to 0.2 mm into it, then held.
  const real v = 10 * mm, from = surface + 0.3 * mm, to = surface - 0.2 * mm;
  const int moving = int(std::lround((from - to) / v / dt));
  real force = 0;
  for (int k = 0; k <= moving + 200; ++k) {
    const real z = k < moving ? from - v * dt * k : to;
    st.tool_pose = Pose{{centre.x, centre.y, z}, {}};
    step(model, st);
    cure_between_steps(cm, st, std::nullopt, dt);
    EXPECT_EQ(st.diagnostics.non_finite, 0u);
    if (k > moving + 100) force += st.tool_wrench.force.z / 100;
  }
  return force;
}

TEST(CurePhysics, ACuredIncrementResistsTheBall) {
  const real paste = press_force(false), set = press_force(true);
  std::printf("force to hold the ball 0.2 mm in: uncured %.3g N, cured %.3g N (%.0fx)\n", paste, set, set / paste);
  EXPECT_GT(paste, 0);
  EXPECT_GE(set, 10 * paste);
}

// Curing while the step runs: the top of the paste sets within 0.1 s of light and stays where it
// set, the paste below it keeps flowing and stays bonded to it, nothing diverges.
TEST(CurePhysics, PasteCuresWhileItIsStepped) {
  const real s = 0.3 * mm, dt = 5e-5;
  Model model = cure_model(s, {-2 * mm, -2 * mm, -2 * mm}, {5 * mm, 5 * mm, 6 * mm}, dt);
  State st;
  const real wall_mass = lattice_particle_mass(kWall.rho0, s, model.kernel);
  std::vector<ParticleInit> walls;
  for (const Vec3& p : open_container({0, 0, 0}, s, 8, 8, 8, 2)) walls.push_back(make_particle(Role::boundary, p, wall_mass, kWall));
  st.add_particles(model, walls);
  add_paste_layers(model, st, s, 9, 9, -0.5 * s, 6);  // 1.8 mm deep
  const CureModel cm = make_cure_model(model, cure_material_preset("composite"), s, kPaste);
  for (int k = 0; k < 500; ++k) step(model, st);
  const CuringLight light = light_above({1.35 * mm, 1.35 * mm, 3 * mm});
  std::uint32_t set_total = 0;
  for (int k = 0; k < 2000; ++k) {
    step(model, st);
    set_total += cure_between_steps(cm, st, light, dt).set;
    ASSERT_EQ(st.diagnostics.non_finite, 0u) << k;
  }
  std::uint32_t rigid = 0, paste = 0, bonded_to_set = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    const std::uint32_t id = st.id[i];
    if (!st.cure.curable[id]) continue;
    if (st.cure.rigid[id]) {
      ++rigid;
      EXPECT_EQ(st.role[i], Role::boundary);
      EXPECT_LT(norm(st.pos[i] - st.cure.gel_pos[id]), 0.05 * s) << "stays where it set (less its shrinkage)";
      EXPECT_GT(st.rho_static[id], 0);
    } else {
      ++paste;
      for (int b = 0; b < st.bonds.count(id); ++b) bonded_to_set += st.cure.rigid[st.bonds.partner(id, b)];
    }
  }
  std::printf("after 0.1 s of light: %u set, %u paste, %u bonds from paste to set paste\n", rigid, paste, bonded_to_set);
  EXPECT_EQ(rigid, set_total);
  EXPECT_GT(rigid, 2u * 81u) << "the top layers set (the gel dose reaches about 1 mm in 0.1 s)";
  EXPECT_GT(paste, 0u) << "the base is still paste";
  EXPECT_GT(bonded_to_set, 0u);
  EXPECT_LT(st.diagnostics.max_speed, 0.1) << "m/s: nothing is thrown about";
}

TEST(CurePhysics, TheVirtualDepthOfCureTestMatchesThePublishedValue) {
  for (real spacing : {0.2 * mm, 0.1 * mm}) {
    DepthOfCureOptions o;
    o.spacing = spacing;
    const DepthOfCureResult r = depth_of_cure_test(o);
    std::printf("%s", depth_of_cure_report(o, r).c_str());
    ASSERT_GT(r.published.depth, 0);
    EXPECT_NEAR(r.depth, r.published.depth, 0.1 * r.published.depth);
    EXPECT_FALSE(r.set_to_bottom);
  }
}

}  // namespace
}  // namespace dentsph::testing
