// The command line refuses bad input with a clear message and a non-zero exit: broken meshes, a
// cavity that does not fit the tooth, broken procedure files. Runs the built `dentsph` binary.
#include <gtest/gtest.h>

#include <array>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/cli_process.hpp"
#include "test_tooth_support.hpp"

namespace dentsph {
namespace {

namespace fs = std::filesystem;

using Result = testing::CliResult;
using testing::dentsph_cli;

void expect_refused(const std::string& args, const std::vector<std::string>& phrases) {
  const Result r = dentsph_cli(args);
  EXPECT_NE(r.code, 0) << args << "\n" << r.output;
  EXPECT_EQ(r.output.find("diverged"), std::string::npos) << r.output;
  for (const std::string& p : phrases) EXPECT_NE(r.output.find(p), std::string::npos) << "'" << p << "' in:\n" << r.output;
}

const fs::path& dir() {
  static const fs::path d = testing::temp_dir("cli");
  return d;
}

void write(const fs::path& f, const std::string& text) { std::ofstream(f) << text; }

TEST(Cli, BadMeshesAreRefused) {
  using testing::box_mesh;
  constexpr real mm = 1e-3;
  TriMesh open = box_mesh({0, 0, 0}, {10 * mm, 9 * mm, 12 * mm});
  open.triangles.pop_back();
  testing::write_ascii_stl(dir() / "open.stl", open);
  expect_refused("run --mesh " + (dir() / "open.stl").string() + " --steps 1 -q", {"open.stl", "not closed", "close the holes"});

  write(dir() / "empty.stl", "");
  expect_refused("run --mesh " + (dir() / "empty.stl").string() + " --steps 1 -q", {"empty.stl", "error:"});

  // Two boxes sharing an edge: the edge has four triangles.
  TriMesh two = box_mesh({0, 0, 0}, {6 * mm, 6 * mm, 12 * mm});
  const TriMesh b = box_mesh({6 * mm, 6 * mm, 0}, {12 * mm, 12 * mm, 12 * mm});
  const auto base = std::uint32_t(two.vertices.size());
  two.vertices.insert(two.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto t : b.triangles) two.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  testing::write_ascii_stl(dir() / "nonmanifold.stl", two);
  expect_refused("run --mesh " + (dir() / "nonmanifold.stl").string() + " --steps 1 -q", {"nonmanifold.stl", "manifold"});

  // A 10 mm tooth written in metres but read as millimetres: 0.01 mm across.
  testing::write_ascii_stl(dir() / "metres.stl", box_mesh({0, 0, 0}, {10 * mm, 9 * mm, 12 * mm}), 1.0);
  expect_refused("run --mesh " + (dir() / "metres.stl").string() + " --steps 1 -q", {"metres.stl", "metres"});
}

TEST(Cli, ACavityLargerThanTheToothIsRefused) {
  constexpr real mm = 1e-3;
  // A 5 x 4.5 mm column: the default 3 x 5 mm Class I runs off it.
  testing::write_ascii_stl(dir() / "narrow.stl", testing::box_mesh({0, 0, 0}, {5 * mm, 4.5 * mm, 14 * mm}));
  expect_refused("run --mesh " + (dir() / "narrow.stl").string() + " --steps 1 -q", {"narrow.stl", "cavity does not fit", "min_wall"});
}

TEST(Cli, BrokenProceduresAreRefused) {
  write(dir() / "order.json", R"({"name": "p", "keyframes": [{"t": 0.5, "position": [0, 0, 3]}, {"t": 0.1, "position": [0, 0, 1]}]})");
  expect_refused("run --procedure " + (dir() / "order.json").string() + " --steps 1 -q",
                 {"order.json", "keyframes[1].t", "strictly increase"});
  write(dir() / "event.json",
        R"({"name": "p", "keyframes": [{"t": 0, "position": [0, 0, 3]}], "events": [{"t": 0, "drip": {}}]})");
  expect_refused("run --procedure " + (dir() / "event.json").string() + " --steps 1 -q", {"event.json", "drip"});
  write(dir() / "volume.json", R"({"name": "p", "keyframes": [{"t": 0, "position": [0, 0, 3]}],
        "events": [{"t": 0, "dispense": {"volume": 1000, "at": [0, 0, -2]}}]})");
  expect_refused("run --procedure " + (dir() / "volume.json").string() + " --steps 1 -q",
                 {"volume.json", "events[0].dispense.volume", "more than the whole cavity"});
  expect_refused("run --procedure " + (dir() / "missing.json").string() + " --steps 1 -q", {"missing.json", "no such file"});
}

TEST(Cli, AProcedureFileRuns) {
  write(dir() / "ok.json", R"({"name": "ok", "keyframes": [{"t": 0, "position": [0, 0, 3]}, {"t": 0.01, "position": [0, 0, 1]}],
        "events": [{"t": 0, "dispense": {"volume": 3, "at": [0, 0, -2]}}]})");
  const Result r = dentsph_cli("run --procedure " + (dir() / "ok.json").string() + " --steps 40 --threads 1 -q --out " +
                               (dir() / "out").string());
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("assessment of the filling"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir() / "out" / "summary.json"));
}

