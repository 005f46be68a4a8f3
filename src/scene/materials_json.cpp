// Materials of a scene: the named table, the default material per role, and per-block overrides
// (docs/scene-format.md, "materials", "roles", "Choosing a block's material").
#include <fmt/format.h>

#include "scene/parse.hpp"

namespace dentsph::scene {

namespace {

// One material field: its JSON key, where it goes, and the physical bounds of a material a step can
// take (a value past them is finite but makes every step's numbers overflow or vanish: a rest
// density of 1e-308 asks for a time step of 1e-312 s).
struct MaterialField {
  std::string_view key;
  real Material::*member;
  real lo, hi;
  std::string_view hint;
};

constexpr MaterialField material_fields[] = {
    {"viscosity", &Material::mu, 0, 1e9,
     "the dynamic viscosity mu in Pa s (0 to 1e9), e.g. 0.5"},
    {"stiffness", &Material::Kp, 1e-6, 1e12,
     "the pressure stiffness Kp in m^2/s^2 (1e-6 to 1e12; sqrt(Kp) is the sound speed), e.g. 60"},
    {"rest_density", &Material::rho0, 1, 1e5,
     "the rest density rho0 in kg/m^3 (1 to 1e5: water 1000, amalgam 11600), e.g. 1000"},
    {"adhesion", &Material::Ka, 0, 1e9,
     "the adhesion strength Ka in Pa (0 to 1e9; 0 for walls and tools), e.g. 200"},
};

// The optional fields: a non-Newtonian material's (docs/model.md, "Rheology"; Newtonian without them) and
// its contact's strength with an instrument ("Tack").
constexpr MaterialField rheology_fields[] = {
    {"flow_index", &Material::flow_index, 0.1, 2,
     "the Herschel-Bulkley flow index n (0.1 to 2; 1 Newtonian, under 1 shear-thinning), e.g. 0.5"},
    {"yield_stress", &Material::yield_stress, 0, 1e7,
     "the yield stress in Pa (0 to 1e7: more is a solid, not a paste; 0: none), e.g. 100"},
    {"max_viscosity", &Material::max_viscosity, 0, 1e9,
     "the unyielded paste's viscosity in Pa s (>= viscosity, at most 1e9: the viscosity solve would not converge "
     "beyond; 0: 1000 times it), e.g. 1e6"},
    {"interface_strength", &Material::interface_strength, 0, 1e7,
     "the tension in Pa a paste's contact with an instrument carries (0 to 1e7; 0: no limit; iisph), e.g. 5e4"},
};

// Reads the rheology fields `m` has into `mat`, then checks the whole law.
void read_rheology(const Reader& m, Material& mat) {
  for (const MaterialField& f : rheology_fields)
    if (m.has(f.key)) mat.*f.member = m.number_in(f.key, f.hint, f.lo, f.hi);
  if (mat.yield_stress > 0 && !(mat.mu > 0))
    m.fail("yield_stress", "a yield stress with no viscosity (the paste would have no law once it flows)",
           "give \"viscosity\" > 0, the plastic viscosity (Pa s) or consistency (Pa s^n) of the flowing paste");
  if (mat.max_viscosity > 0 && mat.max_viscosity < mat.mu)
    m.fail("max_viscosity", fmt::format("{} Pa s is under the viscosity {} Pa s", mat.max_viscosity, mat.mu),
           "give the unyielded viscosity at least the flowing one, or 0 for 1000 times it");
  if (mat.max_viscosity == 0 && !newtonian(mat) && mat.mu > 1e6)
    m.fail("max_viscosity",
           "the unyielded viscosity (1000 times the viscosity) is over 1e9 Pa s (the viscosity solve would not converge)",
           "give max_viscosity at most 1e9 Pa s");
}

constexpr std::string_view role_keys[] = {"material", "boundary", "tool"};  // indexed by Role

// A complete material: all four fields required, the rheology's optional.
Material read_material(const Reader& m) {
  m.only({"viscosity", "stiffness", "rest_density", "adhesion", "flow_index", "yield_stress", "max_viscosity",
          "interface_strength"});
  Material mat;
  for (const MaterialField& f : material_fields) mat.*f.member = m.number_in(f.key, f.hint, f.lo, f.hi);
  read_rheology(m, mat);
  return mat;
}

// An inline override: "base" (optional when the role has a default) plus any of the four fields.
// Without a base, every field is required.
Material read_override(const Reader& m, const SceneMaterials& table,
                       const MaterialDefault& fallback) {
  m.only({"base", "viscosity", "stiffness", "rest_density", "adhesion", "flow_index", "yield_stress",
          "max_viscosity", "interface_strength"});
  std::optional<Material> base = fallback.material;
  if (m.has("base"))
    base = table.lookup(m, "base", m.string("base", "the name of the material to start from"));
  Material mat = base.value_or(Material{});
  for (const MaterialField& f : material_fields) {
    if (base) {
      if (m.has(f.key)) mat.*f.member = m.number_in(f.key, f.hint, f.lo, f.hi);
    } else {
      const std::string hint =
          fmt::format("{} (or a \"base\" material to start from: there is no default from {})",
                      f.hint, fallback.from);
      mat.*f.member = m.number_in(f.key, hint, f.lo, f.hi);
    }
  }
  read_rheology(m, mat);
  return mat;
}

std::vector<std::string_view> names_of(const SceneMaterials& table) {
  std::vector<std::string_view> names;
  for (const auto& [name, mat] : table.by_name) names.push_back(name);
  return names;
}

}  // namespace

const Material& SceneMaterials::lookup(const Reader& at, std::string_view key,
                                      const std::string& name) const {
  if (const auto it = by_name.find(name); it != by_name.end()) return it->second;
  const std::vector<std::string_view> names = names_of(*this);
  const std::string_view guess = closest(name, names);
  at.fail(key, fmt::format("unknown material \"{}\"", name),
          fmt::format("{}the materials defined under \"materials\" are: {}",
                      guess.empty() ? "" : fmt::format("did you mean \"{}\"? ", guess),
                      fmt::join(names, ", ")));
}

SceneMaterials parse_materials(const Reader& root) {
  SceneMaterials table;
  const Reader mats =
      root.object("materials",
                  "the materials by name, e.g. {\"paste\": {\"viscosity\": 0.5, \"stiffness\": "
                  "60, \"rest_density\": 1000, \"adhesion\": 200}}");
  for (const auto& item : root.find("materials")->items()) {
    if (item.key().empty()) mats.fail("\"\"", "empty material name", "give every material a name");
    const Reader m(item.value(), mats.path_of(item.key()), root.source(), "a material");
    table.by_name.emplace(item.key(), read_material(m));
  }
  if (table.by_name.empty())
    mats.fail_here("no materials",
                   "define at least one, e.g. \"paste\": {\"viscosity\": 0.5, ...}");

  if (const std::optional<Reader> roles = root.optional_object(
          "roles", "the default material of each role, e.g. {\"material\": \"paste\"}")) {
    roles->only({role_keys[0], role_keys[1], role_keys[2]});
    for (int r = 0; r < 3; ++r)
      if (roles->has(role_keys[r])) {
        const std::string name =
            roles->string(role_keys[r], "the name of a material under \"materials\"");
        table.role_default[r] = table.lookup(*roles, role_keys[r], name);
        table.role_name[r] = name;
      }
  }
  return table;
}

Material resolve_material(const Reader& owner, const SceneMaterials& table,
                          const MaterialDefault& fallback) {
  const Json* v = owner.find("material");
  if (v == nullptr) {
    if (fallback.material) return *fallback.material;
    owner.fail("material", fmt::format("missing, and there is no default from {}", fallback.from),
               fmt::format("give \"material\": \"<name>\" here, or set {}", fallback.from));
  }
  if (v->is_string()) return table.lookup(owner, "material", v->get<std::string>());
  if (v->is_object())
    return read_override(Reader(*v, owner.path_of("material"), owner.source(), "a material"), table,
                         fallback);
  owner.fail("material", fmt::format("expected a material name or an object, got {}", describe(*v)),
             "give a name (\"paste\") or an override ({\"base\": \"paste\", \"adhesion\": 0})");
}

}  // namespace dentsph::scene
