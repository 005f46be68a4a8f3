// The Model's material table: each particle's one-byte material index, the per-particle values as a
// cache of the table (include/dentsph/material.hpp), the paste and instruments a scene names, and
// edits of the paste between steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "dentsph/dental.hpp"
#include "dentsph/dispense.hpp"
#include "dentsph/paste_presets.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/simulation.hpp"
#include "dentsph/step.hpp"
#include "physics/rheology.hpp"
#include "support/builders.hpp"
#include "support/small_scene.hpp"

namespace dentsph {
namespace {

using testing::lattice;
using testing::params_for_spacing;

// Every particle's cache equals its table entry (or the cure's values where it is marked cured),
// and its index is the one its id was given.
void expect_cache_matches(const Model& model, const State& s, const std::vector<MaterialIndex>& by_id) {
  ASSERT_EQ(s.material.size(), s.size());
  for (std::uint32_t i = 0; i < s.size(); ++i) {
    ASSERT_EQ(s.material[i] & kMaterialMask, by_id[s.id[i]]) << "particle id " << s.id[i];
    const Material& m = (s.material[i] & kCuredMaterial) ? s.cure.cured[s.id[i]] : model.materials[s.material[i]];
    ASSERT_EQ(s.mu[i], m.mu);
    ASSERT_EQ(s.Kp[i], m.Kp);
    ASSERT_EQ(s.rho0[i], m.rho0);
    ASSERT_EQ(s.Ka[i], m.Ka);
  }
}

TEST(MaterialTable, NamesAreUniqueAndUnknownNamesAreRefusedWithTheKnownOnes) {
  MaterialTable t;
  const MaterialIndex a = t.add("paste", {1, 10, 2000, 50});
  const MaterialIndex b = t.add("tooth", {1, 15, 2000, 0});
  EXPECT_EQ(t.find("tooth"), b);
  EXPECT_EQ(t.find(Material{1, 10, 2000, 50}), a);
  EXPECT_FALSE(t.find("wall"));
  EXPECT_THROW(t.add("paste", {2, 10, 2000, 50}), std::invalid_argument);
  EXPECT_EQ(t.intern({1, 10, 2000, 50}), a);  // the same values: the same entry
  const MaterialIndex c = t.intern({3, 10, 2000, 50});
  EXPECT_EQ(c, 2);
  EXPECT_EQ(t.size(), 3u);
  try {
    (void)t.at("pastee", "scene.json: paste");
    FAIL() << "an unknown name was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("scene.json: paste"), std::string::npos) << msg;
    EXPECT_NE(msg.find("\"pastee\""), std::string::npos) << msg;
    EXPECT_NE(msg.find("paste, tooth"), std::string::npos) << msg;
  }
}

// Two materials in a cup: the index and the cache survive the reorder of every step, the removal of
// particles (ids renumbered) and the addition of more.
TEST(MaterialTable, IndexAndCacheRoundTripThroughStepsRemovalAndAddition) {
  constexpr real s = 0.01;
  Model model = make_model(params_for_spacing(s, {-0.05, -0.05, -0.05}, {0.1, 0.1, 0.1}, 1e-4, {0, 0, -9.81}));
  const MaterialIndex soft = model.materials.add("soft", {0.5, 60, 1000, 100});
  const MaterialIndex stiff = model.materials.add("stiff", {0.8, 90, 1200, 20});
  const MaterialIndex wall = model.materials.add("wall", {0.5, 200, 1000, 0});
  std::vector<ParticleInit> ps;
  std::vector<MaterialIndex> by_id;
  const real m = lattice_particle_mass(1000, s, model.kernel);
  int k = 0;
  for (Vec3 p : lattice({0, 0, 0}, s, 4, 4, 4)) {
    const MaterialIndex mi = (k++ % 3 == 0) ? stiff : soft;
    ps.push_back(make_particle(Role::material, p, m, model.materials[mi], {}, mi));
    by_id.push_back(mi);
  }
  for (Vec3 p : lattice({-2 * s, -2 * s, -2 * s}, s, 8, 8, 2)) {
    ps.push_back(make_particle(Role::boundary, p, m, model.materials[wall]));  // found by its values
    by_id.push_back(wall);
  }
  State st;
  st.add_particles(std::as_const(model), ps);
  expect_cache_matches(model, st, by_id);
  for (int n = 0; n < 20; ++n) step(model, st, {1, nullptr});
  ASSERT_TRUE(st.diagnostics.rebuilt);  // no skin: every step sorted and reordered
  expect_cache_matches(model, st, by_id);
  // The table's values reach the particles through the reorder alone: no array of them is permuted.
  model.materials[stiff].mu = 0.9;
  step(model, st, {1, nullptr});
  expect_cache_matches(model, st, by_id);

  // Remove every other material particle (by current index); ids are renumbered in id order.
  std::vector<std::uint8_t> remove(st.size(), 0);
  std::vector<MaterialIndex> kept_by_id;
  for (std::uint32_t id = 0; id < st.size(); ++id) {
    const std::uint32_t i = st.index_of_id[id];
    remove[i] = st.role[i] == Role::material && id % 2 == 0;
    if (!remove[i]) kept_by_id.push_back(by_id[id]);
  }
  st.remove_particles(model, remove);
  expect_cache_matches(model, st, kept_by_id);

  // More particles of a material the table does not have yet: a Model it may grow takes them in.
  const Material new_paste{0.6, 70, 1100, 40};
  std::vector<ParticleInit> more;
  for (Vec3 p : lattice({0, 0, 5 * s}, s, 2, 2, 1)) more.push_back(make_particle(Role::material, p, m, new_paste));
  EXPECT_THROW(st.add_particles(std::as_const(model), more), std::invalid_argument);
  EXPECT_EQ(st.size(), kept_by_id.size());  // refused: nothing added
  st.add_particles(model, more);
  ASSERT_EQ(model.materials.size(), 4u);
  for (std::size_t q = 0; q < more.size(); ++q) kept_by_id.push_back(3);
  for (int n = 0; n < 5; ++n) step(model, st, {1, nullptr});
  expect_cache_matches(model, st, kept_by_id);
}

// Paste the cure has changed keeps its own values (by id) through the reorder, not the table's.
TEST(MaterialTable, CuredPasteKeepsTheCuresValuesThroughTheReorder) {
  constexpr real s = 0.01;
  Model model = make_model(params_for_spacing(s, {-0.05, -0.05, -0.05}, {0.1, 0.1, 0.1}, 1e-4, {0, 0, -9.81}));
  const Material paste{0.5, 60, 1000, 100};
  std::vector<ParticleInit> ps;
  const real m = lattice_particle_mass(1000, s, model.kernel);
  for (Vec3 p : lattice({0, 0, 0}, s, 4, 4, 4)) ps.push_back(make_particle(Role::material, p, m, paste));
  State st;
  st.add_particles(model, ps);
  const Material cured{0.7, 60, 1010, 80};
  const std::uint32_t id = 5;
  st.cure.set_cured(id, cured);
  st.material[st.index_of_id[id]] |= kCuredMaterial;
  st.refresh_materials(model);
  for (int n = 0; n < 10; ++n) step(model, st, {1, nullptr});
  const std::uint32_t i = st.index_of_id[id];
  EXPECT_EQ(st.mu[i], cured.mu);
  EXPECT_EQ(st.rho0[i], cured.rho0);
  EXPECT_EQ(st.Ka[i], cured.Ka);
  for (std::uint32_t j = 0; j < st.size(); ++j)
    if (st.id[j] != id) {
      ASSERT_EQ(st.mu[j], paste.mu);
    }
}

// The built-in dental scene names its paste, its instrument and its tooth; its particles carry them.
TEST(MaterialTable, DentalSceneNamesPasteInstrumentAndTooth) {
  const Scene sc = default_dental_scene();
  const MaterialTable& t = sc.model.materials;
  ASSERT_TRUE(t.paste && t.instrument);
  EXPECT_EQ(t.name(*t.paste), "paste");
  EXPECT_EQ(t.name(*t.instrument), "instrument");
  ASSERT_TRUE(t.find("tooth"));
  const State st = make_state(sc);
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    const MaterialIndex want = st.role[i] == Role::material ? *t.paste
                               : st.role[i] == Role::tool   ? *t.instrument
                                                            : *t.find("tooth");
    ASSERT_EQ(st.material[i], want) << "particle " << i << " of role " << role_name(st.role[i]);
  }
  const IncrementPaste paste = scene_paste(sc);
  EXPECT_EQ(paste.material_index, *t.paste);
  EXPECT_TRUE(paste.material == t[*t.paste]);
}

// An edit of the paste (the viewer's material panel) is an edit of the Model's paste material: the
// paste particles take it, the tooth and the instrument (here of other values, and in the dental
// scene of the same values as each other) keep theirs, through the steps that follow.
TEST(MaterialTable, PasteEditsApplyToPasteParticlesOnly) {
  const Scene sc = testing::small_paste_scene(1e-4, {{0, Pose{{0.02, 0.02, 0.08}, {}}}});
  Simulation sim(sc, {Backend::cpu, 1, false});
  for (int n = 0; n < 5; ++n) sim.step(sim.keyframe_pose());
  const State before = sim.synced();
  const Material edited{0.4, 50, 1000, 80};
  sim.set_paste(sc.model.adhesion, edited);
  for (int n = 0; n < 5; ++n) sim.step(sim.keyframe_pose());
  const State& st = sim.synced();
  const MaterialTable& t = sim.model().materials;
  ASSERT_TRUE(t.paste);
  EXPECT_EQ(t[*t.paste].mu, 0.4);
  EXPECT_EQ(t[*t.paste].rho0, 1000);  // the rest density is not the editor's
  std::uint32_t paste = 0, other = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    const std::uint32_t was = before.index_of_id[st.id[i]];
    if ((st.material[i] & kMaterialMask) == *t.paste) {
      ++paste;
      EXPECT_EQ(st.mu[i], 0.4);
      EXPECT_EQ(st.Kp[i], 50);
      EXPECT_EQ(st.Ka[i], 80);
    } else {
      ++other;
      EXPECT_EQ(st.mu[i], before.mu[was]);
      EXPECT_EQ(st.Kp[i], before.Kp[was]);
      EXPECT_EQ(st.Ka[i], before.Ka[was]);
    }
  }
  EXPECT_EQ(paste, st.count(Role::material));
  EXPECT_GT(other, 0u);
  // An increment dispensed after the edit is of the edited paste.
  ASSERT_GT(sim.dispense(0, scene_paste(sc)) + sim.dispense(default_increment_volume(sc), scene_paste(sc)), 0u);
  sim.step(sim.keyframe_pose());
  const State& after = sim.synced();
  for (std::uint32_t i = 0; i < after.size(); ++i)
    if (after.role[i] == Role::material) {
      ASSERT_EQ(after.mu[i], 0.4);
    }
}

