#include "dental_options.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "dentsph/paste_presets.hpp"

namespace dentsph::cli {

namespace {

Vec3 direction(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

}  // namespace

void DentalOptions::add_options(CLI::App& app, CLI::Option* scene_file, bool with_procedure) {
  auto add = [&](CLI::Option* o) {
    if (scene_file) o->excludes(scene_file);
    options_.push_back(o);
    return o;
  };
  add(app.add_option("--mesh", mesh_, "The tooth: a scanned tooth (STL, OBJ or PLY, in mm); default: the built-in crown")
          ->check(CLI::ExistingFile));
  add(app.add_option("--mesh-units", units_, "The --mesh file's units: mm (default) or m")
          ->check(CLI::IsMember({"mm", "m"})));
  if (with_procedure)
    add(app.add_option("--procedure", procedure_,
                       "Run this filling procedure (JSON, mm in the tooth frame) instead of the built-in one"));
  add(app.add_option("--material", material_,
                     fmt::format("Fill with this paste in SI units, its force rendered at scale 1: {} (docs/model.md, "
                                 "\"Presets\"); default: the paper's 1 Pa s paste at force scale {:.3g}",
                                 fmt::join(paste_preset_names(), ", "), dental_force_scale)));
  add(app.add_option("--temperature", temperature_,
                     "With --material: the paste's temperature in C, 10 to 70 (default 23, a room; 37 the mouth, 54 a "
                     "composite warmer): warmer paste is less viscous (docs/model.md, \"Presets\")"));
  add(app.add_option("--cavity", kind_, "The cavity: class1 (occlusal) or class2 (occlusal and a proximal box)"));
  add(app.add_option("--cavity-side", side_, "Class II: the proximal box's side, mesial (default) or distal"));
  values_.assign(cavity_fields().size(), 0.0);
  for (std::size_t i = 0; i < cavity_fields().size(); ++i) {
    const CavityField& f = cavity_fields()[i];
    add(app.add_option(f.option, values_[i],
                       fmt::format("Cavity: {} (default {:.3g} {}){}", f.hint, CavityParams{}.*f.member / f.scale,
                                   f.unit, f.class_2_only ? "; with --cavity class2" : "")));
  }
  add(app.add_option("--long-axis", long_axis_,
                     "The tooth's long axis towards the crown, X Y Z in the mesh's coordinates (default: found from the "
                     "mesh; the built-in crown's is 0 0 1)")
          ->expected(3));
  add(app.add_option("--mesial", mesial_,
                     "A direction X Y Z towards the tooth's mesial surface (default: the found mesio-distal axis, whose "
                     "sign a single tooth cannot tell)")
          ->expected(3));
}

ToothSpec DentalOptions::tooth() const {
  ToothSpec spec;
  spec.mesh = mesh_;
  if (given("--mesh-units")) {
    if (mesh_.empty())
      throw std::invalid_argument(fmt::format("--mesh-units {}: the built-in crown has no units to give; add --mesh", units_));
    spec.units = units_ == "m" ? MeshUnits::metres : MeshUnits::millimetres;
  }
  if (given("--cavity")) {
    const std::optional<CavityClass> k = cavity_class_from_name(kind_);
    if (!k)
      throw std::invalid_argument(fmt::format(
          "--cavity {}: unknown cavity class; give class1 (occlusal) or class2 (occlusal and one proximal box)", kind_));
    spec.cavity.kind = *k;
  }
  const bool class_2 = spec.cavity.kind == CavityClass::class_2;
  if (given("--cavity-side")) {
    if (!class_2)
      throw std::invalid_argument(
          fmt::format("--cavity-side {}: a Class I cavity has no proximal box; add --cavity class2", side_));
    const std::optional<ProximalSide> s = proximal_side_from_name(side_);
    if (!s) throw std::invalid_argument(fmt::format("--cavity-side {}: unknown side; give mesial or distal", side_));
    spec.cavity.side = *s;
  }
  for (std::size_t i = 0; i < cavity_fields().size(); ++i) {
    const CavityField& f = cavity_fields()[i];
    if (!given(f.option)) continue;
    const CavityValueCheck set = set_cavity_value(spec.cavity, f, values_[i]);
    if (set.outcome == CavityValueCheck::Outcome::needs_class_2)
      throw std::invalid_argument(
          fmt::format("{} {}: a Class I cavity has no proximal box; add --cavity class2", f.option, values_[i]));
    if (set.outcome == CavityValueCheck::Outcome::refused)
      throw std::invalid_argument(fmt::format("{} {}: {}; {}", f.option, values_[i], set.problem, set.fix));
  }
  // The axes are checked where the tooth is prepared (prepare_tooth); with_cavity_options names
  // the options in its refusal.
  if (!long_axis_.empty()) spec.long_axis = direction(long_axis_);
  if (!mesial_.empty()) spec.mesial = direction(mesial_);
  return spec;
}

namespace {

// The tooth's CavityError with the options that set the cavity named; a refused axis with the
// axis options.
template <class Build>
Scene with_cavity_options(Build build) {
  try {
    return build();
  } catch (const ToothAxisError& e) {
    throw std::invalid_argument(fmt::format("--long-axis / --mesial: {}", e.what()));
  } catch (const CavityError& e) {
    std::string msg = e.what();
    for (const CavityField& f : cavity_fields())
      if (msg.find(fmt::format("parameter {} ", f.key)) != std::string::npos) msg += fmt::format(" ({})", f.option);
    throw CavityError(msg + " (the cavity is set by --cavity, --cavity-width, --cavity-length, --cavity-depth, "
                            "--cavity-taper, --cavity-rounding and, for Class II, --cavity-side and --cavity-box-*)");
  }
}

}  // namespace

bool DentalOptions::given(std::string_view name) const {
  return std::any_of(options_.begin(), options_.end(),
                     [&](const CLI::Option* o) { return o->get_name() == name && o->count() > 0; });
}

void DentalOptions::take_material(const std::string& preset, double temperature_c) {
  if (preset.empty() || given("--material")) return;
  material_ = preset;
  if (!given("--temperature")) temperature_ = temperature_c;
}

PastePreset DentalOptions::preset_named(const std::string& name) const {
  try {
    return paste_preset(name, temperature_);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(fmt::format("{}: {}",
                                            std::string(e.what()).find("temperature") != std::string::npos
                                                ? fmt::format("--temperature {}", temperature_)
                                                : fmt::format("--material {}", name),
                                            e.what()));
  }
}

std::optional<PastePreset> DentalOptions::preset() const {
  if (material_.empty()) {
    if (given("--temperature"))
      throw std::invalid_argument(fmt::format(
          "--temperature {}: the paper's paste has no temperature law; add --material (e.g. --material universal)",
          temperature_));
    return std::nullopt;
  }
  return preset_named(material_);
}

namespace {

// The scene filled with `preset`: its force at scale 1, the preset named.
Scene filled_with(Scene sc, const PastePreset& preset) {
  fill_scene_with(sc, preset);
  return sc;
}

}  // namespace

Scene DentalOptions::procedure_scene() const {
  const ToothSpec spec = tooth();
  // --material, or else the procedure file's "material" (at --temperature where given).
  std::optional<PastePreset> p;
  const std::optional<PastePreset> named = given("--material") ? std::nullopt : procedure_paste_preset(procedure_);
  if (named)
    p = given("--temperature") ? preset_named(named->name) : *named;
  else
    p = preset();
  if (!p) return with_cavity_options([&] { return dental_run_scene(spec, procedure_); });
  return filled_with(with_cavity_options([&] { return dental_run_scene(spec, procedure_, dental_params_for(*p)); }), *p);
}

Scene DentalOptions::filled_scene() const { return filled_scene(preset()); }

Scene DentalOptions::filled_scene(const std::optional<PastePreset>& p) const {
  const ToothSpec spec = tooth();
  Scene sc = with_cavity_options([&] {
    return dental_scene(prepare_tooth(spec), p ? dental_params_for(*p) : DentalSceneParams{},
                        spec.mesh.empty() ? std::string("dental_default") : spec.mesh.stem().string(), tooth_name(spec));
  });
  return p ? filled_with(std::move(sc), *p) : sc;
}

}  // namespace dentsph::cli
