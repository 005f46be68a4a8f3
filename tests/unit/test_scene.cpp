// The scene module: lattice samplers, defaults, material precedence, the tool trajectory, the
// initial state, the example scenes, the default particle mass, and the error messages.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <tuple>

#include "dentsph/scene.hpp"
#include "dentsph/solver.hpp"
#include "physics/kernels.hpp"
#include "scene/shapes.hpp"
#include "support/builders.hpp"

namespace dentsph {
namespace {

using nlohmann::json;
constexpr real s = 0.01;  // m, lattice spacing of every test scene (h = 2 s)
constexpr real pi = 3.14159265358979323846;

// ---- helpers
// -------------------------------------------------------------------------------------

// A small valid scene: a plate, a box of paste above it, a one-sphere tool with two keyframes.
json base_scene() {
  return json::parse(R"({
    "name": "base",
    "simulation": {"dt": 5e-4, "h": 0.02},
    "adhesion": {"A": 0.012, "B": 0.03},
    "materials": {
      "paste": {"viscosity": 0.5, "stiffness": 60, "rest_density": 1000, "adhesion": 200},
      "wall": {"viscosity": 0.5, "stiffness": 200, "rest_density": 1000, "adhesion": 0}
    },
    "roles": {"material": "paste", "boundary": "wall", "tool": "wall"},
    "blocks": [
      {"role": "boundary", "shape": "box", "min": [0, 0, 0], "max": [0.04, 0.04, 0.01], "spacing": 0.01},
      {"role": "material", "shape": "box", "min": [0, 0, 0.02], "max": [0.02, 0.02, 0.04], "spacing": 0.01}
    ],
    "tool": {
      "blocks": [{"shape": "sphere", "center": [0, 0, 0], "radius": 0.01, "spacing": 0.01}],
      "keyframes": [{"t": 0, "position": [0.02, 0.02, 0.08]}, {"t": 1, "position": [0.02, 0.02, 0.06]}]
    }
  })");
}

Scene parse(const json& j) { return parse_scene(j.dump(), "test.json"); }

std::size_t count_role(const Scene& sc, Role r) {
  return std::size_t(std::count_if(sc.particles.begin(), sc.particles.end(),
                                   [&](const ParticleInit& p) { return p.role == r; }));
}

// Lattice indices of points relative to `base`, for exact set comparisons.
std::set<std::tuple<long, long, long>> indices(const std::vector<Vec3>& pts, Vec3 base) {
  std::set<std::tuple<long, long, long>> out;
  for (const Vec3& p : pts)
    out.emplace(std::lround((p.x - base.x) / s), std::lround((p.y - base.y) / s),
                std::lround((p.z - base.z) / s));
  return out;
}

bool near(const Vec3& a, const Vec3& b, real tol = 1e-12) { return norm(a - b) <= tol; }

// A non-Newtonian material's fields reach the Model's table (docs/model.md, "Rheology").
TEST(SceneMaterials, RheologyFieldsReachTheTable) {
  json j = base_scene();
  j["simulation"]["solver"] = "iisph";
  j["materials"]["paste"]["flow_index"] = 0.6;
  j["materials"]["paste"]["yield_stress"] = 150;
  const Scene sc = parse(j);
  const MaterialIndex m = *sc.model.materials.find("paste");
  EXPECT_EQ(sc.model.materials[m].flow_index, 0.6);
  EXPECT_EQ(sc.model.materials[m].yield_stress, 150);
  EXPECT_EQ(sc.model.materials[m].max_viscosity, 0) << "0: 1000 times the viscosity";
  EXPECT_FALSE(newtonian(sc.model.materials[m]));
  EXPECT_TRUE(newtonian(sc.model.materials[*sc.model.materials.find("wall")]));
  EXPECT_EQ(sc.model.materials.first_non_newtonian(), m);
  EXPECT_FALSE(sc.model.materials.any_interface_strength());
  // The contact's strength with an instrument (docs/model.md, "Tack").
  j["materials"]["paste"]["interface_strength"] = 5e4;
  const Scene strong = parse(j);
  EXPECT_EQ(strong.model.materials[*strong.model.materials.find("paste")].interface_strength, 5e4);
  EXPECT_TRUE(strong.model.materials.any_interface_strength());
  EXPECT_EQ(contact_strength(5e4, 0), 5e4) << "steel gives none of its own";
  EXPECT_EQ(contact_strength(5e4, 1e4), 1e4) << "the smaller of two";
  EXPECT_EQ(contact_strength(0, 0), 0) << "none";
}

// ---- shapes
// ----------------------------------------------------------------------------------------

TEST(SceneShapes, BoxGivesNPlusOneCubedIncludingFloatingPointEdges) {
  const scene::BoxShape cube{{0, 0, 0}, {0.1, 0.1, 0.1}};
  EXPECT_EQ(scene::sample(cube, s).size(), 11u * 11u * 11u);
  EXPECT_EQ(scene::point_count(cube, s), 11.0 * 11 * 11);
  // 0.29 / 0.01 = 28.999999999999996: 30 points, not 29.
  EXPECT_EQ(scene::sample(scene::BoxShape{{0, 0, 0}, {0.29, 0.005, 0.005}}, s).size(), 30u);
  EXPECT_EQ(scene::point_count(scene::BoxShape{{0, 0, 0}, {0.29, 0.005, 0.005}}, s), 30.0);
  // A max between lattice planes is rounded down: 0.105 holds 11 planes on x.
  const scene::BoxShape odd{{0, 0, 0}, {0.105, 0.05, 0.02}};
  const auto pts = scene::sample(odd, s);
  EXPECT_EQ(pts.size(), 11u * 6u * 3u);
  EXPECT_TRUE(near(pts.front(), {0, 0, 0}));
  EXPECT_TRUE(near(pts.back(), {0.1, 0.05, 0.02}));
}

TEST(SceneShapes, SphereIsTheSymmetricLatticeBall) {
  const Vec3 c{0.3, -0.2, 0.1};
  const auto pts = scene::sample(scene::SphereShape{c, 0.05}, s);
  EXPECT_EQ(pts.size(), 515u) << "lattice points with i^2 + j^2 + k^2 <= 25";
  EXPECT_EQ(scene::point_count(scene::SphereShape{c, 0.05}, s), 515.0);
  const auto idx = indices(pts, c);
  Vec3 sum;
  for (const auto& [i, j, k] : idx) {
    EXPECT_LE(i * i + j * j + k * k, 25);
    EXPECT_TRUE(idx.count({-i, j, k}) && idx.count({i, -j, k}) && idx.count({i, j, -k}) &&
                idx.count({j, i, k}) && idx.count({k, j, i}));
    sum += Vec3{real(i), real(j), real(k)};
  }
  EXPECT_TRUE(near(sum, {0, 0, 0}));
  // The six poles at exactly one radius are in; radius 0.02 gives the 33-point ball.
  EXPECT_TRUE(idx.count({5, 0, 0}) && idx.count({0, 0, -5}));
  EXPECT_EQ(scene::sample(scene::SphereShape{{0, 0, 0}, 0.02}, s).size(), 33u);
}

TEST(SceneShapes, LatticeGivesCountPointsFromOrigin) {
  const scene::LatticeShape l{{1, 2, 3}, {3, 4, 5}};
  const auto pts = scene::sample(l, s);
  ASSERT_EQ(pts.size(), 60u);
  EXPECT_EQ(scene::point_count(l, s), 60.0);
  EXPECT_TRUE(near(pts.front(), {1, 2, 3}));
  EXPECT_TRUE(near(pts.back(), {1.02, 2.03, 3.04}));
}

TEST(SceneShapes, ContainerIsTheShellAroundTheInnerBox) {
  const Vec3 lo{0, 0, 0};
  const scene::ContainerShape open{lo, {0.04, 0.04, 0.03}, 2, true};
  const auto pts = scene::sample(open, s);
  // Outer index box (4+2+2+1)^2 x (3+2+1), minus the inner (4+1)^2 x (3+1).
  EXPECT_EQ(pts.size(), 9u * 9u * 6u - 5u * 5u * 4u);
  EXPECT_EQ(scene::point_count(open, s), double(pts.size()));
  EXPECT_EQ(indices(pts, lo), indices(testing::open_container(lo, s, 4, 4, 3, 2), lo));
  for (const Vec3& p : pts) {  // nothing inside the inner box, the lowest layer one spacing below
    const bool inside =
        p.x > -s / 2 && p.x < 0.04 + s / 2 && p.y > -s / 2 && p.y < 0.04 + s / 2 && p.z > -s / 2;
    EXPECT_FALSE(inside) << p.x << " " << p.y << " " << p.z;
    EXPECT_GE(p.z, -2 * s - 1e-12);
    EXPECT_LE(p.z, 0.03 + 1e-12);
  }
  const scene::ContainerShape closed{lo, {0.04, 0.04, 0.03}, 1, false};
  EXPECT_EQ(scene::sample(closed, s).size(), 7u * 7u * 6u - 5u * 5u * 4u);
  // The inner size is rounded to whole spacings: 0.0404 acts as 0.04.
  EXPECT_EQ(scene::sample(scene::ContainerShape{lo, {0.0404, 0.04, 0.03}, 2, true}, s).size(),
            pts.size());
}

// ---- parsing: defaults and materials
// --------------------------------------------------------------

TEST(SceneParse, AppliesDefaults) {
  json j = base_scene();
  j.erase("tool");
  const Scene sc = parse(j);
  EXPECT_EQ(sc.name, "base");
  EXPECT_EQ(sc.source, "test.json");
  EXPECT_EQ(sc.params.gravity, (Vec3{0, 0, -9.81}));
  EXPECT_EQ(sc.model.max_bonds_per_particle, 64);
  EXPECT_EQ(sc.model.cfl_lambda, 0.4);
  EXPECT_EQ(sc.model.adhesion.eps, 3);
  EXPECT_EQ(sc.model.adhesion.zeta, 2);
  EXPECT_NEAR(sc.model.adhesion.Cd, 6.75, 1e-12);
  EXPECT_EQ(sc.output.snapshot_interval, 0.01);
  EXPECT_TRUE(sc.output.vtk);
  EXPECT_TRUE(sc.output.surface) << "the default";
  EXPECT_EQ(sc.duration, 0);
  EXPECT_TRUE(sc.tool.keyframes.empty());
  // Domain: the particles' bounding box [0, 0.04]^2 x [0, 0.04] padded by 2h = 0.04.
  EXPECT_TRUE(near(sc.model.domain_min, {-0.04, -0.04, -0.04}));
  EXPECT_TRUE(near(sc.model.domain_max, {0.08, 0.08, 0.08}));
  EXPECT_EQ(count_role(sc, Role::boundary), 5u * 5u * 2u);
  EXPECT_EQ(count_role(sc, Role::material), 3u * 3u * 3u);
  const real m = lattice_particle_mass(1000, s, sc.model.kernel);
  for (const ParticleInit& p : sc.particles) {
    EXPECT_EQ(p.mass, m);
    EXPECT_EQ(p.vel, (Vec3{}));
  }
}

TEST(SceneParse, ReadsTheSolverAndTheCommandLineChoosesAnother) {
  json j = base_scene();
  EXPECT_EQ(parse(j).model.solver, Solver::paper) << "the default";
  j["simulation"]["solver"] = "iisph";
  Scene sc = parse(j);
  EXPECT_EQ(sc.params.solver, Solver::iisph);
  EXPECT_EQ(sc.model.solver, Solver::iisph);
  const real dt = sc.model.dt;
  // --solver over the scene's: a scene file keeps its dt.
  select_solver(sc, Solver::paper);
  EXPECT_EQ(sc.model.solver, Solver::paper);
  EXPECT_EQ(sc.model.dt, dt);
  // Each solver object sizes its own buffers for the State: the paper's step has none (its scratch
  // is the State's grid), the iisph solver its rows.
  const State st = make_state(sc);
  const std::unique_ptr<StepSolver> paper = make_solver(sc.model.solver);
  paper->resize(sc.model, st);
  EXPECT_EQ(paper->bytes(), 0u) << "the paper's step sizes no iisph scratch";
  select_solver(sc, Solver::iisph);
  const std::unique_ptr<StepSolver> iisph = make_solver(sc.model.solver);
  EXPECT_EQ(iisph->bytes(), 0u) << "nothing before it is sized";
  iisph->resize(sc.model, make_state(sc));
  EXPECT_GT(iisph->bytes(), 0u);
}

// simulation.iisph: the iisph solver's settings over the defaults; the paper's step ignores them.
TEST(SceneParse, ReadsTheIisphSolversSettings) {
  json j = base_scene();
  EXPECT_EQ(parse(j).model.iisph.stiffness, 0.5) << "the paper's paste's stiffness by default";
  j["simulation"]["iisph"] = {{"stiffness", 1}, {"max_iterations", 20}, {"density_error", 0.001},
                              {"omega", 0.6},   {"viscosity_iterations", 12}, {"cfl", 0.3}, {"gradient", "cubic"}};
  const Scene sc = parse(j);
  EXPECT_EQ(sc.model.iisph.gradient, PressureGradient::cubic);
  EXPECT_EQ(sc.model.iisph.stiffness, 1);
  EXPECT_EQ(sc.model.iisph.max_iterations, 20);
  EXPECT_EQ(sc.model.iisph.density_error, 0.001);
  EXPECT_EQ(sc.model.iisph.omega, 0.6);
  EXPECT_EQ(sc.model.iisph.viscosity_iterations, 12);
  EXPECT_EQ(sc.model.iisph.cfl, 0.3);
  EXPECT_EQ(sc.model.iisph.min_iterations, IisphParams{}.min_iterations) << "not given: the default";
  EXPECT_EQ(sc.model.iisph.density_kernel, DensityKernel::poly6) << "the default";
  j["simulation"]["solver"] = "iisph";
  j["simulation"]["iisph"] = {{"gradient", "cubic"}, {"density_kernel", "cubic"}};
  EXPECT_EQ(parse(j).model.iisph.density_kernel, DensityKernel::cubic);
  EXPECT_TRUE(parse(j).model.kernel.cubic_density);
  j["simulation"].erase("solver");
  j["simulation"]["iisph"] = {{"gradient", "spiky"}};
  EXPECT_EQ(parse(j).model.iisph.gradient, PressureGradient::spiky);
  EXPECT_EQ(parse(j).model.iisph.pressure_solve, PressureSolve::jacobi) << "the default";
  j["simulation"]["iisph"] = {{"pressure_solve", "cg"}, {"max_density_error", 0.005}, {"viscosity_tolerance", 1e-4}};
  const Scene cg = parse(j);
  EXPECT_EQ(cg.model.iisph.pressure_solve, PressureSolve::cg);
  EXPECT_EQ(cg.model.iisph.max_density_error, 0.005);
  EXPECT_EQ(cg.model.iisph.viscosity_tolerance, 1e-4);
  EXPECT_EQ(cg.model.iisph.surface_tension, 0) << "none by default";
  j["simulation"]["iisph"] = {{"surface_tension", 0.04}, {"wetting", 1}};
  const Scene wet = parse(j);
  EXPECT_EQ(wet.model.iisph.surface_tension, 0.04);
  EXPECT_EQ(wet.model.iisph.wetting, 1);
  j["simulation"]["iisph"] = {{"wetting", 1}};
  try {
    (void)parse(j);
    ADD_FAILURE() << "wetting without a surface tension was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("iisph.wetting"), std::string::npos) << e.what();
  }
}

TEST(SceneParse, ReadsGivenSettings) {
  json j = base_scene();
  j["simulation"]["gravity"] = {0, -1, 0};
  j["simulation"]["max_bonds_per_particle"] = 16;
  j["simulation"]["cfl_lambda"] = 0.3;
  j["simulation"]["domain"] = {{"min", {-1, -1, -1}}, {"max", {1, 2, 3}}};
  j["adhesion"]["eps"] = 4;
  j["adhesion"]["zeta"] = 1;
  j["output"] = {{"snapshot_interval", 0}, {"vtk", false}, {"surface", false}};
  j["run"] = {{"duration", 2.5}};
  j["blocks"][1]["velocity"] = {0.1, 0, 0};
  j["blocks"][1]["mass"] = 0.002;
  const Scene sc = parse(j);
  EXPECT_EQ(sc.params.gravity, (Vec3{0, -1, 0}));
  EXPECT_EQ(sc.model.max_bonds_per_particle, 16);
  EXPECT_EQ(sc.model.cfl_lambda, 0.3);
  EXPECT_EQ(sc.model.domain_max, (Vec3{1, 2, 3}));
  EXPECT_EQ(sc.model.adhesion.eps, 4);
  EXPECT_EQ(sc.output.snapshot_interval, 0);
  EXPECT_FALSE(sc.output.vtk);
  EXPECT_FALSE(sc.output.surface);
  EXPECT_EQ(sc.duration, 2.5);
  for (const ParticleInit& p : sc.particles)
    if (p.role == Role::material) {
      EXPECT_EQ(p.vel, (Vec3{0.1, 0, 0}));
      EXPECT_EQ(p.mass, 0.002);
    }
}

TEST(SceneParse, MaterialPrecedenceIsInlineOverNameOverRole) {
  json j = base_scene();
  j["materials"]["stiff"] = {
      {"viscosity", 2}, {"stiffness", 300}, {"rest_density", 1200}, {"adhesion", 50}};
  json block = j["blocks"][1];
  j["blocks"] = json::array();
  auto add = [&](real x, json material) {
    json b = block;
    b["min"] = {x, 0, 0};
    b["max"] = {x + 0.001, 0.001, 0.001};  // one particle at (x, 0, 0)
    if (!material.is_null()) b["material"] = material;
    j["blocks"].push_back(b);
  };
  add(0.0, nullptr);                                // role: paste
  add(0.1, "stiff");                                // by name
  add(0.2, {{"adhesion", 0}});                      // inline over the role's paste
  add(0.3, {{"base", "stiff"}, {"viscosity", 7}});  // inline over a named base
  add(0.4, {{"viscosity", 1}, {"stiffness", 2}, {"rest_density", 3}, {"adhesion", 4}});
  j["tool"]["material"] = {{"base", "stiff"}, {"adhesion", 9}};
  j["tool"]["blocks"].push_back({{"shape", "lattice"},
                                 {"origin", {0, 0, 0.1}},
                                 {"count", {1, 1, 1}},
                                 {"spacing", s},
                                 {"material", {{"stiffness", 500}}}});
  const Scene sc = parse(j);
  ASSERT_EQ(sc.particles.size(), 5u + 7u + 1u);
  auto mat = [&](std::size_t i) { return sc.particles[i].material; };
  EXPECT_EQ(mat(0).Kp, 60);
  EXPECT_EQ(mat(0).Ka, 200);
  EXPECT_EQ(mat(1).Kp, 300);
  EXPECT_EQ(mat(2).Kp, 60);
  EXPECT_EQ(mat(2).Ka, 0);
  EXPECT_EQ(mat(2).mu, 0.5);
  EXPECT_EQ(mat(3).mu, 7);
  EXPECT_EQ(mat(3).Kp, 300);
  EXPECT_EQ(mat(3).rho0, 1200);
  EXPECT_EQ(mat(4).rho0, 3);
  // Tool: tool.material (stiff, Ka 9) over roles.tool (wall); its block overrides stiffness.
  EXPECT_EQ(mat(5).Ka, 9);
  EXPECT_EQ(mat(5).Kp, 300);
  EXPECT_EQ(mat(12).Kp, 500);
  EXPECT_EQ(mat(12).Ka, 9);
  // The default mass follows each block's own rest density.
  EXPECT_EQ(sc.particles[3].mass, lattice_particle_mass(1200, s, sc.model.kernel));
}

// ---- the tool's trajectory and the initial state
// ---------------------------------------------------

TEST(ToolTrajectory, InterpolatesLinearlyAndBySlerpAndClamps) {
  ToolTrajectory traj;
  EXPECT_EQ(traj.at(0.3).position, (Vec3{}));
  EXPECT_EQ(traj.at(0.3).orientation.w, 1);
  const Quat quarter = Quat::from_axis_angle({0, 0, 1}, pi / 2);
  traj.keyframes = {
      {1, Pose{{0, 0, 0}, {}}}, {3, Pose{{2, 4, 6}, quarter}}, {4, Pose{{2, 4, 10}, quarter}}};
  const Pose mid = traj.at(2);
  EXPECT_TRUE(near(mid.position, {1, 2, 3}));
  // Half way through a quarter turn about z: 45 degrees.
  EXPECT_TRUE(near(mid.orientation.rotate({1, 0, 0}), {std::sqrt(0.5), std::sqrt(0.5), 0}, 1e-12));
  EXPECT_TRUE(near(traj.at(1.5).orientation.rotate({1, 0, 0}),
                   {std::cos(pi / 8), std::sin(pi / 8), 0}, 1e-12));
  EXPECT_TRUE(near(traj.at(3.25).position, {2, 4, 7}));
  EXPECT_TRUE(near(traj.at(-5).position, {0, 0, 0}));  // held before the first
  EXPECT_TRUE(near(traj.at(1).position, {0, 0, 0}));
  EXPECT_TRUE(near(traj.at(9).position, {2, 4, 10}));  // held after the last
  EXPECT_TRUE(near(traj.at(9).orientation.rotate({1, 0, 0}), {0, 1, 0}, 1e-12));
}

TEST(SceneParse, ReadsKeyframeRotations) {
  json j = base_scene();
  j["tool"]["keyframes"][1]["rotation"] = {{"axis", {0, 0, 2}}, {"angle_deg", 90}};
  const Scene sc = parse(j);
  EXPECT_TRUE(near(sc.tool.at(1).orientation.rotate({1, 0, 0}), {0, 1, 0}, 1e-12));
  EXPECT_TRUE(near(sc.tool.at(0.5).position, {0.02, 0.02, 0.07}));
}

TEST(MakeState, PlacesTheToolAtItsFirstKeyframe) {
  json j = base_scene();
  j["tool"]["keyframes"][0]["t"] = 0.5;  // the first keyframe after t = 0 still holds at 0
  j["tool"]["keyframes"][1]["t"] = 1.5;
  j["tool"]["keyframes"][0]["rotation"] = {{"axis", {1, 0, 0}}, {"angle_deg", 90}};
  const Scene sc = parse(j);
  const State st = make_state(sc);
  const Pose p0 = sc.tool.keyframes[0].pose;
  EXPECT_EQ(st.tool_pose.position, p0.position);
  EXPECT_EQ(st.tool_pose_applied.position, p0.position);
  ASSERT_EQ(st.size(), sc.particles.size());
  EXPECT_EQ(st.count(Role::tool), 7u);
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    const ParticleInit& init = sc.particles[st.id[i]];
    const Vec3 expected = init.role == Role::tool ? p0.apply(init.pos) : init.pos;
    EXPECT_TRUE(near(st.pos[i], expected));
    EXPECT_EQ(st.mass[i], init.mass);
    EXPECT_EQ(st.Kp[i], init.material.Kp);
  }
}

