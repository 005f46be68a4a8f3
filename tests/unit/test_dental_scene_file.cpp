// Dental scene files (docs/scene-format.md, "Dental scenes"): a tooth (a mesh relative to the
// scene file, or the built-in crown), a cavity and a procedure; every field checked with the
// file, the field and the fix named.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "dentsph/dental.hpp"
#include "dentsph/paste_presets.hpp"
#include "test_tooth_support.hpp"

namespace dentsph {
namespace {

namespace fs = std::filesystem;
constexpr real mm = 1e-3;

const fs::path& dir() {
  static const fs::path d = [] {
    const fs::path p = testing::temp_dir("dental_scene_file");
    fs::create_directories(p / "teeth");
    // A 10 x 9 x 12 mm block stands in for a scanned tooth: the default cavity fits its top.
    testing::write_ascii_stl(p / "teeth" / "block.stl", testing::box_mesh({0, 0, 0}, {10 * mm, 9 * mm, 12 * mm}));
    std::ofstream(p / "fill.json") << R"({"name": "one", "keyframes": [{"t": 0, "position": [0, 0, 3]}],
      "events": [{"t": 0, "dispense": {"cavity_fraction": 0.5, "at": [0, 0, -2]}}]})";
    return p;
  }();
  return d;
}

Scene parse(const std::string& text) { return parse_scene(text, (dir() / "scene.json").string()); }

TEST(DentalSceneFile, AClassTwoCavityOnTheBuiltInCrown) {
  const Scene sc = parse(R"({"name": "c2", "cavity": {"class": "class2", "side": "distal", "width": 3.5,
    "depth": 2.2, "taper_deg": 4, "rounding": 0.4, "box_depth": 3.6}, "haptics": {"force_scale": 2e4}})");
  ASSERT_TRUE(sc.tooth);
  const CavityParams& p = sc.tooth->params();
  EXPECT_EQ(p.kind, CavityClass::class_2);
  EXPECT_EQ(p.side, ProximalSide::distal);
  EXPECT_NEAR(p.width, 3.5 * mm, 1e-12);
  EXPECT_NEAR(p.length, CavityParams{}.length, 1e-12);  // not given: the default
  EXPECT_NEAR(p.depth, 2.2 * mm, 1e-12);
  EXPECT_EQ(p.taper_deg, 4);
  EXPECT_NEAR(p.rounding, 0.4 * mm, 1e-12);
  EXPECT_NEAR(p.box_depth, 3.6 * mm, 1e-12);
  EXPECT_EQ(sc.name, "c2");
  EXPECT_EQ(sc.force_scale, 2e4);
  // The box opens distally: on the frame's -x side.
  const ToothFrame& f = sc.tooth->frame();
  EXPECT_LT(sc.tooth->proximal_box_distance(f.to_world({-4.5 * mm, 0, -2 * mm})), 0);
  EXPECT_GT(sc.tooth->proximal_box_distance(f.to_world({4.5 * mm, 0, -2 * mm})), 0);
  // The built-in procedure, lined with the matrix band: more boundary particles than the Class I.
  EXPECT_FALSE(sc.events.empty());
  const auto boundary = [](const Scene& s) {
    std::size_t n = 0;
    for (const ParticleInit& q : s.particles) n += q.role == Role::boundary;
    return n;
  };
  EXPECT_GT(boundary(sc), boundary(parse(R"({"name": "c1", "tooth": {}})")) + 200);
}

