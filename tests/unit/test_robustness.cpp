// Robust against every input (docs/limits.md): what would hang, take the machine's
// memory or lose work is refused before it starts, naming the file, the field and the fix. Each
// test holds the cases of one class of defect.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "dentsph/dental.hpp"
#include "dentsph/haptics/recording.hpp"
#include "dentsph/haptics/replay.hpp"
#include "dentsph/limits.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/solver.hpp"
#include "dentsph/step.hpp"
#include "dentsph/tools.hpp"
#include "support/cli_process.hpp"

// Built with AddressSanitizer (gcc's __SANITIZE_ADDRESS__, clang's __has_feature): its programs
// reserve terabytes of shadow address space at start, which an address-space limit (ulimit -v) refuses.
#if defined(__SANITIZE_ADDRESS__)
#define DENTSPH_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DENTSPH_UNDER_ASAN 1
#endif
#endif
#ifdef DENTSPH_UNDER_ASAN
constexpr bool kUnderAddressSanitizer = true;
#else
constexpr bool kUnderAddressSanitizer = false;
#endif

namespace dentsph {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::dentsph_cli;

// Every command here ends well within this; one that would hang is killed and fails its test.
constexpr int kCliTimeout = 120;

const fs::path& dir() {
  static const fs::path d = [] {
    const fs::path p = fs::temp_directory_path() / fmt::format("dentsph_robust_{}", ::getpid());
    fs::create_directories(p);
    return p;
  }();
  return d;
}

fs::path write(const std::string& name, const std::string& text) {
  const fs::path f = dir() / name;
  std::ofstream(f) << text;
  return f;
}

// A small valid scene file: a plate, a box of paste, a sphere tool with two keyframes (h = 0.02 m).
json base_scene() {
  return json::parse(R"({
    "name": "base",
    "simulation": {"dt": 5e-4, "h": 0.02},
    "adhesion": {"A": 0.012, "B": 0.03},
    "materials": {
      "paste": {"viscosity": 0.5, "stiffness": 60, "rest_density": 1000, "adhesion": 200},
      "wall": {"viscosity": 0.5, "stiffness": 200, "rest_density": 1000, "adhesion": 0}
    },
    "roles": {"material": "paste", "boundary": "wall", "tool": "wall"},
    "blocks": [
      {"role": "boundary", "shape": "box", "min": [0, 0, 0], "max": [0.04, 0.04, 0.01], "spacing": 0.01},
      {"role": "material", "shape": "box", "min": [0, 0, 0.02], "max": [0.02, 0.02, 0.04], "spacing": 0.01}
    ],
    "tool": {
      "blocks": [{"shape": "sphere", "center": [0, 0, 0], "radius": 0.01, "spacing": 0.01}],
      "keyframes": [{"t": 0, "position": [0.02, 0.02, 0.08]}, {"t": 1, "position": [0.02, 0.02, 0.06]}]
    }
  })");
}

// A small valid procedure file (mm in the tooth frame).
json base_procedure() {
  return json::parse(R"({
    "name": "small",
    "keyframes": [{"t": 0, "position": [0, 0, 3]}, {"t": 0.01, "position": [0, 0, 2]}],
    "events": [{"t": 0, "dispense": {"cavity_fraction": 0.3, "at": [0, 0, -2]}}]
  })");
}

const ToothScene& crown() {
  static const ToothScene ts = default_tooth_scene();
  return ts;
}

