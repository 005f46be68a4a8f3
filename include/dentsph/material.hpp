// Materials (docs/architecture.md, "Materials"): the parameters of a particle's matter, and the
// Model's table of them. Each particle carries a one-byte index into the table (State::material);
// the step reads the per-particle values State::mu, Kp, rho0 and Ka, a cache the State derives from
// the table (and, for paste the cure has changed, from the cure's parameters by id) after every
// reorder and edit instead of permuting them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "dentsph/vec3.hpp"

namespace dentsph {

// Per-particle material parameters. The viscosity is generalised Newtonian (docs/model.md,
// "Rheology"): a Herschel-Bulkley paste, tau = yield_stress + mu gammadot^flow_index once it flows,
// whose effective viscosity tau / gammadot is capped at max_viscosity where it barely flows (the
// regularisation of the unyielded paste); physics/rheology.hpp. flow_index 1 and yield_stress 0 (the
// defaults) are the Newtonian liquid of viscosity mu, stepped as before. The iisph solver alone
// steps a non-Newtonian material; the paper's step and the GPU take mu as a Newtonian viscosity.
struct Material {
  real mu = 0;    // viscosity, Pa s (the consistency K, Pa s^n, of a non-Newtonian material)
  real Kp = 0;    // pressure stiffness, m^2/s^2 (P = Kp (rho - rho0))
  real rho0 = 0;  // rest density, kg/m^3
  real Ka = 0;    // adhesion strength, Pa
  real flow_index = 1;     // n: below 1 shear-thinning, 1 Newtonian
  real yield_stress = 0;   // Pa, the stress below which the paste holds its shape
  real max_viscosity = 0;  // Pa s, the unyielded paste's viscosity (non-Newtonian only; 0: 1000 mu)
  // Pa: the tension a paste particle's contact with an instrument carries before it lets go (the
  // iisph solver; docs/model.md, "Tack"): a pair's is the smaller of its two materials' where both
  // give one, 0 is none (the contact holds whatever the tension, as the no-slip coupling does).
  real interface_strength = 0;
};
inline bool operator==(const Material& a, const Material& b) {
  return a.mu == b.mu && a.Kp == b.Kp && a.rho0 == b.rho0 && a.Ka == b.Ka && a.flow_index == b.flow_index &&
         a.yield_stress == b.yield_stress && a.max_viscosity == b.max_viscosity &&
         a.interface_strength == b.interface_strength;
}
// The strength of a contact between materials of interface strengths a and b (Pa): the smaller of
// those given, 0 (none) where neither gives one.
inline real contact_strength(real a, real b) { return a > 0 && b > 0 ? (a < b ? a : b) : (a > b ? a : b); }
// Whether the viscosity is mu whatever the flow.
inline bool newtonian(const Material& m) { return m.flow_index == 1 && m.yield_stress == 0; }

// A particle's material: an index into Model::materials in the low seven bits; the high bit marks
// paste whose parameters the cure has changed (its values are CureState::cured[id], not the table's).
using MaterialIndex = std::uint8_t;
inline constexpr MaterialIndex kMaterialMask = 0x7f;
inline constexpr MaterialIndex kCuredMaterial = 0x80;
inline constexpr MaterialIndex kNoMaterial = 0xff;  // ParticleInit: find the material by its values

// The names a dental scene gives its materials.
inline constexpr const char* kPasteMaterial = "paste";
inline constexpr const char* kInstrumentMaterial = "instrument";
inline constexpr const char* kToothMaterial = "tooth";

// The paste and the instruments' material of a scene that has no particle of them (an increment
// dispensed, an instrument switched to).
inline constexpr Material kDefaultPaste{1.0, 10, 2000, 50};
inline constexpr Material kDefaultInstrument{1.0, 15, 2000, 0};

struct NamedMaterial {
  std::string name;
  Material material;
  // Room for what curing adds per material (a cure preset of its own): today every paste cures by
  // the one CureModel the run loops are given.
};

// The Model's materials, at most 128, each with a name unique in the table.
class MaterialTable {
 public:
  static constexpr std::size_t kCapacity = kMaterialMask + 1;

  // Adds `material` as `name`. Throws std::invalid_argument for a name already there, an empty
  // name or a full table.
  MaterialIndex add(const std::string& name, const Material& material);
  // The index of `name`, or of the first entry with these values.
  std::optional<MaterialIndex> find(std::string_view name) const;
  std::optional<MaterialIndex> find(const Material& material) const;
  // The index of `name`; std::invalid_argument naming `where` and the known names when it is not there.
  MaterialIndex at(std::string_view name, std::string_view where) const;
  // The index of an entry with these values, added as "material N" when there is none.
  MaterialIndex intern(const Material& material);

  const Material& operator[](MaterialIndex i) const { return entries_[i & kMaterialMask].material; }
  Material& operator[](MaterialIndex i) { return entries_[i & kMaterialMask].material; }
  const std::string& name(MaterialIndex i) const { return entries_[i & kMaterialMask].name; }
  std::size_t size() const { return entries_.size(); }
  bool empty() const { return entries_.empty(); }
  const std::vector<NamedMaterial>& entries() const { return entries_; }
  // The known names, comma-separated (for messages).
  std::string names() const;
  // The first non-Newtonian entry (docs/model.md, "Rheology"), if any.
  std::optional<MaterialIndex> first_non_newtonian() const {
    for (std::size_t i = 0; i < entries_.size(); ++i)
      if (!newtonian(entries_[i].material)) return MaterialIndex(i);
    return std::nullopt;
  }
  // Whether an entry's contact with an instrument has a strength (Material::interface_strength).
  bool any_interface_strength() const {
    for (const auto& e : entries_)
      if (e.material.interface_strength > 0) return true;
    return false;
  }

  // The scene's paste (what increments dispense, what the viewer's paste editor changes) and the
  // instruments' material (what a switch of instrument gives the new tool), where the scene names
  // them: a dental scene its "paste" and "instrument", a scene file the materials of roles.material
  // and of the tool.
  std::optional<MaterialIndex> paste, instrument;

 private:
  std::vector<NamedMaterial> entries_;
};

}  // namespace dentsph
