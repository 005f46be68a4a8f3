// dentsph-viewer as a user runs it, in a virtual display (Xvfb with Mesa's software OpenGL):
// the default scene rendered and saved, scripted input changing the picture and the metrics,
// broken input and closing mid-run ending cleanly. Skipped, with a message, where xvfb-run is
// missing (scripts/install-deps.sh installs it; CI always has it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <stb/stb_image.h>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;

const fs::path kViewer = DENTSPH_VIEWER_BIN;
const fs::path kClient = DENTSPH_HAPTIC_CLIENT;

struct Result {
  int status = -1;
  std::string out, err;
};

fs::path temp(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("dentsph_viewer_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

std::string slurp(const fs::path& f) {
  std::ifstream in(f);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// In sanitizer builds the viewer runs without LeakSanitizer: Mesa's GL driver keeps a few hundred
// bytes it never frees and is unloaded when the window closes, so the leak cannot even be named
// (and suppressed) by its library. The viewer's own code is leak-checked by test_viewer.
constexpr const char* kNoDriverLeakCheck = "env ASAN_OPTIONS=\"${ASAN_OPTIONS}:detect_leaks=0\"";

// Runs the viewer under a fresh virtual display, killed after 240 s whatever happens (a hang is a
// failure, never a stuck test). `inner` may wrap the viewer's command line (e.g. in `timeout`).
Result run_viewer(const std::string& args, const std::string& inner = "") {
  const fs::path out = temp("stdout.txt"), err = temp("stderr.txt");
  const std::string cmd = fmt::format(
      "timeout -s KILL 240 xvfb-run -a -s '-screen 0 1024x768x24' {} {} '{}' --width 800 --height 600 --threads 1 "
      "--timeout 200 {} >'{}' 2>'{}'",
      kNoDriverLeakCheck, inner, kViewer.string(), args, out.string(), err.string());
  const int raw = std::system(cmd.c_str());
  Result r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

bool have_xvfb() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

#define REQUIRE_XVFB()                                                                                  \
  if (!have_xvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/install-deps.sh installs it); " \
                                    "the viewer's window tests need a virtual display"

struct Image {
  int w = 0, h = 0;
  std::vector<unsigned char> rgb;
  explicit Image(const fs::path& f) {
    int n = 0;
    unsigned char* p = stbi_load(f.c_str(), &w, &h, &n, 3);
    if (p) rgb.assign(p, p + std::size_t(w) * std::size_t(h) * 3);
    stbi_image_free(p);
  }
  template <class Pred>
  double share(Pred pred) const {
    std::size_t k = 0;
    for (std::size_t i = 0; i + 2 < rgb.size(); i += 3) k += pred(rgb[i], rgb[i + 1], rgb[i + 2]);
    return rgb.empty() ? 0 : double(k) / double(rgb.size() / 3);
  }
};

// The tooth: bright, warm, unsaturated ivory. The paste: clearly blue.
bool tooth_pixel(int r, int g, int b) { return r > 150 && g > 140 && b > 110 && r >= g && g >= b && r - b < 70; }
bool paste_pixel(int r, int g, int b) { return b > r + 60 && b > g + 20; }

TEST(ViewerGui, DefaultSceneRendersTheToothAndThePaste) {
  REQUIRE_XVFB();
  const fs::path png = temp("default.png");
  fs::remove(png);
  const Result r = run_viewer(fmt::format("--frames 20 --screenshot '{}'", png.string()));
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("wrote"), std::string::npos);
  const Image img(png);
  ASSERT_EQ(img.w, 800);
  ASSERT_EQ(img.h, 600);
  const double tooth = img.share(tooth_pixel), paste = img.share(paste_pixel);
  EXPECT_GT(tooth, 0.05) << "the tooth's ivory covers " << tooth;
  EXPECT_GT(paste, 0.005) << "the paste's blue covers " << paste;
  // Not blank: the background is far from everything.
  EXPECT_LT(img.share([](int r_, int g_, int b_) { return r_ < 40 && g_ < 40 && b_ < 45; }), 0.9);
}

// --surface (key S): the paste drawn as its surface (dentsph/surface.hpp) instead of spheres. The
// same paste covers about as much of the picture (measured 0.0574 against 0.0575 of it at the
// start, a lattice whose spheres hide the gaps of the layer in front) and the pictures differ where
// the paste is (the spheres' highlights and outlines give way to one smooth shading).
TEST(ViewerGui, ThePasteAsItsSurface) {
  REQUIRE_XVFB();
  const fs::path spheres = temp("spheres.png"), surface = temp("surface.png");
  const Result a = run_viewer(fmt::format("--frames 10 --paused --screenshot '{}'", spheres.string()));
  ASSERT_EQ(a.status, 0) << a.out << a.err;
  const Result b = run_viewer(fmt::format("--frames 10 --paused --surface --screenshot '{}'", surface.string()));
  ASSERT_EQ(b.status, 0) << b.out << b.err;
  const Image is(spheres), iv(surface);
  const double with_spheres = is.share(paste_pixel), with_surface = iv.share(paste_pixel);
  EXPECT_GT(with_surface, 0.7 * with_spheres) << "paste-blue share: spheres " << with_spheres << ", surface "
                                              << with_surface;
  EXPECT_LT(with_surface, 1.3 * with_spheres);
  ASSERT_EQ(is.rgb.size(), iv.rgb.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i + 2 < is.rgb.size(); i += 3)
    differ += std::abs(int(is.rgb[i + 2]) - int(iv.rgb[i + 2])) > 40 && (paste_pixel(is.rgb[i], is.rgb[i + 1], is.rgb[i + 2]) ||
                                                                       paste_pixel(iv.rgb[i], iv.rgb[i + 1], iv.rgb[i + 2]));
  EXPECT_GT(double(differ) / double(is.rgb.size() / 3), 0.2 * with_spheres) << "the paste is drawn otherwise";
}

// The surface view keeps pace with the frames (PasteSurfaceView::update): while the paste moves
// (the built-in scene's paste settles from its start), a frame waits for the surface of the paste
// the frame before submitted, so the frames drew a new surface each; one that waited past
// PasteSurfaceView::kMaxWait is counted late (a loaded machine), and only then may a paste go
// unbuilt.
TEST(ViewerGui, TheSurfaceKeepsPaceWithTheFrames) {
  REQUIRE_XVFB();
  const fs::path sum = temp("surface_pace.json");
  const Result r = run_viewer(fmt::format("--frames 40 --surface --summary '{}'", sum.string()));
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  const auto j = nlohmann::json::parse(slurp(sum));
  const auto due = j.at("surface_frames_due").get<std::uint64_t>(), late = j.at("surface_frames_late").get<std::uint64_t>(),
             built = j.at("surfaces_built").get<std::uint64_t>();
  EXPECT_GT(due, 10u) << "the settling paste moved in most of the 40 frames";
  EXPECT_LT(due, 40u) << "the first frame has no surface before it";
  EXPECT_GE(built + late, due) << "every frame on time drew a surface built for it";
}

TEST(ViewerGui, ScriptedInputChangesThePictureAndTheMetrics) {
  REQUIRE_XVFB();
  const fs::path idle = temp("idle.json"), busy = temp("busy.json");
  std::ofstream(idle) << R"({"actions": [{"step": 150, "action": "end"}]})";
  std::ofstream(busy) << R"({"actions": [
      {"step": 0, "action": "move", "position_mm": [1.5, 0, 3]},
      {"step": 10, "action": "dispense"},
      {"step": 20, "action": "colour_by", "mode": "speed"},
      {"step": 150, "action": "end"}]})";
  const fs::path png_a = temp("a.png"), png_b = temp("b.png"), sum_a = temp("a.json"), sum_b = temp("b.json");
  auto args = [](const fs::path& script, const fs::path& png, const fs::path& sum) {
    return fmt::format("--frames 5 --script '{}' --screenshot '{}' --summary '{}'", script.string(), png.string(),
                       sum.string());
  };
  const Result a = run_viewer(args(idle, png_a, sum_a));
  const Result b = run_viewer(args(busy, png_b, sum_b));
  ASSERT_EQ(a.status, 0) << a.out << a.err;
  ASSERT_EQ(b.status, 0) << b.out << b.err;
  const auto ja = nlohmann::json::parse(slurp(sum_a)), jb = nlohmann::json::parse(slurp(sum_b));
  EXPECT_GE(ja["sim"]["steps"].get<int>(), 150);
  EXPECT_GT(jb["particles"]["material"].get<int>(), ja["particles"]["material"].get<int>());
  EXPECT_GT(jb["assessment"]["material_particles"].get<int>(), ja["assessment"]["material_particles"].get<int>());
  EXPECT_GT(jb["assessment"]["overfill_mm3"].get<double>() + jb["assessment"]["outside_particles"].get<double>(),
            ja["assessment"]["overfill_mm3"].get<double>() + ja["assessment"]["outside_particles"].get<double>());
  const Image ia(png_a), ib(png_b);
  ASSERT_EQ(ia.rgb.size(), ib.rgb.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i + 2 < ia.rgb.size(); i += 3)
    differ += std::abs(ia.rgb[i] - ib.rgb[i]) + std::abs(ia.rgb[i + 1] - ib.rgb[i + 1]) +
                  std::abs(ia.rgb[i + 2] - ib.rgb[i + 2]) > 60;
  EXPECT_GT(double(differ) / double(ia.rgb.size() / 3), 0.01);
  // Coloured by speed, the paste is no longer the role's blue.
  EXPECT_LT(ib.share(paste_pixel), ia.share(paste_pixel));
}

