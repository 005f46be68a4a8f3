// The paste's surface (dentsph/surface.hpp): OpenVDB's level set of the particles' spheres, meshed.
// On constructed particle sets with known surfaces: a lattice block (its faces half a spacing
// outside its outer particles, its volume n s^3) and a ball; the mesh is closed and wound outward;
// bad input is refused naming the problem.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "dentsph/model.hpp"
#include "dentsph/surface.hpp"
#include "io/vtk_writer.hpp"

namespace dentsph {
namespace {

constexpr real s = 0.3e-3;  // m, the dental paste's spacing

std::vector<Vec3> block(int nx, int ny, int nz) {
  std::vector<Vec3> p;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) p.push_back({i * s, j * s, k * s});
  return p;
}

// Every edge is shared by exactly two triangles, once in each direction: closed and consistently
// wound.
bool closed_and_oriented(const SurfaceMesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& t : m.triangles)
    for (int e = 0; e < 3; ++e) ++edges[{t[e], t[(e + 1) % 3]}];
  for (const auto& [e, n] : edges)
    if (n != 1 || edges.count({e.second, e.first}) == 0 || edges.at({e.second, e.first}) != 1) return false;
  return true;
}

// The volume the triangles enclose (divergence theorem): positive when wound outward.
real enclosed_volume(const SurfaceMesh& m) {
  real v = 0;
  for (const auto& t : m.triangles) v += dot(m.vertices[t[0]], cross(m.vertices[t[1]], m.vertices[t[2]])) / 6;
  return v;
}

// A block of 20 x 20 x 10 particles: its surface lies half a spacing outside its outer particles
// within a voxel (the edges rounded by the filter lie inside), the volume is the particles' n s^3
// within 1% (fitted: 0.4% over), the mesh closed and wound outward.
TEST(Surface, ALatticeBlocksFacesLieHalfASpacingOutsideItsParticles) {
  const std::vector<Vec3> p = block(20, 20, 10);
  const SurfaceMesh m = particle_surface(p, s);
  ASSERT_FALSE(m.empty());
  EXPECT_NEAR(m.voxel, s / 3, 1e-12);
  const real n_s3 = real(p.size()) * s * s * s;
  std::printf("volume / n s^3 %.4f\n", m.volume / n_s3);
  EXPECT_NEAR(m.volume / n_s3, 1.0, 0.01) << "the enclosed volume against n s^3";
  EXPECT_TRUE(closed_and_oriented(m));
  EXPECT_NEAR(enclosed_volume(m), m.volume, 1e-6 * m.volume) << "wound outward";
  Vec3 lo{1, 1, 1}, hi{-1, -1, -1};
  for (const Vec3& v : m.vertices) {
    lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
    hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
  }
  const Vec3 want_lo{-s / 2, -s / 2, -s / 2}, want_hi{19.5 * s, 19.5 * s, 9.5 * s};
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(lo[a], want_lo[a], m.voxel) << "axis " << a;
    EXPECT_NEAR(hi[a], want_hi[a], m.voxel) << "axis " << a;
  }
}

// A ball of particles (a lattice within radius R = 8 spacings): every vertex within 1.5 voxels of the
// sphere of the ball's own volume, sqrt3(3 n s^3 / 4 pi), and two balls far apart are two closed
// surfaces in one mesh.
TEST(Surface, ABallsSurfaceIsASphere) {
  std::vector<Vec3> p;
  const int r = 8;
  for (int i = -r; i <= r; ++i)
    for (int j = -r; j <= r; ++j)
      for (int k = -r; k <= r; ++k)
        if (i * i + j * j + k * k <= r * r) p.push_back({i * s, j * s, k * s});
  const SurfaceMesh m = particle_surface(p, s);
  const real R = std::cbrt(3 * real(p.size()) * s * s * s / (4 * M_PI));
  real worst = 0;
  for (const Vec3& v : m.vertices) worst = std::max(worst, std::abs(norm(v) - R));
  std::printf("worst %.3f voxels\n", worst / m.voxel);
  EXPECT_LT(worst, 1.5 * m.voxel) << "m: the furthest vertex from the sphere";
  EXPECT_TRUE(closed_and_oriented(m));
  std::vector<Vec3> two = p;
  for (const Vec3& q : p) two.push_back(q + Vec3{40 * s, 0, 0});
  const SurfaceMesh m2 = particle_surface(two, s);
  EXPECT_EQ(m2.triangles.size(), 2 * m.triangles.size()) << "two balls: twice the triangles";
  EXPECT_NEAR(m2.volume, 2 * m.volume, 1e-3 * m.volume);
}