TEST(Cli, ImpossibleCavityOptionsNameTheOptionAndTheFix) {
  expect_refused("run --cavity-width -1 --steps 1 -q", {"--cavity-width -1", "must be > 0 mm", "bucco-lingual width"});
  expect_refused("run --cavity-length 0 --steps 1 -q", {"--cavity-length 0", "must be > 0 mm"});
  expect_refused("run --cavity-taper 40 --steps 1 -q", {"--cavity-taper 40", "< 30 degrees", "2 to 8 is usual"});
  expect_refused("run --cavity-rounding -0.1 --steps 1 -q", {"--cavity-rounding", "must be >= 0 mm"});
  expect_refused("run --cavity class3 --steps 1 -q", {"--cavity class3", "give class1", "class2"});
  expect_refused("run --cavity-side distal --steps 1 -q", {"--cavity-side distal", "no proximal box", "--cavity class2"});
  expect_refused("run --cavity-box-depth 4 --steps 1 -q", {"--cavity-box-depth", "--cavity class2"});
  expect_refused("run --cavity class2 --cavity-side left --steps 1 -q", {"--cavity-side left", "mesial or distal"});
  expect_refused("run --long-axis 0 0 0 --steps 1 -q", {"--long-axis", "not a direction"});
  // The library's refusals reach the user with their reason, and the options that set the cavity.
  expect_refused("run --cavity-depth 5 --steps 1 -q",
                 {"the built-in crown: cavity does not fit", "pulpal floor", "shallower", "--cavity-depth"});
  expect_refused("run --cavity class2 --cavity-box-depth 1 --steps 1 -q", {"box_depth", "pulpal floor", "(--cavity-box-depth)"});
  expect_refused("run --mesial 0 0 1 --steps 1 -q", {"--long-axis / --mesial", "within 10 degrees of the long axis"});
  // A scene file says its own cavity.
  expect_refused("run scenes/tool_press.json --cavity class2 --steps 1 -q", {"--cavity", "excludes"});
  for (const char* args : {"run --cavity-width -1 --steps 1 -q", "run --cavity-depth 5 --steps 1 -q"})
    EXPECT_EQ(dentsph_cli(args).code, 2) << args;
}

// Numeric options that are not numbers, infinite or far out of what the program can use are refused
// before anything runs, naming the option and its range: --force-scale nan was replaced by the
// default without a word, --stiffness 1e308 rendered 0 N a whole session, --workspace-scale 1e308
// sent the tool to -6.6e291 m and reported "completed". The library refuses them too.
TEST(Cli, NumericOptionsOutOfRangeAreRefused) {
  const char* rt = "run --realtime --device scripted --duration 0.2 -q ";
  for (const auto& [option, value, range] :
       std::vector<std::array<std::string, 3>>{{"--force-scale", "nan", "1e-06 to 1e+09"},
                                                {"--force-scale", "inf", "1e-06 to 1e+09"},
                                                {"--stiffness", "1e308", "1 to 1e+07"},
                                                {"--damping", "-inf", "0 to 10000"},
                                                {"--workspace-scale", "1e308", "0.0001 to 10000"},
                                                {"--haptic-rate", "nan", "500 to 4000"},
                                                {"--sim-rate", "nan", "0 to 1e+07"},
                                                {"--solve-deadline", "1.5", "0 to 1"}}) {
    const Result r = dentsph_cli(std::string(rt) + option + " " + value);
    EXPECT_EQ(r.code, 2) << option << " " << value << ": " << r.output;
    EXPECT_NE(r.output.find(option + ": Value " + value + " not in range " + range), std::string::npos)
        << option << " " << value << ": " << r.output;
  }
  const Result o = dentsph_cli(std::string(rt) + "--workspace-origin 0 nan 0");
  EXPECT_EQ(o.code, 2) << o.output;
  EXPECT_NE(o.output.find("--workspace-origin"), std::string::npos) << o.output;
  // --help shows each range (docs/command-line.md says so).
  const Result help = dentsph_cli("run --help");
  EXPECT_NE(help.output.find("FLOAT in 1 to 1e+07"), std::string::npos) << help.output;
  EXPECT_NE(help.output.find("FLOAT in 0.0001 to 10000"), std::string::npos) << help.output;
  const Result d = dentsph_cli("run --duration nan -q");
  EXPECT_EQ(d.code, 2) << d.output;
  EXPECT_NE(d.output.find("--duration: Value nan not in range"), std::string::npos) << d.output;
}

nlohmann::json read_json(const fs::path& f) {
  std::ifstream in(f);
  return nlohmann::json::parse(in);
}