TEST(DentalSceneFile, TheSolverChoosesTheStepAndItsTimeStep) {
  const Scene paper = parse(R"({"name": "p", "tooth": {}, "simulation": {"solver": "paper"}})");
  EXPECT_EQ(paper.model.solver, Solver::paper);
  EXPECT_EQ(paper.model.dt, dental_time_step(Solver::paper));
  Scene iisph = parse(R"({"name": "i", "tooth": {}, "simulation": {"solver": "iisph"}})");
  EXPECT_EQ(iisph.model.solver, Solver::iisph);
  EXPECT_EQ(iisph.model.dt, dental_time_step(Solver::iisph));
  EXPECT_EQ(dental_time_step(Solver::iisph), 1.5e-3);
  EXPECT_EQ(parse(R"({"name": "d", "tooth": {}})").model.solver, Solver::iisph) << "a dental scene's default";
  // The instruments are the solver's: the iisph solver's ball burnisher has two layers (tools.hpp).
  const auto tool_count = [](const std::vector<ParticleInit>& ps) {
    return std::count_if(ps.begin(), ps.end(), [](const ParticleInit& p) { return p.role == Role::tool; });
  };
  EXPECT_EQ(tool_count(paper.particles), 42);
  EXPECT_EQ(tool_count(iisph.particles), 52);
  // --solver over the file's: a dental scene takes the solver's time step and instruments with it,
  // particle for particle the paper's scene.
  select_solver(iisph, Solver::paper);
  EXPECT_EQ(iisph.model.solver, Solver::paper);
  EXPECT_EQ(iisph.model.dt, paper.model.dt);
  const auto same = [](const std::vector<ParticleInit>& a, const std::vector<ParticleInit>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
      EXPECT_EQ(a[k].role, b[k].role) << k;
      EXPECT_EQ(a[k].pos, b[k].pos) << k;
      EXPECT_EQ(a[k].mass, b[k].mass) << k;
      EXPECT_EQ(a[k].material_index, b[k].material_index) << k;
    }
  };
  same(iisph.particles, paper.particles);
  ASSERT_EQ(iisph.events.size(), paper.events.size());
  for (std::size_t e = 0; e < paper.events.size(); ++e) same(iisph.events[e].particles, paper.events[e].particles);
  // A switch_tool event's instrument too: the built-in procedure's plugger, made a ball.
  const auto plugger = std::find_if(iisph.events.begin(), iisph.events.end(), [](const ProcedureEvent& e) {
    return e.kind == ProcedureEvent::Kind::switch_tool;
  });
  ASSERT_NE(plugger, iisph.events.end());
  EXPECT_EQ(plugger->tool, "flat_plugger");
  EXPECT_GT(plugger->tool_spacing, 0);
  plugger->tool = "ball_burnisher";
  select_solver(iisph, Solver::iisph);
  EXPECT_EQ(tool_count(iisph.particles), 52);
  EXPECT_EQ(tool_count(plugger->particles), 52);
  EXPECT_EQ(plugger->particles.front().mass, paper.particles.back().mass) << "the instrument's mass kept";
}

// simulation.iisph over the dental scenes' settings (omega 0.7), and a wrong one named.
TEST(DentalSceneFile, TheIisphSolversSettings) {
  const Scene sc = parse(R"({"name": "i", "tooth": {}, "simulation": {"solver": "iisph", "iisph": {"stiffness": 1}}})");
  EXPECT_EQ(sc.model.iisph.stiffness, 1);
  EXPECT_EQ(sc.model.iisph.omega, 0.7) << "the dental scenes' relaxation kept";
  EXPECT_EQ(parse(R"({"name": "d", "tooth": {}})").model.iisph.stiffness, 0.5);
  try {
    parse(R"({"name": "i", "tooth": {}, "simulation": {"iisph": {"viscosity_iterations": 0}}})");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("simulation.iisph.viscosity_iterations"), std::string::npos) << msg;
    EXPECT_NE(msg.find("[1, 1000]"), std::string::npos) << msg;
  }
  try {  // checked when read, before the tooth is prepared and its Model made
    parse(R"({"name": "i", "tooth": {}, "simulation": {"iisph": {"stiffness": 2}}})");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("scene.json: simulation.iisph.stiffness: must be in (0, 1], got 2; "), std::string::npos) << msg;
  }
  // A scene whose density is the cubic spline's (its particles of that kernel's lattice mass) is not
  // switched to the paper's step, which sums poly6 (--solver paper, a GPU backend): refused, naming
  // the setting.
  Scene cubic = parse(R"({"name": "c", "tooth": {}, "simulation": {"solver": "iisph",
                          "iisph": {"gradient": "cubic", "density_kernel": "cubic"}}})");
  EXPECT_TRUE(cubic.model.kernel.cubic_density);
  try {
    (void)choose_solver(cubic, "paper", false);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("iisph.density_kernel \"cubic\""), std::string::npos) << msg;
    EXPECT_NE(msg.find("--solver paper"), std::string::npos) << msg;
  }
  EXPECT_THROW((void)choose_solver(cubic, "", /*gpu_backend=*/true), std::invalid_argument);
  EXPECT_NO_THROW((void)choose_solver(cubic, "iisph", false)) << "its own solver";
}