TEST(Surface, NoParticlesIsAnEmptySurfaceAndBadInputIsRefused) {
  EXPECT_TRUE(particle_surface({}, s).empty());
  const std::vector<Vec3> one{{0, 0, 0}};
  auto refused = [&](std::vector<Vec3> p, real spacing, SurfaceParams params, const std::string& words) {
    try {
      (void)particle_surface(p, spacing, params);
      ADD_FAILURE() << "accepted: " << words;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  refused(one, 0, {}, "spacing 0 m");
  refused(one, std::nan(""), {}, "spacing nan m");
  refused({{0, std::nan(""), 0}}, s, {}, "particle 0 is not at a finite position");
  SurfaceParams p;
  p.voxels_per_spacing = 100;
  refused(one, s, p, "voxels_per_spacing 100: give 1 to 8");
  p = {};
  p.radius_per_spacing = 0.1;
  refused(one, s, p, "radius_per_spacing 0.1");
  p = {};
  p.inset_per_spacing = 0.6;
  refused(one, s, p, "inset_per_spacing 0.6: give 0 to half the radius");
  p = {};
  p.radius_per_spacing = 0.5;
  p.inset_per_spacing = 0.25;
  p.voxels_per_spacing = 1;  // spheres of a quarter voxel, which OpenVDB would leave out
  refused(one, s, p, "radius_per_spacing less inset_per_spacing is 0.25 voxels: give at least 0.5");
  p = {};
  p.smoothing = -1;
  refused(one, s, p, "smoothing -1");
}

// The paste's surface of a state: its paste (material, and paste that has set: State::is_paste) within
// the box given, finite; written as VTK polygon data.
TEST(Surface, ThePastesSurfaceIsItsMaterialsAndIsWrittenForParaView) {
  State st;
  std::vector<ParticleInit> ps;
  const Material paste{1, 10, 2000, 0};
  for (const Vec3& x : block(6, 6, 6)) ps.push_back(make_particle(Role::material, x, 1e-9, paste));
  for (const Vec3& x : block(6, 6, 6)) ps.push_back(make_particle(Role::boundary, x + Vec3{20 * s, 0, 0}, 1e-9, paste));
  Model model;
  st.add_particles(model, ps);
  const Vec3 lo{-1, -1, -1}, hi{1, 1, 1};
  const SurfaceMesh m = paste_surface(st, s, lo, hi);
  const SurfaceMesh alone = particle_surface(block(6, 6, 6), s);
  EXPECT_EQ(m.triangles.size(), alone.triangles.size()) << "the boundary block has no surface";
  for (const Vec3& v : m.vertices) EXPECT_LT(v.x, 6 * s);
  // Paste that has set (a rigid boundary particle) is paste: the second block has a surface too.
  State set = st;
  for (std::uint32_t i = 0; i < set.size(); ++i)
    if (set.role[i] == Role::boundary) set.cure.rigid[set.id[i]] = 1;
  EXPECT_EQ(paste_surface(set, s, lo, hi).triangles.size(), 2 * alone.triangles.size());
  // Paste outside the box, or not at a finite position (a diverged run's), has none; nothing thrown.
  State flung = st;
  flung.pos[0] = Vec3{50, 0, 0};
  flung.pos[1] = Vec3{0, std::nan(""), 0};
  EXPECT_NO_THROW((void)paste_surface(flung, s, lo, hi));
  EXPECT_FALSE(paste_surface(flung, s, lo, hi).empty());
  EXPECT_TRUE(paste_surface(st, s, Vec3{1, 1, 1}, Vec3{2, 2, 2}).empty()) << "no paste in that box";
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "dentsph_surface_test.vtp";
  io::write_vtp(file, m);
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  const std::string xml = text.str();
  EXPECT_NE(xml.find("<VTKFile type=\"PolyData\""), std::string::npos);
  EXPECT_NE(xml.find("NumberOfPoints=\"" + std::to_string(m.vertices.size()) + "\""), std::string::npos);
  EXPECT_NE(xml.find("NumberOfPolys=\"" + std::to_string(m.triangles.size()) + "\""), std::string::npos);
  // The appended block: positions (3 floats a vertex), connectivity (3 ints a triangle), offsets
  // (one a triangle), each after its 8-byte count; the first position is the first vertex's.
  const std::size_t start = xml.find("<AppendedData encoding=\"raw\">\n_");
  ASSERT_NE(start, std::string::npos);
  const std::size_t data = start + std::string("<AppendedData encoding=\"raw\">\n_").size();
  const std::size_t bytes = 3 * 8 + m.vertices.size() * 12 + m.triangles.size() * 16;
  ASSERT_GE(xml.size(), data + bytes);
  std::uint64_t count = 0;
  float first[3];
  std::memcpy(&count, xml.data() + data, 8);
  std::memcpy(first, xml.data() + data + 8, 12);
  EXPECT_EQ(count, m.vertices.size() * 12);
  EXPECT_FLOAT_EQ(first[0], float(m.vertices[0].x));
  EXPECT_FLOAT_EQ(first[2], float(m.vertices[0].z));
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace dentsph