// The curing light as an instrument: turned on over the cavity (the script's light_on, as the L
// key), its light guide and beam drawn, and the paste coloured by its degree of conversion
// (--colour-by conversion): under 0.8 s of light the paste's top turns from the map's dark purple
// (uncured) to green; without the light it stays purple and no beam is drawn.
TEST(ViewerGui, TheCuringLightCuresThePasteColouredByConversion) {
  REQUIRE_XVFB();
  const fs::path lit = temp("light.json"), dark = temp("dark.json");
  std::ofstream(lit) << R"({"actions": [{"step": 0, "action": "light_on"}, {"step": 16000, "action": "end"}]})";
  std::ofstream(dark) << R"({"actions": [{"step": 200, "action": "end"}]})";
  const fs::path png_lit = temp("light.png"), png_dark = temp("dark.png");
  auto args = [](const fs::path& script, const fs::path& png) {
    // The paper's step: the script counts its steps (16,000 of 50 us: 0.8 s of light).
    return fmt::format("--solver paper --colour-by conversion --frames 5 --script '{}' --screenshot '{}'", script.string(),
                       png.string());
  };
  const Result a = run_viewer(args(lit, png_lit));
  const Result b = run_viewer(args(dark, png_dark));
  ASSERT_EQ(a.status, 0) << a.out << a.err;
  ASSERT_EQ(b.status, 0) << b.out << b.err;
  const Image ia(png_lit), ib(png_dark);
  // Cured paste: the colour map's green to yellow (green well above red and blue's share).
  auto cured = [](int r, int g, int) { return g > 60 && g > r + 20; };
  // Uncured paste: the map's bottom, dark purple.
  auto uncured = [](int r, int g, int b_) { return g < 40 && r > 35 && b_ > 45 && b_ > g + 30; };
  // The beam's rods: pale violet.
  auto beam = [](int r, int g, int b_) { return r > 90 && std::abs(r - g) < 20 && b_ > r + 35; };
  std::printf("cured paste %.4f / %.4f, uncured %.4f / %.4f, beam %.4f / %.4f of the picture (lit / dark)\n",
              ia.share(cured), ib.share(cured), ia.share(uncured), ib.share(uncured), ia.share(beam), ib.share(beam));
  // (The display panel's colour bar is in both pictures.)
  EXPECT_GT(ia.share(cured) - ib.share(cured), 0.003) << "the lit paste's top is green";
  EXPECT_GT(ib.share(uncured), 0.005) << "the uncured paste is the map's purple";
  EXPECT_GT(ia.share(beam) - ib.share(beam), 0.0001) << "the beam is drawn";
}