TEST(MakeState, WithoutAToolUsesTheIdentityPose) {
  json j = base_scene();
  j.erase("tool");
  const State st = make_state(parse(j));
  EXPECT_EQ(st.tool_pose.position, (Vec3{}));
  EXPECT_EQ(st.tool_pose.orientation.w, 1);
  EXPECT_EQ(st.count(Role::tool), 0u);
}

// The default mass puts an interior particle of a lattice at rest density under poly6.
TEST(SceneParse, DefaultMassGivesRestDensityInside) {
  json j = base_scene();
  j.erase("tool");
  j["blocks"] = json::array({{{"role", "material"},
                              {"shape", "lattice"},
                              {"origin", {0, 0, 0}},
                              {"count", {9, 9, 9}},
                              {"spacing", s}}});
  const Scene sc = parse(j);
  const State st = make_state(sc);
  ASSERT_EQ(st.size(), 729u);
  const Vec3 centre{4 * s, 4 * s, 4 * s};
  std::uint32_t c = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i)
    if (norm(st.pos[i] - centre) < norm(st.pos[c] - centre)) c = i;
  ASSERT_TRUE(near(st.pos[c], centre));
  real rho = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i)
    rho += st.mass[i] * kernels::poly6(norm2(st.pos[i] - st.pos[c]), sc.model.kernel);
  EXPECT_NEAR(rho, 1000, 1e-9);
  // A corner particle has only the octant i, j, k >= 0 of its neighbourhood. With h = 2 s the
  // poly6 weights (4 - q)^3, q = i^2 + j^2 + k^2 < 4, sum to 330 in all and 170 in the octant.
  real rho_corner = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i)
    rho_corner += st.mass[i] * kernels::poly6(norm2(st.pos[i]), sc.model.kernel);
  EXPECT_NEAR(rho_corner, 1000.0 * 170 / 330, 1e-9);
}