// A paste edit is made on the Simulation's own Model, the one its stepper reads: the adhesion
// kernel and the paste change, and the rest of the run's Model stays (dt, the other materials, and
// the wall field that keeps the iisph paste out of the tooth). Before, the viewer built a Model
// from the scene's parameters and the run took that one: an edit in the viewer took the dental
// scene's wall field away. An impossible kernel is refused and changes nothing.
TEST(MaterialTable, APasteEditKeepsTheRunsModel) {
  const Scene sc = default_dental_procedure();
  ASSERT_TRUE(sc.model.walls) << "the iisph dental scene's wall field";
  Simulation sim(sc, {Backend::cpu, 1, false});
  AdhesionParams adhesion = sc.model.adhesion;
  adhesion.eps = 4;
  Material paste = scene_paste(sc).material;
  paste.mu *= 2;
  sim.set_paste(adhesion, paste);
  const Model& m = sim.model();
  EXPECT_EQ(m.walls, sc.model.walls);
  EXPECT_EQ(m.dt, sc.model.dt);
  EXPECT_EQ(m.materials.size(), sc.model.materials.size());
  EXPECT_EQ(m.adhesion.eps, 4);
  EXPECT_NE(m.adhesion.Cd, sc.model.adhesion.Cd) << "the kernel's constants derived again";
  EXPECT_EQ(m.materials[*m.materials.paste].mu, paste.mu);
  AdhesionParams impossible = adhesion;
  impossible.eps = 1;  // under zeta
  EXPECT_THROW(sim.set_paste(impossible, paste), std::invalid_argument);
  EXPECT_EQ(sim.model().adhesion.eps, 4);
  EXPECT_TRUE(sim.step(sim.keyframe_pose()));
}