// Set paste stops the mouse's instrument: the paste heaped in the cavity cured under 3 s of light,
// then the instrument sent down to 4 mm below the occlusal reference stays on the set paste's top
// (above the reference, where the floor is 1.9 mm below it), drawn there in the instrument's
// salmon on the paste's green (coloured by conversion, cut by the section).
TEST(ViewerGui, TheMousesInstrumentStopsOnSetPaste) {
  REQUIRE_XVFB();
  const fs::path script = temp("set_press.json"), png = temp("set_press.png"), sum = temp("set_press_summary.json");
  std::ofstream(script) << R"({"actions": [{"step": 0, "action": "light_on"}, {"step": 2000, "action": "light_off"},
    {"step": 2000, "action": "move", "position_mm": [0, 0, -4]}, {"step": 2800, "action": "end"}]})";
  const Result r = run_viewer(fmt::format("--colour-by conversion --section --frames 5 --script '{}' --screenshot '{}' "
                                          "--summary '{}'",
                                          script.string(), png.string(), sum.string()));
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  const nlohmann::json j = nlohmann::json::parse(slurp(sum));
  const double z = j["tool_position_mm"][2].get<double>();
  std::printf("the instrument ended at z = %.3f mm (tooth frame)\n", z);
  EXPECT_GT(z, 0.0) << "it went into the set paste";
  const Image im(png);
  auto instrument = [](int r_, int g, int b) { return r_ > 200 && r_ > g + 20 && g > b + 10 && r_ - b > 50 && g > 140; };
  auto cured = [](int r_, int g, int) { return g > 60 && g > r_ + 20; };
  std::printf("instrument %.4f, cured paste %.4f of the picture\n", im.share(instrument), im.share(cured));
  EXPECT_GT(im.share(instrument), 0.001) << "the instrument is drawn";
  EXPECT_GT(im.share(cured), 0.01) << "the set paste is drawn";
}