// ---- the example scenes
// ----------------------------------------------------------------------------

// Acoustic limit of docs/model.md, "Stability": dt <= lambda h / sqrt(max Kp).
real acoustic_limit(const Scene& sc) {
  real kp = 0;
  for (const ParticleInit& p : sc.particles) kp = std::max(kp, p.material.Kp);
  return sc.model.cfl_lambda * sc.model.kernel.h / std::sqrt(kp);
}

// Smallest distance between a particle of role a and one of role b (tool at pose `tool`).
real gap(const Scene& sc, Role a, Role b, const Pose& tool = {}) {
  auto at = [&](const ParticleInit& p) { return p.role == Role::tool ? tool.apply(p.pos) : p.pos; };
  real d = 1e30;
  for (const ParticleInit& p : sc.particles)
    if (p.role == a)
      for (const ParticleInit& q : sc.particles)
        if (q.role == b) d = std::min(d, norm(at(p) - at(q)));
  return d;
}

TEST(ExampleScenes, BlobOnPlate) {
  const Scene sc = load_scene("scenes/blob_on_plate.json");
  EXPECT_EQ(sc.name, "blob_on_plate");
  EXPECT_EQ(sc.source, "scenes/blob_on_plate.json");
  EXPECT_EQ(count_role(sc, Role::material), 515u);
  EXPECT_EQ(count_role(sc, Role::boundary), 31u * 31u * 3u);
  EXPECT_EQ(count_role(sc, Role::tool), 0u);
  EXPECT_EQ(sc.duration, 1.0);
  EXPECT_EQ(sc.output.snapshot_interval, 0.01);
  EXPECT_LT(sc.params.gravity.z, 0);
  EXPECT_LE(sc.model.dt, acoustic_limit(sc));
  // The blob starts 0.03 m above the plate, out of the kernel's reach.
  EXPECT_NEAR(gap(sc, Role::material, Role::boundary), 0.03, 1e-12);
  const State st = make_state(sc);
  EXPECT_EQ(st.size(), sc.particles.size());
}

