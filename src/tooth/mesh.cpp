// TriMesh measures and the repair report's summary line.
#include <fmt/format.h>

#include <limits>

#include "dentsph/tooth.hpp"
#include "tooth/geometry.hpp"

namespace dentsph {

Bounds TriMesh::bounds() const {
  constexpr real inf = std::numeric_limits<real>::infinity();
  Bounds b{{inf, inf, inf}, {-inf, -inf, -inf}};
  for (const Vec3& v : vertices) {
    b.min = vmin(b.min, v);
    b.max = vmax(b.max, v);
  }
  return b;
}

real TriMesh::volume() const {
  // Divergence theorem over signed tetrahedra from a vertex of the mesh (not the coordinate
  // origin): a mesh far from the origin would otherwise lose digits to cancellation.
  if (triangles.empty()) return 0;
  const Vec3 o = vertices[triangles[0][0]];
  real v6 = 0;
  for (const auto& t : triangles)
    v6 += dot(vertices[t[0]] - o, cross(vertices[t[1]] - o, vertices[t[2]] - o));
  return v6 / 6;
}

real TriMesh::area() const {
  real a2 = 0;
  for (const auto& t : triangles)
    a2 += norm(cross(vertices[t[1]] - vertices[t[0]], vertices[t[2]] - vertices[t[0]]));
  return a2 / 2;
}

bool MeshReport::repaired() const {
  return merged_vertices > 0 || dropped_degenerate > 0 || dropped_duplicate > 0 ||
         dropped_pieces > 0 || turned_triangles > 0;
}

std::string MeshReport::summary() const {
  std::string s =
      fmt::format("{}: {} triangles read, {:.2f} x {:.2f} x {:.2f} mm, {:.1f} mm^3", source,
                  triangles_in, extent.x * 1e3, extent.y * 1e3, extent.z * 1e3, volume * 1e9);
  if (!repaired()) return s + "; nothing repaired";
  s += "; repaired:";
  if (merged_vertices) s += fmt::format(" merged {} duplicate vertices,", merged_vertices);
  if (dropped_degenerate) s += fmt::format(" dropped {} degenerate triangles,", dropped_degenerate);
  if (dropped_duplicate) s += fmt::format(" dropped {} repeated triangles,", dropped_duplicate);
  if (dropped_pieces)
    s += fmt::format(" dropped {} loose pieces ({} triangles),", dropped_pieces,
                     dropped_piece_triangles);
  if (inside_out)
    s += fmt::format(" turned the inside-out surface outwards ({} triangles),", turned_triangles);
  else if (turned_triangles)
    s += fmt::format(" turned {} triangles to agree with their neighbours,", turned_triangles);
  s.pop_back();
  return s;
}

}  // namespace dentsph
