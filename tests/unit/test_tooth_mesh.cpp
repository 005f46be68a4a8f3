// Mesh loading, checks and repairs: the real molars, every file format, each repair on a cube
// built to need it, each refusal and its message, and the built-in crown.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include <fmt/format.h>

#include "test_tooth_support.hpp"

namespace dentsph {
namespace {

using namespace dentsph::testing;
constexpr real mm = 1e-3;

std::string refusal(const TriMesh& soup) {
  try {
    repair_mesh(soup, "test mesh");
  } catch (const MeshError& e) {
    return e.what();
  }
  return "(accepted)";
}
std::string load_refusal(const fs::path& f, MeshUnits units = MeshUnits::millimetres) {
  try {
    load_mesh(f, units);
  } catch (const MeshError& e) {
    return e.what();
  }
  return "(accepted)";
}

// ---- the real molars

TEST(ToothMesh, RealMolarsLoadClosedOutwardAndToothSized) {
  DENTSPH_NEED_DATA();
  struct Expect {
    fs::path file;
    std::size_t triangles;
    Vec3 extent;  // mm, from the data's README
  };
  for (const Expect& e :
       {Expect{molar_36, 43980, {13.8, 11.2, 18.0}}, Expect{molar_46, 45040, {13.6, 11.1, 17.4}}}) {
    SCOPED_TRACE(e.file.string());
    const LoadedMesh m = load_mesh(e.file);
    EXPECT_EQ(m.report.triangles_in, e.triangles);
    EXPECT_EQ(m.mesh.triangles.size(), e.triangles);  // nothing dropped
    EXPECT_EQ(m.report.dropped_degenerate + m.report.dropped_duplicate + m.report.dropped_pieces,
              0u);
    EXPECT_EQ(m.report.turned_triangles, 0u);  // the scans face outwards already
    EXPECT_TRUE(closed_and_consistent(m.mesh));
    EXPECT_GT(m.mesh.volume(), 0);
    // A closed surface of 2 V / 3 triangles per vertex (Euler, genus 0): n_t = 2 n_v - 4.
    EXPECT_EQ(m.mesh.triangles.size(), 2 * m.mesh.vertices.size() - 4);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(m.report.extent[k] / mm, e.extent[k], 0.1);
    EXPECT_GT(m.report.volume, 600 * mm * mm * mm);  // a molar: roughly 0.6 to 1.2 cm^3
    EXPECT_LT(m.report.volume, 1200 * mm * mm * mm);
  }
}

// ---- formats

TEST(ToothMesh, AsciiStlBinaryStlObjAndPlyOfACubeLoadIdentically) {
  const TriMesh cube = cube_mesh(10 * mm);
  const fs::path dir = temp_dir("formats");
  write_ascii_stl(dir / "cube_ascii.stl", cube);
  write_binary_stl(dir / "cube_binary.stl", cube);
  write_obj(dir / "cube.obj", cube);
  write_ply(dir / "cube.ply", cube);
  std::vector<std::vector<std::array<real, 3>>> corners;
  for (const char* name : {"cube_ascii.stl", "cube_binary.stl", "cube.obj", "cube.ply"}) {
    SCOPED_TRACE(name);
    const LoadedMesh m = load_mesh(dir / name);
    EXPECT_EQ(m.mesh.vertices.size(), 8u);
    EXPECT_EQ(m.mesh.triangles.size(), 12u);
    EXPECT_NEAR(m.mesh.volume(), 1000 * mm * mm * mm, 1e-15);
    EXPECT_TRUE(closed_and_consistent(m.mesh));
    EXPECT_FALSE(m.report.inside_out);
    EXPECT_EQ(m.report.turned_triangles, 0u);
    std::vector<std::array<real, 3>> c;
    for (const Vec3& v : m.mesh.vertices) c.push_back({v.x, v.y, v.z});
    std::sort(c.begin(), c.end());
    corners.push_back(c);
  }
  for (std::size_t k = 1; k < corners.size(); ++k) EXPECT_EQ(corners[k], corners[0]);
  EXPECT_EQ(corners[0].front(), (std::array<real, 3>{0, 0, 0}));
  EXPECT_NEAR(corners[0].back()[0], 10 * mm, 1e-12);  // millimetres read as such
  fs::remove_all(dir);
}

TEST(ToothMesh, UnitsScaleTheMeshAndWrongUnitsAreNamed) {
  const fs::path dir = temp_dir("units");
  // A 10 mm cube written in metres, read as millimetres: 0.01 mm across.
  write_ascii_stl(dir / "in_metres.stl", cube_mesh(10 * mm), 1.0);
  const std::string msg = load_refusal(dir / "in_metres.stl");
  EXPECT_NE(msg.find("in_metres.stl"), std::string::npos) << msg;
  EXPECT_NE(msg.find("0.01 mm across"), std::string::npos) << msg;
  EXPECT_NE(msg.find("--mesh-units m"), std::string::npos) << msg;
  EXPECT_NE(msg.find("tooth.units"), std::string::npos) << msg;
  const LoadedMesh ok = load_mesh(dir / "in_metres.stl", MeshUnits::metres);
  EXPECT_NEAR(ok.report.extent.x, 10 * mm, 1e-9);  // files hold floats
  // A 10 mm cube in millimetres read as metres: 10 m across.
  write_ascii_stl(dir / "in_mm.stl", cube_mesh(10 * mm));
  const std::string big = load_refusal(dir / "in_mm.stl", MeshUnits::metres);
  EXPECT_NE(big.find("--mesh-units mm"), std::string::npos) << big;
  fs::remove_all(dir);
}

TEST(ToothMesh, MissingEmptyAndUnreadableFilesAreRefusedByName) {
  const fs::path dir = temp_dir("bad_files");
  EXPECT_NE(load_refusal(dir / "nope.stl").find("nope.stl: no such file"), std::string::npos);
  std::ofstream(dir / "empty.stl").close();
  EXPECT_NE(load_refusal(dir / "empty.stl").find("empty.stl: is empty"), std::string::npos);
  std::ofstream(dir / "junk.obj") << "this is not a mesh\n";
  const std::string junk = load_refusal(dir / "junk.obj");
  EXPECT_NE(junk.find("junk.obj"), std::string::npos) << junk;
  EXPECT_EQ(junk.find("(accepted)"), std::string::npos) << junk;
  std::ofstream(dir / "points.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::string points = load_refusal(dir / "points.obj");
  EXPECT_NE(points.find("points.obj"), std::string::npos) << points;
  EXPECT_EQ(points.find("(accepted)"), std::string::npos) << points;
  fs::remove_all(dir);
}

// What assimp would hang on, allocate for or abort on is refused first: a PLY header without its
// end_header line (assimp 5.2 looped for ever: found by fuzz_mesh), a PLY header declaring more
// than the file holds, a face of no vertex, and formats other than STL, OBJ and PLY (by name).
TEST(ToothMesh, WhatAssimpWouldHangOrAbortOnIsRefusedFirst) {
  const fs::path dir = temp_dir("assimp_hangs");
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                             "property float z\nelement face 4\nproperty list uchar int v\n";
  std::ofstream(dir / "no_end.ply") << header << "3 1 2 3\n";
  const std::string no_end = load_refusal(dir / "no_end.ply");
  EXPECT_NE(no_end.find("no_end.ply: is not a complete PLY file (its header has no end_header line)"),
            std::string::npos) << no_end;
  std::ofstream(dir / "huge.ply") << "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\n"
                                     "property float x\nproperty float y\nproperty float z\nend_header\n\1\2\3";
  const std::string huge = load_refusal(dir / "huge.ply");
  EXPECT_NE(huge.find("huge.ply: its PLY header declares elements of at least 3e+09 bytes"), std::string::npos) << huge;
  // A face list of length 0: assimp's validation passed it and its triangulation aborted the
  // program (an assertion; found by fuzz_mesh).
  std::ofstream(dir / "empty_face.ply") << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                                           "property float y\nproperty float z\nelement face 4\n"
                                           "property list uchar int vertex_indices\nend_header\n"
                                           "0 0 0\n10 0 0\n0 10 0\n0 0 10\n3 0 2 1\n0\n3 0 3 2\n3 1 2 3\n";
  const std::string empty_face = load_refusal(dir / "empty_face.ply");
  EXPECT_NE(empty_face.find("empty_face.ply: face 1 has no vertices"), std::string::npos) << empty_face;
  std::ofstream(dir / "odd_line.ply") << "ply\nformat ascii 1.0\nehement%vertex 4\n" << header.substr(header.find("property"))
                                       << "end_header\n0 0 0\n10 0 0\n0 10 0\n0 0 10\n3 0 2 1\n";
  const std::string odd = load_refusal(dir / "odd_line.ply");
  EXPECT_NE(odd.find("odd_line.ply: line 3 of its PLY header begins with \"ehement%vertex\""), std::string::npos) << odd;
  std::ofstream(dir / "tab_end.ply") << header << "end_header\v1 0 0\n";
  const std::string tab_end = load_refusal(dir / "tab_end.ply");
  EXPECT_NE(tab_end.find("tab_end.ply: line 9 of its PLY header"), std::string::npos) << tab_end;
  // An element named by digits run into a word: assimp read the digits as its count and allocated
  // 100 GB for it (found by fuzz_mesh).
  std::ofstream(dir / "digit_name.ply") << "ply\nformat ascii 1.0\nelement 99999999999999999999vertex 4\n"
                                         << header.substr(header.find("property")) << "end_header\n0 0 0\n";
  const std::string digit_name = load_refusal(dir / "digit_name.ply");
  EXPECT_NE(digit_name.find("digit_name.ply: line 3 of its PLY header names an element that is not a plain word"),
            std::string::npos) << digit_name;
  std::ofstream(dir / "odd_name.ply") << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float!z\nend_header\n";
  const std::string odd_name = load_refusal(dir / "odd_name.ply");
  EXPECT_NE(odd_name.find("odd_name.ply: line 4 of its PLY header is not \"property TYPE NAME\""), std::string::npos)
      << odd_name;
  // An ASCII body of bytes that are not numbers (NUL bytes: the input a fuzz session stopped on with
  // the heap found corrupt in assimp's reader; docs/fuzzing.md) is refused naming its line.
  {
    std::ofstream nul(dir / "nul_body.ply", std::ios::binary);
    const std::string body = "0 0 0\n10 0 0\n0 1" + std::string(10, '\0') + "\n4 1 2 3\n";
    nul << header << "end_header\n" << body;
  }
  const std::string nul_body = load_refusal(dir / "nul_body.ply");
  EXPECT_NE(nul_body.find("nul_body.ply: line 12 of its ASCII PLY body holds a byte that is not part of a number"),
            std::string::npos) << nul_body;
  // An ASCII body is walked as its header declares it: assimp 5.2 asked for gigabytes on a body
  // that ended inside its first vertex with a number of 63 digits (found by fuzz_mesh).
  const std::string tetra = "end_header\n0 0 0\n10 0 0\n0 10 0\n0 0 10\n3 0 2 1\n3 0 1 3\n3 0 3 2\n";
  auto refused = [&](const std::string& file, const std::string& text, const std::string& message) {
    std::ofstream(dir / file) << text;
    const std::string got = load_refusal(dir / file);
    EXPECT_NE(got.find(file + ": " + message), std::string::npos) << got;
  };
  refused("long_number.ply", header + "end_header\n" + std::string(63, '7'),
          "line 10 of its ASCII PLY body holds a number of more than 32 characters");
  refused("short_body.ply", header + tetra,
          "its ASCII PLY body ends before the v of face 4 of the 4 its header declares; the file is truncated");
  refused("long_body.ply", header + tetra + "3 1 2 3\n5\n",
          "line 18 of its ASCII PLY body holds more numbers than its header declares (\"5\" after the last face)");
  refused("huge_coordinate.ply", header + "end_header\n0 0 0\n1e39 0 0\n",
          "line 11 of its ASCII PLY body holds \"1e39\" for the x of vertex 2, which is not a float number");
  refused("long_list.ply", header + tetra + "300 1 2 3\n",
          "line 17 of its ASCII PLY body holds \"300\" for the v of face 4, which is not a uchar number");
  // A binary body is walked the same way: each list's length read, the file long enough for it.
  {
    const std::string binary_header = "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\n"
                                      "property float y\nproperty float z\nelement face 4\n"
                                      "property list uchar int vertex_indices\nend_header\n";
    std::string body;
    for (const float v : {0.f, 0.f, 0.f, 10.f, 0.f, 0.f, 0.f, 10.f, 0.f, 0.f, 0.f, 10.f})
      body.append(reinterpret_cast<const char*>(&v), 4);
    for (const auto& f : {std::array<int, 3>{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}) {
      body += char(3);
      body.append(reinterpret_cast<const char*>(f.data()), 12);
    }
    auto write = [&](const std::string& file, const std::string& bytes) {
      std::ofstream(dir / file, std::ios::binary) << binary_header << bytes;
    };
    write("binary_whole.ply", body);
    EXPECT_NO_THROW((void)load_mesh(dir / "binary_whole.ply", MeshUnits::millimetres));
    // The last face's list says 200 indices where its 3 are: the file is 788 bytes short.
    std::string long_list = body;
    long_list[long_list.size() - 13] = char(200);
    write("binary_long_list.ply", long_list);
    const std::string got = load_refusal(dir / "binary_long_list.ply");
    EXPECT_NE(got.find("binary_long_list.ply: its binary PLY body ends before the vertex_indices of face 4 of the 4 its "
                       "header declares; the file is truncated"),
              std::string::npos) << got;
  }
  // The same body whole, its faces' list named as assimp reads it: accepted.
  std::ofstream(dir / "whole.ply") << header.substr(0, header.size() - 2) << "vertex_indices\n" << tetra << "3 1 2 3\n";
  EXPECT_NO_THROW((void)load_mesh(dir / "whole.ply", MeshUnits::millimetres));
  std::ofstream(dir / "cube.off") << "OFF\n8 12 0\n";
  const std::string off = load_refusal(dir / "cube.off");
  EXPECT_NE(off.find("cube.off: is not an STL, OBJ or PLY file"), std::string::npos) << off;
  // OBJ: assimp 5.2 freed memory twice on a face line of garbage indices (found by fuzz_mesh): a
  // statement it would take by its first letter, a face naming a vertex not defined before it, and
  // bytes that are not text are refused, each naming its line.
  const std::string vertices = "v 0 0 0\nv 10 0 0\nv 0 10 0\nv 0 0 10\n";
  std::ofstream(dir / "f_glued.obj") << vertices << "f444444444 4a\n";
  const std::string glued = load_refusal(dir / "f_glued.obj");
  EXPECT_NE(glued.find("f_glued.obj: line 5 begins with \"f444444444\""), std::string::npos) << glued;
  std::ofstream(dir / "far_face.obj") << vertices << "f 1 2 3\nf 1 2 5\n";
  const std::string far = load_refusal(dir / "far_face.obj");
  EXPECT_NE(far.find("far_face.obj: line 6: \"5\" names no vertex of the 4"), std::string::npos) << far;
  std::ofstream(dir / "back_face.obj") << vertices << "f -1 -2 -5\n";
  EXPECT_NE(load_refusal(dir / "back_face.obj").find("\"-5\" names no vertex"), std::string::npos);
  std::ofstream(dir / "control.obj") << vertices << "f 1 2\x01 3\n";
  EXPECT_NE(load_refusal(dir / "control.obj").find("control.obj: line 5 is not text"), std::string::npos);
  fs::remove_all(dir);
}

// A mesh of more triangles than a tooth needs is refused before assimp reads it (2 million took
// 2.4 GB and 23 s), and so is one whose loading would take more memory than the run may use: each
// counted from what the file says, a binary STL's header (the files here are sparse: 100 MB that
// take no disk), an ASCII STL's facets, a PLY header's faces, an OBJ's face lines.
TEST(ToothMesh, AMeshOfMoreTrianglesThanTheLimitOrTheMemoryIsRefusedBeforeItIsRead) {
  const fs::path dir = temp_dir("mesh_size");
  auto binary_stl = [&](const fs::path& f, std::uint32_t n) {
    {
      std::ofstream o(f, std::ios::binary);
      char head[84] = {};
      std::memcpy(head + 80, &n, 4);
      o.write(head, sizeof head);
    }
    fs::resize_file(f, 84 + 50 * std::uintmax_t(n));
  };
  binary_stl(dir / "two_million.stl", 2'000'000);
  const std::string big = load_refusal(dir / "two_million.stl");
  EXPECT_NE(big.find("two_million.stl: holds 2000000 triangles, more than the 1000000 a tooth mesh may have"),
            std::string::npos) << big;
  EXPECT_NE(big.find("decimate it"), std::string::npos) << big;
  std::ofstream(dir / "many.ply") << "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                                     "property float y\nproperty float z\nelement face 1500000\n"
                                     "property list uchar int vertex_indices\nend_header\n";
  fs::resize_file(dir / "many.ply", 40'000'000);
  EXPECT_NE(load_refusal(dir / "many.ply").find("many.ply: holds 1500000 triangles"), std::string::npos);
  // Under a memory limit of 32 MB (DENTSPH_MEMORY_LIMIT_MB) 60,000 triangles (72 MB to load) are
  // refused naming the memory; an ASCII STL's facets and an OBJ's faces are counted too.
  binary_stl(dir / "sixty_thousand.stl", 60'000);
  {
    std::ofstream o(dir / "ascii.stl");
    o << "solid s\n";
    for (int k = 0; k < 30'000; ++k)
      o << "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n";
    o << "endsolid s\n";
    std::ofstream obj(dir / "quads.obj");
    obj << "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\n";
    for (int k = 0; k < 15'000; ++k) obj << "f 1 2 3 4\n";
  }
  ASSERT_EQ(setenv("DENTSPH_MEMORY_LIMIT_MB", "32", 1), 0);
  const std::string memory = load_refusal(dir / "sixty_thousand.stl");
  const std::string ascii = load_refusal(dir / "ascii.stl");
  const std::string quads = load_refusal(dir / "quads.obj");
  ASSERT_EQ(unsetenv("DENTSPH_MEMORY_LIMIT_MB"), 0);
  EXPECT_NE(memory.find("sixty_thousand.stl: its 60000 triangles take about 68 MB to load, more than the 32 MB"),
            std::string::npos) << memory;
  EXPECT_NE(ascii.find("ascii.stl: its 30000 triangles take about 34 MB"), std::string::npos) << ascii;
  EXPECT_NE(quads.find("quads.obj: its 30000 triangles take about 34 MB"), std::string::npos) << quads;
  // Without the limit the ASCII STL is read (and refused for what it is: one triangle, many times).
  EXPECT_EQ(load_refusal(dir / "ascii.stl").find("triangles take about"), std::string::npos);
  fs::remove_all(dir);
}

// A face that names a vertex the file lacks: refused by name, before assimp's processing steps
// (which index past the vertex array: a crash, or a garbage vertex that differs from run to run).
TEST(ToothMesh, AFaceNamingAMissingVertexIsRefusedNotRead) {
  const fs::path dir = temp_dir("bad_index");
  for (int missing : {4, 7, 1000000}) {
    const fs::path f = dir / fmt::format("tetra_{}.ply", missing);
    std::ofstream(f) << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                        "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
                        "0 0 0\n10 0 0\n0 10 0\n0 0 10\n3 0 2 1\n3 0 1 3\n"
                     << "3 0 3 " << missing << "\n3 1 2 3\n";
    for (int repeat = 0; repeat < 3; ++repeat) {  // the same message every time: nothing uninitialised read
      const std::string msg = load_refusal(f);
      EXPECT_NE(msg.find(f.filename().string()), std::string::npos) << msg;
      EXPECT_EQ(msg.find("(accepted)"), std::string::npos) << msg;
      EXPECT_NE(msg.find("damaged"), std::string::npos) << msg;
      EXPECT_NE(msg.find("export it again"), std::string::npos) << msg;
    }
    EXPECT_EQ(load_refusal(f), load_refusal(f));
  }
  fs::remove_all(dir);
}

// ---- repairs

TEST(ToothMesh, DuplicateVerticesAreMergedWithinTheTolerance) {
  TriMesh soup = unshared(cube_mesh(10 * mm));  // 36 corner records for 8 corners
  soup.vertices[5] += Vec3{1e-9, -1e-9, 0};     // a nanometre off: still the same corner
  const LoadedMesh m = repair_mesh(soup, "soup");
  EXPECT_EQ(m.mesh.vertices.size(), 8u);
  EXPECT_EQ(m.report.merged_vertices, 28u);
  EXPECT_TRUE(closed_and_consistent(m.mesh));
  EXPECT_TRUE(m.report.repaired());
  EXPECT_NE(m.report.summary().find("merged 28 duplicate vertices"), std::string::npos)
      << m.report.summary();
  // 10 micrometres off is a different point: the cube is then open.
  TriMesh apart = unshared(cube_mesh(10 * mm));
  apart.vertices[5] += Vec3{10e-6, 0, 0};
  EXPECT_NE(refusal(apart).find("not closed"), std::string::npos);
}

TEST(ToothMesh, FlippedTrianglesAndInsideOutSurfacesAreTurned) {
  TriMesh one = cube_mesh(10 * mm);
  std::swap(one.triangles[7][1], one.triangles[7][2]);
  const LoadedMesh a = repair_mesh(one, "one flipped");
  EXPECT_EQ(a.report.turned_triangles, 1u);
  EXPECT_FALSE(a.report.inside_out);
  EXPECT_TRUE(closed_and_consistent(a.mesh));
  EXPECT_NEAR(a.mesh.volume(), 1000 * mm * mm * mm, 1e-15);

  TriMesh inside_out = cube_mesh(10 * mm);
  for (auto& t : inside_out.triangles) std::swap(t[1], t[2]);
  std::swap(inside_out.triangles[3][1], inside_out.triangles[3][2]);  // and one the other way
  const LoadedMesh b = repair_mesh(inside_out, "inside out");
  EXPECT_TRUE(b.report.inside_out);
  EXPECT_EQ(b.report.turned_triangles, 11u);
  EXPECT_GT(b.mesh.volume(), 0);
  EXPECT_TRUE(closed_and_consistent(b.mesh));
}

TEST(ToothMesh, DegenerateAndRepeatedTrianglesAreDropped) {
  TriMesh m = cube_mesh(10 * mm);
  m.triangles.push_back({0, 0, 5});  // two corners at one vertex
  m.triangles.push_back(m.triangles[2]);
  const LoadedMesh r = repair_mesh(m, "extras");
  EXPECT_EQ(r.report.dropped_degenerate, 1u);
  EXPECT_EQ(r.report.dropped_duplicate, 1u);
  EXPECT_EQ(r.mesh.triangles.size(), 12u);
  EXPECT_TRUE(closed_and_consistent(r.mesh));
}

TEST(ToothMesh, SmallLoosePiecesAreDroppedComparablePiecesRefused) {
  const TriMesh cube = cube_mesh(10 * mm);
  const TriMesh debris = translated(cube_mesh(0.5 * mm), {20 * mm, 0, 0});  // 0.25% of the area
  const LoadedMesh r = repair_mesh(joined(cube, debris), "with debris");
  EXPECT_EQ(r.report.dropped_pieces, 1u);
  EXPECT_EQ(r.report.dropped_piece_triangles, 12u);
  EXPECT_NEAR(r.mesh.volume(), 1000 * mm * mm * mm, 1e-15);

  const std::string two = refusal(joined(cube, translated(cube_mesh(8 * mm), {20 * mm, 0, 0})));
  EXPECT_NE(two.find("2 separate pieces"), std::string::npos) << two;
  EXPECT_NE(two.find("one tooth per file"), std::string::npos) << two;
}

// ---- refusals

TEST(ToothMesh, AMissingTriangleIsRefusedAsOpenWithTheCount) {
  TriMesh m = cube_mesh(10 * mm);
  m.triangles.pop_back();
  const std::string msg = refusal(m);
  EXPECT_NE(msg.find("test mesh: is not closed: 3 boundary edges"), std::string::npos) << msg;
  EXPECT_NE(msg.find("Close Holes"), std::string::npos) << msg;
}

TEST(ToothMesh, NonManifoldEdgesAreRefused) {
  // Two cubes sharing one edge: four triangles meet on it.
  const TriMesh a = cube_mesh(10 * mm);
  const TriMesh b = translated(cube_mesh(10 * mm), {10 * mm, 10 * mm, 0});
  const std::string msg = refusal(joined(a, b));
  EXPECT_NE(msg.find("not manifold: 1 edges shared by more than two triangles"), std::string::npos)
      << msg;
}

TEST(ToothMesh, EmptyFlatAndNonFiniteMeshesAreRefused) {
  EXPECT_NE(refusal(TriMesh{}).find("holds no triangles"), std::string::npos);
  TriMesh flat = cube_mesh(10 * mm);
  for (Vec3& v : flat.vertices) v.z = 0;  // every corner merges with another: all degenerate
  EXPECT_NE(refusal(flat).find("test mesh:"), std::string::npos);
  EXPECT_EQ(refusal(flat).find("(accepted)"), std::string::npos);
  TriMesh nan = cube_mesh(10 * mm);
  nan.vertices[3].y = std::nan("");
  EXPECT_NE(refusal(nan).find("non-finite"), std::string::npos);
  TriMesh out_of_range = cube_mesh(10 * mm);
  out_of_range.triangles[0][1] = 99;
  EXPECT_NE(refusal(out_of_range).find("refers to vertex 99"), std::string::npos);
}

// ---- built-in crown

TEST(ToothMesh, BuiltInCrownPassesTheChecksUnrepairedAndIsMolarSized) {
  const MolarCrown crown = molar_crown();
  EXPECT_FALSE(crown.report.repaired()) << crown.report.summary();
  EXPECT_TRUE(closed_and_consistent(crown.mesh));
  EXPECT_NEAR(crown.report.extent.x / mm, 11.0, 0.2);
  EXPECT_NEAR(crown.report.extent.y / mm, 10.0, 0.2);
  EXPECT_NEAR(crown.report.extent.z / mm, 7.0, 0.2);
  const Bounds b = crown.mesh.bounds();
  EXPECT_NEAR(b.min.z, 0, 1e-9);  // flat base on z = 0
  // It round-trips through a file like any scan.
  const fs::path dir = temp_dir("crown");
  write_binary_stl(dir / "crown.stl", crown.mesh);
  const LoadedMesh back = load_mesh(dir / "crown.stl");
  EXPECT_EQ(back.mesh.triangles.size(), crown.mesh.triangles.size());
  EXPECT_NEAR(back.mesh.volume(), crown.mesh.volume(), 1e-6 * crown.mesh.volume());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace dentsph
