// repair_mesh(): from a triangle soup to a closed, manifold, outward mesh, or a MeshError that
// says what is wrong, where, and what to do. The order matters: merging vertices is what makes
// neighbouring triangles share edges, and loose pieces are dropped before the closedness check
// so that a scan's debris does not make the tooth itself look open.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "dentsph/tooth.hpp"
#include "tooth/disk_set.hpp"
#include "tooth/geometry.hpp"

namespace dentsph {

namespace {

using Tri = std::array<std::uint32_t, 3>;

// Vertices closer than this fraction of the bounding-box diagonal are one vertex: far above
// float round-off in a 20 mm scan (1e-7 relative), far below its triangle size (~0.1 mm).
constexpr real merge_tolerance = 1e-6;
// Loose pieces below this fraction of the main piece's area are scan debris and dropped.
constexpr real debris_fraction = 0.01;
// A tooth is 5 to 30 mm across; outside this range the units are almost surely wrong.
constexpr real min_extent = 3e-3, max_extent = 50e-3;  // m

[[noreturn]] void fail(const std::string& source, const std::string& problem,
                       const std::string& fix) {
  throw MeshError(fmt::format("{}: {}; {}", source, problem, fix));
}

std::string mm(const Vec3& p) {
  return fmt::format("({:.3f}, {:.3f}, {:.3f}) mm", p.x * 1e3, p.y * 1e3, p.z * 1e3);
}

struct DisjointSets {
  std::vector<std::uint32_t> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) { parent[find(a)] = find(b); }
};

// Maps every vertex to the first vertex within `tol` (hash grid of cell `tol`, 27 cells).
std::vector<std::uint32_t> merge_vertices(const std::vector<Vec3>& v, real tol) {
  std::unordered_map<CellKey, std::vector<std::uint32_t>, CellHash> cells;
  cells.reserve(v.size());
  std::vector<std::uint32_t> rep(v.size());
  const real tol2 = tol * tol;
  for (std::uint32_t a = 0; a < v.size(); ++a) {
    const CellKey key = cell_of(v[a], tol);
    rep[a] = a;
    for (std::int64_t di = -1; di <= 1 && rep[a] == a; ++di)
      for (std::int64_t dj = -1; dj <= 1 && rep[a] == a; ++dj)
        for (std::int64_t dk = -1; dk <= 1 && rep[a] == a; ++dk) {
          auto it = cells.find({key.i + di, key.j + dj, key.k + dk});
          if (it == cells.end()) continue;
          for (std::uint32_t b : it->second)
            if (norm2(v[a] - v[b]) <= tol2) {
              rep[a] = b;
              break;
            }
        }
    if (rep[a] == a) cells[key].push_back(a);
  }
  return rep;
}

// Undirected edges with the triangles using them, grouped.
struct HalfEdge {
  std::uint64_t key;  // (min vertex << 32) | max vertex
  std::uint32_t triangle;
  bool forward;  // the triangle runs min -> max along it
};
std::vector<HalfEdge> sorted_half_edges(const std::vector<Tri>& tris) {
  std::vector<HalfEdge> h;
  h.reserve(3 * tris.size());
  for (std::uint32_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t u = tris[t][k], v = tris[t][(k + 1) % 3];
      h.push_back({(std::min(u, v) << 32) | std::max(u, v), t, u < v});
    }
  std::sort(h.begin(), h.end(), [](const HalfEdge& a, const HalfEdge& b) {
    return a.key != b.key ? a.key < b.key : a.triangle < b.triangle;
  });
  return h;
}
template <class F>
void for_each_edge(const std::vector<HalfEdge>& h, F&& f) {  // f(first, count)
  for (std::size_t i = 0; i < h.size();) {
    std::size_t j = i;
    while (j < h.size() && h[j].key == h[i].key) ++j;
    f(i, j - i);
    i = j;
  }
}
Vec3 edge_midpoint(const std::vector<Vec3>& v, std::uint64_t key) {
  return (v[key >> 32] + v[key & 0xffffffffu]) / real(2);
}

real triangle_area(const std::vector<Vec3>& v, const Tri& t) {
  return norm(cross(v[t[1]] - v[t[0]], v[t[2]] - v[t[0]])) / 2;
}

// Keeps the piece (edge-connected set of triangles) of largest area; drops pieces under
// debris_fraction of it, refuses if another piece is larger than that.
void keep_main_piece(std::vector<Tri>& tris, const std::vector<Vec3>& v, MeshReport& r) {
  DisjointSets sets(tris.size());
  const auto h = sorted_half_edges(tris);
  for_each_edge(h, [&](std::size_t first, std::size_t n) {
    for (std::size_t k = 1; k < n; ++k) sets.unite(h[first].triangle, h[first + k].triangle);
  });
  std::unordered_map<std::uint32_t, real> area;
  for (std::uint32_t t = 0; t < tris.size(); ++t) area[sets.find(t)] += triangle_area(v, tris[t]);
  if (area.size() == 1) return;
  std::vector<std::pair<real, std::uint32_t>> pieces;
  for (auto [root, a] : area) pieces.emplace_back(a, root);
  std::sort(pieces.rbegin(), pieces.rend());
  if (pieces[1].first >= debris_fraction * pieces[0].first) {
    std::size_t big = 0;
    for (const auto& p : pieces) big += p.first >= debris_fraction * pieces[0].first;
    fail(r.source,
         fmt::format("holds {} separate pieces of comparable size (the two largest have areas "
                     "{:.1f} and {:.1f} mm^2) and {} pieces in all",
                     big, pieces[0].first * 1e6, pieces[1].first * 1e6, pieces.size()),
         "export one tooth per file, or delete the extra pieces in a mesh editor");
  }
  const std::uint32_t main = pieces[0].second;
  std::vector<Tri> kept;
  for (std::uint32_t t = 0; t < tris.size(); ++t) {
    if (sets.find(t) == main)
      kept.push_back(tris[t]);
    else
      ++r.dropped_piece_triangles;
  }
  r.dropped_pieces = pieces.size() - 1;
  tris = std::move(kept);
}

void check_closed_and_manifold(const std::vector<Tri>& tris, const std::vector<Vec3>& v,
                               const MeshReport& r) {
  const auto h = sorted_half_edges(tris);
  std::size_t open = 0, multi = 0;
  std::uint64_t open_at = 0, multi_at = 0;
  for_each_edge(h, [&](std::size_t first, std::size_t n) {
    if (n == 1 && open++ == 0) open_at = h[first].key;
    if (n > 2 && multi++ == 0) multi_at = h[first].key;
  });
  if (open > 0)
    fail(r.source,
         fmt::format("is not closed: {} boundary edges (edges of only one triangle), the first "
                     "at {}",
                     open, mm(edge_midpoint(v, open_at))),
         "close the holes (e.g. MeshLab: Filters > Remeshing > Close Holes) and export again");
  if (multi > 0)
    fail(r.source,
         fmt::format("is not manifold: {} edges shared by more than two triangles, the first at {}",
                     multi, mm(edge_midpoint(v, multi_at))),
         "remove the inner or doubled faces (e.g. MeshLab: Filters > Cleaning and Repairing > "
         "Repair non Manifold Edges) and export again");
  // Vertex-manifold: the triangles around each vertex form one fan. Two solids touching at a
  // vertex share it with two fans; the link of the vertex (its neighbours, joined by the
  // triangles' opposite edges) then has two components.
  struct Corner {
    std::uint32_t vertex, a, b;
  };
  std::vector<Corner> corners;
  corners.reserve(3 * tris.size());
  for (const Tri& t : tris)
    for (int k = 0; k < 3; ++k) corners.push_back({t[k], t[(k + 1) % 3], t[(k + 2) % 3]});
  std::sort(corners.begin(), corners.end(),
            [](const Corner& x, const Corner& y) { return x.vertex < y.vertex; });
  std::size_t pinched = 0;
  std::uint32_t pinched_at = 0;
  std::vector<std::uint32_t> ids;
  for (std::size_t i = 0; i < corners.size();) {
    std::size_t j = i;
    while (j < corners.size() && corners[j].vertex == corners[i].vertex) ++j;
    ids.clear();
    for (std::size_t k = i; k < j; ++k) {
      ids.push_back(corners[k].a);
      ids.push_back(corners[k].b);
    }
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    DisjointSets link(ids.size());
    auto local = [&](std::uint32_t x) {
      return std::uint32_t(std::lower_bound(ids.begin(), ids.end(), x) - ids.begin());
    };
    for (std::size_t k = i; k < j; ++k) link.unite(local(corners[k].a), local(corners[k].b));
    std::size_t fans = 0;
    for (std::uint32_t k = 0; k < ids.size(); ++k) fans += link.find(k) == k;
    if (fans > 1 && pinched++ == 0) pinched_at = corners[i].vertex;
    i = j;
  }
  if (pinched > 0)
    fail(r.source,
         fmt::format("is not manifold: {} vertices join separate fans of triangles (surfaces "
                     "touching at a point), the first at {}",
                     pinched, mm(v[pinched_at])),
         "split or remove the touching parts (e.g. MeshLab: Filters > Cleaning and Repairing > "
         "Repair non Manifold Vertices) and export again");
}

// Turns triangles so that every edge is run in opposite directions by its two triangles
// (breadth-first from triangle 0), then the whole surface outwards. Returns the turned count.
std::size_t orient(std::vector<Tri>& tris, const std::vector<Vec3>& v, MeshReport& r) {
  const auto h = sorted_half_edges(tris);
  // neighbour[t][k]: the triangle across t's k-th shared edge, and whether it runs the edge
  // the same way (then exactly one of the two must turn).
  struct Link {
    std::uint32_t other;
    bool same;
  };
  std::vector<std::vector<Link>> links(tris.size());
  for_each_edge(h, [&](std::size_t first, std::size_t n) {
    if (n != 2) return;
    const HalfEdge &a = h[first], &b = h[first + 1];
    links[a.triangle].push_back({b.triangle, a.forward == b.forward});
    links[b.triangle].push_back({a.triangle, a.forward == b.forward});
  });
  std::vector<int> flip(tris.size(), -1);
  std::vector<std::uint32_t> queue{0};
  flip[0] = 0;
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const std::uint32_t t = queue[q];
    for (const Link& l : links[t]) {
      const int want = flip[t] ^ int(l.same);
      if (flip[l.other] < 0) {
        flip[l.other] = want;
        queue.push_back(l.other);
      } else if (flip[l.other] != want) {
        fail(r.source,
             fmt::format("cannot be oriented (a Moebius-like surface): the triangles near {} "
                         "cannot all agree on their outside",
                         mm(v[tris[t][0]])),
             "rebuild the surface (e.g. MeshLab: Filters > Remeshing > Screened Poisson) and "
             "export again");
      }
    }
  }
  std::size_t turned = 0;
  for (std::size_t t = 0; t < tris.size(); ++t)
    if (flip[t] == 1) std::swap(tris[t][1], tris[t][2]), ++turned;
  TriMesh probe{v, tris};
  if (probe.volume() < 0) {
    for (Tri& t : tris) std::swap(t[1], t[2]);
    turned = tris.size() - turned;
  }
  return turned;
}