TEST(ExampleScenes, ToolPress) {
  const Scene sc = load_scene("scenes/tool_press.json");
  EXPECT_EQ(sc.name, "tool_press");
  EXPECT_EQ(count_role(sc, Role::material), 13u * 13u * 7u);
  EXPECT_EQ(count_role(sc, Role::boundary), 17u * 17u * 13u - 13u * 13u * 11u);
  EXPECT_EQ(count_role(sc, Role::tool), 33u);
  EXPECT_EQ(sc.duration, 1.5);
  EXPECT_LE(sc.model.dt, acoustic_limit(sc));
  // The paste touches the walls at one spacing, nothing overlaps.
  EXPECT_NEAR(gap(sc, Role::material, Role::boundary), s, 1e-12);
  // The tool starts 0.03 m above the paste, goes 0.03 m into it (down 0.06 m over 0.5 s),
  // holds for 0.25 s and is back up at 1.25 s, inside the run.
  EXPECT_NEAR(gap(sc, Role::material, Role::tool, sc.tool.at(0)), 0.03, 1e-12);
  EXPECT_NEAR(sc.tool.at(0).position.z - sc.tool.at(0.5).position.z, 0.06, 1e-12);
  EXPECT_EQ(sc.tool.at(0.5).position, sc.tool.at(0.75).position);
  EXPECT_EQ(sc.tool.at(1.25).position, sc.tool.at(0).position);
  EXPECT_LT(sc.tool.keyframes.back().t, sc.duration);
  // At the deepest point the tool stays clear of the floor and the walls.
  EXPECT_GE(gap(sc, Role::tool, Role::boundary, sc.tool.at(0.5)), 0.03 - 1e-12);
  const State st = make_state(sc);
  EXPECT_EQ(st.count(Role::tool), 33u);
}

