// The command line refuses bad input with a clear message and a non-zero exit: broken meshes, a
// cavity that does not fit the tooth, broken procedure files. Runs the built `dentsph` binary.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "test_tooth_support.hpp"

namespace dentsph {
namespace {

namespace fs = std::filesystem;

struct Result {
  int code = -1;
  std::string output;  // stdout and stderr
};

Result dentsph_cli(const std::string& args) {
  const std::string cmd = std::string(DENTSPH_CLI) + " " + args + " 2>&1";
  Result r;
  FILE* p = popen(cmd.c_str(), "r");
  if (p == nullptr) return r;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) r.output.append(buf, n);
  const int status = pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

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

}  // namespace
}  // namespace dentsph