void check_size(const Vec3& extent, const MeshReport& r) {
  const real across = std::fmax(extent.x, std::fmax(extent.y, extent.z));
  if (across >= min_extent && across <= max_extent) return;
  const std::string problem = fmt::format(
      "is {:.4g} mm across ({:.4g} x {:.4g} x {:.4g} mm), but a tooth is 5 to 30 mm across",
      across * 1e3, extent.x * 1e3, extent.y * 1e3, extent.z * 1e3);
  std::string fix;
  if (across < min_extent && across * 1e3 >= min_extent && across * 1e3 <= max_extent)
    fix = "is the file in metres? say so: dentsph's --mesh-units m, a dental scene file's tooth.units \"m\" "
          "(MeshUnits::metres in C++)";
  else if (across > max_extent && across * 1e-3 >= min_extent && across * 1e-3 <= max_extent)
    fix = "is the file in millimetres? say so: dentsph's --mesh-units mm (the default), a dental scene file's "
          "tooth.units \"mm\" (MeshUnits::millimetres in C++)";
  else
    fix =
        "check the file's units (dentsph's --mesh-units mm or m, a dental scene file's tooth.units) and that "
        "it holds one tooth";
  fail(r.source, problem, fix);
}

}  // namespace

LoadedMesh repair_mesh(TriMesh soup, const std::string& source) {
  MeshReport r;
  r.source = source;
  r.triangles_in = soup.triangles.size();
  r.vertices_in = soup.vertices.size();
  if (soup.triangles.empty())
    fail(source, "holds no triangles",
         "export the tooth as a triangle surface (STL, OBJ or PLY), not as points or lines");
  for (std::size_t t = 0; t < soup.triangles.size(); ++t)
    for (std::uint32_t i : soup.triangles[t])
      if (i >= soup.vertices.size())
        fail(source,
             fmt::format("triangle {} refers to vertex {} of {}", t, i, soup.vertices.size()),
             "the file is damaged: export it again");
  for (std::size_t i = 0; i < soup.vertices.size(); ++i)
    if (!is_finite(soup.vertices[i]))
      fail(source, fmt::format("vertex {} has a non-finite coordinate", i),
           "the file is damaged: export it again");

  // Merge duplicates (STL stores every corner of every triangle on its own).
  const Bounds b = soup.bounds();
  const real diagonal = norm(b.max - b.min);
  if (!(diagonal > 0))
    fail(source, "has all its vertices at one point", "export the tooth's surface again");
  const auto rep = merge_vertices(soup.vertices, merge_tolerance * diagonal);
  std::vector<Tri> tris;
  tris.reserve(soup.triangles.size());
  for (const Tri& t : soup.triangles) {
    const Tri m{rep[t[0]], rep[t[1]], rep[t[2]]};
    if (m[0] == m[1] || m[1] == m[2] || m[2] == m[0]) {
      ++r.dropped_degenerate;
      continue;
    }
    tris.push_back(m);
  }
  // The same triangle twice (either winding) makes its edges look non-manifold: keep the first.
  {
    std::vector<std::pair<std::array<std::uint32_t, 3>, std::uint32_t>> keyed;
    keyed.reserve(tris.size());
    for (std::uint32_t t = 0; t < tris.size(); ++t) {
      auto k = tris[t];
      std::sort(k.begin(), k.end());
      keyed.emplace_back(k, t);
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<char> drop(tris.size(), 0);
    for (std::size_t i = 1; i < keyed.size(); ++i)
      if (keyed[i].first == keyed[i - 1].first) drop[keyed[i].second] = 1;
    std::vector<Tri> unique;
    unique.reserve(tris.size());
    for (std::uint32_t t = 0; t < tris.size(); ++t) {
      if (drop[t])
        ++r.dropped_duplicate;
      else
        unique.push_back(tris[t]);
    }
    tris = std::move(unique);
  }
  if (tris.empty())
    fail(source, "has only degenerate triangles (every triangle has two corners at one point)",
         "export the tooth's surface again");

  keep_main_piece(tris, soup.vertices, r);
  check_closed_and_manifold(tris, soup.vertices, r);
  r.turned_triangles = orient(tris, soup.vertices, r);
  r.inside_out = 2 * r.turned_triangles > tris.size();

  // Compact: keep only the vertices the triangles use, in first-use order.
  LoadedMesh out;
  std::vector<std::uint32_t> index(soup.vertices.size(), UINT32_MAX);
  for (Tri& t : tris)
    for (std::uint32_t& i : t) {
      if (index[i] == UINT32_MAX) {
        index[i] = std::uint32_t(out.mesh.vertices.size());
        out.mesh.vertices.push_back(soup.vertices[i]);
      }
      i = index[i];
    }
  out.mesh.triangles = std::move(tris);
  r.merged_vertices = 0;
  for (std::uint32_t i = 0; i < rep.size(); ++i) r.merged_vertices += rep[i] != i;

  const Bounds kb = out.mesh.bounds();
  r.extent = kb.max - kb.min;
  r.volume = out.mesh.volume();
  r.area = out.mesh.area();
  check_size(r.extent, r);
  if (!(r.volume > 1e-9 * r.area * norm(r.extent)))
    fail(source, "encloses no volume (a flat or doubled-over surface)",
         "export the tooth as a closed solid surface");
  out.report = std::move(r);
  return out;
}

}  // namespace dentsph