nlohmann::json scene_json() {
  return nlohmann::json::parse(R"({
    "name": "named",
    "simulation": {"dt": 5e-4, "h": 0.02},
    "adhesion": {"A": 0.012, "B": 0.03},
    "materials": {
      "putty": {"viscosity": 0.5, "stiffness": 60, "rest_density": 1000, "adhesion": 200},
      "steel": {"viscosity": 0.5, "stiffness": 200, "rest_density": 1000, "adhesion": 0},
      "enamel": {"viscosity": 0.5, "stiffness": 200, "rest_density": 1000, "adhesion": 0}
    },
    "roles": {"material": "putty", "boundary": "enamel", "tool": "steel"},
    "blocks": [
      {"role": "boundary", "shape": "box", "min": [0, 0, 0], "max": [0.04, 0.04, 0.01], "spacing": 0.01},
      {"role": "material", "shape": "box", "min": [0, 0, 0.02], "max": [0.02, 0.02, 0.04], "spacing": 0.01},
      {"role": "material", "shape": "box", "min": [0.03, 0, 0.02], "max": [0.04, 0.01, 0.03], "spacing": 0.01,
       "material": {"base": "putty", "viscosity": 2}}
    ],
    "tool": {
      "blocks": [{"shape": "sphere", "center": [0, 0, 0], "radius": 0.01, "spacing": 0.01}],
      "keyframes": [{"t": 0, "position": [0.02, 0.02, 0.08]}, {"t": 1, "position": [0.02, 0.02, 0.06]}]
    }
  })");
}

