// The filling assessment on constructed states: a cavity with a particle on every lattice point
// scores full and void-free whatever the lattice's offset against the voxels; holes of known
// volume are found as voids of that volume; a hole open to the surface and the space the tool
// takes are not voids; a slab above the margin is overfill of its volume; particles in the
// tooth wall or off the domain are leaked, non-finite or far ones lost; and the force
// statistics, the report and the JSON carry the numbers.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "dentsph/assess.hpp"
#include "dentsph/model.hpp"
#include "dentsph/state.hpp"
#include "dentsph/tools.hpp"
#include "support/builders.hpp"

namespace dentsph {
namespace {

using namespace dentsph::testing;
constexpr real mm = 1e-3, mm3 = mm * mm * mm;
constexpr real s = default_tooth_spacing;  // 0.3 mm
const Material paste{1.0, 10, 2000, 50};

// A prepared tooth, its assessor at the defaults (voxels of s / 2), the model of the built-in
// scene's domain (the cavity's bounds and 4 mm around them), and the tooth-frame lattice of
// pitch s (shifted by `offset`) cut to the cavity.
struct Case {
  PreparedTooth tooth;
  CavityAssessor assessor;
  Model model;
  Bounds local;             // m, frame coordinates: the cavity's bounds
  std::vector<Vec3> frame;  // m, lattice points in the cavity, frame coordinates
  std::vector<Vec3> world;  // the same, world

  // `assessor` is built from `t` when not given (copies share the voxels).
  Case(const PreparedTooth& t, Vec3 offset, std::optional<CavityAssessor> a = std::nullopt)
      : tooth(t),
        assessor(a ? *a : CavityAssessor(t)),
        model(make_model(domain(t))),
        local(frame_bounds(t)) {
    model.materials.add("paste", paste);
    for (const Vec3& q : lattice_in(offset))
      if (tooth.in_cavity(tooth.frame().to_world(q))) add(q);
  }