// What would lose a session at its end is refused before it runs: a student or exercise name
// that is not UTF-8 (it failed in the JSON writer after the whole session: summary.json empty, no
// report, no store entry) and a session store that cannot be opened (checked after the run before).
TEST(Cli, NamesAndTheStoreAreCheckedBeforeTheSession) {
  const fs::path out = dir() / "early";
  fs::remove_all(out);
  const Result latin1 = dentsph_cli("run --steps 2 -q --student \"$(printf 'Jos\\351')\" --out " + out.string());
  EXPECT_EQ(latin1.code, 2) << latin1.output;
  EXPECT_NE(latin1.output.find("--student: not UTF-8 text: byte 0xE9 at position 3"), std::string::npos) << latin1.output;
  const Result control = dentsph_cli("run --steps 2 -q --exercise \"$(printf 'a\\033b')\" --out " + out.string());
  EXPECT_EQ(control.code, 2) << control.output;
  EXPECT_NE(control.output.find("--exercise: a control character"), std::string::npos) << control.output;
  EXPECT_FALSE(fs::exists(out / "summary.json"));
  for (const std::string& db : {std::string("./no/dir/s.sqlite"), (dir() / "text.sqlite").string()}) {
    std::ofstream(dir() / "text.sqlite") << "not a database\n";
    const Result r = dentsph_cli("run --steps 2 -q --db " + db + " --out " + out.string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(db), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out / "summary.json")) << "the session ran before the store was checked";
  }
  // An empty store address is refused (it was taken for none, silently); a report from a store that
  // is not there names it instead of making an empty one; a libpq key-value address is a PostgreSQL
  // store (it made an SQLite file of that name) and its password is never printed.
  expect_refused("run --steps 2 -q --db \"\" --out " + out.string(), {"--db", "an empty session store address"});
  EXPECT_FALSE(fs::exists(out / "summary.json"));
  const fs::path typo = dir() / "typo.sqlite";
  fs::remove(typo);
  expect_refused("report --db " + typo.string() + " --out " + (dir() / "typo.html").string(),
                 {typo.string(), "no such session store"});
  EXPECT_FALSE(fs::exists(typo)) << "a report made the store it reads";
  const fs::path kv = dir() / "key_value";
  const auto spooled = testing::run_command("cd " + dir().string() + " && DENTSPH_STORE_SPOOL=" + (dir() / "spool").string() +
                                            " " + DENTSPH_CLI + " run --steps 2 -q --out " + kv.string() +
                                     " --db \"host=127.0.0.1 port=1 password=s3cret dbname=x\"");
  EXPECT_EQ(spooled.code, 0) << spooled.output;
  EXPECT_NE(spooled.output.find("password=***"), std::string::npos) << spooled.output;
  EXPECT_EQ(spooled.output.find("s3cret"), std::string::npos) << spooled.output;
  for (const auto& e : fs::directory_iterator(dir()))
    EXPECT_EQ(e.path().filename().string().find("host="), std::string::npos) << "an SQLite file named by the address";
  // An unreachable server whose spool folder cannot be made: said before the session, naming the
  // folder and the fix (a filesystem exception after the session before).
  const auto no_spool = testing::run_command("DENTSPH_STORE_SPOOL=/proc/dentsph-spool " + std::string(DENTSPH_CLI) +
                                             " run --steps 2 -q --out " + kv.string() +
                                             " --db postgresql://tutor@127.0.0.1:1/dentsph");
  EXPECT_EQ(no_spool.code, 2) << no_spool.output;
  EXPECT_NE(no_spool.output.find("the spool folder /proc/dentsph-spool cannot be made"), std::string::npos)
      << no_spool.output;
  EXPECT_NE(no_spool.output.find("DENTSPH_STORE_SPOOL"), std::string::npos) << no_spool.output;
  // UTF-8 names go through to the summary.
  const Result ok = dentsph_cli("run --steps 2 -q --student \"José\" --out " + out.string());
  ASSERT_EQ(ok.code, 0) << ok.output;
  EXPECT_EQ(read_json(out / "summary.json")["session"]["student"], "José");
}


