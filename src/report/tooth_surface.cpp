// The prepared tooth's surface for pictures (tooth_surface.hpp): the mesh outside the cavity and
// the cavity's boundary, triangulated by marching tetrahedra, inside the tooth.
#include "report/tooth_surface.hpp"

#include <algorithm>
#include <cmath>

#include "dentsph/mesh_normals.hpp"

namespace dentsph::report {

namespace {

// Cube corners (x fastest) and the cube's split into six tetrahedra around its diagonal 0-6.
constexpr int kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
constexpr int kTet[6][4] = {{0, 5, 1, 6}, {0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}};

Vec3 crossing(const Vec3& a, double va, const Vec3& b, double vb) {
  const double t = va / (va - vb);
  return a + (b - a) * t;
}

}  // namespace

ToothSurface tooth_surface(const PreparedTooth& tooth, double cell) {
  ToothSurface s;
  s.tooth = &tooth;
  const Bounds cb = tooth.cavity_bounds();
  const Vec3 extent = cb.max - cb.min;
  if (!(cell > 0)) cell = std::max(0.05e-3, std::max({extent.x, extent.y, extent.z}) / 40);
  const Vec3 lo = cb.min - Vec3{2 * cell, 2 * cell, 2 * cell};
  int n[3];
  for (int a = 0; a < 3; ++a) n[a] = std::max(1, int(std::ceil((extent[a] + 4 * cell) / cell)));
  auto at = [&](int i, int j, int k) { return lo + Vec3{i * cell, j * cell, k * cell}; };
  auto idx = [&](int i, int j, int k) { return (std::size_t(k) * (n[1] + 1) + std::size_t(j)) * (n[0] + 1) + std::size_t(i); };
  std::vector<double> c(std::size_t(n[0] + 1) * (n[1] + 1) * (n[2] + 1));
  for (int k = 0; k <= n[2]; ++k)
    for (int j = 0; j <= n[1]; ++j)
      for (int i = 0; i <= n[0]; ++i) c[idx(i, j, k)] = tooth.cavity_distance(at(i, j, k)).distance;

  auto add = [&](const Vec3& p0, const Vec3& p1, const Vec3& p2) {
    ToothSurface::Wall w;
    w.p = {p0, p1, p2};
    bool any_inside = false;
    for (int v = 0; v < 3; ++v) {
      w.n[v] = tooth.cavity_distance(w.p[v]).normal;
      w.tooth_distance[v] = tooth.tooth().signed_distance(w.p[v]);
      any_inside |= w.tooth_distance[v] < cell;
    }
    if (any_inside) s.walls.push_back(w);
  };
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        Vec3 p[8];
        double v[8];
        bool neg = false, pos = false;
        for (int q = 0; q < 8; ++q) {
          const int a = i + kCorner[q][0], b = j + kCorner[q][1], e = k + kCorner[q][2];
          p[q] = at(a, b, e);
          v[q] = c[idx(a, b, e)];
          (v[q] < 0 ? neg : pos) = true;
        }
        if (!neg || !pos) continue;
        for (const auto& t : kTet) {
          int in[4], out[4], ni = 0, no = 0;
          for (int q : t) (v[q] < 0 ? in[ni++] : out[no++]) = q;
          if (ni == 0 || no == 0) continue;
          auto x = [&](int a, int b) { return crossing(p[a], v[a], p[b], v[b]); };
          if (ni == 1) {
            add(x(in[0], out[0]), x(in[0], out[1]), x(in[0], out[2]));
          } else if (no == 1) {
            add(x(out[0], in[0]), x(out[0], in[1]), x(out[0], in[2]));
          } else {
            const Vec3 a = x(in[0], out[0]), b = x(in[0], out[1]), d = x(in[1], out[1]), e = x(in[1], out[0]);
            add(a, b, d);
            add(a, d, e);
          }
        }
      }

  const TriMesh& mesh = tooth.tooth().mesh();
  s.vertex_normals = vertex_normals(mesh.vertices, mesh.triangles);
  return s;
}

void draw_tooth(Canvas& canvas, const ToothSurface& s, Rgb enamel, const std::function<bool(const Vec3&)>& clip) {
  const PreparedTooth& tooth = *s.tooth;
  const TriMesh& mesh = tooth.tooth().mesh();
  const Vec3 forward = canvas.camera().forward();
  const auto outside_cavity = [&](const Vec3& p, const std::array<double, 3>&) {
    return (!clip || clip(p)) && tooth.cavity_distance(p).distance > 0;
  };
  for (const auto& t : mesh.triangles) {
    const std::array<Vec3, 3> p = {mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]};
    // Closed and outward: a triangle facing away is hidden by the front (or by the section's
    // cut face), so it is not drawn.
    if (dot(cross(p[1] - p[0], p[2] - p[0]), forward) > 0) continue;
    canvas.triangle(p, {s.vertex_normals[t[0]], s.vertex_normals[t[1]], s.vertex_normals[t[2]]}, enamel,
                    outside_cavity);
  }
  for (const ToothSurface::Wall& w : s.walls) {
    const auto in_tooth = [&](const Vec3& p, const std::array<double, 3>& b) {
      return b[0] * w.tooth_distance[0] + b[1] * w.tooth_distance[1] + b[2] * w.tooth_distance[2] < 0 &&
             (!clip || clip(p));
    };
    canvas.triangle(w.p, w.n, enamel, in_tooth);
  }
}

}  // namespace dentsph::report