  static ModelParams domain(const PreparedTooth& t) {
    const Bounds cb = t.cavity_bounds();
    const Vec3 pad{4 * mm, 4 * mm, 4 * mm};
    return params_for_spacing(s, cb.min - pad, cb.max + pad);
  }
  static Bounds frame_bounds(const PreparedTooth& t) {
    const Bounds cb = t.cavity_bounds();
    Bounds b{t.frame().to_local(cb.min), t.frame().to_local(cb.min)};
    for (int k = 0; k < 8; ++k) {
      const Vec3 c = t.frame().to_local(
          {k & 1 ? cb.max.x : cb.min.x, k & 2 ? cb.max.y : cb.min.y, k & 4 ? cb.max.z : cb.min.z});
      b.min = {std::min(b.min.x, c.x), std::min(b.min.y, c.y), std::min(b.min.z, c.z)};
      b.max = {std::max(b.max.x, c.x), std::max(b.max.y, c.y), std::max(b.max.z, c.z)};
    }
    return b;
  }
  // Lattice points (frame coordinates) in the cavity's bounds grown by 2 mm (room for a slab).
  std::vector<Vec3> lattice_in(Vec3 offset) const {
    std::vector<Vec3> pts;
    auto range = [](real lo, real hi, real off) {
      return std::pair<int, int>{int(std::floor((lo - off) / s)), int(std::ceil((hi - off) / s))};
    };
    const auto [i0, i1] = range(local.min.x - 2 * mm, local.max.x + 2 * mm, offset.x);
    const auto [j0, j1] = range(local.min.y - 2 * mm, local.max.y + 2 * mm, offset.y);
    const auto [k0, k1] = range(local.min.z, local.max.z + 2 * mm, offset.z);
    for (int k = k0; k <= k1; ++k)
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) pts.push_back(offset + Vec3{i * s, j * s, k * s});
    return pts;
  }
  void add(const Vec3& q) {
    frame.push_back(q);
    world.push_back(tooth.frame().to_world(q));
  }
};

State material_state(const Model& model, const std::vector<Vec3>& world,
                     const std::vector<Vec3>& tool = {}) {
  std::vector<ParticleInit> ps;
  for (const Vec3& p : world) ps.push_back(particle(Role::material, p, 1e-8, paste));
  for (const Vec3& p : tool) ps.push_back(particle(Role::tool, p, 1e-8, paste));
  State st;
  st.add_particles(model, ps);
  return st;
}

Assessment assess(const Case& c, const std::vector<Vec3>& world,
                  const std::vector<Vec3>& tool = {}) {
  return c.assessor.assess(material_state(c.model, world, tool), c.model);
}

// The built-in scene's tooth (default_tooth_scene(): the molar crown with the default Class I,
// 2 mm deep), carved here without the boundary sampling the assessment does not need.
const MolarCrown& crown() {
  static const MolarCrown c = molar_crown();
  return c;
}
const PreparedTooth& default_tooth() {
  static const PreparedTooth t = carve_cavity(MeshDistance(crown().mesh), crown().frame);
  return t;
}
const Case& default_case() {
  static const Case c(default_tooth(), {});
  return c;
}

// A 3 mm deep, 4 x 6 mm Class I in the built-in crown: room for a hole of 3 spacings radius
// with two spacings of material on every side (the default cavity is 2 mm deep).
const Case& deep_case() {
  static const Case c = [] {
    CavityParams p;
    p.depth = 3 * mm;
    p.width = 4 * mm;
    p.length = 6 * mm;
    return Case(carve_cavity(MeshDistance(crown().mesh), crown().frame, p), {});
  }();
  return c;
}

// Removes the points within `radius` of `centre` (frame coordinates); returns how many.
int remove_ball(const Case& c, std::vector<Vec3>& world, Vec3 centre, real radius) {
  std::vector<Vec3> kept;
  int removed = 0;
  for (const Vec3& w : world) {
    if (norm(c.tooth.frame().to_local(w) - centre) < radius)
      ++removed;
    else
      kept.push_back(w);
  }
  world = kept;
  return removed;
}

real ball_radius(real volume) { return std::cbrt(3 * volume / (4 * std::numbers::pi)); }

// The radius at which the measured hole of `removed` lattice particles should end. The hole is
// the region where the colour field is under 1/2, whose volume for a flat surface is what the
// removed particles stood for (removed s^3). On a surface curved with radius R that level sits
// inside the particles' volume by about the B-spline's variance over R, s^2 / (3 R) (0.035 mm
// for R = 3 s): the smoothing of a concave surface, which the hole's equivalent radius shows.
real expected_hole_radius(int removed) {
  const real R = ball_radius(removed * s * s * s);
  return R - s * s / (3 * R);
}

TEST(Assess, GeometryIsVoxelisedOnce) {
  const Case& c = default_case();
  EXPECT_DOUBLE_EQ(c.assessor.voxel(), s / 2);
  // The voxelised cavity against the octree volume of carve_cavity (32.9 mm^3): the voxels'
  // error is of the order of the surface (~50 mm^2) times a few percent of a voxel.
  EXPECT_NEAR(c.assessor.cavity_volume() / mm3, default_tooth().cavity_volume() / mm3, 1.0);
  EXPECT_EQ(c.assessor.params().wall_standoff, s);
  EXPECT_EQ(c.assessor.params().leak_depth, s / 2);
  AssessParams bad;
  bad.voxel = s / 20;
  EXPECT_THROW(
      {
        try {
          CavityAssessor(default_tooth(), bad);
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find("voxel"), std::string::npos) << e.what();
          throw;
        }
      },
      std::invalid_argument);
}

TEST(Assess, FullCavityScoresFullAndVoidFreeAtAnyLatticeOffset) {
  // Aligned with the voxels, shifted by half a voxel diagonal, and at an arbitrary offset: the
  // colour field is a partition of unity on the lattice, so none leaves holes between particles.
  for (const Vec3 offset : {Vec3{}, Vec3{0.25, 0.25, 0.25} * s, Vec3{0.5, 0.1, 0.7} * s}) {
    const Case c(default_tooth(), offset, default_case().assessor);
    ASSERT_GT(c.world.size(), 1000u);
    const Assessment a = assess(c, c.world);
    // The only empty cavity voxels are at the opening, where the top layer of particles lies
    // up to a spacing below the occlusal surface (a free surface half a spacing above it):
    // about a quarter of 0.5 s on average over the ~17 mm^2 opening, 2% of the cavity.
    EXPECT_GE(a.fill_fraction, 0.97) << offset.x;
    EXPECT_LE(a.fill_fraction, 1.0);
    EXPECT_EQ(a.void_count, 0);
    EXPECT_EQ(a.void_volume_mm3, 0);
    // Conversely the top particles' volumes reach up to half a spacing above the surface.
    EXPECT_LT(a.overfill_mm3, 1.0);
    EXPECT_EQ(a.leaked_particles, 0u);
    EXPECT_EQ(a.lost_particles, 0u);
    EXPECT_EQ(a.outside_particles, 0u);
    EXPECT_EQ(a.material_particles, c.world.size());
    EXPECT_NEAR(a.filled_volume_mm3, a.fill_fraction * a.cavity_volume_mm3, 1e-9);
  }
}