// A scene file's named materials become the Model's table; its paste and instrument are those
// roles.material and roles.tool name; an inline material gets an entry of its own.
TEST(MaterialTable, SceneFileNamesItsMaterials) {
  const Scene sc = parse_scene(scene_json().dump(), "named.json");
  const MaterialTable& t = sc.model.materials;
  ASSERT_TRUE(t.find("putty") && t.find("steel") && t.find("enamel"));
  ASSERT_TRUE(t.paste && t.instrument);
  EXPECT_EQ(t.name(*t.paste), "putty");
  EXPECT_EQ(t.name(*t.instrument), "steel");
  EXPECT_EQ(t.size(), 4u);  // and the inline {"base": "putty", "viscosity": 2}
  const State st = make_state(sc);
  std::uint32_t thick = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    if (st.role[i] == Role::material && st.mu[i] == 2) ++thick;
    if (st.role[i] == Role::material && st.mu[i] != 2) {
      ASSERT_EQ(st.material[i], *t.paste);
    }
  }
  EXPECT_GT(thick, 0u);
  EXPECT_EQ(scene_paste(sc).material_index, *t.paste);
}

TEST(MaterialTable, SceneFileRefusesAnUnknownMaterialNamingFileAndField) {
  nlohmann::json j = scene_json();
  j["roles"]["material"] = "puty";
  try {
    (void)parse_scene(j.dump(), "named.json");
    FAIL() << "an unknown material name was accepted";
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("named.json"), std::string::npos) << msg;
    EXPECT_NE(msg.find("roles.material"), std::string::npos) << msg;
    EXPECT_NE(msg.find("\"puty\""), std::string::npos) << msg;
    EXPECT_NE(msg.find("putty"), std::string::npos) << msg;  // the fix: the known names
  }
  j = scene_json();
  j["blocks"][1]["material"] = "steal";
  try {
    (void)parse_scene(j.dump(), "named.json");
    FAIL() << "an unknown material name was accepted";
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("named.json"), std::string::npos) << msg;
    EXPECT_NE(msg.find("blocks[1].material"), std::string::npos) << msg;
  }
}

// The table holds 128 materials (a one-byte index, its high bit the cure's): a scene file with more
// is refused naming the file and the field, not with an error from deep inside.
TEST(MaterialTable, SceneFileWithTooManyMaterialsIsRefused) {
  nlohmann::json j = scene_json();
  for (int k = 0; k < 130; ++k)
    j["materials"]["extra" + std::to_string(k)] = {
        {"viscosity", 0.5}, {"stiffness", 60 + k}, {"rest_density", 1000}, {"adhesion", 0}};
  try {
    (void)parse_scene(j.dump(), "many.json");
    FAIL() << "131 materials were accepted";
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("many.json"), std::string::npos) << msg;
    EXPECT_NE(msg.find("materials"), std::string::npos) << msg;
    EXPECT_NE(msg.find("at most 128"), std::string::npos) << msg;
  }
}