// "material" fills the scene with a paste preset at force scale 1 (docs/model.md, "Presets"), its
// iisph settings still the file's to change; a wrong one names the field and the choices.
TEST(DentalSceneFile, AMaterialPresetFillsIt) {
  const Scene sc = parse(R"({"name": "u", "tooth": {}, "material": {"preset": "universal", "temperature_c": 37},
                             "simulation": {"iisph": {"max_iterations": 80}}})");
  EXPECT_EQ(sc.paste_preset, "universal");
  EXPECT_EQ(sc.paste_temperature_c, 37);
  EXPECT_EQ(sc.force_scale, 1);
  const Material paste = sc.model.materials[*sc.model.materials.paste];
  EXPECT_EQ(paste, paste_preset("universal", 37).paste) << "the preset's paste, its contact's strength included";
  EXPECT_TRUE(sc.model.iisph.wall_rest_density) << "the preset's settings";
  EXPECT_EQ(sc.model.iisph.max_iterations, 80) << "the file's own over the preset's";
  EXPECT_EQ(parse(R"({"name": "f", "tooth": {}, "material": "flowable"})").paste_preset, "flowable");
  EXPECT_TRUE(parse(R"({"name": "d", "tooth": {}})").paste_preset.empty());
  const std::vector<std::pair<std::string, std::string>> broken = {
      {R"({"name": "x", "tooth": {}, "material": "putty"})", "choose flowable, universal, packable, amalgam"},
      {R"({"name": "x", "tooth": {}, "material": {"preset": "universal", "temperature_c": 90}})", "outside 10 to 70 C"},
      {R"({"name": "x", "tooth": {}, "material": 3})", "expected a preset's name or an object"},
      {R"({"name": "x", "tooth": {}, "material": "packable", "simulation": {"solver": "paper"}})", "set simulation.solver"},
  };
  for (const auto& [text, phrase] : broken)
    try {
      parse(text);
      ADD_FAILURE() << text << " is refused";
    } catch (const SceneError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("scene.json: material"), std::string::npos) << msg;
      EXPECT_NE(msg.find(phrase), std::string::npos) << msg;
    }
}

TEST(DentalSceneFile, TheShippedExampleIsAClassTwo) {
  const Scene sc = load_scene("scenes/class2_fill.json");
  ASSERT_TRUE(sc.tooth);
  EXPECT_EQ(sc.tooth->params().kind, CavityClass::class_2);
  EXPECT_EQ(sc.tooth->params().side, ProximalSide::distal);
  EXPECT_EQ(sc.name, "class2_distal_fill");
  EXPECT_EQ(sc.events.size(), parse(R"({"name": "d", "tooth": {}})").events.size());  // the built-in procedure
}

TEST(DentalSceneFile, MeshAndProcedurePathsAreRelativeToTheSceneFile) {
  std::ofstream(dir() / "scene.json") << R"({"name": "block", "tooth": {"mesh": "teeth/block.stl",
    "long_axis": [0, 0, 2], "mesial": [-1, 0, 0]}, "procedure": "fill.json"})";
  const Scene sc = load_scene(dir() / "scene.json");  // the working directory is elsewhere
  ASSERT_TRUE(sc.tooth);
  EXPECT_NE(sc.source.find("block.stl"), std::string::npos) << sc.source;
  EXPECT_EQ(sc.name, "block");
  ASSERT_EQ(sc.events.size(), 1u);  // fill.json's one increment
  const ToothFrame& f = sc.tooth->frame();
  EXPECT_NEAR(f.z.z, 1, 1e-12);   // the given axis
  EXPECT_NEAR(f.x.x, -1, 1e-12);  // the given mesial direction
  EXPECT_NEAR(sc.tooth->report().occlusal_point.z, 12 * mm, 1e-6);  // the block's top
}