TEST(Assess, EmptyCavityIsUnfilledAndOpen) {
  const Case& c = default_case();
  const Assessment a = assess(c, {});
  EXPECT_EQ(a.fill_fraction, 0);
  EXPECT_EQ(a.void_count, 0);  // its empty space reaches the outside
  EXPECT_EQ(a.overfill_mm3, 0);
  EXPECT_EQ(a.material_particles, 0u);
  EXPECT_NEAR(a.cavity_volume_mm3, c.assessor.cavity_volume() / mm3, 1e-9);

  // A layer of two spacings on the floor leaves the rest open: no voids, partly filled.
  std::vector<Vec3> floor;
  for (std::size_t q = 0; q < c.frame.size(); ++q)
    if (c.frame[q].z < -1.4 * mm) floor.push_back(c.world[q]);
  const Assessment f = assess(c, floor);
  EXPECT_EQ(f.void_count, 0);
  EXPECT_GT(f.fill_fraction, 0.1);
  EXPECT_LT(f.fill_fraction, 0.6);
}

TEST(Assess, HoleOfKnownVolumeIsOneVoidOfThatVolume) {
  const Case& c = deep_case();
  const Vec3 centre{0, 0, -1.5 * mm};  // 1.5 mm below the reference, 1.5 mm above the floor
  const real radius = 3 * s;
  std::vector<Vec3> world = c.world;
  const int removed = remove_ball(c, world, centre, radius);
  // Its equivalent radius is within a quarter voxel (0.0375 mm) of the expected one; the volume
  // is 2.47 mm^3 against 2.75 mm^3 removed (3.05 mm^3 for the ideal ball of 3 spacings).
  const Assessment a = assess(c, world);
  EXPECT_EQ(a.void_count, 1);
  EXPECT_DOUBLE_EQ(a.largest_void_mm3, a.void_volume_mm3);
  EXPECT_NEAR(ball_radius(a.void_volume_mm3 * mm3), expected_hole_radius(removed), s / 8)
      << a.void_volume_mm3 << " mm^3, " << removed << " particles removed";
  // The volume missing from the fill is the void (the opening's loss is the same as full).
  const Assessment full = assess(c, c.world);
  EXPECT_NEAR((full.fill_fraction - a.fill_fraction) * a.cavity_volume_mm3, a.void_volume_mm3,
              1e-9);
  // Where it is: its centre within a voxel of the hole's, 1.5 mm from the floor and more than
  // 1 mm from the walls (the deep cavity is 4 mm wide): inside the filling, not against a wall.
  ASSERT_EQ(a.voids.size(), 1u);
  EXPECT_NEAR(norm(a.voids[0].centre_mm - centre / mm), 0, a.voxel_mm);
  EXPECT_DOUBLE_EQ(a.voids[0].volume_mm3, a.void_volume_mm3);
  EXPECT_NEAR(a.voids[0].wall_distance_mm, 1.5, 0.1);
  EXPECT_EQ(a.voids[0].against, "bulk");
  EXPECT_TRUE(full.voids.empty());

  // Two holes of two spacings, 3 mm apart along the cavity: two voids, each about its volume.
  world = c.world;
  const int r1 = remove_ball(c, world, {-1.5 * mm, 0, -1.5 * mm}, 2 * s);
  const int r2 = remove_ball(c, world, {1.5 * mm, 0, -1.5 * mm}, 2 * s);
  const Assessment two = assess(c, world);
  EXPECT_EQ(two.void_count, 2);
  ASSERT_EQ(two.voids.size(), 2u);  // found in voxel order: mesial x < 0 first
  EXPECT_NEAR(two.voids[0].centre_mm.x, -1.5, 0.1);
  EXPECT_NEAR(two.voids[1].centre_mm.x, 1.5, 0.1);
  EXPECT_NEAR(two.voids[0].volume_mm3 + two.voids[1].volume_mm3, two.void_volume_mm3, 1e-12);
  EXPECT_NEAR(ball_radius(two.largest_void_mm3 * mm3), expected_hole_radius(std::max(r1, r2)),
              s / 8);
  EXPECT_NEAR(ball_radius(two.void_volume_mm3 * mm3 / 2), expected_hole_radius((r1 + r2) / 2),
              s / 8);
}