TEST(Cli, AClassTwoRunOnTheBuiltInCrown) {
  const fs::path out = dir() / "class2";
  const Result r = dentsph_cli("run --cavity class2 --cavity-side distal --cavity-width 3.5 --cavity-taper 4 --steps 5 "
                               "--threads 1 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("cavity     Class II, outline 3.5 x 5 mm"), std::string::npos) << r.output;
  const nlohmann::json cavity = read_json(out / "summary.json").at("cavity");
  EXPECT_EQ(cavity.at("class"), "class2");
  EXPECT_EQ(cavity.at("side"), "distal");
  EXPECT_DOUBLE_EQ(cavity.at("width_mm").get<double>(), 3.5);
  EXPECT_DOUBLE_EQ(cavity.at("taper_deg").get<double>(), 4);
  EXPECT_DOUBLE_EQ(cavity.at("box_depth_mm").get<double>(), 3.5);
  EXPECT_GT(cavity.at("volume_mm3").get<double>(), 40);  // the Class I is 32.5 mm^3
  EXPECT_GE(cavity.at("thinnest_wall_mm").get<double>(), 1.0);
}

// `run --material` fills the built-in procedure with a paste preset in SI units at force scale 1
// (docs/model.md, "Presets"); an unknown preset and the paper's step are refused.
TEST(Cli, AMaterialPresetFillsAtForceScaleOne) {
  const fs::path out = dir() / "universal";
  const Result r = dentsph_cli("run --material universal --steps 5 --threads 1 --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json s = read_json(out / "summary.json");
  EXPECT_EQ(s.at("material").at("preset"), "universal");
  EXPECT_DOUBLE_EQ(s.at("material").at("temperature_c").get<double>(), 23);
  EXPECT_DOUBLE_EQ(s.at("tool").at("force_scale").get<double>(), 1.0);
  EXPECT_GT(s.at("solver").at("viscosity").at("rheology").at("iterations").get<double>(), 0) << "the paste is non-Newtonian";
  EXPECT_NE(r.output.find("rheology:"), std::string::npos) << r.output;
  EXPECT_EQ(s.at("solver").at("viscous_pressure").at("step"), 0.5) << "a preset is solved with the viscous pressure";
  // The compression measured at each step's start, beside the solve's predicted density error.
  const nlohmann::json& compression = s.at("solver").at("compression");
  EXPECT_GE(compression.at("mean").get<double>(), 0);
  EXPECT_GE(compression.at("mean_max").get<double>(), compression.at("mean").get<double>());
  EXPECT_GE(compression.at("particle_max").get<double>(), compression.at("mean_max").get<double>());
  EXPECT_NE(r.output.find("compression measured at a step's start"), std::string::npos) << r.output;
  const nlohmann::json own = [&] {
    const fs::path plain = dir() / "paper_paste";
    const Result p = dentsph_cli("run --steps 5 --threads 1 --out " + plain.string());
    EXPECT_EQ(p.code, 0) << p.output;
    return read_json(plain / "summary.json");
  }();
  EXPECT_TRUE(own.at("material").is_null()) << "the scene's own paste";
  EXPECT_GT(own.at("tool").at("force_scale").get<double>(), 1000.0);
  expect_refused("run --material putty --steps 1", {"--material putty", "choose flowable, universal, packable, amalgam"});
  expect_refused("run --material packable --solver paper --steps 1", {"non-Newtonian", "--solver iisph"});
  expect_refused("run --material flowable --temperature 80 --steps 1", {"--temperature 80", "outside 10 to 70 C"});
  expect_refused("run --temperature 37 --steps 1", {"--temperature 37", "add --material"});
  const fs::path warm = dir() / "warm";
  const Result w = dentsph_cli("run --material universal --temperature 54 --steps 2 --threads 1 --out " + warm.string());
  ASSERT_EQ(w.code, 0) << w.output;
  EXPECT_DOUBLE_EQ(read_json(warm / "summary.json").at("material").at("temperature_c").get<double>(), 54);
  // A realtime session's recording names its paste, and `replay` takes it: bit for bit without the
  // options, and another temperature differs.
  const fs::path rt = dir() / "warm_realtime";
  const Result session = dentsph_cli("run --realtime --device scripted --duration 0.3 --material universal --temperature 37 "
                                     "--threads 1 -q --out " + rt.string());
  ASSERT_EQ(session.code, 0) << session.output;
  const nlohmann::json recorded = read_json(rt / "recording" / "session.json").at("material");
  EXPECT_EQ(recorded.at("preset"), "universal");
  EXPECT_DOUBLE_EQ(recorded.at("temperature_c").get<double>(), 37);
  const Result same = dentsph_cli("replay " + (rt / "recording").string());
  EXPECT_EQ(same.code, 0) << same.output;
  EXPECT_NE(same.output.find(" 0 tool forces differ"), std::string::npos) << same.output;
  EXPECT_EQ(dentsph_cli("replay " + (rt / "recording").string() + " --temperature 23").code, 4) << "a colder paste differs";
}

// `dentsph replay` without a scene file replays into the procedure that `dentsph run --realtime`
// ran, with the same tooth options.
TEST(Cli, ReplayTakesTheCavityOptionsOfTheRun) {
  const fs::path out = dir() / "rt";
  const std::string cavity = " --cavity-width 3.5 --cavity-depth 2.2";
  const Result r = dentsph_cli("run --realtime --duration 0.3 --threads 1 -q --out " + out.string() + cavity);
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json summary = read_json(out / "summary.json");
  EXPECT_DOUBLE_EQ(summary.at("cavity").at("depth_mm").get<double>(), 2.2);
  // The rendered force's spectrum above 100 Hz, from the session's ticks.
  const nlohmann::json& spectrum = summary.at("haptic").at("spectrum");
  EXPECT_GT(spectrum.at("ticks").get<int>(), 64) << spectrum;
  for (const char* key : {"above_rms_N", "above_share", "fluctuation_rms_N", "peak_hz", "peak_amplitude_N"})
    EXPECT_TRUE(spectrum.at(key).is_number() && std::isfinite(spectrum.at(key).get<double>())) << key << ": " << spectrum;
  EXPECT_LE(spectrum.at("above_share").get<double>(), 1.0);
  EXPECT_FALSE(spectrum.at("bands").empty());
  EXPECT_NE(r.output.find("force above 100 Hz: rms "), std::string::npos) << r.output;
  const Result same = dentsph_cli("replay " + (out / "recording").string() + cavity);
  EXPECT_EQ(same.code, 0) << same.output;
  EXPECT_NE(same.output.find(" 0 tool forces differ"), std::string::npos) << same.output;
  // Another cavity is another scene: the forces differ.
  EXPECT_EQ(dentsph_cli("replay " + (out / "recording").string()).code, 4);
}

// --backend under the realtime runtime and replay: the built-in procedure runs end to end on the
// GPU's algorithm (cuda-emulation, the CUDA backend's stage bodies on the CPU), its summary and its
// recording name the backend; the recording replays bit for bit on its backend and within the
// backends' parity tolerance on the CPU. Without --solver the GPU backend takes the paper's step (the
// dental scenes' default, the iisph solver, has none there), saying so; the recording names the step,
// and a replay without --solver takes it.
TEST(Cli, RealtimeRunsAndReplaysOnTheCudaEmulation) {
  const fs::path out = dir() / "rt_emulation";
  const Result r = dentsph_cli("run --realtime --backend cuda-emulation --device scripted --duration 2 --threads 1 -q --out " +
                               out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("the GPU backend runs the paper's step (the scene's iisph solver has none there)"),
            std::string::npos) << r.output;
  EXPECT_EQ(read_json(out / "summary.json").at("solver").at("name"), "paper");
  EXPECT_EQ(read_json(out / "recording" / "session.json").at("solver"), "paper");
  EXPECT_NE(r.output.find("simulation (cuda-emulation)"), std::string::npos) << r.output;
  const nlohmann::json s = read_json(out / "summary.json");
  EXPECT_EQ(s.at("backend"), "cuda-emulation");
  EXPECT_EQ(s.at("sim").at("backend"), "cuda-emulation");
  EXPECT_EQ(s.at("status"), "completed");
  EXPECT_GT(s.at("steps").get<int>(), 10);
  EXPECT_GT(s.at("particles").at("material").get<int>(), 0) << "the procedure's first increment went in on the GPU path";
  EXPECT_EQ(read_json(out / "recording" / "session.json").at("backend"), "cuda-emulation");
  const std::string recording = (out / "recording").string();
  const Result same = dentsph_cli("replay " + recording + " --backend cuda-emulation");
  EXPECT_EQ(same.code, 0) << same.output;
  EXPECT_NE(same.output.find(" 0 tool forces differ"), std::string::npos) << same.output;
  const Result cpu = dentsph_cli("replay " + recording + " --threads 1");
  EXPECT_EQ(cpu.code, 0) << cpu.output;
  EXPECT_NE(cpu.output.find("on cpu (recorded on cuda-emulation)"), std::string::npos) << cpu.output;
  EXPECT_NE(cpu.output.find(" 0 forces outside the parity tolerance"), std::string::npos) << cpu.output;
}

// --backend cuda where the CUDA backend cannot run (no GPU, or a build without it): every command
// that takes it refuses with exit status 2 and the reason, before stepping.
// --solve-deadline reaches the runtime and its summary counts the steps cut (how many depends on how
// far the host took the simulation in the run's wall time: HapticRuntime.ASolveDeadlineIsCounted
// holds the counting itself, run until the simulation is past the first press).
TEST(Cli, ARealtimeSolveDeadlineIsCounted) {
  const fs::path out = dir() / "rt_deadline";
  const Result r = dentsph_cli("run --realtime --device scripted --duration 2 --solve-deadline 1e-6 -q --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json s = read_json(out / "summary.json");
  const nlohmann::json& d = s.at("solver").at("on_deadline");
  EXPECT_LE(d.at("share").get<double>(), 1.0) << s.at("solver").dump();
  // No step the deadline cut was left further than 10 times the paper paste's mean density error
  // target (0.2%: kDeadlineErrorFactor).
  EXPECT_LE(d.at("residual_max").get<double>(), 10 * 0.002 * (1 + 1e-9)) << s.at("solver").dump();
}

TEST(Cli, TheCudaBackendWithoutAGpuIsRefusedWithTheReason) {
  const fs::path out = dir() / "rt_for_cuda";
  ASSERT_EQ(dentsph_cli("run scenes/tool_press.json --realtime --duration 0.2 --threads 1 -q --out " + out.string()).code, 0);
  for (const std::string& args : std::vector<std::string>{"run scenes/tool_press.json --backend cuda --steps 1 -q",
                                 "run scenes/tool_press.json --realtime --backend cuda --duration 1 -q",
                                 "replay " + (out / "recording").string() + " scenes/tool_press.json --backend cuda",
                                 "bench --backend cuda --quick"}) {
    const Result r = dentsph_cli(args);
    if (r.code == 0) GTEST_SKIP() << "the CUDA backend runs here: " << args;
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("error: --backend cuda: "), std::string::npos) << r.output;
    const bool reason = r.output.find("no CUDA device: ") != std::string::npos ||
                        r.output.find("this build has no CUDA backend: ") != std::string::npos;
    EXPECT_TRUE(reason) << r.output;
    EXPECT_EQ(r.output.find("steps ("), std::string::npos) << "nothing stepped: " << r.output;
  }
}

TEST(Cli, ADentalSceneFileIsValidatedAndRun) {
  const Result v = dentsph_cli("validate scenes/class2_fill.json");
  EXPECT_EQ(v.code, 0) << v.output;
  EXPECT_NE(v.output.find("cavity     Class II"), std::string::npos) << v.output;
  EXPECT_NE(v.output.find("ok: scenes/class2_fill.json is a valid scene"), std::string::npos) << v.output;

  write(dir() / "deep.json", R"({"name": "deep", "cavity": {"depth": 5}})");
  const Result bad = dentsph_cli("validate " + (dir() / "deep.json").string());
  EXPECT_EQ(bad.code, 2) << bad.output;
  EXPECT_NE(bad.output.find("deep.json: cavity: the built-in crown: cavity does not fit"), std::string::npos) << bad.output;

  const fs::path out = dir() / "scene_class2";
  const Result r = dentsph_cli("run scenes/class2_fill.json --steps 3 --threads 1 -q --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(read_json(out / "summary.json").at("cavity").at("class"), "class2");
}

// --mesh-units m reads a mesh written in metres; other units, or units without a mesh, are refused.
TEST(Cli, MeshUnitsReadAMeshInMetres) {
  constexpr real mm = 1e-3;
  const fs::path f = dir() / "block_in_m.stl";
  testing::write_ascii_stl(f, testing::box_mesh({0, 0, 0}, {10 * mm, 9 * mm, 12 * mm}), 1.0);
  expect_refused("run --mesh " + f.string() + " --steps 1 -q", {"block_in_m.stl", "--mesh-units m"});
  const Result ok = dentsph_cli("run --mesh " + f.string() + " --mesh-units m --steps 1 --threads 1 -q --out " +
                                (dir() / "units_out").string());
  EXPECT_EQ(ok.code, 0) << ok.output;
  EXPECT_EQ(read_json(dir() / "units_out" / "summary.json").at("steps"), 1);
  const Result cm = dentsph_cli("run --mesh " + f.string() + " --mesh-units cm --steps 1 -q");
  EXPECT_EQ(cm.code, 2) << cm.output;
  EXPECT_NE(cm.output.find("--mesh-units"), std::string::npos) << cm.output;
  const Result alone = dentsph_cli("run --mesh-units m --steps 1 -q");
  EXPECT_EQ(alone.code, 2) << alone.output;
  EXPECT_NE(alone.output.find("--mesh-units m: the built-in crown has no units to give; add --mesh"), std::string::npos)
      << alone.output;
}

TEST(Cli, TheDepthOfCureTest) {
  const Result r = dentsph_cli("material-test depth-of-cure --spacing 0.2");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("depth of cure: 3.00 mm"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("published: 3.00 mm"), std::string::npos) << r.output;
  const Result longer = dentsph_cli("material-test depth-of-cure --spacing 0.2 --time 40 --irradiance 1200");
  EXPECT_NE(longer.output.find("1200 mW/cm2 for 40 s"), std::string::npos) << longer.output;
  expect_refused("material-test depth-of-cure --material amalgam", {"sets by itself, not by light"});
  expect_refused("material-test depth-of-cure --material glass", {"--material"});
  expect_refused("material-test depth-of-cure --irradiance 0", {"--irradiance"});
}

// A procedure file's "material" fills the run with that preset at force scale 1; --material takes
// precedence, and --temperature warms the procedure's preset.
TEST(Cli, AProcedureFilesMaterialFillsTheRun) {
  const fs::path proc = dir() / "flowable_procedure.json";
  write(proc, R"({"name": "flowable_press", "material": "flowable",
                  "keyframes": [{"t": 0, "position": [0, 0, 3]}, {"t": 0.01, "position": [0, 0, 2.9]}],
                  "events": [{"t": 0, "dispense": {"volume": 5, "at": [0, 0, -2]}}]})");
  auto material_of = [&](const std::string& options, const std::string& name) {
    const fs::path out = dir() / name;
    const Result r = dentsph_cli("run --procedure " + proc.string() + " --steps 2 --threads 1 -q " + options +
                                 " --out " + out.string());
    EXPECT_EQ(r.code, 0) << r.output;
    return read_json(out / "summary.json");
  };
  const nlohmann::json own = material_of("", "procedure_material");
  EXPECT_EQ(own.at("material").at("preset"), "flowable");
  EXPECT_DOUBLE_EQ(own.at("tool").at("force_scale").get<double>(), 1.0);
  EXPECT_EQ(material_of("--material packable", "procedure_material_over").at("material").at("preset"), "packable");
  const nlohmann::json warm = material_of("--temperature 37", "procedure_material_warm");
  EXPECT_EQ(warm.at("material").at("preset"), "flowable");
  EXPECT_DOUBLE_EQ(warm.at("material").at("temperature_c").get<double>(), 37);
  write(dir() / "putty_procedure.json", R"({"name": "p", "material": "putty", "keyframes": [{"t": 0, "position": [0, 0, 3]}]})");
  expect_refused("run --procedure " + (dir() / "putty_procedure.json").string() + " --steps 1",
                 {"putty_procedure.json", "material", "choose flowable"});
}

// The presets' handling tests (docs/model.md, "Handling tests"): the figures printed beside their
// published range, and with --out result.json (each figure's name, value, unit, range or null,
// source) and the plot; an unknown paste, a temperature out of range and an output folder that is
// a file are refused.
TEST(Cli, TheHandlingTestsWriteTheirResultAndPlot) {
  const fs::path out = dir() / "rheometer";
  // Three rates of the flow curve (--shear-rates), in half the time of the command's seven.
  const Result r = dentsph_cli("material-test rheometer --material flowable --shear-rates 10,20,50 --out " + out.string() +
                               " --threads 2");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("viscosity at 10 /s"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(published 1310 to 2200 Pa s: in range)"), std::string::npos) << r.output;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(out / "result.json"));
  EXPECT_EQ(j.at("test"), "rheometer");
  EXPECT_EQ(j.at("material"), "flowable");
  bool eta = false, index = false, phase = false;
  for (const nlohmann::json& f : j.at("figures")) {
    ASSERT_TRUE(f.contains("name") && f.contains("value") && f.contains("unit") && f.contains("range") &&
                f.contains("source"))
        << f.dump();
    if (f.at("name") == "viscosity at 10 /s") {
      eta = true;
      EXPECT_EQ(f.at("unit"), "Pa s");
      EXPECT_EQ(f.at("range"), nlohmann::json::array({1310.0, 2200.0}));
      EXPECT_GE(f.at("value").get<double>(), 1310.0);
      EXPECT_LE(f.at("value").get<double>(), 2200.0);
      EXPECT_EQ(f.at("in_range"), true);
      EXPECT_NE(f.at("source").get<std::string>().find("Loumprinis"), std::string::npos);
    }
    if (f.at("name") == "flow index") {
      index = true;
      EXPECT_TRUE(f.at("range").is_null()) << "no published range: none claimed";
    }
    if (f.at("name") == "phase angle at 10 rad/s") {  // the departure, shown against its range
      phase = true;
      EXPECT_EQ(f.at("unit"), "deg");
      EXPECT_EQ(f.at("range"), nlohmann::json::array({30.9, 78.1}));
      EXPECT_EQ(f.at("in_range"), false);
      EXPECT_NE(f.at("source").get<std::string>().find("no elasticity"), std::string::npos);
    }
  }
  EXPECT_TRUE(eta && index && phase) << j.dump(2);
  ASSERT_EQ(j.at("curves").size(), 2u);
  EXPECT_EQ(j.at("curves")[0].at("file"), "flow_curve.svg");
  EXPECT_EQ(j.at("curves")[1].at("file"), "oscillation.svg");
  EXPECT_TRUE(fs::is_regular_file(out / "oscillation.svg"));
  std::ifstream svg(out / "flow_curve.svg");
  const std::string text((std::istreambuf_iterator<char>(svg)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("<svg"), std::string::npos);
  EXPECT_NE(text.find("<polyline"), std::string::npos);
  EXPECT_NE(text.find("viscosity (Pa s)"), std::string::npos);

  expect_refused("material-test slump --material putty", {"--material", "putty"});
  expect_refused("material-test rheometer --temperature 80", {"--temperature"});
  expect_refused("material-test rheometer --shear-rates 10,5", {"--shear-rates 10,5", "ascending"});
  expect_refused("material-test rheometer --shear-rates 10", {"--shear-rates 10", "at least two"});
  expect_refused("material-test rheometer --shear-rates 0,10", {"--shear-rates"});
  expect_refused("material-test tack --instrument teflon", {"--instrument", "teflon"});
  write(dir() / "a_file", "x");
  expect_refused("material-test slump --out " + (dir() / "a_file").string(), {"--out", "a_file"});
}

TEST(Cli, TheSolverIsChosenValidatedAndRefusedOnTheGpu) {
  // validate says which limits hold: the paper's acoustic and viscous, or the iisph velocity CFL.
  const Result paper = dentsph_cli("validate scenes/tool_press.json");
  EXPECT_EQ(paper.code, 0) << paper.output;
  EXPECT_NE(paper.output.find("solver     paper"), std::string::npos) << paper.output;
  EXPECT_NE(paper.output.find("limits: acoustic"), std::string::npos) << paper.output;
  nlohmann::json scene;
  std::ifstream("scenes/tool_press.json") >> scene;
  scene["simulation"]["solver"] = "iisph";
  write(dir() / "press_iisph.json", scene.dump());
  const Result iisph = dentsph_cli("validate " + (dir() / "press_iisph.json").string());
  EXPECT_EQ(iisph.code, 0) << iisph.output;
  EXPECT_NE(iisph.output.find("solver     iisph"), std::string::npos) << iisph.output;
  EXPECT_NE(iisph.output.find("velocity CFL"), std::string::npos) << iisph.output;
  // A dt over the velocity CFL limit of the tool's speed is refused, naming the field and the fix.
  scene["simulation"]["dt"] = 0.1;
  write(dir() / "press_fast.json", scene.dump());
  expect_refused("validate " + (dir() / "press_fast.json").string(),
                 {"press_fast.json: simulation.dt", "velocity CFL limit", "set simulation.dt to at most"});
  // An unknown solver in the file names the field and the choices.
  scene["simulation"]["solver"] = "fast";
  write(dir() / "press_unknown.json", scene.dump());
  expect_refused("validate " + (dir() / "press_unknown.json").string(),
                 {"simulation.solver", "unknown solver \"fast\"", "\"paper\"", "\"iisph\""});
  // --solver over the scene's, written to the summary.
  const fs::path out = dir() / "press_solver";
  const Result r = dentsph_cli("run scenes/tool_press.json --solver iisph --steps 3 --threads 1 -q --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json sum = read_json(out / "summary.json");
  EXPECT_EQ(sum.at("solver").at("name"), "iisph");
  EXPECT_EQ(sum.at("solver").at("pressure_solve"), "jacobi") << "the default";
  EXPECT_EQ(sum.at("solver").at("gradient"), "spiky") << "the default";
  EXPECT_EQ(sum.at("solver").at("density_kernel"), "poly6") << "the default";
  EXPECT_GE(sum.at("solver").at("pressure_iterations").at("max").get<int>(), 1);
  // --pressure-solve over the scene's, written to the summary with the largest error it measured;
  // an unknown one is refused naming the choices.
  const fs::path cg = dir() / "press_cg";
  const Result c = dentsph_cli("run scenes/tool_press.json --solver iisph --pressure-solve cg --steps 3 --threads 1 -q --out " +
                               cg.string());
  ASSERT_EQ(c.code, 0) << c.output;
  const nlohmann::json cg_sum = read_json(cg / "summary.json");
  EXPECT_EQ(cg_sum.at("solver").at("pressure_solve"), "cg");
  EXPECT_GT(cg_sum.at("solver").at("pressure_max_error").get<double>(), 0);
  EXPECT_EQ(cg_sum.at("solver").at("on_deadline").at("steps"), 0) << "an offline run has no deadline";
  expect_refused("run scenes/tool_press.json --pressure-solve multigrid --steps 1 -q", {"--pressure-solve", "jacobi", "cg"});
  // --viscous-pressure over the scene's (none), written to the summary with the largest it reached;
  // a step outside [0, 1] is refused naming the option.
  EXPECT_EQ(cg_sum.at("solver").at("viscous_pressure").at("step"), 0) << "none by default";
  EXPECT_EQ(cg_sum.at("solver").at("viscous_pressure").at("max_Pa"), 0);
  const fs::path vp = dir() / "press_vp";
  const Result v = dentsph_cli("run scenes/tool_press.json --solver iisph --viscous-pressure 0.5 --steps 20 --threads 1 "
                               "--out " + vp.string());
  ASSERT_EQ(v.code, 0) << v.output;
  EXPECT_NE(v.output.find("viscous pressure: step 0.5"), std::string::npos) << v.output;
  const nlohmann::json vp_sum = read_json(vp / "summary.json");
  EXPECT_EQ(vp_sum.at("solver").at("viscous_pressure").at("step"), 0.5);
  // The pressed paste builds one (measured 66 Pa in 20 steps of 1 Pa s paste).
  EXPECT_GT(vp_sum.at("solver").at("viscous_pressure").at("max_Pa").get<double>(), 0);
  expect_refused("run scenes/tool_press.json --viscous-pressure 2 --steps 1 -q", {"--viscous-pressure", "0", "1"});
  EXPECT_EQ(sum.at("stability").at("dt_s"), 5e-4) << "a scene file keeps its dt";
  // The built-in procedure takes the solver's dental time step with it.
  const fs::path dental = dir() / "dental_solver";
  const Result d = dentsph_cli("run --solver iisph --steps 2 --threads 1 -q --out " + dental.string());
  ASSERT_EQ(d.code, 0) << d.output;
  EXPECT_EQ(read_json(dental / "summary.json").at("stability").at("dt_s"), 1.5e-3);
  EXPECT_EQ(read_json(dental / "summary.json").at("solver").at("name"), "iisph");
  EXPECT_TRUE(read_json(dental / "summary.json").at("solver").contains("wall_projections"));
  EXPECT_EQ(read_json(dental / "summary.json").at("solver").at("held_outside_domain"), 0) << "nothing fell off";
  const Result p = dentsph_cli("run --solver paper --steps 2 --threads 1 -q --out " + dental.string());
  ASSERT_EQ(p.code, 0) << p.output;
  EXPECT_EQ(read_json(dental / "summary.json").at("stability").at("dt_s"), 5e-5);
  EXPECT_EQ(read_json(dental / "summary.json").at("solver").at("name"), "paper");
  // The GPU backend has the paper's step only: refused with exit status 2, the solver and the fix named.
  for (const char* backend : {"cuda", "cuda-emulation"}) {
    const Result g = dentsph_cli(std::string("run --solver iisph --backend ") + backend + " --steps 2 -q --out " +
                                 (dir() / "gpu").string());
    EXPECT_EQ(g.code, 2) << g.output;
    for (const char* phrase : {"the GPU backend has the paper's step only", "solver is iisph", "--solver paper"})
      EXPECT_NE(g.output.find(phrase), std::string::npos) << "'" << phrase << "' in:\n" << g.output;
  }
  expect_refused("run --solver fast --steps 2", {"--solver"});
}

}  // namespace
}  // namespace dentsph