// tooth.units: "mm" (the default) or "m", only with a mesh; the wrong units are refused naming the
// field that fixes them.
TEST(DentalSceneFile, TheMeshUnitsAreReadAndChecked) {
  testing::write_ascii_stl(dir() / "teeth" / "block_m.stl", testing::box_mesh({0, 0, 0}, {10 * mm, 9 * mm, 12 * mm}), 1.0);
  const Scene in_m = parse(R"({"name": "m", "tooth": {"mesh": "teeth/block_m.stl", "units": "m"}, "procedure": "fill.json"})");
  ASSERT_TRUE(in_m.tooth);
  EXPECT_NEAR(in_m.tooth->report().occlusal_point.z, 12 * mm, 1e-6);
  const Scene in_mm = parse(R"({"name": "mm", "tooth": {"mesh": "teeth/block.stl", "units": "mm"}, "procedure": "fill.json"})");
  ASSERT_TRUE(in_mm.tooth);
  EXPECT_NEAR(in_mm.tooth->report().occlusal_point.z, 12 * mm, 1e-6);
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {R"({"name": "x", "tooth": {"mesh": "teeth/block_m.stl"}})", {"scene.json: tooth.mesh", "0.012 mm across", "tooth.units \"m\""}},
      {R"({"name": "x", "tooth": {"mesh": "teeth/block.stl", "units": "m"}})", {"scene.json: tooth.mesh", "tooth.units"}},
      {R"({"name": "x", "tooth": {"mesh": "teeth/block.stl", "units": "cm"}})", {"scene.json: tooth.units", "\"cm\"", "give \"mm\""}},
      {R"({"name": "x", "tooth": {"units": "m"}})", {"scene.json: tooth.units", "without a mesh", "add tooth.mesh"}},
      {R"({"name": "x", "tooth": {"mesh": "teeth/block.stl", "units": 1000}})", {"scene.json: tooth.units", "expected a string"}},
  };
  for (const auto& [text, phrases] : cases) {
    try {
      (void)parse(text);
      ADD_FAILURE() << "no error for " << text;
    } catch (const SceneError& e) {
      for (const std::string& p : phrases)
        EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << "'" << p << "' in: " << e.what();
    }
  }
}

// The one check of a cavity number that scene files and the command line share: the value set in
// metres (or degrees), a proximal box's number refused on a Class I, an impossible value refused
// with its fix, and nothing set when refused.
TEST(DentalSceneFile, CavityValuesAreCheckedAndSetInOnePlace) {
  auto field = [](std::string_view key) {
    for (const CavityField& f : cavity_fields())
      if (key == f.key) return f;
    throw std::logic_error("no such cavity field");
  };
  CavityParams p;
  EXPECT_EQ(set_cavity_value(p, field("width"), 2.5).outcome, CavityValueCheck::Outcome::set);
  EXPECT_DOUBLE_EQ(p.width, 2.5 * mm);
  EXPECT_EQ(set_cavity_value(p, field("taper_deg"), 0).outcome, CavityValueCheck::Outcome::set);
  EXPECT_EQ(p.taper_deg, 0);
  const real box = p.box_width;
  EXPECT_EQ(set_cavity_value(p, field("box_width"), 2).outcome, CavityValueCheck::Outcome::needs_class_2);
  EXPECT_EQ(p.box_width, box);
  const CavityValueCheck bad = set_cavity_value(p, field("depth"), -1);
  EXPECT_EQ(bad.outcome, CavityValueCheck::Outcome::refused);
  EXPECT_NE(bad.problem.find("must be > 0 mm"), std::string::npos) << bad.problem;
  EXPECT_NE(bad.fix.find("pulpal floor"), std::string::npos) << bad.fix;
  EXPECT_EQ(p.depth, CavityParams{}.depth);
  EXPECT_EQ(set_cavity_value(p, field("taper_deg"), 30).outcome, CavityValueCheck::Outcome::refused);
  EXPECT_EQ(set_cavity_value(p, field("length"), std::nan("")).outcome, CavityValueCheck::Outcome::refused);
  p.kind = CavityClass::class_2;
  EXPECT_EQ(set_cavity_value(p, field("box_width"), 2).outcome, CavityValueCheck::Outcome::set);
  EXPECT_DOUBLE_EQ(p.box_width, 2 * mm);
}