TEST(ViewerGui, BrokenSceneMeshOrScriptEndsWithAMessage) {
  REQUIRE_XVFB();
  const fs::path scene = temp("broken_scene.json"), mesh = temp("open.stl"), script = temp("bad_script.json");
  std::ofstream(scene) << R"({"name": "x", "simulation": {"dt": 1e-4})";
  // One triangle: an open surface.
  std::ofstream(mesh) << "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 10 0 0\nvertex 0 10 0\n"
                         "endloop\nendfacet\nendsolid t\n";
  std::ofstream(script) << R"({"actions": [{"step": 0, "action": "explode"}]})";
  Result r = run_viewer(fmt::format("'{}' --frames 5", scene.string()));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("broken_scene.json"), std::string::npos) << r.err;
  r = run_viewer(fmt::format("--mesh '{}' --frames 5", mesh.string()));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("open.stl"), std::string::npos) << r.err;
  r = run_viewer(fmt::format("--script '{}' --frames 5", script.string()));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("actions[0].action"), std::string::npos) << r.err;
  // The cavity options are dentsph run's: the same checks, the same messages.
  r = run_viewer("--cavity-depth 5 --frames 5");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("cavity does not fit"), std::string::npos) << r.err;
  r = run_viewer("--cavity-box-width 2 --frames 5");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--cavity class2"), std::string::npos) << r.err;
}