// ---- errors
// ----------------------------------------------------------------------------------------

struct BrokenCase {
  const char* what;
  std::function<void(json&)> mutate;
  std::string path;       // the message must read "broken.json: <path>..."
  std::string also = "";  // and contain this
};

// Test listings show the case's name rather than its bytes.
void PrintTo(const BrokenCase& c, std::ostream* os) {
  for (const char* p = c.what; *p; ++p) *os << (std::isalnum(static_cast<unsigned char>(*p)) ? *p : '_');
}

const BrokenCase broken_cases[] = {
    {"missing dt", [](json& j) { j["simulation"].erase("dt"); }, "simulation.dt", "missing"},
    {"negative spacing", [](json& j) { j["blocks"][1]["spacing"] = -0.01; }, "blocks[1].spacing",
     "> 0"},
    {"spacing over h", [](json& j) { j["blocks"][0]["spacing"] = 0.03; }, "blocks[0].spacing",
     "larger than h"},
    {"spacing under a tenth of h", [](json& j) { j["blocks"][0]["spacing"] = 1e-7; }, "blocks[0].spacing",
     "under h / 10"},
    {"typo in a block", [](json& j) { j["blocks"][0]["spacng"] = 0.01; }, "blocks[0].spacng",
     "did you mean \"spacing\""},
    {"typo at the top", [](json& j) { j["simulaton"] = j["simulation"]; }, "simulaton",
     "simulation"},
    {"field of another shape", [](json& j) { j["blocks"][0]["radius"] = 0.1; }, "blocks[0].radius",
     "unknown field"},
    {"A >= h", [](json& j) { j["adhesion"]["A"] = 0.02; }, "adhesion.A", "A < h < B"},
    {"eps <= zeta",
     [](json& j) {
       j["adhesion"]["eps"] = 2;
       j["adhesion"]["zeta"] = 3;
     },
     "adhesion.eps", "zeta"},
    {"bad max_bonds", [](json& j) { j["simulation"]["max_bonds_per_particle"] = 0; },
     "simulation.max_bonds_per_particle", "[1, 1024]"},
    {"unknown material", [](json& j) { j["blocks"][1]["material"] = "pastee"; },
     "blocks[1].material", "did you mean \"paste\""},
    {"unknown role material", [](json& j) { j["roles"]["boundary"] = "steel"; }, "roles.boundary",
     "wall"},
    {"no material for the role", [](json& j) { j["roles"].erase("boundary"); },
     "blocks[0].material", "roles.boundary"},
    {"incomplete inline material",
     [](json& j) {
       j["roles"].erase("boundary");
       j["blocks"][0]["material"] = {{"stiffness", 5}};
     },
     "blocks[0].material.viscosity", "base"},
    {"negative stiffness", [](json& j) { j["materials"]["paste"]["stiffness"] = -1; },
     "materials.paste.stiffness", "must be in [1e-06, 1e+12], got -1"},
    {"vector of 2",
     [](json& j) {
       j["blocks"][0]["min"] = {0, 0};
     },
     "blocks[0].min", "3 numbers"},
    {"string for a number", [](json& j) { j["simulation"]["h"] = "0.02"; }, "simulation.h",
     "a string"},
    {"string in a vector",
     [](json& j) {
       j["simulation"]["gravity"] = {0, 0, "down"};
     },
     "simulation.gravity[2]", "expected a number"},
    {"min above max", [](json& j) { j["blocks"][0]["max"][2] = -0.01; }, "blocks[0].max",
     "exceed min"},
    {"zero radius", [](json& j) { j["tool"]["blocks"][0]["radius"] = 0; }, "tool.blocks[0].radius",
     "> 0"},
    {"fractional count",
     [](json& j) {
       j["blocks"][1] = {{"role", "material"},
                         {"shape", "lattice"},
                         {"origin", {0, 0, 0}},
                         {"count", {2, 2, 2.5}},
                         {"spacing", 0.01}};
     },
     "blocks[1].count[2]", "whole number"},
    {"tiny container",
     [](json& j) {
       j["blocks"][0] = {{"role", "boundary"},
                         {"shape", "container"},
                         {"min", {0, 0, 0}},
                         {"max", {0.004, 0.1, 0.1}},
                         {"spacing", 0.01}};
     },
     "blocks[0].max", "one spacing"},
    {"too many particles",
     [](json& j) {
       j["blocks"][0]["max"] = {10, 10, 10};
     },
     "blocks[0]", "limit"},
    {"empty blocks", [](json& j) { j["blocks"] = json::array(); }, "blocks", "empty"},
    {"unknown shape", [](json& j) { j["blocks"][0]["shape"] = "cube"; }, "blocks[0].shape", "box"},
    {"tool role in blocks", [](json& j) { j["blocks"][0]["role"] = "tool"; }, "blocks[0].role",
     "tool.blocks"},
    {"velocity on a wall",
     [](json& j) {
       j["blocks"][0]["velocity"] = {0, 0, 1};
     },
     "blocks[0].velocity", "static"},
    {"tool without keyframes", [](json& j) { j["tool"].erase("keyframes"); }, "tool.keyframes",
     "missing"},
    {"tool with empty keyframes", [](json& j) { j["tool"]["keyframes"] = json::array(); },
     "tool.keyframes", "empty"},
    {"keyframes not increasing", [](json& j) { j["tool"]["keyframes"][1]["t"] = 0; },
     "tool.keyframes[1].t", "strictly increase"},
    {"negative first keyframe", [](json& j) { j["tool"]["keyframes"][0]["t"] = -1; },
     "tool.keyframes[0].t", ">= 0"},
    {"zero rotation axis",
     [](json& j) {
       j["tool"]["keyframes"][0]["rotation"] = {{"axis", {0, 0, 0}}, {"angle_deg", 10}};
     },
     "tool.keyframes[0].rotation.axis", "non-zero"},
    {"inverted domain",
     [](json& j) {
       j["simulation"]["domain"] = {{"min", {1, 1, 1}}, {"max", {0, 0, 0}}};
     },
     "simulation.domain", "min"},
    {"negative duration",
     [](json& j) {
       j["run"] = {{"duration", -1}};
     },
     "run.duration", "> 0"},
    {"empty name", [](json& j) { j["name"] = ""; }, "name", "empty"},
    {"unknown solver", [](json& j) { j["simulation"]["solver"] = "isph"; }, "simulation.solver",
     "give \"paper\" (the paper's explicit step) or \"iisph\""},
    {"solver not a string", [](json& j) { j["simulation"]["solver"] = 2; }, "simulation.solver", "expected a string"},
    {"iisph stiffness over 1", [](json& j) { j["simulation"]["iisph"] = {{"stiffness", 2}}; },
     "simulation.iisph.stiffness", "must be in (0, 1], got 2"},
    {"iisph omega 0", [](json& j) { j["simulation"]["iisph"] = {{"omega", 0}}; }, "simulation.iisph.omega", "> 0"},
    {"iisph too many iterations", [](json& j) { j["simulation"]["iisph"] = {{"max_iterations", 5000}}; },
     "simulation.iisph.max_iterations", "must be in [2, 1000], got 5000"},
    {"iisph unknown gradient", [](json& j) { j["simulation"]["iisph"] = {{"gradient", "wendland"}}; },
     "simulation.iisph.gradient", "give \"spiky\" (the paper's kernel, lattice-scaled) or \"cubic\""},
    {"iisph unknown density kernel", [](json& j) { j["simulation"]["iisph"] = {{"density_kernel", "wendland"}}; },
     "simulation.iisph.density_kernel", "give \"poly6\" (the paper's, the default) or \"cubic\""},
    {"iisph cubic density with the spiky gradient",
     [](json& j) { j["simulation"]["iisph"] = {{"density_kernel", "cubic"}}; }, "simulation.iisph.density_kernel",
     "set iisph.gradient to \"cubic\""},
    {"gravity of 1e308", [](json& j) { j["simulation"]["gravity"] = {0, 0, -1e308}; }, "simulation.gravity",
     "over the largest of 1000 m/s^2"},
    {"a denormal particle mass", [](json& j) { j["blocks"][1]["mass"] = 5e-324; }, "blocks[1].mass",
     "times from the mass that puts this lattice at its rest density"},
    {"iisph unknown pressure solve", [](json& j) { j["simulation"]["iisph"] = {{"pressure_solve", "multigrid"}}; },
     "simulation.iisph.pressure_solve", "give \"jacobi\" (relaxed Jacobi, the default) or \"cg\""},
    {"iisph largest error under the mean's",
     [](json& j) { j["simulation"]["iisph"] = {{"density_error", 0.01}, {"max_density_error", 0.001}}; },
     "simulation.iisph.max_density_error", "must be in [density_error, 1)"},
    {"iisph viscosity tolerance of 1.5", [](json& j) { j["simulation"]["iisph"] = {{"viscosity_tolerance", 1.5}}; },
     "simulation.iisph.viscosity_tolerance", "must be in [0, 1), got 1.5"},
    {"iisph misspelt", [](json& j) { j["simulation"]["iisph"] = {{"stifness", 1}}; }, "simulation.iisph",
     "stiffness"},
    {"not an object", [](json& j) { j["blocks"][0] = 3; }, "blocks[0]", "object"},
    {"a flow index of 5",
     [](json& j) {
       j["simulation"]["solver"] = "iisph";
       j["materials"]["paste"]["flow_index"] = 5;
     },
     "materials.paste.flow_index", "must be in [0.1, 2], got 5"},
    {"a yield stress with no viscosity",
     [](json& j) {
       j["simulation"]["solver"] = "iisph";
       j["materials"]["paste"]["viscosity"] = 0;
       j["materials"]["paste"]["yield_stress"] = 100;
     },
     "materials.paste.yield_stress", "a yield stress with no viscosity"},
    {"an unyielded viscosity under the flowing one",
     [](json& j) {
       j["simulation"]["solver"] = "iisph";
       j["materials"]["paste"]["yield_stress"] = 100;
       j["materials"]["paste"]["max_viscosity"] = 0.1;
     },
     "materials.paste.max_viscosity", "under the viscosity"},
    {"a negative yield stress",
     [](json& j) {
       j["simulation"]["solver"] = "iisph";
       j["materials"]["paste"]["yield_stress"] = -1;
     },
     "materials.paste.yield_stress", "must be in [0, 1e+07], got -1"},
    {"a non-Newtonian paste on the paper's step", [](json& j) { j["materials"]["paste"]["flow_index"] = 0.5; },
     "materials.paste", "set simulation.solver to \"iisph\""},
    {"iisph rheology iterations 0", [](json& j) { j["simulation"]["iisph"] = {{"rheology_iterations", 0}}; },
     "simulation.iisph.rheology_iterations", "[1, 100]"},
    {"iisph rheology forcing 2", [](json& j) { j["simulation"]["iisph"] = {{"rheology_forcing", 2}}; },
     "simulation.iisph.rheology_forcing", "[0, 1]"},
    {"an interface strength on the paper's step", [](json& j) { j["materials"]["paste"]["interface_strength"] = 5e4; },
     "materials.paste", "drop interface_strength"},
    {"an interface strength over 1e7 Pa",
     [](json& j) {
       j["simulation"]["solver"] = "iisph";
       j["materials"]["paste"]["interface_strength"] = 2e7;
     },
     "materials.paste.interface_strength", "must be in [0, 1e+07], got 2e+07"},
    {"a rest density of 1e-308", [](json& j) { j["materials"]["paste"]["rest_density"] = 1e-308; },
     "materials.paste.rest_density", "must be in [1, 100000], got 1e-308"},
    {"a viscosity of 1e300", [](json& j) { j["materials"]["paste"]["viscosity"] = 1e300; },
     "materials.paste.viscosity", "must be in [0, 1e+09], got 1e+300"},
    {"a stiffness of 1e300", [](json& j) { j["materials"]["paste"]["stiffness"] = 1e300; },
     "materials.paste.stiffness", "must be in [1e-06, 1e+12], got 1e+300"},
    {"a yield stress of 1e8",
     [](json& j) {
       j["simulation"]["solver"] = "iisph";
       j["materials"]["paste"]["yield_stress"] = 1e8;
     },
     "materials.paste.yield_stress", "must be in [0, 1e+07], got 1e+08"},
};