TEST(Assess, VoxelisationDoesNotDependOnTheThreadCount) {
  const Case& c = default_case();
  std::vector<Vec3> world = c.world;
  remove_ball(c, world, {0, 0, -1.0 * mm}, 2 * s);  // a void, 0.4 mm under the surface
  const State st = material_state(c.model, world);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const CavityAssessor one(c.tooth);
  omp_set_num_threads(3);
  const CavityAssessor three(c.tooth);
  omp_set_num_threads(threads);
  EXPECT_EQ(one.cavity_voxels(), three.cavity_voxels());
  const Assessment a = one.assess(st, c.model), b = three.assess(st, c.model);
  EXPECT_EQ(a.void_count, 1);
  EXPECT_EQ(assessment_json(a), assessment_json(b));
  EXPECT_EQ(assessment_json(a), assessment_json(c.assessor.assess(st, c.model)));
}

TEST(Assess, VoidsUnderTheMinimumVolumeAreNotCounted) {
  const Case& c = default_case();
  std::vector<Vec3> world = c.world;
  remove_ball(c, world, {0, 0, -1.0 * mm}, 2 * s);
  const State st = material_state(c.model, world);
  const Assessment a = c.assessor.assess(st, c.model);
  ASSERT_EQ(a.void_count, 1);
  AssessParams p;
  p.min_void_mm3 = a.void_volume_mm3 + 0.01;
  const Assessment small = CavityAssessor(c.tooth, p).assess(st, c.model);
  EXPECT_EQ(small.void_count, 0);
  EXPECT_EQ(small.void_volume_mm3, 0);
  EXPECT_EQ(small.fill_fraction, a.fill_fraction);  // still empty, just not a void: a pore
  EXPECT_EQ(small.pore_count, 1);
  EXPECT_DOUBLE_EQ(small.pore_volume_mm3, a.void_volume_mm3);
  EXPECT_DOUBLE_EQ(small.min_void_mm3, p.min_void_mm3);
  p.min_void_mm3 = a.void_volume_mm3 - 0.01;
  const Assessment large = CavityAssessor(c.tooth, p).assess(st, c.model);
  EXPECT_EQ(large.void_count, 1);
  EXPECT_EQ(large.pore_count, 0);
  EXPECT_THROW(CavityAssessor(c.tooth, AssessParams{.min_void_mm3 = -1}), std::invalid_argument);
}

// A gap under one particle's volume (spacing^3, the default min_void_mm3) is below what the
// particles resolve: porosity, reported apart, not a void. Measured on the deep cavity's lattice
// (voxels of half a spacing): four particles taken out around a point a quarter spacing off a
// lattice site leave one empty voxel (0.0034 mm^3), a pore; seven (a particle and its six
// nearest) leave 8 voxels, 0.027 mm^3, exactly a particle's volume: the smallest void.
TEST(Assess, AGapUnderAParticlesVolumeIsPorosityNotAVoid) {
  const Case& c = deep_case();
  const Vec3 site{0, 0, -1.5 * mm};
  const real particle_mm3 = s * s * s / mm3;
  EXPECT_DOUBLE_EQ(c.assessor.params().min_void_mm3, particle_mm3);
  std::vector<Vec3> world = c.world;
  ASSERT_EQ(remove_ball(c, world, site + Vec3{0.25, 0.25, 0.25} * s, 1.01 * s), 4);
  const Assessment pore = assess(c, world);
  EXPECT_EQ(pore.void_count, 0);
  EXPECT_EQ(pore.void_volume_mm3, 0);
  EXPECT_EQ(pore.pore_count, 1);
  EXPECT_GT(pore.pore_volume_mm3, 0);
  EXPECT_LT(pore.pore_volume_mm3, particle_mm3);
  EXPECT_NE(pore.report().find("0 voids (0.000 mm^3) and 1 pore under 0.027 mm^3"), std::string::npos)
      << pore.report();
  const auto j = nlohmann::json::parse(assessment_json(pore));
  EXPECT_EQ(j["pore_count"], 1);
  EXPECT_DOUBLE_EQ(j["pore_volume_mm3"].get<double>(), pore.pore_volume_mm3);
  EXPECT_DOUBLE_EQ(j["min_void_mm3"].get<double>(), particle_mm3);

  world = c.world;
  ASSERT_EQ(remove_ball(c, world, site, 1.01 * s), 7);
  const Assessment gap = assess(c, world);
  EXPECT_EQ(gap.void_count, 1);
  EXPECT_EQ(gap.pore_count, 0);
  EXPECT_NEAR(gap.void_volume_mm3, particle_mm3, 1e-12);
  EXPECT_EQ(gap.report().find("pore"), std::string::npos);
}

