// Dental procedures (docs/procedure-format.md): a procedure file's instrument, keyframes and
// events, given in millimetres in the tooth frame, placed on a lined tooth. The keyframes and
// events are read by the scene reader's own code (tool_json.cpp) with a Placement that converts
// millimetres in the tooth frame to metres in the world and lays increments into the cavity.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "dentsph/dental.hpp"
#include "dentsph/limits.hpp"
#include "dentsph/tools.hpp"
#include "scene/parse.hpp"
#include "scene/paste_sites.hpp"

namespace dentsph {

namespace {

using scene::Range;
using scene::Reader;

constexpr real mm = 1e-3;

// The tooth frame's rotation (columns x, y, z) as a quaternion.
Quat frame_rotation(const ToothFrame& f) {
  const real m00 = f.x.x, m11 = f.y.y, m22 = f.z.z;
  const real tr = m00 + m11 + m22;
  Quat q;
  if (tr > 0) {
    const real r = std::sqrt(1 + tr) * 2;
    q = {0.25 * r, (f.y.z - f.z.y) / r, (f.z.x - f.x.z) / r, (f.x.y - f.y.x) / r};
  } else if (m00 > m11 && m00 > m22) {
    const real r = std::sqrt(1 + m00 - m11 - m22) * 2;
    q = {(f.y.z - f.z.y) / r, 0.25 * r, (f.y.x + f.x.y) / r, (f.z.x + f.x.z) / r};
  } else if (m11 > m22) {
    const real r = std::sqrt(1 + m11 - m00 - m22) * 2;
    q = {(f.z.x - f.x.z) / r, (f.y.x + f.x.y) / r, 0.25 * r, (f.z.y + f.y.z) / r};
  } else {
    const real r = std::sqrt(1 + m22 - m00 - m11) * 2;
    q = {(f.x.y - f.y.x) / r, (f.z.x + f.x.z) / r, (f.z.y + f.y.z) / r, 0.25 * r};
  }
  return q.normalized();
}

// The sites an increment can take: in the cavity, or above the occlusal reference over it.
std::vector<Vec3> increment_sites(const PreparedTooth& tooth, real s) {
  std::vector<Vec3> sites;
  for (const scene::PasteSite& p : scene::paste_sites(tooth, s))
    if (p.in_cavity || p.over_cavity) sites.push_back(p.local);
  return sites;
}

struct ProcedureContext {
  const ToothScene& tooth;
  const DentalSceneParams& params;
  const Model& model;
  std::vector<Vec3> sites;  // increment_sites
  scene::ParticleBudget& budget;
};

// {"volume": mm^3 | "cavity_fraction": share, "at": [x, y, z] mm}: round(volume / s^3) particles
// on the lattice sites from at's height up that are free when the increment is laid, lowest
// layer first, nearest `at` first in each layer.
void cavity_increment(const Reader& d, const ProcedureContext& ctx, ProcedureEvent& ev) {
  d.only({"volume", "cavity_fraction", "at"});
  const PreparedTooth& tooth = ctx.tooth.tooth;
  const real s = ctx.tooth.boundary.spacing;
  const real cavity_mm3 = tooth.cavity_volume() / (mm * mm * mm);
  const real particle_mm3 = std::pow(s / mm, 3);
  if (d.has("volume") == d.has("cavity_fraction"))
    d.fail_here("needs exactly one of \"volume\" (mm^3) and \"cavity_fraction\" (a share of the cavity's volume)",
                "give e.g. {\"volume\": 10, \"at\": [0, 0, -2]} or {\"cavity_fraction\": 0.33, \"at\": [0, 0, -2]}");
  const std::string field = d.has("volume") ? "volume" : "cavity_fraction";
  const real volume = d.has("volume")
                          ? d.number("volume", "the increment's volume in mm^3, e.g. 10", Range::positive)
                          : cavity_mm3 * d.number("cavity_fraction", "the increment's share of the cavity, e.g. 0.33",
                                                  Range::positive);
  if (volume < particle_mm3)
    d.fail(field, fmt::format("{:.4g} mm^3 is less than one particle ({:.4g} mm^3)", volume, particle_mm3),
           "give at least one particle's volume; a cavity is filled in increments of a few mm^3");
  if (volume > cavity_mm3 * (1 + 1e-9))
    d.fail(field, fmt::format("{:.4g} mm^3 is more than the whole cavity holds ({:.4g} mm^3)", volume, cavity_mm3),
           "split the filling into increments of at most the cavity's volume (at most 2 mm deep each is the "
           "clinical rule)");
  const Vec3 at = d.vec3("at", "the increment's lowest point [x, y, z] in mm in the tooth frame, e.g. [0, 0, -2]") * mm;
  std::vector<Vec3> sites;
  for (const Vec3& p : ctx.sites)
    if (p.z >= at.z - 0.5 * s) sites.push_back(p);
  const auto count = std::size_t(std::lround(volume / particle_mm3));
  if (count > sites.size())
    d.fail(field,
           fmt::format("{:.4g} mm^3 ({} particles) does not fit in the cavity's outline above z = {:.3g} mm ({} sites)",
                       volume, count, at.z / mm, sites.size()),
           "give a smaller volume or a lower \"at\"");
  auto key = [&](const Vec3& p) {
    return std::pair{std::lround((p.z - at.z) / s), (p.x - at.x) * (p.x - at.x) + (p.y - at.y) * (p.y - at.y)};
  };
  std::stable_sort(sites.begin(), sites.end(), [&](const Vec3& a, const Vec3& b) { return key(a) < key(b); });
  // Every increment holds all its candidate sites: thousands of increments would hold millions.
  ctx.budget.add(d, field, double(sites.size()), double(count), "give fewer increments");
  const real m = lattice_particle_mass(ctx.params.paste.rho0, s, ctx.model.kernel);
  for (const Vec3& p : sites)
    ev.particles.push_back(make_particle(Role::material, tooth.frame().to_world(p), m, ctx.params.paste, {},
                                           ctx.model.materials.paste.value_or(kNoMaterial)));
  ev.count = count;
  ev.clearance = 0.9 * s;
}

}  // namespace

Scene dental_procedure(const ToothScene& tooth, const std::string& procedure_json, const std::string& source,
                       const DentalSceneParams& dp) {
  const scene::Json json = scene::parse_json(procedure_json, source);
  const Reader root(json, "", source, "a procedure");
  root.only({"name", "description", "tool", "keyframes", "events", "duration", "material"});
  (void)scene::read_paste_preset(root);  // checked here; the caller fills with it (procedure_paste_preset)
  const std::string name = root.string("name", "the procedure's name, e.g. \"three_increments\"");
  (void)root.optional_string("description", "a description of the procedure");

  Scene sc = dental_base_scene(tooth, dp, name, source);
  const real s = tooth.boundary.spacing;
  const ToothFrame& fr = tooth.tooth.frame();
  const Quat frame_q = frame_rotation(fr);
  scene::ParticleBudget budget(sc.model.max_bonds_per_particle, sc.model.neighbour_skin > 0);
  budget.add(root, "", double(sc.particles.size()), double(sc.particles.size()), "choose a smaller tooth");
  const ProcedureContext ctx{tooth, dp, sc.model, increment_sites(tooth.tooth, s), budget};

  scene::Placement place;
  place.length_unit = "mm in the tooth frame";
  place.length_scale = mm;
  place.to_world = [&](const Pose& p) { return Pose{fr.to_world(p.position), frame_q * p.orientation}; };
  place.dispense = [&](const Reader& d, ProcedureEvent& ev) { cavity_increment(d, ctx, ev); };
  place.budget = &budget;
  place.solver = sc.model.solver;

  const std::string tool = root.optional_string("tool", "the first instrument: ball_burnisher, flat_plugger or condenser")
                               .value_or("ball_burnisher");
  ToolShape shape;
  try {
    shape = tool_by_name(tool, s, sc.model.solver);
  } catch (const std::invalid_argument& err) {
    root.fail("tool", err.what(), "use one of the known instruments");
  }
  const real tool_mass = lattice_particle_mass(dp.wall.rho0, s, sc.model.kernel);
  budget.add(root, "tool", double(shape.points.size()), double(shape.points.size()), "choose another instrument");
  for (const ParticleInit& p : tool_particles(shape, tool_mass, dp.wall, *sc.model.materials.instrument)) sc.particles.push_back(p);
  sc.instrument = tool;
  sc.instrument_spacing = s;
  sc.tool = scene::read_trajectory(root, place);
  if (root.has("events")) sc.events = scene::read_events(root, place, nullptr, dp.wall, sc.model.kernel);
  sc.duration = root.number_or("duration", sc.tool.keyframes.back().t,
                               "the procedure's length in s (default: the last keyframe's time)", Range::positive);
  fit_dental_time_step(sc);  // the iisph solver's step within the instrument's fastest speed
  // The run's length: at most limits::max_run_steps steps.
  if (const std::string problem = limits::run_length_problem(sc.duration, sc.model.dt); !problem.empty()) {
    const std::string field =
        root.has("duration") ? std::string("duration")
                             : fmt::format("keyframes[{}].t", sc.tool.keyframes.size() - 1);
    root.fail(field, fmt::format("the procedure's length: {}", problem),
              fmt::format("end the procedure within {:.4g} s", double(limits::max_run_steps) * sc.model.dt));
  }
  return sc;
}

Scene load_dental_procedure(const ToothScene& tooth, const std::filesystem::path& file, const DentalSceneParams& dp) {
  return dental_procedure(tooth, scene::read_text_file(file, "the procedure file"), file.string(), dp);
}

Scene default_dental_procedure(const DentalSceneParams& dp) {
  return dental_procedure(default_tooth_scene(), std::string(default_procedure_json()), "built-in default_procedure",
                          dp);
}

Scene procedure_or_built_in(const ToothScene& tooth, const std::filesystem::path& file, const DentalSceneParams& dp) {
  return file.empty() ? dental_procedure(tooth, std::string(default_procedure_json()), "built-in default_procedure", dp)
                      : load_dental_procedure(tooth, file, dp);
}

Scene dental_run_scene(const ToothSpec& spec, const std::filesystem::path& procedure_file, const DentalSceneParams& dp) {
  Scene sc = procedure_or_built_in(prepare_tooth(spec), procedure_file, dp);
  sc.source = fmt::format("{} on {}", sc.source, tooth_name(spec));
  return sc;
}

std::optional<PastePreset> procedure_paste_preset(const std::filesystem::path& file) {
  if (file.empty()) return std::nullopt;
  const std::string source = file.string();
  const scene::Json json = scene::parse_json(scene::read_text_file(file, "the procedure file"), source);
  return scene::read_paste_preset(Reader(json, "", source, "a procedure"));
}

}  // namespace dentsph
