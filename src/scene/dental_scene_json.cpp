// Dental scene files (docs/scene-format.md, "Dental scenes"): a filling procedure on a tooth (a
// mesh, or the built-in crown) with a cavity, each part checked with the file, the field and the
// fix named.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <stdexcept>

#include "dentsph/dental.hpp"
#include "dentsph/paste_presets.hpp"
#include "scene/parse.hpp"

namespace dentsph::scene {

namespace {

// A path of the scene file, relative to the scene file's folder.
std::filesystem::path relative_to_scene(const Reader& root, const std::string& path) {
  const std::filesystem::path p(path);
  return p.is_absolute() ? p : std::filesystem::path(root.source()).parent_path() / p;
}

// The file of field `key` of `owner`: must exist.
std::filesystem::path existing_file(const Reader& owner, std::string_view key, std::string_view hint,
                                    const Reader& root) {
  const std::string given = owner.string(key, hint);
  if (given.empty()) owner.fail(key, "is empty", fmt::format("give {}", hint));
  const std::filesystem::path file = relative_to_scene(root, given);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    owner.fail(key, fmt::format("{} ({})", std::filesystem::exists(file, ec) ? "not a regular file" : "no such file",
                                file.string()),
               "check the path: it is relative to the scene file's folder");
  return file;
}

}  // namespace

bool is_dental_scene(const Reader& root) { return root.has("tooth") || root.has("cavity") || root.has("procedure"); }

CavityParams read_cavity(const Reader& c) {
  std::vector<std::string_view> known = {"class", "side"};
  for (const CavityField& f : cavity_fields()) known.push_back(f.key);
  c.only(known);
  CavityParams p;
  if (const std::optional<std::string> kind = c.optional_string("class", "the cavity's class: \"class1\" or \"class2\"")) {
    const std::optional<CavityClass> k = cavity_class_from_name(*kind);
    if (!k)
      c.fail("class", fmt::format("unknown class \"{}\"", *kind),
             "give \"class1\" (occlusal) or \"class2\" (occlusal and one proximal box)");
    p.kind = *k;
  }
  const bool class_2 = p.kind == CavityClass::class_2;
  if (const std::optional<std::string> side = c.optional_string("side", "the proximal box's side: \"mesial\" or \"distal\"")) {
    if (!class_2)
      c.fail("side", "is the proximal box's side, but the cavity is class1", "add \"class\": \"class2\" or leave it out");
    const std::optional<ProximalSide> s = proximal_side_from_name(*side);
    if (!s) c.fail("side", fmt::format("unknown side \"{}\"", *side), "give \"mesial\" or \"distal\"");
    p.side = *s;
  }
  for (const CavityField& f : cavity_fields()) {
    if (!c.has(f.key)) continue;
    const CavityValueCheck set = set_cavity_value(p, f, c.number(f.key, f.hint));
    if (set.outcome == CavityValueCheck::Outcome::needs_class_2)
      c.fail(f.key, "is a proximal box's parameter, but the cavity is class1", "add \"class\": \"class2\" or leave it out");
    if (set.outcome == CavityValueCheck::Outcome::refused) c.fail(f.key, set.problem, set.fix);
  }
  return p;
}

// "material": a paste preset's name, or {"preset": name, "temperature_c": C} (docs/model.md,
// "Presets"); none: the paper's paste.
std::optional<PastePreset> read_paste_preset(const Reader& root) {
  const Json* v = root.find("material");
  if (v == nullptr) return std::nullopt;
  std::string name;
  real temperature = 23;
  const std::string choices = fmt::format("{}", fmt::join(paste_preset_names(), ", "));
  if (v->is_string()) {
    name = v->get<std::string>();
  } else if (v->is_object()) {
    const Reader m(*v, root.path_of("material"), root.source(), "a paste preset");
    m.only({"preset", "temperature_c"});
    name = m.string("preset", fmt::format("the preset's name: {}", choices));
    temperature = m.number_or("temperature_c", temperature, "the paste's temperature in C, 10 to 70, e.g. 37");
  } else {
    root.fail("material", fmt::format("expected a preset's name or an object, got {}", describe(*v)),
              fmt::format("give \"material\": \"universal\" or {{\"preset\": \"universal\", \"temperature_c\": 37}} ({})",
                          choices));
  }
  try {
    return paste_preset(name, temperature);
  } catch (const std::invalid_argument& e) {
    root.fail("material", e.what(), fmt::format("give one of {} at 10 to 70 C", choices));
  }
}

Scene parse_dental_scene(const Reader& root) {
  root.only({"name", "description", "tooth", "cavity", "procedure", "haptics", "student", "exercise", "simulation",
             "material"});
  const std::string name = root.string("name", "the scene's name, e.g. \"class2_fill\"");
  if (name.empty()) root.fail("name", "is empty", "give the scene a name");
  (void)root.optional_string("description", "a description of the scene");

  ToothSpec spec;
  if (const std::optional<Reader> t = root.optional_object(
          "tooth", "the tooth {\"mesh\": \"molar.stl\"} (mm; leave it out for the built-in crown)")) {
    t->only({"mesh", "units", "long_axis", "mesial"});
    if (t->has("mesh"))
      spec.mesh = existing_file(*t, "mesh", "the tooth's surface (STL, OBJ or PLY in mm), e.g. \"molar.stl\"", root);
    if (const std::optional<std::string> u = t->optional_string("units", "the mesh file's units, \"mm\" or \"m\"")) {
      if (*u == "mm") spec.units = MeshUnits::millimetres;
      else if (*u == "m") spec.units = MeshUnits::metres;
      else t->fail("units", fmt::format("is \"{}\"", *u), "give \"mm\" (the default) or \"m\"");
      if (!t->has("mesh")) t->fail("units", "is given without a mesh", "add tooth.mesh or leave units out");
    }
    spec.long_axis = t->optional_vec3("long_axis", "the long axis towards the crown [x, y, z] in the mesh's coordinates");
    spec.mesial = t->optional_vec3("mesial", "a direction towards the tooth's mesial surface [x, y, z]");
  }
  if (const std::optional<Reader> c = root.optional_object(
          "cavity", "the cavity {\"class\": \"class2\", \"width\": 3, \"length\": 5, \"depth\": 2, ...} (mm)"))
    spec.cavity = read_cavity(*c);
  std::filesystem::path procedure;
  if (root.has("procedure"))
    procedure = existing_file(root, "procedure", "the procedure file (docs/procedure-format.md), e.g. \"fill.json\"", root);

  // The tooth's and the cavity's own messages carry their fix.
  std::optional<ToothScene> tooth;
  try {
    tooth = prepare_tooth(spec);
  } catch (const MeshError& e) {
    throw SceneError(fmt::format("{}: tooth.mesh: {}", root.source(), e.what()));
  } catch (const CavityError& e) {
    throw SceneError(fmt::format("{}: cavity: {}", root.source(), e.what()));
  } catch (const ToothAxisError& e) {
    root.fail("tooth", e.what(), "give the tooth's axes in the mesh's coordinates, or leave them out");
  }
  // The step that runs it; its time step is the solver's for dental scenes (dental_time_step).
  DentalSceneParams params;
  // The scene's "material", or its procedure file's.
  std::optional<PastePreset> preset = read_paste_preset(root);
  if (!preset) preset = procedure_paste_preset(procedure);
  if (preset) params = dental_params_for(*preset, params);
  if (const std::optional<Reader> sim = root.optional_object(
          "simulation", "the simulation settings of a dental scene: {\"solver\": \"iisph\"}")) {
    sim->only({"solver", "iisph"});
    params.solver = read_solver(*sim, params.solver);
    params.iisph = read_iisph(*sim, params.iisph);
  }
  if (preset && params.solver != Solver::iisph)
    root.fail("material", fmt::format("the preset \"{}\" is a non-Newtonian paste, which the paper's step cannot step",
                                      preset->name),
              "set simulation.solver to \"iisph\" or leave it out, or drop \"material\" for the paper's paste");
  Scene sc = procedure_or_built_in(*tooth, procedure, params);
  if (preset) fill_scene_with(sc, *preset);  // its force in newtons (a file's haptics.force_scale, read below, still wins)
  sc.name = name;
  sc.source = fmt::format("{} ({} on {})", root.source(), sc.source, tooth_name(spec));
  read_haptics(root, sc);
  read_session_names(root, sc);
  return sc;
}

}  // namespace dentsph::scene