TEST(Assess, VoidAgainstTheFloorOrAWallSaysSo) {
  // Holes of two spacings touching the 3 mm deep cavity's floor and its mesial wall.
  const Case& c = deep_case();
  std::vector<Vec3> world = c.world;
  remove_ball(c, world, {0, 0, -2.9 * mm}, 2 * s);
  const Assessment floor = assess(c, world);
  ASSERT_EQ(floor.voids.size(), 1u);
  EXPECT_EQ(floor.voids[0].against, "floor");
  EXPECT_LT(floor.voids[0].wall_distance_mm, 0.6);
  world = c.world;
  remove_ball(c, world, {-2.9 * mm, 0, -1.5 * mm}, 2 * s);
  const Assessment wall = assess(c, world);
  ASSERT_EQ(wall.voids.size(), 1u);
  EXPECT_EQ(wall.voids[0].against, "wall");
  const std::string j = assessment_json(wall);
  EXPECT_NE(j.find("\"against\": \"wall\""), std::string::npos) << j;
  EXPECT_NE(j.find("\"centre_mm\""), std::string::npos) << j;
}

TEST(Assess, HoleAtAnOffsetLatticeIsFoundAlike) {
  const Case c(deep_case().tooth, Vec3{0.5, 0.3, 0.6} * s, deep_case().assessor);
  std::vector<Vec3> world = c.world;
  const int removed = remove_ball(c, world, {0.2 * mm, -0.1 * mm, -1.4 * mm}, 3 * s);
  const Assessment a = assess(c, world);
  EXPECT_EQ(a.void_count, 1);
  EXPECT_NEAR(ball_radius(a.void_volume_mm3 * mm3), expected_hole_radius(removed), s / 8);
}

TEST(Assess, HoleOpenToTheSurfaceIsNotAVoid) {
  const Case& c = deep_case();
  std::vector<Vec3> world = c.world;
  // A pit reaching from 1.2 mm deep up through the opening (the reference is z = 0).
  remove_ball(c, world, {0, 0, -0.3 * mm}, 3 * s);
  const Assessment a = assess(c, world);
  EXPECT_EQ(a.void_count, 0);
  EXPECT_LT(a.fill_fraction, assess(c, c.world).fill_fraction - 0.02);
}

TEST(Assess, SpaceTakenByTheToolIsNotAVoid) {
  const Case& c = deep_case();
  std::vector<Vec3> world = c.world;
  // The paper's ball burnisher (42 particles on a sphere of 1.1 mm) buried in the paste, the
  // paste cleared one spacing around its particles.
  std::vector<Vec3> ball = ball_burnisher(1.1 * mm, s).points;
  Vec3 mid;
  for (const Vec3& b : ball) mid += b / real(ball.size());
  for (Vec3& b : ball) b -= mid;
  const real R = norm(ball.front());
  const Vec3 centre{0, 0, -1.5 * mm};
  remove_ball(c, world, centre, R + s);
  std::vector<Vec3> tool;
  for (const Vec3& b : ball) tool.push_back(c.tooth.frame().to_world(centre + b));
  EXPECT_EQ(assess(c, world, tool).void_count, 0);
  // Without the tool the same hole is a void.
  EXPECT_EQ(assess(c, world).void_count, 1);
}