TEST(ViewerGui, ClosingMidRunStopsCleanly) {
  REQUIRE_XVFB();
  // No frame count: it would run until closed. SIGTERM after 4 s takes the window-close path.
  const Result r = run_viewer("", "timeout --preserve-status -s TERM 4");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("closed before the end"), std::string::npos) << r.out << r.err;
}

TEST(ViewerGui, RendersTheHapticRuntimeWithAScriptedDevice) {
  REQUIRE_XVFB();
  const fs::path sum = temp("scripted.json");
  const Result r = run_viewer(fmt::format("--device scripted --frames 30 --summary '{}'", sum.string()));
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("haptic loop"), std::string::npos) << r.out;  // the runtime's report at the end
  const auto j = nlohmann::json::parse(slurp(sum));
  const auto& h = j["realtime"]["haptic"];
  EXPECT_GT(h["ticks"].get<double>(), 100);
  EXPECT_GT(h["rate_hz"].get<double>(), 0);
  EXPECT_LE(h["max_force_N"].get<double>(), 9.0);  // the Falcon profile's limit
  EXPECT_GT(j["realtime"]["sim"]["steps"].get<int>(), 0);
  EXPECT_GT(j["sim"]["steps"].get<int>(), 0);  // the viewer's snapshots came from the runtime's simulation
  // The report beside the summary: a run folder with the runtime's sections, the recording and
  // the pictures (rendered in a browser by test_report_browser).
  const fs::path report = sum.parent_path() / (sum.stem().string() + "_report");
  EXPECT_TRUE(fs::exists(report / "report.html")) << r.out;
  EXPECT_TRUE(fs::exists(report / "tooth_cut.png"));
  EXPECT_TRUE(fs::exists(report / "recording" / "steps.csv"));
  const auto rs = nlohmann::json::parse(slurp(report / "summary.json"));
  EXPECT_EQ(rs["haptic"]["ticks"], h["ticks"]);
  EXPECT_EQ(rs["assessment"], j["assessment"]);
  EXPECT_NE(slurp(report / "report.html").find("id=\"haptic\""), std::string::npos);
}

// The GPU's algorithm behind the window (--backend cuda-emulation, the CUDA backend's stage bodies
// on the CPU): the scene renders as on the CPU and steps, its summary names the backend; under the
// haptic runtime (--device scripted) the runtime steps on it too.
TEST(ViewerGui, RendersAndStepsOnTheCudaEmulation) {
  REQUIRE_XVFB();
  const fs::path png = temp("emulation.png"), sum = temp("emulation.json");
  fs::remove(png);
  // The GPU backends run the paper's step only: without --solver the viewer takes it and says so.
  Result r = run_viewer(fmt::format("--backend cuda-emulation --frames 20 --screenshot '{}' --summary '{}'",
                                    png.string(), sum.string()));
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("the GPU backend runs the paper's step (the scene's iisph solver has none there)"),
            std::string::npos) << r.out;
  const Image img(png);
  EXPECT_GT(img.share(tooth_pixel), 0.05);
  EXPECT_GT(img.share(paste_pixel), 0.005);
  auto j = nlohmann::json::parse(slurp(sum));
  EXPECT_EQ(j["backend"], "cuda-emulation");
  EXPECT_GT(j["sim"]["steps"].get<int>(), 0);
  EXPECT_EQ(j["particles"]["material"], 1600);
  // Without a device the viewer's own loop keeps every step's tool force: its report plots it.
  const fs::path report = sum.parent_path() / (sum.stem().string() + "_report");
  const std::string csv = slurp(report / "tool_force.csv");
  EXPECT_GE(long(std::count(csv.begin(), csv.end(), '\n')), j["sim"]["steps"].get<long>() + 1)
      << "a header and a row for every step";
  EXPECT_NE(slurp(report / "report.html").find("id=\"force-plot\""), std::string::npos);

  r = run_viewer(fmt::format("--solver paper --backend cuda-emulation --device scripted --frames 30 --summary '{}'", sum.string()));
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  j = nlohmann::json::parse(slurp(sum));
  EXPECT_EQ(j["backend"], "cuda-emulation");
  EXPECT_EQ(j["realtime"]["sim"]["backend"], "cuda-emulation");
  EXPECT_GT(j["realtime"]["sim"]["steps"].get<int>(), 0);
  EXPECT_FALSE(fs::exists(report / "tool_force.csv")) << "under a device the recording holds the forces";
}

