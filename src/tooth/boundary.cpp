// sample_boundary(): layers of evenly spaced points on the prepared surface around the cavity.
//
// Layer k is the level set {distance = -k s} of the prepared tooth's signed distance (exact
// inside the prepared tooth, so the layers are true offsets of the surface). Its points come
// from a lattice of pitch s / 3 in the tooth frame: lattice points within half a diagonal of
// the level set are projected onto it along the gradient, then thinned greedily in lattice
// order to a maximal Poisson-disk set of radius 0.9 s. On the flat floor and the walls this
// reproduces the frame-aligned square lattice of pitch s; on curved parts it stays even (no two
// points closer than 0.9 s), but a greedy Poisson-disk set leaves holes up to about a spacing
// wide there. The surface layer (layer 0), the one the paste touches, is closed by a second pass:
// under every projected lattice point farther than 0.7 s from every point taken, a point is added
// 0.75 s deep (labelled layer 0). The scanned molars' walls had such holes in their upper thirds,
// where paste at rest crept into the tooth (slowly, at zero pressure, drawn by its bonds to the
// lining and by gravity).
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <functional>
#include <cmath>
#include <tuple>
#include <vector>

#include "dentsph/tooth.hpp"
#include "tooth/disk_set.hpp"
#include "tooth/geometry.hpp"