// The paste presets (docs/model.md, "Presets"): non-Newtonian pastes in SI units whose viscosity at
// 10 /s sits in its published range (chosen there: a calibration, not a prediction) and whose
// viscosity and yield stress rise from flowable to universal to packable (Lee, Son & Um 2003's
// order); an unknown name is refused with the choices.
TEST(PastePresets, AnchoredToTheirPublishedViscosityAndOrdered) {
  const std::vector<std::string>& names = paste_preset_names();
  ASSERT_EQ(names.size(), 4u);
  real last_viscosity = 0, last_yield = -1;
  for (const std::string name : {"flowable", "universal", "packable"}) {
    const PastePreset p = paste_preset(name);
    EXPECT_EQ(p.name, name);
    EXPECT_FALSE(newtonian(p.paste)) << name;
    // The viscosity the solver gives the flowing paste at 10 /s is the anchored figure (its yield
    // stress's share included).
    EXPECT_NEAR(rheology::effective_viscosity(p.paste, 10), p.viscosity_at_10, 1e-9 * p.viscosity_at_10);
    EXPECT_GE(p.paste.rho0, 1900) << name << ": composites are 2.0 to 2.2 g/cm^3";
    EXPECT_LE(p.paste.rho0, 2200) << name;
    EXPECT_GE(p.viscosity_at_10, p.published_low) << name << ": " << p.source;
    EXPECT_LE(p.viscosity_at_10, p.published_high) << name << ": " << p.source;
    EXPECT_GT(p.viscosity_at_10, last_viscosity) << name;
    EXPECT_GT(p.paste.yield_stress, last_yield) << name;
    last_viscosity = p.viscosity_at_10;
    last_yield = p.paste.yield_stress;
    EXPECT_EQ(p.paste.interface_strength, kPasteSteelStrength) << name << ": its contact with steel";
    const DentalSceneParams dp = dental_params_for(p);
    EXPECT_EQ(dp.paste, p.paste) << name << ": the dental scenes' paste, its contact's strength included";
    EXPECT_GE(dp.wall.Kp, dp.paste.Kp) << "walls at least as stiff as the paste";
    EXPECT_EQ(dp.solver, Solver::iisph);
    EXPECT_EQ(dp.iisph.viscous_pressure, kPresetViscousPressure) << "the paste keeps its volume";
  }
  // The one published ratio no constant was set from (the rheometer checks it): the flowable's to a
  // conventional composite's, Lee, Son & Um 2003's 0.04 to 0.56.
  ASSERT_TRUE(paste_preset("flowable").published_ratio.has_value());
  EXPECT_EQ(*paste_preset("flowable").published_ratio, (std::array<real, 2>{0.04, 0.56}));
  for (const std::string name : {"universal", "packable", "amalgam"})
    EXPECT_FALSE(paste_preset(name).published_ratio.has_value()) << name;
  // Warmer paste is less viscous (Arrhenius, E/R = 3462 K): fitted to the lower end of the
  // published 41 to 92% drop from 23 to 37 C, it predicts 0.33 of the viscosity at 54 C, inside the
  // 0.32 to 0.39 of Loumprinis et al. 2021's unplugging forces (2.9 to 6.2 N at 54 C over 7.5 to
  // 19.2 N at 23 C, the force taken proportional to the consistency).
  EXPECT_DOUBLE_EQ(paste_temperature_factor(23), 1.0);
  EXPECT_NEAR(paste_temperature_factor(37), 0.59, 0.005);
  EXPECT_GT(paste_temperature_factor(54), 6.2 / 19.2);  // the strongest product's ratio, 0.323
  EXPECT_LT(paste_temperature_factor(54), 2.9 / 7.5);   // the weakest's, 0.387
  EXPECT_NEAR(paste_preset("universal", 37).viscosity_at_10, 0.59 * paste_preset("universal").viscosity_at_10,
              0.005 * paste_preset("universal").viscosity_at_10);
  EXPECT_NEAR(paste_preset("universal", 37).paste.yield_stress, 0.59 * paste_preset("universal").paste.yield_stress,
              0.005 * paste_preset("universal").paste.yield_stress)
      << "the whole flow curve lower by the same factor";
  for (const real t : {9.9, 70.1})
    try {
      (void)paste_preset("universal", t);
      ADD_FAILURE() << t << " C is refused";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("outside 10 to 70 C"), std::string::npos) << e.what();
    }
  const PastePreset amalgam = paste_preset("amalgam");
  EXPECT_EQ(amalgam.cure, "amalgam");
  EXPECT_NEAR(amalgam.paste.rho0, 11600, 1);
  try {
    (void)paste_preset("putty");
    FAIL() << "an unknown preset is refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("choose flowable, universal, packable, amalgam"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dentsph