// --material fills the viewer's scene with a paste preset at force scale 1 (docs/model.md,
// "Presets"): the picture shows the tooth and the paste, the assessment's scale is 1; an unknown
// preset is refused before the window opens.
TEST(ViewerGui, AMaterialPresetFillsTheViewersScene) {
  REQUIRE_XVFB();
  const fs::path png = temp("packable.png"), sum = temp("packable.json");
  fs::remove(png);
  Result r = run_viewer(fmt::format("--material packable --frames 20 --screenshot '{}' --summary '{}'", png.string(),
                                    sum.string()));
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  const Image img(png);
  EXPECT_GT(img.share(tooth_pixel), 0.05);
  EXPECT_GT(img.share(paste_pixel), 0.005);
  const auto j = nlohmann::json::parse(slurp(sum));
  EXPECT_DOUBLE_EQ(j["assessment"]["force_scale"].get<double>(), 1.0);
  EXPECT_GT(j["sim"]["steps"].get<int>(), 0);
  r = run_viewer("--material putty --frames 1");
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("choose flowable, universal, packable, amalgam"), std::string::npos) << r.err;
}

// The Material panel's preset chooser (the script's load_preset, as its "Load preset" button): the
// built-in scene filled again with packable at 37 C, reset, its force at scale 1; the paste and its
// force scale in the summary; the paper's paste before it. A script naming an unknown preset or a
// temperature out of range is refused naming the field.
TEST(ViewerGui, ThePresetChooserFillsTheSceneWithAnotherPaste) {
  REQUIRE_XVFB();
  const fs::path script = temp("load_preset.json"), png = temp("load_preset.png"), sum = temp("load_preset.json.out");
  std::ofstream(script) << R"({"actions": [{"step": 5, "action": "load_preset", "preset": "packable", "temperature_c": 37},
                                          {"step": 20, "action": "end"}]})";
  Result r = run_viewer(fmt::format("--frames 10 --script '{}' --screenshot '{}' --summary '{}'", script.string(),
                                    png.string(), sum.string()));
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  const auto j = nlohmann::json::parse(slurp(sum));
  ASSERT_TRUE(j["material"].is_object()) << j.dump(2);
  EXPECT_EQ(j["material"]["preset"], "packable");
  EXPECT_DOUBLE_EQ(j["material"]["temperature_c"].get<double>(), 37);
  EXPECT_DOUBLE_EQ(j["force_scale"].get<double>(), 1.0);
  EXPECT_NE(j.value("message", std::string()).find("filled with packable at 37 C"), std::string::npos) << j.dump(2);
  const Image img(png);
  EXPECT_GT(img.share(tooth_pixel), 0.05) << "the tooth is drawn after the reset";
  const fs::path plain = temp("no_preset.json.out");
  r = run_viewer(fmt::format("--frames 3 --summary '{}'", plain.string()));
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  const auto p = nlohmann::json::parse(slurp(plain));
  EXPECT_TRUE(p["material"].is_null()) << "the paper's paste";
  EXPECT_GT(p["force_scale"].get<double>(), 1000.0);
  const fs::path bad = temp("bad_preset.json");
  std::ofstream(bad) << R"({"actions": [{"step": 5, "action": "load_preset", "preset": "putty"}]})";
  r = run_viewer(fmt::format("--script '{}' --frames 3", bad.string()));
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("actions[0].preset"), std::string::npos) << r.err;
  std::ofstream(bad) << R"({"actions": [{"step": 5, "action": "load_preset", "preset": "flowable", "temperature_c": 90}]})";
  r = run_viewer(fmt::format("--script '{}' --frames 3", bad.string()));
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("actions[0].temperature_c"), std::string::npos) << r.err;
}