// The message of the SceneError that reading `text` as a scene (or, with `procedure`, as a
// procedure on the built-in crown) throws; "" when it is accepted.
std::string refusal(const json& j, bool procedure = false) {
  try {
    if (procedure)
      (void)dental_procedure(crown(), j.dump(), "p.json");
    else
      (void)parse_scene(j.dump(), "s.json");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

void expect_refused(const json& j, const std::vector<std::string>& phrases, bool procedure = false) {
  const std::string msg = refusal(j, procedure);
  ASSERT_FALSE(msg.empty()) << j.dump();
  for (const std::string& p : phrases) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' in: " << msg;
}

void expect_cli_refused(const std::string& args, const std::vector<std::string>& phrases) {
  const testing::CliResult r = dentsph_cli(args, kCliTimeout);
  EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
  for (const std::string& p : phrases)
    EXPECT_NE(r.output.find(p), std::string::npos) << "'" << p << "' in (" << args << "):\n" << r.output;
}

// ---- class 2: hangs -------------------------------------------------------------------------------

// A lattice spacing far under h made the particle mass sum loop (h/s)^3 times (1e-7 m never ended).
TEST(Robustness, ALatticeSpacingFarUnderHIsRefusedWhereverItIsGiven) {
  for (const real tiny : {1e-7, 5e-324, 0.0019}) {  // h / 10 is 0.002 m
    json block = base_scene();
    block["blocks"][1]["spacing"] = tiny;
    expect_refused(block, {"s.json: blocks[1].spacing", "under h / 10", "give a spacing between h / 10 = 0.002 m"});
    json tool = base_scene();
    tool["tool"]["blocks"][0]["spacing"] = tiny;
    expect_refused(tool, {"tool.blocks[0].spacing", "under h / 10"});
    json dispense = base_scene();
    dispense["tool"]["events"] = json::parse(R"([{"t": 0.5, "dispense": {"volume": 1e-6, "at": [0, 0, 0.1]}}])");
    dispense["tool"]["events"][0]["dispense"]["spacing"] = tiny;
    expect_refused(dispense, {"tool.events[0].dispense.spacing", "under h / 10"});
    json instrument = base_scene();
    instrument["tool"]["events"] = json::parse(R"([{"t": 0.5, "switch_tool": {"name": "flat_plugger"}}])");
    instrument["tool"]["events"][0]["switch_tool"]["spacing"] = tiny;
    expect_refused(instrument, {"tool.events[0].switch_tool.spacing", "under h / 10"});
    json procedure = base_procedure();
    procedure["events"].push_back({{"t", 0.005}, {"switch_tool", {{"name", "condenser"}, {"spacing", tiny}}}});  // in mm: h / 10 is 0.06 mm
    expect_refused(procedure, {"p.json: events[1].switch_tool.spacing", "between h / 10 = 0.06 mm"}, true);
  }
  // h / 10 itself is accepted (and its mass sum is short).
  json fine = base_scene();
  fine["blocks"][1]["spacing"] = 0.002;
  EXPECT_EQ(refusal(fine), "");
  // The library refuses it too, instead of looping.
  const Model m = parse_scene(base_scene().dump(), "s.json").model;
  EXPECT_THROW((void)lattice_particle_mass(1000, 1e-7, m.kernel), std::invalid_argument);
  EXPECT_THROW((void)lattice_particle_mass(1000, 0.03, m.kernel), std::invalid_argument);
  EXPECT_GT(lattice_particle_mass(1000, 0.002, m.kernel), 0);
  // The command line says the same, and does not hang.
  json hang = base_scene();
  hang["blocks"][1]["spacing"] = 1e-7;
  const fs::path f = write("hang_spacing.json", hang.dump());
  expect_cli_refused("validate " + f.string(), {"hang_spacing.json: blocks[1].spacing", "under h / 10"});
}

// A time step of 5e-324 s or a duration of 1e308 s passed `validate` and never ended.
TEST(Robustness, ATimeStepOrARunThatCouldNeverEndIsRefused) {
  json dt = base_scene();
  dt["simulation"]["dt"] = 5e-324;
  expect_refused(dt, {"s.json: simulation.dt", "under the smallest time step of 1e-09 s"});
  json run = base_scene();
  run["run"] = {{"duration", 1e308}};
  expect_refused(run, {"s.json: run.duration", "over the limit of 100000000 steps", "give at most 5e+04 s"});
  run["run"]["duration"] = double(limits::max_run_steps) * 5e-4;  // the longest run
  EXPECT_EQ(refusal(run), "");
  json procedure = base_procedure();
  procedure["duration"] = 1e308;
  expect_refused(procedure, {"p.json: duration", "over the limit of 100000000 steps"}, true);
  json keyframe = base_procedure();
  keyframe["keyframes"][1]["t"] = 1e300;
  expect_refused(keyframe, {"p.json: keyframes[1].t", "over the limit"}, true);

  // The command line: the scene's fields through validate and run, and the options of run.
  const fs::path never = write("never.json", dt.dump());
  expect_cli_refused("validate " + never.string(), {"never.json: simulation.dt", "smallest time step"});
  run["run"]["duration"] = 1e308;
  const fs::path endless = write("endless.json", run.dump());
  expect_cli_refused("validate " + endless.string(), {"endless.json: run.duration", "over the limit"});
  expect_cli_refused("run -q " + endless.string(), {"endless.json: run.duration", "over the limit"});
  const fs::path ok = write("ok.json", base_scene().dump());
  expect_cli_refused("run -q --steps 100000001 " + ok.string(), {"--steps 100000001", "over the limit of 100000000"});
  expect_cli_refused("run -q --duration 1e308 " + ok.string(), {"--duration 1e+308", "over the limit", "give at most"});
  expect_cli_refused("run -q --realtime --duration 1e308 " + ok.string(), {"--duration 1e+308", "at most 3600 s"});
}

// ---- class 3: runaway memory ---------------------------------------------------------------------

// A box block of 2.25 million particles (131^3 at h / 10).
json big_block(const char* role) {
  return {{"role", role}, {"shape", "box"}, {"min", {0, 0, 0}}, {"max", {0.26, 0.26, 0.26}}, {"spacing", 0.002}};
}

// The 20-million limit was per block: ten blocks, or increments asking for 1e12 m^3, grew until the
// machine's memory was gone and ended in a bare std::bad_alloc. The whole scene is counted now,
// before any of its particles are made.
TEST(Robustness, AWholeSceneOverTheParticleOrMemoryLimitIsRefusedBeforeItIsMade) {
  // Whether this machine has the memory for `n` particles (else the memory limit refuses first).
  auto roomy = [](double n) {
    return limits::memory_limit_bytes() >= limits::scene_bytes(std::uint64_t(n), std::uint64_t(n), 64, false);
  };
  constexpr double big = 131.0 * 131 * 131;
  json ten = base_scene();
  for (int b = 0; b < 10; ++b) ten["blocks"].push_back(big_block("boundary"));
  // Blocks 0 and 1 are the base's; the fifth big one (blocks[6]) crosses 10 million.
  if (roomy(4 * big))
    expect_refused(ten, {"s.json: blocks[6]: brings the scene to 1.12e+07 particles in the simulation",
                         "over the limit of 10000000", "Resource limits", "use a larger spacing or smaller shapes"});
  else
    expect_refused(ten, {"s.json: blocks[", "the scene needs about"});
  // Blocks under the limit and an increment that takes the sum over it: refused at the increment,
  // before the blocks are made.
  json sum = base_scene();
  for (int b = 0; b < 4; ++b) sum["blocks"].push_back(big_block("boundary"));
  sum["tool"]["events"] = json::parse(R"([{"t": 0.5, "dispense": {"volume": 1e-6, "at": [0, 0, 0.1]}},
                                          {"t": 0.6, "dispense": {"volume": 0.03, "at": [0, 0, 0.1], "spacing": 0.002}}])");
  if (roomy(4 * big))
    expect_refused(sum, {"s.json: tool.events[1].dispense.volume: brings the scene to", "give a smaller volume"});
  // A 2 KB file asking for 1e12 m^3, or an infinite volume's worth of particles.
  json huge = base_scene();
  huge["tool"]["events"] = json::parse(R"([{"t": 0.5, "dispense": {"volume": 1e12, "at": [0, 0, 0.1]}}])");
  expect_refused(huge, {"tool.events[0].dispense.volume", "over the limit of 10000000"});
  huge["tool"]["events"][0]["dispense"]["volume"] = 1e300;
  expect_refused(huge, {"tool.events[0].dispense.volume", "over the limit of 10000000"});
  // Memory: with 1024 bonds a particle takes about 5 KB: 7 million would need about 35 GiB.
  json bonds = base_scene();
  bonds["simulation"]["max_bonds_per_particle"] = 1024;
  for (int b = 0; b < 3; ++b) bonds["blocks"].push_back(big_block("material"));
  expect_refused(bonds, {"s.json: blocks[", "the scene needs about",
                         fmt::format("over the {:.3g} GiB a scene may take",
                                     double(limits::memory_limit_bytes()) / double(1 << 30))});
  // Events: thousands of them, each holding its candidate sites, are refused by their count.
  json many = base_procedure();
  for (int e = 1; e < 20000; ++e)
    many["events"].push_back({{"t", 0.0}, {"dispense", {{"volume", 1}, {"at", {0, 0, -2}}}}});
  expect_refused(many, {"p.json: events: 20000 events, over the limit of 1000 per file"}, true);
  json scene_many = base_scene();
  scene_many["tool"]["events"] = json::array();
  for (int e = 0; e < 1001; ++e)
    scene_many["tool"]["events"].push_back({{"t", 0.5}, {"switch_tool", {{"name", "ball_burnisher"}}}});
  expect_refused(scene_many, {"tool.events: 1001 events, over the limit of 1000"});
  // The library's increment refuses to be made, instead of looping over (R / s)^3 lattice points.
  EXPECT_THROW((void)material_increment({}, 1e12, 1e-3, 1e-6, Material{1, 10, 1000, 0}), std::invalid_argument);
  EXPECT_GE(increment_points_bound(1e-6, 1e-3), double(material_increment({}, 1e-6, 1e-3, 1e-6, {1, 10, 1000, 0}).size()));
}

// The memory estimate is an upper one for either solver (--solver may choose the other after the
// scene is built): a real state takes no more than it says.
TEST(Robustness, TheMemoryEstimateBoundsARealState) {
  for (const Solver solver : {Solver::iisph, Solver::paper}) {
    DentalSceneParams dp;
    dp.solver = solver;
    const Scene sc = default_dental_scene(dp);
    State st = make_state(sc);
    const std::unique_ptr<StepSolver> s = make_solver(sc.model.solver);
    s->step(sc.model, st, {});  // the step's scratch allocated, the solver's own with it
    const std::size_t held = st.bytes_per_particle() + s->bytes() / st.size();
    const std::uint64_t estimate = limits::state_bytes_per_particle(sc.model.max_bonds_per_particle, sc.model.neighbour_skin > 0);
    std::printf("%s: estimate %llu bytes a particle, the state and its solver %zu\n", solver_name(solver),
                (unsigned long long)estimate, held);
    EXPECT_GE(estimate, held) << solver_name(solver);
    EXPECT_LE(estimate, 3 * held) << solver_name(solver) << ": an estimate, not a blanket refusal";
  }
  EXPECT_EQ(limits::memory_problem(1000, 1000, 64, true, limits::max_scene_bytes), "");
  EXPECT_NE(limits::memory_problem(1000, 20'000'000, 64, true, std::uint64_t(1) << 30).find("over the 1 GiB"),
            std::string::npos);
  EXPECT_LE(limits::memory_limit_bytes(), limits::max_scene_bytes);
}

// `material-test depth-of-cure --spacing 0.02 --mould-length 50` (both in their documented ranges)
// allocated until std::bad_alloc at 3.3 GB: now counted first and refused naming both options, and
// under an address-space limit (ulimit -v of 2 GB) what fits the machine but not the process is
// refused too, never a bad_alloc.
TEST(Robustness, ADepthOfCureMouldTooLargeToHoldIsRefusedBeforeItIsMade) {
  expect_cli_refused("material-test depth-of-cure --spacing 0.02 --mould-length 50",
                     {"7.86e+07 particles", "over the limit of 10000000", "--spacing", "--mould-length"});
  if (kUnderAddressSanitizer)
    GTEST_SKIP() << "the mould over the particle limit is refused (above); under ulimit -v AddressSanitizer cannot "
                    "reserve its shadow memory and aborts at start, so the address-space limit is tested in the other "
                    "builds";
  const testing::CliResult r = testing::run_command(
      "sh -c 'ulimit -v 2000000 && exec " + std::string(DENTSPH_CLI) +
          " material-test depth-of-cure --spacing 0.1 --mould-length 50'",
      kCliTimeout);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("a scene may take here"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("bad_alloc"), std::string::npos) << r.output;
}

// ---- class 7: lost work --------------------------------------------------------------------------

// `run --realtime --out DIR` with an unwritable DIR ran the whole session and failed at its end,
// losing the recording; `--out ""` exited 0 and wrote nothing.
TEST(Robustness, AnOutputFolderThatCannotBeWrittenIsRefusedBeforeTheRunStarts) {
  const fs::path blocker = write("not_a_folder", "a file where the output folder should go");
  for (const fs::path& out : {blocker, blocker / "sub"}) {
    for (const std::string run : {"run -q --realtime --duration 3 --threads 1", "run -q --steps 20 --threads 1"}) {
      const testing::CliResult r = dentsph_cli(run + " --out " + out.string(), kCliTimeout);
      EXPECT_EQ(r.code, 2) << run << "\n" << r.output;
      EXPECT_NE(r.output.find("--out " + out.string()), std::string::npos) << r.output;
      EXPECT_NE(r.output.find("nothing was run"), std::string::npos) << r.output;
      EXPECT_EQ(r.output.find(" steps ("), std::string::npos) << "the run started:\n" << r.output;
    }
  }
  expect_cli_refused("run -q --steps 5 --out \"\"", {"--out \"\"", "an empty path writes nothing"});
  expect_cli_refused("run -q --realtime --duration 1 --out \"\"", {"--out \"\"", "an empty path writes nothing"});
  // A folder that can be made is made, and the run writes into it.
  const fs::path fresh = dir() / "made" / "by" / "run";
  const testing::CliResult ok = dentsph_cli("run -q --steps 5 --threads 1 --out " + fresh.string(), kCliTimeout);
  EXPECT_EQ(ok.code, 0) << ok.output;
  EXPECT_TRUE(fs::is_regular_file(fresh / "summary.json"));
  for (const auto& e : fs::directory_iterator(fresh))
    EXPECT_EQ(e.path().filename().string().find(".dentsph_write_check"), std::string::npos) << "the check's file is removed";
}

// ---- class 8: messages ---------------------------------------------------------------------------

bool has_long_number(const std::string& text) {
  int digits = 0;
  for (char c : text) {
    digits = std::isdigit(static_cast<unsigned char>(c)) ? digits + 1 : 0;
    if (digits >= 20) return true;
  }
  return false;
}

// A cavity width of 1e308 printed a 310-digit width and advised a rounding of -8.3e307 mm; `run`
// on a missing scene exited 105 (CLI11's code, where the README says 2); `replay` of a recording
// holding a NaN pose said "1 tool forces differ (largest difference 0 N)".
TEST(Robustness, MessagesAreShortAndTrue) {
  for (const std::string option : {"--cavity-width", "--cavity-length", "--cavity-depth", "--cavity-rounding"}) {
    const testing::CliResult r = dentsph_cli("run -q --steps 1 " + option + " 1e308", kCliTimeout);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(option + " 1e+308"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("< 50 mm, got 1e+308"), std::string::npos) << r.output;
    EXPECT_FALSE(has_long_number(r.output)) << r.output;
    EXPECT_LT(r.output.size(), 400u) << r.output;
  }
  json cavity = {{"name", "wide"}, {"cavity", {{"width", 1e308}}}};
  expect_refused(cavity, {"s.json: cavity.width: must be > 0 mm and < 50 mm, got 1e+308", "e.g. 3"});
  EXPECT_FALSE(has_long_number(refusal(cavity)));
  // The tooth library refuses absurd magnitudes first too, with a short message.
  for (real CavityParams::*member : {&CavityParams::width, &CavityParams::rounding, &CavityParams::min_wall}) {
    ToothSpec spec;
    spec.cavity.*member = 1e308;
    try {
      (void)prepare_tooth(spec);
      ADD_FAILURE() << "accepted";
    } catch (const CavityError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("must be under 50 mm (no tooth is that large)"), std::string::npos) << msg;
      EXPECT_FALSE(has_long_number(msg)) << msg;
    }
  }

  // A missing scene file: exit 2, naming it.
  const testing::CliResult missing = dentsph_cli("run -q " + (dir() / "no_such_scene.json").string(), kCliTimeout);
  EXPECT_EQ(missing.code, 2) << missing.output;
  EXPECT_NE(missing.output.find("no_such_scene.json"), std::string::npos) << missing.output;
  EXPECT_EQ(dentsph_cli("run --no-such-option", kCliTimeout).code, 2);
  EXPECT_EQ(dentsph_cli("run --help", kCliTimeout).code, 0);

  // A recording holding a NaN pose is refused when it is read, naming the file, the line and the
  // column, instead of replaying NaN forces into a comparison.
  Recording rec;
  rec.mode = "coupling";
  rec.haptic_rate_hz = 1000;
  const Scene sc = default_dental_procedure();
  for (std::uint64_t k = 0; k < 3; ++k) rec.steps.push_back({k, 0.001 * double(k), sc.tool.at(0), {}});
  const fs::path good = dir() / "recording_ok";
  save_recording(good, rec);
  const testing::CliResult replayed = dentsph_cli("replay " + good.string(), kCliTimeout);
  EXPECT_NE(replayed.output.find("replayed 3 steps"), std::string::npos) << replayed.output;
  for (const auto& [column, value, phrase] :
       {std::tuple{3, "nan", "column 3 (x): 'nan' is not a finite number"},
        std::tuple{7, "inf", "column 7 (qx): 'inf' is not a finite number"},
        std::tuple{1, "-1", "column 1 (step): -1 is not a whole number"},
        std::tuple{6, "0.5", "columns 6 to 9 (qw, qx, qy, qz): the orientation has length"}}) {
    const fs::path bad = dir() / fmt::format("recording_bad_{}", column);
    save_recording(bad, rec);
    std::vector<std::string> lines;
    {
      std::ifstream in(bad / "steps.csv");
      for (std::string l; std::getline(in, l);) lines.push_back(l);
    }
    std::vector<std::string> cells;
    std::stringstream ss(lines[2]);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    cells[std::size_t(column - 1)] = value;
    lines[2] = fmt::format("{}", fmt::join(cells, ","));
    std::ofstream out(bad / "steps.csv");
    for (const std::string& l : lines) out << l << "\n";
    out.close();
    try {
      (void)load_recording(bad);
      ADD_FAILURE() << "accepted " << value;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("steps.csv: line 3, " + std::string(phrase)), std::string::npos) << e.what();
    }
    const testing::CliResult r = dentsph_cli("replay " + bad.string(), kCliTimeout);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find(phrase), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("differ"), std::string::npos) << r.output;
  }
  // session.json's numbers are checked too.
  const fs::path bad_session = dir() / "recording_bad_session";
  save_recording(bad_session, rec);
  std::ofstream(bad_session / "session.json") << R"({"mode": "coupling", "dispense_volume": -1})";
  EXPECT_THROW((void)load_recording(bad_session), std::runtime_error);
  // And its solver's name.
  std::ofstream(bad_session / "session.json") << R"({"mode": "coupling", "solver": "fast"})";
  try {
    (void)load_recording(bad_session);
    ADD_FAILURE() << "accepted solver \"fast\"";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("session.json: solver: expected \"paper\" or \"iisph\", got \"fast\""),
              std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dentsph