class BrokenScene : public ::testing::TestWithParam<BrokenCase> {};

TEST_P(BrokenScene, NamesTheSourceAndTheField) {
  const BrokenCase& c = GetParam();
  json j = base_scene();
  c.mutate(j);
  try {
    parse_scene(j.dump(), "broken.json");
    FAIL() << c.what << ": no error";
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("broken.json: " + c.path), std::string::npos) << c.what << ": " << msg;
    EXPECT_NE(msg.find(c.also), std::string::npos) << c.what << ": " << msg;
    EXPECT_NE(msg.find("; "), std::string::npos) << c.what << ": no fix in " << msg;
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, BrokenScene, ::testing::ValuesIn(broken_cases),
                         [](const ::testing::TestParamInfo<BrokenCase>& info) {
                           std::string name = info.param.what;
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

void expect_error(const std::string& text, const std::string& part1, const std::string& part2) {
  try {
    parse_scene(text, "broken.json");
    FAIL() << "no error for " << text;
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(part1), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(part2), std::string::npos) << e.what();
  }
}

TEST(SceneErrors, SyntaxErrorsNameLineAndColumn) {
  expect_error("{\n  \"name\": \"x\",\n}", "broken.json: line 3, column 1: syntax error",
               "trailing commas");
  expect_error("{\"name\": \"x\", \"simulation\": {\"dt\": NaN}}", "broken.json: line 1", "NaN");
  expect_error("{\"name\": \"x\", \"simulation\": {\"dt\": 1e999}}", "broken.json: ", "overflow");
  expect_error("", "broken.json: line 1, column 1", "end of input");
  expect_error("[1, 2]", "broken.json: (top level): expected a scene", "{");
}

TEST(SceneErrors, AProcedureFileIsToldFromAScene) {
  try {
    load_scene("scenes/default_procedure.json");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("scenes/default_procedure.json: keyframes: this is a filling procedure"), std::string::npos) << msg;
    EXPECT_NE(msg.find("--procedure"), std::string::npos) << msg;
  }
}

TEST(SceneErrors, MissingFileNamesTheFile) {
  try {
    load_scene("scenes/no_such_scene.json");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("scenes/no_such_scene.json: cannot read"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(load_scene("scenes"), SceneError);  // a directory
}

}  // namespace
}  // namespace dentsph