// --backend cuda where it cannot run: exit status 2 and the reason, no window.
TEST(ViewerGui, TheCudaBackendWithoutAGpuIsAClearError) {
  REQUIRE_XVFB();
  const Result r = run_viewer("--solver paper --backend cuda --frames 1");
  if (r.status == 0) GTEST_SKIP() << "the CUDA backend runs here";
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("error: --backend cuda: "), std::string::npos) << r.err;
  EXPECT_TRUE(r.err.find("no CUDA device: ") != std::string::npos ||
              r.err.find("this build has no CUDA backend: ") != std::string::npos)
      << r.err;
}

TEST(ViewerGui, ALostDeviceConnectionDegradesToZeroForce) {
  REQUIRE_XVFB();
  // The reference client waits for the viewer's bridge to answer (--wait: a viewer that starts
  // slowly, under a sanitizer on a busy host, missed its first poses), plays 1.5 s and leaves
  // without a goodbye; the viewer keeps drawing for another few seconds, its bridge times the
  // session out and renders zero force.
  const int port = 40000 + int(::getpid() % 20000);
  const fs::path sum = temp("udp.json"), client_report = temp("client.json"), out = temp("udp_out.txt");
  const std::string cmd = fmt::format(
      "timeout -s KILL 240 xvfb-run -a -s '-screen 0 1024x768x24' {} sh -c \"'{}' --width 640 --height 480 --threads 1 "
      "--timeout 200 --max-fps 30 --frames 150 --device udp --port {} --summary '{}' & v=$!; "
      "'{}' --port {} --wait 60 --duration 1.5 --no-bye --report '{}' >/dev/null; wait $v\" >'{}' 2>&1",
      kNoDriverLeakCheck, kViewer.string(), port, sum.string(), kClient.string(), port, client_report.string(),
      out.string());
  const int raw = std::system(cmd.c_str());
  ASSERT_EQ(WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, 0) << slurp(out);
  const auto j = nlohmann::json::parse(slurp(sum));
  const auto& dev = j["realtime"]["device"];
  EXPECT_GT(dev["poses"].get<double>(), 100) << dev.dump();
  EXPECT_GE(dev["timeouts"].get<double>(), 1) << dev.dump();  // the silent client's session ended
  const auto& h = j["realtime"]["haptic"];
  EXPECT_GT(h["watchdog"]["pose_stale_ticks"].get<double>(), 0);
  EXPECT_LE(h["max_force_N"].get<double>(), 9.0);
  // What the client saw while it played: forces answering its poses, finite, within the limit.
  const auto c = nlohmann::json::parse(slurp(client_report));
  EXPECT_GT(c["forces_received"].get<double>(), 100);
  EXPECT_EQ(c["non_finite_forces"].get<double>(), 0);
  EXPECT_EQ(c["forces_over_limit"].get<double>(), 0);
  EXPECT_EQ(c["echo_mismatches"].get<double>(), 0);
}

TEST(ViewerGui, NoDisplayIsAClearError) {
  const fs::path err = temp("nodisplay.txt");
  const std::string cmd = fmt::format("env -u DISPLAY -u WAYLAND_DISPLAY timeout -s KILL 60 '{}' --frames 1 2>'{}' >/dev/null",
                                      kViewer.string(), err.string());
  const int raw = std::system(cmd.c_str());
  EXPECT_EQ(WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, 2);
  EXPECT_NE(slurp(err).find("xvfb-run"), std::string::npos) << slurp(err);
}

}  // namespace