TEST(DentalSceneFile, ErrorsNameTheFileTheFieldAndTheFix) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {R"({"name": "x", "cavity": {"widht": 3}})", {"scene.json: cavity.widht", "unknown field", "width"}},
      {R"({"name": "x", "cavity": {"width": -1}})", {"scene.json: cavity.width", "must be > 0 mm", "bucco-lingual"}},
      {R"({"name": "x", "cavity": {"taper_deg": 40}})", {"cavity.taper_deg", "< 30 degrees", "2 to 8"}},
      {R"({"name": "x", "cavity": {"rounding": "big"}})", {"cavity.rounding", "a string"}},
      {R"({"name": "x", "cavity": {"box_width": 2}})", {"cavity.box_width", "class1", "\"class\": \"class2\""}},
      {R"({"name": "x", "cavity": {"side": "mesial"}})", {"cavity.side", "class1"}},
      {R"({"name": "x", "cavity": {"class": "class3"}})", {"cavity.class", "class3", "\"class1\""}},
      {R"({"name": "x", "cavity": {"class": "class2", "side": "left"}})", {"cavity.side", "left", "\"distal\""}},
      {R"({"name": "x", "cavity": {"depth": 5}})", {"scene.json: cavity: ", "does not fit", "shallower"}},
      {R"({"name": "x", "cavity": {"class": "class2", "box_depth": 1}})", {"scene.json: cavity: ", "box_depth", "pulpal floor"}},
      {R"({"name": "x", "tooth": {"mesh": "teeth/none.stl"}})", {"scene.json: tooth.mesh", "no such file", "none.stl", "relative to the scene file"}},
      {R"({"name": "x", "tooth": {"mesh": "fill.json"}})", {"scene.json: tooth.mesh", "fill.json"}},
      {R"({"name": "x", "tooth": {"long_axis": [0, 0, 0]}})", {"scene.json: tooth", "long axis", "non-zero"}},
      {R"({"name": "x", "tooth": {"mesial": [0, 0, 1]}})", {"scene.json: tooth", "mesial", "across the tooth"}},
      {R"({"name": "x", "tooth": {"axis": [0, 0, 1]}})", {"tooth.axis", "unknown field", "long_axis"}},
      {R"({"name": "x", "procedure": "none.json"})", {"scene.json: procedure", "no such file", "relative to the scene file"}},
      {R"({"name": "x", "tooth": {}, "blocks": []})", {"scene.json: blocks", "unknown field"}},
      {R"({"tooth": {}})", {"scene.json: name", "missing"}},
      {R"({"name": "x", "tooth": {}, "simulation": {"solver": "fast"}})", {"scene.json: simulation.solver", "\"fast\"", "\"paper\"", "\"iisph\""}},
      {R"({"name": "x", "tooth": {}, "simulation": {"dt": 1e-3}})", {"scene.json: simulation.dt", "unknown field", "solver"}},
  };
  for (const auto& [text, phrases] : cases) {
    try {
      (void)parse(text);
      ADD_FAILURE() << "no error for " << text;
    } catch (const SceneError& e) {
      for (const std::string& p : phrases)
        EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << "'" << p << "' in: " << e.what();
    }
  }
}

TEST(DentalSceneFile, ABrokenProcedureFileIsNamedWithItsLine) {
  std::ofstream(dir() / "broken.json") << "{\n  \"name\": \"b\",\n}";
  try {
    (void)parse(R"({"name": "x", "procedure": "broken.json"})");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.json: line 3, column 1: syntax error"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dentsph
