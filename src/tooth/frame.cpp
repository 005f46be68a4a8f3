// The tooth frame: from the principal axes of the solid (volume moments of the closed mesh,
// integrated exactly over signed tetrahedra, so that uneven triangle sizes do not bias it).
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "dentsph/tooth.hpp"
#include "tooth/geometry.hpp"

namespace dentsph {

using tooth::normalized;

Vec3 ToothFrame::to_local(const Vec3& world) const {
  const Vec3 d = world - origin;
  return {dot(d, x), dot(d, y), dot(d, z)};
}

Vec3 ToothFrame::to_world(const Vec3& local) const {
  return origin + x * local.x + y * local.y + z * local.z;
}

ToothFrame make_tooth_frame(const Vec3& origin, const Vec3& long_axis, const Vec3& mesial_hint) {
  const Vec3 z = normalized(long_axis);
  const Vec3 x = normalized(mesial_hint - z * dot(mesial_hint, z));
  if (norm2(z) == 0 || norm2(x) == 0)
    throw std::invalid_argument(fmt::format(
        "tooth frame: the long axis ({}, {}, {}) must be non-zero and the mesial hint ({}, {}, "
        "{}) not parallel to it",
        long_axis.x, long_axis.y, long_axis.z, mesial_hint.x, mesial_hint.y, mesial_hint.z));
  return {origin, x, cross(z, x), z};
}

namespace {

// Area of the section of the closed mesh by the plane {p : dot(p - c, n) = 0}: the crossing
// segments of the triangles, each run counter-clockwise about n (the solid on its left), summed
// with the shoelace formula.
real section_area(const TriMesh& mesh, const Vec3& c, const Vec3& n) {
  real twice = 0;
  for (const auto& t : mesh.triangles) {
    const Vec3 v[3] = {mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]};
    const real s[3] = {dot(v[0] - c, n), dot(v[1] - c, n), dot(v[2] - c, n)};
    Vec3 ends[2];
    int found = 0;
    for (int k = 0; k < 3 && found < 2; ++k) {
      const int l = (k + 1) % 3;
      if ((s[k] < 0) != (s[l] < 0)) ends[found++] = v[k] + (v[l] - v[k]) * (s[k] / (s[k] - s[l]));
    }
    if (found < 2) continue;
    Vec3 p = ends[0], q = ends[1];
    const Vec3 face = cross(v[1] - v[0], v[2] - v[0]);
    if (dot(q - p, cross(n, face)) < 0) std::swap(p, q);
    twice += dot(n, cross(p - c, q - c));
  }
  return twice / 2;
}

}  // namespace

ToothFrame find_tooth_frame(const TriMesh& mesh) {
  // Moments about a vertex of the mesh (see TriMesh::volume) of the tetrahedra (o, a, b, c):
  // volume V = det / 6, first moment V (a + b + c) / 4, second moment
  // V / 20 (a a^T + b b^T + c c^T + s s^T) with s = a + b + c.
  const Vec3 o = mesh.vertices.at(0);
  real vol = 0;
  Vec3 first;
  tooth::Mat3 second{};
  for (const auto& t : mesh.triangles) {
    const Vec3 a = mesh.vertices[t[0]] - o, b = mesh.vertices[t[1]] - o,
               c = mesh.vertices[t[2]] - o;
    const real v = dot(a, cross(b, c)) / 6;
    const Vec3 s = a + b + c;
    vol += v;
    first += s * (v / 4);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        second[i][j] += v / 20 * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + s[i] * s[j]);
  }
  if (!(vol > 0))
    throw std::invalid_argument("find_tooth_frame: the mesh encloses no volume (run repair_mesh)");
  const Vec3 mean = first / vol;
  tooth::Mat3 cov;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) cov[i][j] = second[i][j] / vol - mean[i] * mean[j];
  const auto eig = tooth::symmetric_eigen(cov);
  const Vec3 centroid = o + mean;
  Vec3 z = eig.vectors[0], x = eig.vectors[1];

  // The crown is the end with the larger sections: a molar's roots are two or three thin
  // prongs. Compare the mean section area over the outer 30% at each end.
  real lo = 1e300, hi = -1e300;
  for (const Vec3& v : mesh.vertices) {
    lo = std::fmin(lo, dot(v - centroid, z));
    hi = std::fmax(hi, dot(v - centroid, z));
  }
  constexpr int slices = 24;
  real low_end = 0, high_end = 0;
  for (int k = 0; k < slices; ++k) {
    const real f = (k + 0.5) / slices;
    if (f > 0.3 && f < 0.7) continue;
    const real a = section_area(mesh, centroid + z * (lo + f * (hi - lo)), z);
    (f < 0.5 ? low_end : high_end) += a;
  }
  if (low_end > high_end) z = -z;
  // Deterministic sign for x: its largest component positive.
  const int big = std::fabs(x.x) >= std::fabs(x.y) && std::fabs(x.x) >= std::fabs(x.z)
                      ? 0
                      : (std::fabs(x.y) >= std::fabs(x.z) ? 1 : 2);
  if (x[big] < 0) x = -x;
  return make_tooth_frame(centroid, z, x);
}

}  // namespace dentsph
