// Output files: VTK snapshots, the .pvd index, tool_force.csv and summary.json.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include <stb/stb_image.h>

#include "dentsph/io/summary.hpp"
#include "io/preview.hpp"
#include "io/vtk_writer.hpp"
#include "support/builders.hpp"

namespace dentsph {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("dentsph_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(Vtu, HeaderAndPositionsRoundTrip) {
  Model model = make_model(testing::params_for_spacing(0.01, {0, 0, 0}, {0.1, 0.1, 0.1}));
  State st;
  const Material m{0.1, 10, 1000, 5};
  st.add_particles(model, {testing::particle(Role::material, {0.01, 0.02, 0.03}, 1e-3, m),
                           testing::particle(Role::boundary, {0.04, 0.05, 0.06}, 1e-3, m),
                           testing::particle(Role::material, {-1.5, 2.5, 1e3}, 1e-3, m)});
  const fs::path f = temp_dir("vtu") / "s.vtu";
  io::write_vtu(f, st);
  const std::string text = slurp(f);
  EXPECT_NE(text.find("NumberOfPoints=\"3\""), std::string::npos);
  for (const char* name : {"velocity", "density", "pressure", "role", "bond_count", "id", "conversion", "dose_J_per_cm2", "position"})
    EXPECT_NE(text.find(std::string("Name=\"") + name + "\""), std::string::npos) << name;
  // The first appended array is the positions (offset 0): a UInt64 byte count, then 9 doubles.
  const std::size_t start = text.find("<AppendedData encoding=\"raw\">\n_");
  ASSERT_NE(start, std::string::npos);
  const char* p = text.data() + start + std::strlen("<AppendedData encoding=\"raw\">\n_");
  std::uint64_t bytes = 0;
  std::memcpy(&bytes, p, 8);
  ASSERT_EQ(bytes, 9 * sizeof(double));
  double xyz[9];
  std::memcpy(xyz, p + 8, sizeof xyz);
  EXPECT_EQ(xyz[0], 0.01);
  EXPECT_EQ(xyz[4], 0.05);
  EXPECT_EQ(xyz[8], 1e3);
  EXPECT_EQ(text.substr(text.size() - 30).find("</VTKFile>") != std::string::npos, true);
}

TEST(Preview, ShowsMaterialAndWallsInTheirColours) {
  Model model = make_model(testing::params_for_spacing(0.01, {0, 0, 0}, {0.1, 0.1, 0.1}));
  const Material m{0.1, 10, 1000, 5};
  std::vector<ParticleInit> ps;
  for (Vec3 p : testing::lattice({0, 0, 0.01}, 0.01, 5, 5, 3)) ps.push_back(testing::particle(Role::material, p, 1e-3, m));
  for (Vec3 p : testing::lattice({-0.02, -0.02, 0}, 0.01, 9, 9, 1)) ps.push_back(testing::particle(Role::boundary, p, 1e-3, m));
  State st;
  st.add_particles(model, ps);
  const fs::path f = temp_dir("png") / "p.png";
  io::write_preview_png(f, st, {0, 0, 1}, 0.02, 200);
  int w = 0, h = 0, c = 0;
  unsigned char* px = stbi_load(f.c_str(), &w, &h, &c, 3);
  ASSERT_NE(px, nullptr);
  EXPECT_EQ(w, 404);
  EXPECT_EQ(h, 200);
  int blue = 0, sand = 0, background = 0;
  for (int i = 0; i < w * h; ++i) {
    const int r = px[3 * i], g = px[3 * i + 1], b = px[3 * i + 2];
    blue += b > r + 60 && b > g + 30;
    sand += r > b + 40 && g > b + 20;
    background += r > 240 && g > 240 && b > 240;
  }
  stbi_image_free(px);
  EXPECT_GT(blue, 2000) << "material";
  EXPECT_GT(sand, 1000) << "boundary";
  EXPECT_GT(background, 5000) << "not all covered";
}

TEST(Pvd, IndexListsEverySnapshot) {
  const fs::path d = temp_dir("pvd");
  io::PvdIndex index(d / "p.pvd");
  index.add(0.0, "particles/a.vtu");
  index.add(0.25, "particles/b.vtu");
  const std::string text = slurp(d / "p.pvd");
  EXPECT_NE(text.find("timestep=\"0.25\""), std::string::npos);
  EXPECT_NE(text.find("file=\"particles/a.vtu\""), std::string::npos);
  EXPECT_EQ(index.size(), 2u);
}

TEST(ToolForceCsv, HeaderAndRows) {
  const fs::path d = temp_dir("csv");
  {
    io::ToolForceCsv csv(d / "f.csv");
    csv.add(0.0, {{1, 2, 3}, {4, 5, 6}});
    csv.add(1e-4, {{-1, 0, 0}, {0, 0, 0.5}});
  }
  std::ifstream in(d / "f.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "t,fx,fy,fz,tx,ty,tz");
  std::getline(in, line);
  EXPECT_EQ(line, "0,1,2,3,4,5,6");
  std::getline(in, line);
  EXPECT_EQ(line, "0.0001,-1,0,0,0,0,0.5");
}

TEST(Summary, HasTheDocumentedKeys) {
  RunSummary s;
  s.steps = 10;
  s.material = 5;
  s.bonds.formed = 3;
  s.limits.acoustic = 1e-3;
  s.limits.viscous = std::numeric_limits<real>::infinity();
  const auto j = nlohmann::json::parse(io::summary_json(s));
  EXPECT_EQ(j["steps"], 10);
  for (const char* k : {"sim_time_s", "wall_time_s", "steps_per_second", "particles", "bonds", "stability"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["particles"]["material"], 5);
  EXPECT_EQ(j["bonds"]["formed"], 3);
  for (const char* k : {"current", "formed", "broken", "overflowed"}) EXPECT_TRUE(j["bonds"].contains(k)) << k;
  EXPECT_TRUE(j["stability"]["limits_s"]["viscous"].is_null()) << "infinite limits are written as null";
  EXPECT_DOUBLE_EQ(j["stability"]["limits_s"]["acoustic"].get<double>(), 1e-3);
}

}  // namespace
}  // namespace dentsph
