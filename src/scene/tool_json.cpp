// The tool of a scene: its particles in the tool frame and its keyframed trajectory
// (docs/scene-format.md, "tool").
#include <fmt/format.h>

#include "dentsph/tools.hpp"
#include "scene/parse.hpp"

namespace dentsph::scene {

namespace {

constexpr real pi = 3.14159265358979323846;

// "rotation": {"axis": [x, y, z], "angle_deg": a}, a right-handed rotation about a non-zero axis.
Quat read_rotation(const Reader& r) {
  r.only({"axis", "angle_deg"});
  const Vec3 axis = r.vec3("axis", "the rotation axis [x, y, z] (any non-zero length)");
  if (norm2(axis) == 0) r.fail("axis", "is zero", "give a non-zero axis, e.g. [0, 0, 1]");
  const real deg = r.number("angle_deg", "the rotation angle in degrees about the axis");
  return Quat::from_axis_angle(axis, deg * pi / 180);
}

ToolKeyframe read_keyframe(const Reader& k, const ToolKeyframe* previous, const Placement& place) {
  k.only({"t", "position", "rotation"});
  ToolKeyframe kf;
  kf.t = k.number("t", "the keyframe time in s", Range::non_negative);
  if (previous != nullptr && !(kf.t > previous->t))
    k.fail("t", fmt::format("{} s is not after the previous keyframe's {} s", kf.t, previous->t),
           "keyframe times must strictly increase");
  kf.pose.position =
      place.length_scale *
      k.vec3("position", fmt::format("the tool-frame origin's position [x, y, z] in {}", place.length_unit));
  if (const std::optional<Reader> rot =
          k.optional_object("rotation", "the orientation {\"axis\": [0, 0, 1], \"angle_deg\": 0}"))
    kf.pose.orientation = read_rotation(*rot);
  return kf;
}

// The scene file's increment: {"volume": m^3, "at": [x, y, z], "spacing": m}, a sphere of lattice
// points of roles.material (spacing default h / 2), counted in `budget` before it is made.
std::vector<ParticleInit> sphere_increment(const Reader& d, const SceneMaterials& materials, const KernelCoeffs& kernel,
                                           ParticleBudget* budget) {
  d.only({"volume", "at", "spacing"});
  const real volume = d.number("volume", "the increment's volume in m^3, e.g. 8e-9 (8 mm^3)", Range::positive);
  const Vec3 at = d.vec3("at", "the increment's centre [x, y, z] in m");
  const real spacing = d.number_or("spacing", kernel.h / 2, "the particle spacing in m", Range::positive);
  if (const std::string problem = limits::spacing_problem(spacing, kernel.h); !problem.empty())
    d.fail("spacing", problem, limits::spacing_fix(kernel.h));
  const std::optional<Material>& m = materials.default_for(Role::material);
  if (!m) d.fail_here("has no material", "set roles.material to the paste's material");
  if (budget) {
    const double n = increment_points_bound(volume, spacing);
    budget->add(d, "volume", n, n, "give a smaller volume (m^3: 8e-9 is 8 mm^3)");
  }
  return material_increment(at, volume, spacing, lattice_particle_mass(m->rho0, spacing, kernel), *m);
}

// The curing light of a "cure" event: {"position": [x, y, z], "direction": [x, y, z], "duration": s,
// "irradiance": mW/cm^2, "diameter": length}, lengths in the placement's unit, placed in the world.
void read_cure(const Reader& c, const Placement& place, ProcedureEvent& ev) {
  c.only({"position", "direction", "duration", "irradiance", "diameter"});
  ev.kind = ProcedureEvent::Kind::cure;
  ev.duration = c.number("duration", "how long the light stays on in s, e.g. 20", Range::positive);
  CuringLight& light = ev.light;
  const Vec3 tip = place.length_scale *
                   c.vec3("position", fmt::format("the light tip's centre [x, y, z] in {}", place.length_unit));
  Vec3 direction{0, 0, -1};
  if (c.has("direction")) {
    direction = c.vec3("direction", "where the beam points [x, y, z], e.g. [0, 0, -1] (down)");
    if (!(norm2(direction) > 0)) c.fail("direction", "is zero", "give a non-zero direction, e.g. [0, 0, -1]");
  }
  const real mw = c.number_or("irradiance", 1000, "the light's irradiance in mW/cm^2, e.g. 1000", Range::positive);
  if (mw > 10000)
    c.fail("irradiance", fmt::format("{} mW/cm^2 is more than any curing light gives", mw),
           "give the irradiance in mW/cm^2: 400 to 3000 for dental curing lights, 1000 is typical");
  light.irradiance = mw * W_per_m2_per_mW_per_cm2;
  light.diameter = place.length_scale * c.number_or("diameter", 10e-3 / place.length_scale,
                                                    fmt::format("the light tip's diameter in {}, e.g. {}",
                                                                place.length_unit, 10e-3 / place.length_scale),
                                                    Range::positive);
  if (place.to_world) {
    const Vec3 at = place.to_world(Pose{tip, {}}).position;
    light.direction = place.to_world(Pose{tip + direction, {}}).position - at;
    light.tip = at;
  } else {
    light.tip = tip;
    light.direction = direction;
  }
  light.direction = light.direction / norm(light.direction);
}

// One event: {"t": s, "dispense": {...}}, {"t": s, "switch_tool": {"name": "flat_plugger",
// "spacing": length}} or {"t": s, "cure": {...}} (read_cure). Spacing defaults to h / 2; the
// instrument is of the tool's material.
ProcedureEvent read_event(const Reader& e, const ProcedureEvent* previous, const Placement& place,
                          const SceneMaterials* materials, const Material& tool_material, const KernelCoeffs& kernel) {
  e.only({"t", "dispense", "switch_tool", "cure"});
  ProcedureEvent ev;
  ev.t = e.number("t", "the event time in s", Range::non_negative);
  if (previous != nullptr && ev.t < previous->t)
    e.fail("t", fmt::format("{} s is before the previous event's {} s", ev.t, previous->t),
           "list events in time order");
  if (int(e.has("dispense")) + int(e.has("switch_tool")) + int(e.has("cure")) != 1)
    e.fail_here("needs exactly one of \"dispense\", \"switch_tool\" and \"cure\"",
                "give {\"t\": 1.0, \"dispense\": {\"volume\": ..., \"at\": [x, y, z]}}, "
                "{\"t\": 1.0, \"switch_tool\": {\"name\": \"flat_plugger\"}} or "
                "{\"t\": 1.0, \"cure\": {\"position\": [x, y, z], \"duration\": 20}}");
  if (const std::optional<Reader> c = e.optional_object("cure", "the curing light {\"position\": [x, y, z], \"duration\": 20}")) {
    read_cure(*c, place, ev);
  } else if (const std::optional<Reader> d = e.optional_object("dispense", "the increment {\"volume\": ..., \"at\": [x, y, z]}")) {
    ev.kind = ProcedureEvent::Kind::dispense;
    if (place.dispense)
      place.dispense(*d, ev);
    else
      ev.particles = sphere_increment(*d, *materials, kernel, place.budget);
  } else {
    const Reader sw = e.object("switch_tool", "the instrument {\"name\": \"flat_plugger\"}");
    sw.only({"name", "spacing"});
    ev.kind = ProcedureEvent::Kind::switch_tool;
    ev.tool = sw.string("name", "ball_burnisher, flat_plugger or condenser");
    const real spacing =
        place.length_scale * sw.number_or("spacing", kernel.h / 2 / place.length_scale,
                                          fmt::format("the particle spacing in {}", place.length_unit), Range::positive);
    const char* unit = place.length_scale == 1 ? "m" : "mm";
    if (const std::string problem = limits::spacing_problem(spacing, kernel.h, unit, place.length_scale);
        !problem.empty())
      sw.fail("spacing", problem, limits::spacing_fix(kernel.h, unit, place.length_scale));
    ToolShape shape;
    try {
      shape = tool_by_name(ev.tool, spacing, place.solver);
    } catch (const std::invalid_argument& err) {
      sw.fail("name", err.what(), "use one of the known instruments");
    }
    if (place.budget)
      place.budget->add(sw, "name", double(shape.points.size()), double(shape.points.size()),
                        "switch instruments less often");
    ev.particles = tool_particles(shape, lattice_particle_mass(tool_material.rho0, spacing, kernel), tool_material);
    ev.tool_spacing = spacing;
  }
  return ev;
}

}  // namespace

ToolTrajectory read_trajectory(const Reader& owner, const Placement& place) {
  const Json& kfs = owner.array(
      "keyframes", fmt::format("at least one keyframe, e.g. [{{\"t\": 0, \"position\": [0, 0, 1]}}] ({})",
                               place.length_unit));
  ToolTrajectory traj;
  for (std::size_t i = 0; i < kfs.size(); ++i)
    traj.keyframes.push_back(read_keyframe(owner.element(kfs, "keyframes", i, "a keyframe"),
                                           i > 0 ? &traj.keyframes.back() : nullptr, place));
  if (place.to_world)
    for (ToolKeyframe& kf : traj.keyframes) kf.pose = place.to_world(kf.pose);
  return traj;
}

std::vector<ProcedureEvent> read_events(const Reader& owner, const Placement& place, const SceneMaterials* materials,
                                        const Material& tool_material, const KernelCoeffs& kernel) {
  const Json& evs = owner.array("events", "a list of events [{\"t\": 1.0, \"dispense\": {...}}]");
  check_event_count(owner, evs.size());
  std::vector<ProcedureEvent> events;
  for (std::size_t i = 0; i < evs.size(); ++i)
    events.push_back(read_event(owner.element(evs, "events", i, "an event"), i > 0 ? &events.back() : nullptr, place,
                                materials, tool_material, kernel));
  return events;
}

ToolPart parse_tool(const Reader& tool, const SceneMaterials& materials, const KernelCoeffs& kernel,
                    ParticleBudget& budget, Solver solver) {
  tool.only({"material", "blocks", "keyframes", "events"});
  // The tool's own material (default roles.tool) is the default of each of its blocks.
  MaterialDefault tool_material{materials.default_for(Role::tool), "roles.tool"};
  if (tool.has("material"))
    tool_material = {resolve_material(tool, materials, tool_material), "tool.material"};
  else
    tool_material.from = "tool.material or roles.tool";

  ToolPart part;
  const Json& blocks = tool.array("blocks",
                                  "the tool's shape as blocks in the tool frame, e.g. "
                                  "[{\"shape\": \"sphere\", ...}]");
  const BlockContext ctx{Role::tool, materials, tool_material, kernel, &budget};
  for (std::size_t i = 0; i < blocks.size(); ++i)
    part.blocks.push_back(plan_block(tool.element(blocks, "blocks", i, "a block"), ctx));
  part.trajectory = read_trajectory(tool, Placement{});
  if (tool.has("events")) {
    if (!tool_material.material) tool.fail("events", "need the tool's material", "set tool.material or roles.tool");
    Placement place;
    place.budget = &budget;
    place.solver = solver;
    part.events = read_events(tool, place, &materials, *tool_material.material, kernel);
  }
  return part;
}

}  // namespace dentsph::scene
