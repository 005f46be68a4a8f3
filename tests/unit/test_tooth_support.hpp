// Shared helpers of the tooth tests: where the real scans are, small meshes built in code, mesh
// files written in each format, and brute-force references.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "dentsph/tooth.hpp"

namespace dentsph::testing {

namespace fs = std::filesystem;

// The real molars (tests run from the project root; the data sit beside the project).
inline const fs::path data_dir = "../shared/data";
inline const fs::path molar_36 = data_dir / "molar_FDI36_lower_left_first.stl";
inline const fs::path molar_46 = data_dir / "molar_FDI46_lower_right_first.stl";
inline const fs::path molar_axes = data_dir / "molar_axes_mandible.json";

inline bool have_data() {
  return fs::exists(molar_36) && fs::exists(molar_46) && fs::exists(molar_axes);
}
#define DENTSPH_NEED_DATA()                                                                      \
  do {                                                                                           \
    if (!::dentsph::testing::have_data())                                                        \
      GTEST_SKIP() << "the real molar scans are absent (expected in ../shared/data relative to " \
                      "the project root, working directory "                                     \
                   << ::std::filesystem::current_path() << "): skipped";                         \
  } while (0)

inline fs::path temp_dir(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("dentsph_tooth_" + name + "_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

// Box [lo, hi] as 8 shared vertices and 12 outward triangles.
inline TriMesh box_mesh(Vec3 lo, Vec3 hi) {
  TriMesh m;
  for (int k = 0; k < 8; ++k)
    m.vertices.push_back({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
  // Quads counter-clockwise seen from outside; vertex index = x + 2 y + 4 z.
  const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : quads) {
    m.triangles.push_back({std::uint32_t(q[0]), std::uint32_t(q[1]), std::uint32_t(q[2])});
    m.triangles.push_back({std::uint32_t(q[0]), std::uint32_t(q[2]), std::uint32_t(q[3])});
  }
  return m;
}
inline TriMesh cube_mesh(real side) { return box_mesh({0, 0, 0}, {side, side, side}); }

// The same triangles with every corner stored on its own (as STL stores them).
inline TriMesh unshared(const TriMesh& m) {
  TriMesh s;
  for (const auto& t : m.triangles) {
    const auto base = std::uint32_t(s.vertices.size());
    for (std::uint32_t i : t) s.vertices.push_back(m.vertices[i]);
    s.triangles.push_back({base, base + 1, base + 2});
  }
  return s;
}

inline TriMesh translated(TriMesh m, Vec3 d) {
  for (Vec3& v : m.vertices) v += d;
  return m;
}
inline TriMesh joined(const TriMesh& a, const TriMesh& b) {
  TriMesh m = a;
  const auto base = std::uint32_t(a.vertices.size());
  m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto t : b.triangles) m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  return m;
}

// Icosphere of radius r: the icosahedron subdivided `levels` times, projected on the sphere.
inline TriMesh icosphere(real r, int levels) {
  const real g = (1 + std::sqrt(5.0)) / 2;
  TriMesh m;
  m.vertices = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.vertices.push_back((m.vertices[a] + m.vertices[b]) / real(2));
      return mid[key] = std::uint32_t(m.vertices.size() - 1);
    };
    std::vector<std::array<std::uint32_t, 3>> next;
    for (auto t : m.triangles) {
      const std::uint32_t a = midpoint(t[0], t[1]), b = midpoint(t[1], t[2]),
                          c = midpoint(t[2], t[0]);
      next.insert(next.end(), {{t[0], a, c}, {t[1], b, a}, {t[2], c, b}, {a, b, c}});
    }
    m.triangles = std::move(next);
  }
  for (Vec3& v : m.vertices) v = v * (r / norm(v));
  return m;
}

// Unsigned distance to the nearest triangle, by trying every triangle (the BVH's reference).
inline real brute_distance(const TriMesh& m, const Vec3& p) {
  real best = std::numeric_limits<real>::infinity();
  for (const auto& t : m.triangles) {
    const Vec3 a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
    // Nearest point by projecting on the plane, else on the three edges.
    const Vec3 n = cross(b - a, c - a);
    const real nn = norm2(n);
    real d = std::numeric_limits<real>::infinity();
    if (nn > 0) {
      const Vec3 q = p - n * (dot(p - a, n) / nn);
      const real u = dot(cross(c - b, q - b), n), v = dot(cross(a - c, q - c), n),
                 w = dot(cross(b - a, q - a), n);
      if (u >= 0 && v >= 0 && w >= 0) d = norm(p - q);
    }
    for (auto [e0, e1] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
      const Vec3 e = e1 - e0;
      const real s = std::clamp(dot(p - e0, e) / norm2(e), real(0), real(1));
      d = std::min(d, norm(p - (e0 + e * s)));
    }
    best = std::min(best, d);
  }
  return best;
}

// Inside by ray parity along an irrational direction (the independent reference).
inline bool parity_inside(const TriMesh& m, const Vec3& p) {
  const Vec3 d = Vec3{0.5377, 0.8312, 0.1421} / norm(Vec3{0.5377, 0.8312, 0.1421});
  int crossings = 0;
  for (const auto& t : m.triangles) {
    const Vec3 a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
    const Vec3 e1 = b - a, e2 = c - a, q = cross(d, e2);
    const real det = dot(e1, q);
    if (std::fabs(det) < 1e-30) continue;
    const Vec3 s = p - a;
    const real u = dot(s, q) / det;
    const Vec3 r = cross(s, e1);
    const real v = dot(d, r) / det, tt = dot(e2, r) / det;
    crossings += u >= 0 && v >= 0 && u + v <= 1 && tt > 0;
  }
  return crossings % 2 == 1;
}

// Mesh files in millimetres (coordinates in metres times `scale`).
inline void write_ascii_stl(const fs::path& f, const TriMesh& m, real scale = 1e3) {
  std::ofstream o(f);
  o.precision(9);
  o << "solid test\n";
  for (const auto& t : m.triangles) {
    o << " facet normal 0 0 0\n  outer loop\n";
    for (std::uint32_t i : t)
      o << "   vertex " << m.vertices[i].x * scale << ' ' << m.vertices[i].y * scale << ' '
        << m.vertices[i].z * scale << '\n';
    o << "  endloop\n endfacet\n";
  }
  o << "endsolid test\n";
}
inline void write_binary_stl(const fs::path& f, const TriMesh& m, real scale = 1e3) {
  std::ofstream o(f, std::ios::binary);
  char header[80] = "dentsph test cube";  // must not start with "solid": that reads as ASCII
  o.write(header, 80);
  const auto n = std::uint32_t(m.triangles.size());
  o.write(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : m.triangles) {
    float rec[12] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      rec[3 + 3 * k] = float(m.vertices[t[k]].x * scale);
      rec[4 + 3 * k] = float(m.vertices[t[k]].y * scale);
      rec[5 + 3 * k] = float(m.vertices[t[k]].z * scale);
    }
    o.write(reinterpret_cast<const char*>(rec), sizeof rec);
    const std::uint16_t attr = 0;
    o.write(reinterpret_cast<const char*>(&attr), 2);
  }
}
inline void write_obj(const fs::path& f, const TriMesh& m, real scale = 1e3) {
  std::ofstream o(f);
  o.precision(9);
  for (const Vec3& v : m.vertices)
    o << "v " << v.x * scale << ' ' << v.y * scale << ' ' << v.z * scale << '\n';
  for (const auto& t : m.triangles)
    o << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
}
inline void write_ply(const fs::path& f, const TriMesh& m, real scale = 1e3) {
  std::ofstream o(f);
  o.precision(9);
  o << "ply\nformat ascii 1.0\nelement vertex " << m.vertices.size()
    << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << m.triangles.size()
    << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Vec3& v : m.vertices)
    o << v.x * scale << ' ' << v.y * scale << ' ' << v.z * scale << '\n';
  for (const auto& t : m.triangles) o << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
}

// Every edge used by exactly two triangles, in opposite directions (closed and consistently
// oriented), checked independently of repair_mesh().
inline bool closed_and_consistent(const TriMesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  for (const auto& [e, n] : directed) {
    if (n != 1) return false;
    auto it = directed.find({e.second, e.first});
    if (it == directed.end() || it->second != 1) return false;
  }
  return true;
}

}  // namespace dentsph::testing