namespace dentsph {

namespace {

constexpr int refine = 3;        // lattice points per spacing
constexpr real exclusion = 0.9;  // Poisson-disk radius, in spacings
// The surface layer's widest hole, in spacings: just under the square lattice's own (s / sqrt 2,
// the centre of a lattice square), so that flat walls get no extra points.
constexpr real hole = 0.7;
// How deep under a hole of the surface layer the point that closes it goes, in spacings (towards
// the next layer): 0 (on the surface) leaked nothing on the scans but pushed the paste off the
// built-in crown's walls (fill 0.964, 3 voids); 0.5 left a void in the crown and a particle in
// FDI 46's Class II; 0.75 and 1 did neither.
constexpr real closing_depth = 0.75;
constexpr int newton_steps = 6;
constexpr real on_surface = 1e-6;  // projection tolerance, in spacings

// The layers' source: a 1-Lipschitz signed distance whose level sets k * step (k = 0 .. layers
// - 1) are the layers, and a 1-Lipschitz region distance: layer k keeps the points where it is
// at most margin + k |step| and `keep` (if any) agrees.
struct LevelSets {
  std::function<SurfacePoint(const Vec3&)> surface;
  real step = 0;
  std::function<real(const Vec3&)> region;
  std::function<bool(const Vec3&, const SurfacePoint&)> keep;
};

BoundarySamples sample_layers(const PreparedTooth& tooth, const BoundaryParams& params, real margin,
                              const LevelSets& src);

}  // namespace

BoundarySamples sample_boundary(const PreparedTooth& tooth, const BoundaryParams& params) {
  const real s = params.spacing;
  if (!(s > 0) || !std::isfinite(s))
    throw std::invalid_argument(
        fmt::format("sample_boundary: spacing = {} m must be > 0 (the material spacing)", s));
  if (params.layers < 1 || params.layers > 16)
    throw std::invalid_argument(
        fmt::format("sample_boundary: layers = {} must be in [1, 16]", params.layers));
  const real margin = params.margin > 0 ? params.margin : 2 * s;
  return sample_layers(tooth, params, margin,
                       {[&](const Vec3& p) { return tooth.distance(p); }, -params.spacing,
                        [&](const Vec3& p) { return tooth.cavity_distance(p).distance; }, {}});
}

BoundarySamples matrix_band(const PreparedTooth& tooth, real spacing) {
  if (tooth.params().kind != CavityClass::class_2)
    throw std::invalid_argument("matrix_band: the cavity is Class I: it has no proximal box to close");
  BoundaryParams bp;
  bp.spacing = spacing;
  const Vec3 z = tooth.frame().z;
  // On the original contour and one spacing outside it, where the proximal box cut it away and
  // the contour faces sideways (up to the marginal ridge's crest), plus a margin around.
  return sample_layers(tooth, bp, 2 * spacing,
                       {[&](const Vec3& p) { return tooth.tooth().query(p); }, spacing,
                        [&](const Vec3& p) { return tooth.proximal_box_distance(p); },
                        [z](const Vec3&, const SurfacePoint& sp) { return std::fabs(dot(sp.normal, z)) < 0.5; }});
}

namespace {

// A coarse cell of edge s centred on s (i, j, k) of the tooth frame, with the prepared tooth's and
// the region's distances at its centre; it holds refine^3 points of the fine lattice of pitch
// s / refine, indexed (refine i + a, refine j + b, refine k + d).
struct Coarse {
  std::int64_t i, j, k;
  real dp, dc;  // prepared-tooth and cavity distances at the centre
};

// A fine lattice point projected onto a layer's level set.
struct Candidate {
  std::int64_t i, j, k;  // fine lattice index, the thinning order
  Vec3 p;
  Vec3 normal;  // the distance's gradient at p
};

// The coarse cells over the removed tooth's box (grown by the band and the layers) that can hold
// layer points: their centre within half a diagonal of the layers' level range and of the band.
std::vector<Coarse> cells_near_layers(const PreparedTooth& tooth, const BoundaryParams& params, real margin,
                                      const LevelSets& src) {
  const real s = params.spacing;
  const ToothFrame& f = tooth.frame();
  const Bounds local = tooth::box_of_corners(tooth.cavity_bounds(), [&f](const Vec3& p) { return f.to_local(p); });
  const real grow = margin + (params.layers + 1) * s;
  const auto lo = [&](real v) { return std::int64_t(std::floor((v - grow) / s)); };
  const auto hi = [&](real v) { return std::int64_t(std::ceil((v + grow) / s)); };
  const std::int64_t i0 = lo(local.min.x), i1 = hi(local.max.x), j0 = lo(local.min.y),
                     j1 = hi(local.max.y), k0 = lo(local.min.z), k1 = hi(local.max.z);
  const real half_diag = s * std::sqrt(real(3)) / 2;
  const real deepest = params.layers * s;
  const real level_lo = std::min(real(0), (params.layers - 1) * src.step),
             level_hi = std::max(real(0), (params.layers - 1) * src.step);
  // Both distances are 1-Lipschitz, so blocks of 4^3 cells are ruled out at once from their
  // centre: far from the surface a distance query costs several times more than near it.
  auto relevant = [&](real dp, real dc, real slack) {
    return dc <= margin + deepest + half_diag + slack && dp <= level_hi + half_diag + slack &&
           dp >= level_lo - half_diag - slack;
  };
  constexpr std::int64_t block = 4;
  const real block_slack = s * block * std::sqrt(real(3)) / 2;
  struct Block {
    std::int64_t i, j, k;
  };
  std::vector<Block> blocks;
  for (std::int64_t bk = k0; bk <= k1; bk += block)
    for (std::int64_t bj = j0; bj <= j1; bj += block)
      for (std::int64_t bi = i0; bi <= i1; bi += block) blocks.push_back({bi, bj, bk});
  // Queries are independent: threads fill their own lists, merged in thread order (the layers'
  // candidates are sorted afterwards, so the result does not depend on the thread count).
  std::vector<std::vector<Coarse>> found{std::size_t(omp_get_max_threads())};
#pragma omp parallel
  {
    auto& mine = found[std::size_t(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 4)
    for (std::size_t n = 0; n < blocks.size(); ++n) {
      const auto [bi, bj, bk] = blocks[n];
      const real mid = (block - 1) / 2.0;
      const Vec3 centre = f.to_world(Vec3{bi + mid, bj + mid, bk + mid} * s);
      const real bdc = src.region(centre);
      if (bdc > margin + deepest + half_diag + block_slack) continue;
      if (!relevant(src.surface(centre).distance, bdc, block_slack)) continue;
      for (std::int64_t k = bk; k < std::min(bk + block, k1 + 1); ++k)
        for (std::int64_t j = bj; j < std::min(bj + block, j1 + 1); ++j)
          for (std::int64_t i = bi; i < std::min(bi + block, i1 + 1); ++i) {
            const Vec3 p = f.to_world(Vec3{real(i), real(j), real(k)} * s);
            const real dc = src.region(p);
            if (dc > margin + deepest + half_diag) continue;
            const real dp = src.surface(p).distance;
            if (relevant(dp, dc, 0)) mine.push_back({i, j, k, dp, dc});
          }
    }
  }
  std::vector<Coarse> coarse;
  for (auto& v : found) coarse.insert(coarse.end(), v.begin(), v.end());
  return coarse;
}

// The fine lattice points of the cells near the level set `level` projected onto it (Newton on the
// distance function) and kept where they lie within `band` of the region and `keep` agrees; in
// lattice order.
std::vector<Candidate> layer_candidates(const std::vector<Coarse>& coarse, const ToothFrame& f, real s, real level,
                                        real band, const LevelSets& src) {
  const real c = s / refine;
  const real half_diag = s * std::sqrt(real(3)) / 2;
  const real fine_reach = c * std::sqrt(real(3)) / 2;
  const real centre = c * (refine - 1) / 2.0;  // fine points sit symmetrically in the cell
  std::vector<const Coarse*> cells;
  for (const Coarse& q : coarse)
    if (std::fabs(q.dp - level) <= half_diag && q.dc <= band + half_diag) cells.push_back(&q);
  std::vector<std::vector<Candidate>> per_thread{std::size_t(omp_get_max_threads())};
#pragma omp parallel
  {
    auto& mine = per_thread[std::size_t(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 16)
    for (std::size_t n = 0; n < cells.size(); ++n) {
      const Coarse& q = *cells[n];
      for (int d = 0; d < refine; ++d)
        for (int b = 0; b < refine; ++b)
          for (int a = 0; a < refine; ++a) {
            const Vec3 offset = Vec3{real(a), real(b), real(d)} * c - Vec3{1, 1, 1} * centre;
            // Lipschitz: skip fine points the cell centre's distance already rules out.
            if (std::fabs(q.dp - level) - norm(offset) > fine_reach) continue;
            Vec3 p = f.to_world(Vec3{real(q.i), real(q.j), real(q.k)} * s + offset);
            SurfacePoint sp = src.surface(p);
            if (std::fabs(sp.distance - level) > fine_reach) continue;
            // Newton on the distance function (|gradient| = 1): one step lands on the level
            // set unless the nearest feature changes; a few more settle creases.
            bool ok = false;
            for (int it = 0; it < newton_steps; ++it) {
              const real e = sp.distance - level;
              if (std::fabs(e) <= on_surface * s) {
                ok = true;
                break;
              }
              p -= sp.normal * e;
              sp = src.surface(p);
            }
            if (!ok || src.region(p) > band || (src.keep && !src.keep(p, sp))) continue;
            mine.push_back({refine * q.i + a, refine * q.j + b, refine * q.k + d, p, sp.normal});
          }
    }
  }
  std::vector<Candidate> cand;
  for (auto& v : per_thread) cand.insert(cand.end(), v.begin(), v.end());
  std::sort(cand.begin(), cand.end(), [](const Candidate& x, const Candidate& y) {
    return std::tie(x.k, x.j, x.i) < std::tie(y.k, y.j, y.i);
  });
  return cand;
}

BoundarySamples sample_layers(const PreparedTooth& tooth, const BoundaryParams& params, real margin,
                              const LevelSets& src) {
  const real s = params.spacing;
  const std::vector<Coarse> coarse = cells_near_layers(tooth, params, margin, src);
  BoundarySamples out;
  out.spacing = s;
  for (int layer = 0; layer < params.layers; ++layer) {
    const std::vector<Candidate> cand =
        layer_candidates(coarse, tooth.frame(), s, layer * src.step, margin + layer * s, src);
    // Thinned greedily in lattice order to a Poisson-disk set.
    DiskSet disks(exclusion * s);
    const std::size_t first = out.points.size();
    for (const Candidate& q : cand)
      if (disks.try_add(q.p)) {
        out.points.push_back(q.p);
        out.layer.push_back(layer);
      }
    // Close the holes of the surface layer: where a candidate lies farther than `hole` from
    // every point taken, a point goes under it (closing_depth, towards the next layer), which
    // stops paste sinking into the hole without pushing the paste at the surface away.
    if (layer == 0) {
      DiskSet fill(hole * s);
      for (std::size_t n = first; n < out.points.size(); ++n) fill.add(out.points[n]);
      for (const Candidate& q : cand)
        if (fill.try_add(q.p)) {
          // Where the offset along the normal would come out on the cavity's side of the surface
          // (a thin or folded part), the point stays on the surface.
          const Vec3 under = q.p + q.normal * (closing_depth * src.step);
          out.points.push_back(src.surface(under).distance / src.step > 0 ? under : q.p);
          out.layer.push_back(layer);
        }
    }
  }
  return out;
}

}  // namespace

}  // namespace dentsph