TEST(Assess, SlabAboveTheMarginIsOverfillOfItsVolume) {
  const Case& c = default_case();
  const PreparedTooth& t = c.tooth;
  // Lattice points above the occlusal surface over the outline (inside the cavity's shape,
  // outside the tooth), up to 3 spacings above the highest point of the cavity.
  std::vector<Vec3> world = c.world;
  int slab = 0;
  for (const Vec3& q : c.lattice_in({})) {
    const Vec3 w = t.frame().to_world(q);
    if (q.z <= c.local.max.z + 3 * s && t.cavity_distance(w).distance < 0 &&
        t.tooth().signed_distance(w) > 0) {
      world.push_back(w);
      ++slab;
    }
  }
  ASSERT_GT(slab, 300);
  const real expected = slab * s * s * s / mm3;  // mm^3, what the slab's particles stand for
  const Assessment full = assess(c, c.world), a = assess(c, world);
  // The slab's lowest particles stand partly for the cavity's top, which the full cavity left
  // empty (2% of it, 0.65 mm^3): the overfill is the slab's volume less that, and the two
  // together are the slab's volume (the colour field's level 1/2 keeps the volume a lattice
  // stands for). Measured: 2.5% and 0.3% under.
  const real gained = a.filled_volume_mm3 - full.filled_volume_mm3;
  EXPECT_NEAR(a.overfill_mm3 - full.overfill_mm3, expected, 0.05 * expected)
      << a.overfill_mm3 << " mm^3 measured, slab of " << slab << " particles";
  EXPECT_NEAR(a.overfill_mm3 - full.overfill_mm3 + gained, expected, 0.015 * expected);
  EXPECT_GE(a.fill_fraction, full.fill_fraction);  // the slab covers the opening
  EXPECT_GE(a.fill_fraction, 0.97);
  EXPECT_EQ(a.void_count, 0);
  EXPECT_EQ(a.leaked_particles, 0u);
}

TEST(Assess, LeakedLostAndOutsideParticlesAreCounted) {
  const Case& c = default_case();
  const PreparedTooth& t = c.tooth;
  const ToothFrame& f = t.frame();
  std::vector<Vec3> world = c.world;
  // In the tooth wall, beside the cavity (in the voxelised box) and below the floor (outside
  // it, 3 mm down): deeper than half a spacing.
  const std::vector<Vec3> wall = {f.to_world({0, 2.3 * mm, -1 * mm}),
                                  f.to_world({0, -2.3 * mm, -1.2 * mm}),
                                  f.to_world({3.4 * mm, 0, -1 * mm}), f.to_world({0, 0, -2.8 * mm}),
                                  f.to_world({0, 0, -5 * mm})};
  for (const Vec3& w : wall) {
    ASSERT_LT(t.distance(w).distance, -s) << "in the tooth wall";
    world.push_back(w);
  }
  // A quarter spacing into the floor (shallower than the leak depth): not leaked.
  const SurfacePoint floor = t.distance(f.to_world({0, 0, -2 * mm - 0.25 * s}));
  world.push_back(floor.closest - floor.normal * (0.25 * s));
  ASSERT_NEAR(t.distance(world.back()).distance, -0.25 * s, 1e-3 * s);
  // Off the domain (4 mm beyond the cavity's bounds) but within the lost distance (5 mm).
  const Bounds cb = t.cavity_bounds();
  world.push_back(cb.max + Vec3{4.5 * mm, 0, 0});
  world.push_back(cb.min - Vec3{0, 0, 4.5 * mm});
  // Lost: non-finite, or farther than 5 mm from the cavity's bounds.
  constexpr real nan = std::numeric_limits<real>::quiet_NaN();
  constexpr real inf = std::numeric_limits<real>::infinity();
  world.push_back({nan, 0, 0});
  world.push_back({0, inf, 0});
  world.push_back(cb.max + Vec3{0, 0, 1.0});  // a metre off
  world.push_back(cb.min - Vec3{0, 5.5 * mm, 0});
  // Outside the voxelised box (2 mm above the cavity's bounds) but in the domain: counted as
  // outside, nothing else.
  world.push_back(f.to_world({0, 0, c.local.max.z + 3 * mm}));

  const Assessment a = assess(c, world);
  EXPECT_EQ(a.leaked_particles, 5u + 2u);
  EXPECT_EQ(a.lost_particles, 4u);
  EXPECT_EQ(a.outside_particles, 1u);
  EXPECT_EQ(a.material_particles, world.size());
  // The leaked and lost particles do not change the fill.
  const Assessment full = assess(c, c.world);
  EXPECT_NEAR(a.fill_fraction, full.fill_fraction, 1e-3);
  EXPECT_EQ(a.void_count, 0);
}

