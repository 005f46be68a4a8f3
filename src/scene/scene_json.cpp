// parse_scene and load_scene: the top level of a scene file, its simulation settings, and the
// Model built from them (docs/scene-format.md).
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "scene/parse.hpp"

namespace dentsph::scene {

Solver read_solver(const Reader& simulation, Solver fallback) {
  const std::optional<std::string> name =
      simulation.optional_string("solver", "the step that runs the scene: \"paper\" or \"iisph\"");
  if (!name) return fallback;
  const std::optional<Solver> s = solver_from_name(*name);
  if (!s)
    simulation.fail("solver", fmt::format("unknown solver \"{}\"", *name),
                    "give \"paper\" (the paper's explicit step) or \"iisph\" (the implicit solver, docs/model.md)");
  return *s;
}

namespace {

// make_model's messages read "<field>: <problem>; <fix>" with fields named as in ModelParams:
// adhesion.* keep their name, the rest live under "simulation".
[[noreturn]] void throw_model_error(const std::invalid_argument& e, const std::string& source) {
  const std::string_view msg = e.what();
  const auto colon = msg.find(": ");
  const std::string_view field = msg.substr(0, colon);
  const std::string path = field.starts_with("adhesion") ? std::string(field) : fmt::format("simulation.{}", field);
  const std::string_view rest = colon == std::string_view::npos ? msg : msg.substr(colon + 2);
  // Keep our "<problem>; <fix>" shape where make_model gave no fix.
  const bool has_fix = rest.find("; ") != std::string_view::npos;
  throw SceneError(fmt::format("{}: {}: {}{}", source, path, rest, has_fix ? "" : "; see docs/scene-format.md"));
}

}  // namespace

IisphParams read_iisph(const Reader& simulation, IisphParams p) {
  const std::optional<Reader> i = simulation.optional_object(
      "iisph", "the iisph solver's settings {\"stiffness\": 0.5, \"max_iterations\": 12, ...} (docs/model.md)");
  if (!i) return p;
  i->only({"stiffness", "max_iterations", "density_error", "max_density_error", "pressure_solve", "omega",
           "viscosity_iterations", "viscosity_tolerance", "cfl", "gradient", "density_kernel", "rheology_iterations",
           "rheology_tolerance", "rheology_forcing", "wall_rest_density", "viscous_pressure", "surface_tension", "wetting"});
  if (const std::optional<std::string> ps =
          i->optional_string("pressure_solve", "how the pressure is solved: \"jacobi\" or \"cg\"")) {
    const std::optional<PressureSolve> solve = pressure_solve_from_name(*ps);
    if (!solve)
      i->fail("pressure_solve", fmt::format("unknown pressure solve \"{}\"", *ps),
              "give \"jacobi\" (relaxed Jacobi, the default) or \"cg\" (projected conjugate gradients, for deep or "
              "stiff scenes; docs/model.md)");
    p.pressure_solve = *solve;
  }
  if (const std::optional<std::string> g =
          i->optional_string("gradient", "the pressure's kernel gradient: \"spiky\" or \"cubic\"")) {
    const std::optional<PressureGradient> grad = gradient_from_name(*g);
    if (!grad)
      i->fail("gradient", fmt::format("unknown gradient \"{}\"", *g),
              "give \"spiky\" (the paper's kernel, lattice-scaled) or \"cubic\" (the cubic spline; docs/model.md)");
    p.gradient = *grad;
  }
  if (const std::optional<std::string> k =
          i->optional_string("density_kernel", "the density's kernel: \"poly6\" or \"cubic\"")) {
    const std::optional<DensityKernel> kernel = density_kernel_from_name(*k);
    if (!kernel)
      i->fail("density_kernel", fmt::format("unknown density kernel \"{}\"", *k),
              "give \"poly6\" (the paper's, the default) or \"cubic\" (the cubic spline, with gradient \"cubic\"; "
              "docs/model.md)");
    p.density_kernel = *kernel;
  }
  p.stiffness = i->number_or("stiffness", p.stiffness,
                             "the share of Kp the solve's equation of state takes: 0.5 the paper's paste's "
                             "stiffness, 1 the equation of state as written",
                             Range::positive);
  p.max_iterations = int(i->integer_or("max_iterations", p.max_iterations,
                                       "the pressure iterations at most, e.g. 12 (the solve always takes 2)",
                                       p.min_iterations, 1000));
  p.density_error = i->number_or("density_error", p.density_error, "the pressure solve's target mean density error, e.g. 0.002",
                                 Range::positive);
  p.max_density_error = i->number_or("max_density_error", p.max_density_error,
                                     "the cg pressure solve's target largest density error, e.g. 0.01", Range::positive);
  p.omega = i->number_or("omega", p.omega, "the Jacobi relaxation, in (0, 1], e.g. 0.5", Range::positive);
  p.viscosity_iterations = int(i->integer_or("viscosity_iterations", p.viscosity_iterations,
                                             "the viscosity's conjugate-gradient iterations, e.g. 8", 1, 1000));
  p.viscosity_tolerance = i->number_or("viscosity_tolerance", p.viscosity_tolerance,
                                       "the viscosity solve's relative residual, e.g. 1e-3 (0: a fixed count)",
                                       Range::non_negative);
  p.cfl = i->number_or("cfl", p.cfl, "the velocity Courant number, about 0.4", Range::positive);
  p.rheology_iterations = int(i->integer_or("rheology_iterations", p.rheology_iterations,
                                            "a non-Newtonian material's viscosity solves a step at most, e.g. 3", 1, 100));
  p.viscous_pressure = i->number_or("viscous_pressure", p.viscous_pressure,
                                    "the viscous pressure's step, in [0, 1]: 0.5 the presets', 0 none (docs/model.md)",
                                    Range::non_negative);
  p.surface_tension = i->number_or("surface_tension", p.surface_tension,
                                   "the paste's surface tension in N/m, in [0, 1]: 0 none, about 0.04 a resin's (docs/model.md)",
                                   Range::non_negative);
  p.wetting = i->number_or("wetting", p.wetting,
                           "the paste's wetting of walls, its adhesion over its cohesion, in [0, 2]: 0 none (docs/model.md)",
                           Range::non_negative);
  p.rheology_tolerance = i->number_or("rheology_tolerance", p.rheology_tolerance,
                                      "the relative change of a viscosity that ends a step's Picard iterations, e.g. 0.02",
                                      Range::non_negative);
  p.rheology_forcing = i->number_or("rheology_forcing", p.rheology_forcing,
                                    "a Picard solve's residual over the viscosities' change, in [0, 1]: 0 none (the default), 0.1 usual",
                                    Range::non_negative);
  p.wall_rest_density = i->boolean_or("wall_rest_density", p.wall_rest_density,
                                   "true: a wall's density target is the larger of rho0 and its walls' own (for stiff pastes)");
  try {
    check_iisph_params(p);  // make_model does too, but a dental scene's Model is made later
  } catch (const std::invalid_argument& e) {
    throw_model_error(e, simulation.source());
  }
  return p;
}

namespace {

// nlohmann's messages read "[json.exception.parse_error.101] parse error at line 3, column 7:
// syntax error ...": the location becomes the path slot of ours, the rest the problem.
[[noreturn]] void fail_syntax(const std::string& source, const Json::exception& e) {
  std::string_view msg = e.what();
  if (const auto bracket = msg.find("] "); bracket != std::string_view::npos)
    msg.remove_prefix(bracket + 2);
  std::string where = "JSON";
  constexpr std::string_view at = "parse error at ";
  if (msg.starts_with(at)) {
    msg.remove_prefix(at.size());
    const auto colon = msg.find(": ");
    where = std::string(msg.substr(0, colon));
    msg.remove_prefix(colon == std::string_view::npos ? msg.size() : colon + 2);
  }
  fail(source, where, msg,
       "fix the JSON syntax (strict JSON: no comments, no trailing commas, no NaN or Infinity, "
       "numbers within double range)");
}

Model build_model(const ModelParams& p, const std::string& source) {
  try {
    return make_model(p);
  } catch (const std::invalid_argument& e) {
    throw_model_error(e, source);
  }
}

struct Domain {
  bool given = false;
  Vec3 min, max;  // m
};

// "simulation": time step, kernel support, gravity and the tunables of the Model.
ModelParams read_simulation(const Reader& root, Domain& domain) {
  const Reader sim =
      root.object("simulation", "the simulation settings {\"dt\": 5e-4, \"h\": 0.02, ...}");
  sim.only({"dt", "h", "gravity", "max_bonds_per_particle", "cfl_lambda", "neighbour_skin", "grid_reach", "domain",
            "solver", "iisph"});
  ModelParams p;
  p.solver = read_solver(sim, Solver::paper);
  p.iisph = read_iisph(sim, p.iisph);
  p.dt = sim.number("dt", "the time step in s, e.g. 5e-4", Range::positive);
  p.h = sim.number("h", "the kernel support in m, about twice the spacing, e.g. 0.02",
                   Range::positive);
  p.gravity = sim.vec3_or("gravity", p.gravity, "the gravity [gx, gy, gz] in m/s^2");
  p.max_bonds_per_particle = int(sim.integer_or(
      "max_bonds_per_particle", p.max_bonds_per_particle, "the bond capacity per particle, e.g. 32",
      std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
  p.cfl_lambda = sim.number_or("cfl_lambda", p.cfl_lambda, "the acoustic Courant number, about 0.4",
                               Range::positive);
  // Checked against h by make_model (its message names the field).
  p.neighbour_skin = sim.number_or("neighbour_skin", p.neighbour_skin,
                                   "the neighbour lists' skin in m, 0 to h (about 0.1 h)", Range::non_negative);
  p.grid_reach = int(sim.integer_or("grid_reach", p.grid_reach, "1, 2 or 3", std::numeric_limits<int>::min(),
                                    std::numeric_limits<int>::max()));
  if (const std::optional<Reader> d = sim.optional_object(
          "domain", "the grid region {\"min\": [x, y, z], \"max\": [x, y, z]} in m")) {
    d->only({"min", "max"});
    domain = {true, d->vec3("min", "the domain's lower corner in m"),
              d->vec3("max", "the domain's upper corner in m")};
  }
  return p;
}

// "adhesion": the support [A, B] of the adhesion kernel and its exponents (docs/model.md, "Kernels": the paper's eq. 12).
AdhesionParams read_adhesion(const Reader& root) {
  const Reader a = root.object("adhesion", "the adhesion kernel {\"A\": 0.012, \"B\": 0.03}");
  a.only({"A", "B", "eps", "zeta"});
  AdhesionParams p;
  p.A = a.number("A", "the bond-forming distance in m, a little under h", Range::positive);
  p.B = a.number("B", "the bond-breaking distance in m, a little over h", Range::positive);
  p.eps = a.number_or("eps", p.eps, "the rising exponent, 3 in the paper", Range::positive);
  p.zeta = a.number_or("zeta", p.zeta, "the falling exponent, 2 in the paper", Range::positive);
  return p;
}

OutputSettings read_output(const Reader& root) {
  OutputSettings out;
  if (const std::optional<Reader> o = root.optional_object(
          "output", "the output settings {\"snapshot_interval\": 0.01, \"vtk\": true, \"surface\": true}")) {
    o->only({"snapshot_interval", "vtk", "surface"});
    out.snapshot_interval = o->number_or(
        "snapshot_interval", out.snapshot_interval,
        "the simulated time between snapshots in s (0: none), e.g. 0.01", Range::non_negative);
    out.vtk = o->boolean_or("vtk", out.vtk, "true to write .vtu snapshots and a .pvd index");
    out.surface = o->boolean_or("surface", out.surface,
                                "true to write the paste's surface (.vtp) beside each snapshot, where the paste has a "
                                "spacing");
  }
  return out;
}

// run.duration: at most limits::max_run_steps steps of dt.
real read_duration(const Reader& root, real dt) {
  const std::optional<Reader> run = root.optional_object("run", "{\"duration\": 1.0}");
  if (!run) return 0;
  run->only({"duration"});
  const real duration = run->number_or("duration", 0, "the default run length in s of simulated time",
                                       Range::positive);
  if (const std::string problem = limits::run_length_problem(duration, dt); !problem.empty())
    run->fail("duration", problem,
              fmt::format("give at most {:.4g} s (or a larger simulation.dt)", double(limits::max_run_steps) * dt));
  return duration;
}

// The blocks, read, checked and counted; made by make_blocks once every other count is in.
std::vector<BlockPlan> read_blocks(const Reader& root, const SceneMaterials& materials,
                                   const KernelCoeffs& kernel, ParticleBudget& budget) {
  const Json& blocks = root.array("blocks",
                                  "at least one block of particles, e.g. [{\"role\": \"material\", "
                                  "\"shape\": \"box\", ...}]");
  std::vector<BlockPlan> plans;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const Reader b = root.element(blocks, "blocks", i, "a block");
    const Role role = parse_role(b);
    const MaterialDefault fallback{materials.default_for(role),
                                   fmt::format("roles.{}", role_name(role))};
    plans.push_back(plan_block(b, {role, materials, fallback, kernel, &budget}));
  }
  return plans;
}

// Default domain: the bounding box of the world particles and of the tool's particles at every
// keyframe, padded by 2h. (Between keyframes a rotating tool may leave it; the grid wraps, so
// that costs time, never correctness.)
Domain bounding_domain(const std::vector<ParticleInit>& world, const std::vector<ParticleInit>& tool_particles,
                       const ToolTrajectory& trajectory, real h) {
  constexpr real inf = std::numeric_limits<real>::infinity();
  Vec3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
  auto grow = [&](const Vec3& p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  };
  for (const ParticleInit& p : world) grow(p.pos);
  for (const ToolKeyframe& kf : trajectory.keyframes)
    for (const ParticleInit& p : tool_particles) grow(kf.pose.apply(p.pos));
  const Vec3 pad{2 * h, 2 * h, 2 * h};
  return {true, lo - pad, hi + pad};
}

}  // namespace

Json parse_json(const std::string& text, const std::string& source) {
  try {
    return Json::parse(text);
  } catch (const Json::exception& e) {  // parse_error, and out_of_range for numbers like 1e999
    fail_syntax(source, e);
  }
}

std::string read_text_file(const std::filesystem::path& file, std::string_view what) {
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw SceneError(fmt::format("{}: cannot read {}: {}; check the path", name, what,
                                 std::filesystem::exists(file, ec) ? "not a regular file" : "no such file"));
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  if (in) text << in.rdbuf();
  if (!in || in.bad())
    throw SceneError(fmt::format("{}: cannot read {}: {}; check its permissions", name, what, std::strerror(errno)));
  return text.str();
}

void read_haptics(const Reader& root, Scene& scene) {
  if (const std::optional<Reader> h = root.optional_object("haptics", "{\"force_scale\": 20}")) {
    h->only({"force_scale"});
    scene.force_scale = h->number_or("force_scale", scene.force_scale,
                                     "device N per simulated N of tool force for the haptic runtime, e.g. 20",
                                     Range::positive);
  }
}

void read_session_names(const Reader& root, Scene& sc) {
  sc.student = root.optional_string("student", "who runs the scene, e.g. \"A. Student\" (the report's title)").value_or("");
  sc.exercise = root.optional_string("exercise", "the exercise, e.g. \"class I, lower molar\"").value_or("");
}

}  // namespace dentsph::scene

namespace dentsph {

Scene parse_scene(const std::string& json_text, const std::string& source) {
  using namespace scene;
  const Json json = parse_json(json_text, source);
  const Reader root(json, "", source, "a scene");
  if (is_dental_scene(root)) return parse_dental_scene(root);
  // A filling procedure (procedure-format.md) given where a scene is expected.
  if (root.has("keyframes") && !root.has("simulation"))
    root.fail("keyframes", "this is a filling procedure, not a scene",
              "run it with `dentsph run --procedure FILE`, or name it in a dental scene file's \"procedure\"");
  root.only({"name", "description", "simulation", "adhesion", "materials", "roles", "blocks",
             "tool", "output", "run", "haptics", "student", "exercise"});

  Scene sc;
  sc.source = source;
  sc.name = root.string("name", "the scene's name, e.g. \"blob_on_plate\"");
  if (sc.name.empty()) root.fail("name", "is empty", "give the scene a name");
  (void)root.optional_string("description", "a description of the scene");

  // Check the physical parameters first (a provisional domain: the particles are not known yet):
  // the blocks need a valid h and kernel for their spacing check and default particle mass.
  Domain domain;
  sc.params = read_simulation(root, domain);
  sc.params.adhesion = read_adhesion(root);
  sc.params.domain_min = domain.given ? domain.min : Vec3{-1, -1, -1};
  sc.params.domain_max = domain.given ? domain.max : Vec3{1, 1, 1};
  const KernelCoeffs kernel = build_model(sc.params, source).kernel;

  const SceneMaterials materials = parse_materials(root);
  if (sc.params.solver != Solver::iisph)
    for (const auto& [name, material] : materials.by_name) {
      if (!newtonian(material))
        root.fail(fmt::format("materials.{}", name), "a non-Newtonian material (flow_index or yield_stress) on the paper's step",
                  "set simulation.solver to \"iisph\" (the solver that steps a rheology; docs/model.md), or drop "
                  "flow_index and yield_stress");
      else if (material.interface_strength > 0)
        root.fail(fmt::format("materials.{}", name), "an interface_strength on the paper's step (its contact has none)",
                  "set simulation.solver to \"iisph\" (docs/model.md, \"Tack\"), or drop interface_strength");
    }
  // Every block, the tool and every event counted before their particles are made: the blocks'
  // (the most) once every count is in.
  ParticleBudget budget(sc.params.max_bonds_per_particle, sc.params.neighbour_skin > 0);
  const std::vector<BlockPlan> world = read_blocks(root, materials, kernel, budget);
  std::optional<ToolPart> tool;
  if (const std::optional<Reader> t =
          root.optional_object("tool", "the tool {\"blocks\": [...], \"keyframes\": [...]}"))
    tool = parse_tool(*t, materials, kernel, budget, sc.params.solver);
  sc.particles = make_blocks(world);
  if (tool) {
    const std::vector<ParticleInit> tool_particles = make_blocks(tool->blocks);
    if (!domain.given) domain = bounding_domain(sc.particles, tool_particles, tool->trajectory, sc.params.h);
    sc.particles.insert(sc.particles.end(), tool_particles.begin(), tool_particles.end());
    sc.events = std::move(tool->events);
    sc.tool = std::move(tool->trajectory);
  } else if (!domain.given) {
    domain = bounding_domain(sc.particles, {}, {}, sc.params.h);
  }
  sc.output = read_output(root);
  sc.duration = read_duration(root, sc.params.dt);
  read_haptics(root, sc);
  read_session_names(root, sc);

  sc.params.domain_min = domain.min;
  sc.params.domain_max = domain.max;
  sc.model = build_model(sc.params, source);
  // The Model's table: the named materials (the paste and the instruments those roles.material and
  // roles.tool name), then the values of inline materials.
  MaterialTable& table = sc.model.materials;
  try {
    for (const auto& [name, material] : materials.by_name) table.add(name, material);
    if (!materials.role_name[int(Role::material)].empty()) table.paste = table.find(materials.role_name[int(Role::material)]);
    if (!materials.role_name[int(Role::tool)].empty()) table.instrument = table.find(materials.role_name[int(Role::tool)]);
    intern_scene_materials(sc);
  } catch (const std::invalid_argument& e) {  // the table is full
    root.fail("materials", e.what(),
              fmt::format("use at most {} different materials (the named ones, and inline ones with values of their own)",
                          MaterialTable::kCapacity));
  }
  return sc;
}

Scene load_scene(const std::filesystem::path& file) {
  return parse_scene(scene::read_text_file(file, "the scene file"), file.string());
}

}  // namespace dentsph