TEST(Assess, ForceStatsAndDurationReachTheAssessment) {
  ForceStats fs;
  const real dt = 1e-3;
  fs.add({0, 0, 0}, dt);  // lifted
  fs.add({3, 4, 0}, dt);  // 5 N
  fs.add({0, 0, -1}, dt);
  fs.add({0, 0, 0}, dt);
  EXPECT_DOUBLE_EQ(fs.peak_N, 5);
  EXPECT_DOUBLE_EQ(fs.contact_s, 2 * dt);
  EXPECT_DOUBLE_EQ(fs.elapsed_s, 4 * dt);
  EXPECT_DOUBLE_EQ(fs.mean_N(), 3);  // over the contact only
  EXPECT_EQ(ForceStats{}.mean_N(), 0);

  const Case& c = default_case();
  State st = material_state(c.model, c.world);
  st.time = 1.25;
  const Assessment a = c.assessor.assess(st, c.model, fs, 1.5e4);
  EXPECT_DOUBLE_EQ(a.peak_tool_force_N, 5);  // simulated N
  EXPECT_DOUBLE_EQ(a.mean_tool_force_N, 3);
  EXPECT_DOUBLE_EQ(a.force_scale, 1.5e4);
  EXPECT_DOUBLE_EQ(a.peak_device_force_N, 5 * 1.5e4);  // rendered on a device
  EXPECT_DOUBLE_EQ(a.mean_device_force_N, 3 * 1.5e4);
  EXPECT_DOUBLE_EQ(c.assessor.assess(st, c.model, fs).peak_device_force_N, 5);  // no scale given: 1
  EXPECT_DOUBLE_EQ(a.contact_s, 2 * dt);
  EXPECT_DOUBLE_EQ(a.duration_s, 1.25);
}

TEST(Assess, ReportAndJsonCarryTheMetrics) {
  Assessment a;
  a.fill_fraction = 0.9512;
  a.void_count = 2;
  a.void_volume_mm3 = 0.75;
  a.largest_void_mm3 = 0.5;
  a.overfill_mm3 = 3.25;
  a.leaked_particles = 7;
  a.lost_particles = 4;
  a.material_particles = 1600;
  a.peak_tool_force_N = 0.125;
  a.mean_tool_force_N = 0.0625;
  a.force_scale = 16;
  a.peak_device_force_N = 2;
  a.mean_device_force_N = 1;
  a.duration_s = 2;
  a.cavity_volume_mm3 = 32.5;
  a.voxel_mm = 0.15;
  const std::string r = a.report();
  for (const char* part :
       {"95.1%", "32.50 mm^3", "2 voids", "0.750 mm^3", "largest 0.500", "overfill 3.25 mm^3",
        "1600 particles", "7 leaked", "4 lost", "peak 0.125 N, mean 0.0625 N simulated",
        "force scale 16: peak 2 N, mean 1 N"})
    EXPECT_NE(r.find(part), std::string::npos) << part << " in\n" << r;
  EXPECT_EQ(std::count(r.begin(), r.end(), '\n'), 3);

  const std::string j = assessment_json(a);
  for (const char* part :
       {"\"fill_fraction\": 0.9512", "\"void_count\": 2", "\"void_volume_mm3\": 0.75",
        "\"overfill_mm3\": 3.25", "\"leaked_particles\": 7", "\"lost_particles\": 4",
        "\"peak_tool_force_N\": 0.125", "\"mean_tool_force_N\": 0.0625", "\"duration_s\": 2",
        "\"force_scale\": 16", "\"peak_device_force_N\": 2", "\"mean_device_force_N\": 1"})
    EXPECT_NE(j.find(part), std::string::npos) << part << " in\n" << j;
  a.fill_fraction = std::numeric_limits<real>::quiet_NaN();
  EXPECT_NE(assessment_json(a).find("\"fill_fraction\": null"), std::string::npos);
}

}  // namespace
}  // namespace dentsph
