// The restoration's surface graded (surface_grade.hpp; docs/assessment.md, "The surface graded").
#include "dentsph/surface_grade.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace dentsph {

namespace {

// Just below the intact surface: where a column's opening is read (m).
constexpr real kBelowTop = 5e-6;

// A world box's extent in the tooth frame (its eight corners').
Bounds local_box(const ToothFrame& f, const Bounds& b) {
  Bounds out{{1e9, 1e9, 1e9}, {-1e9, -1e9, -1e9}};
  for (int c = 0; c < 8; ++c) {
    const Vec3 l = f.to_local({(c & 1) ? b.max.x : b.min.x, (c & 2) ? b.max.y : b.min.y, (c & 4) ? b.max.z : b.min.z});
    out.min = {std::min(out.min.x, l.x), std::min(out.min.y, l.y), std::min(out.min.z, l.z)};
    out.max = {std::max(out.max.x, l.x), std::max(out.max.y, l.y), std::max(out.max.z, l.z)};
  }
  return out;
}

// Heights along the tooth's long axis, in its frame (m; z = 0 at the occlusal reference).
class Columns {
 public:
  Columns(const PreparedTooth& tooth, const SurfaceMesh& paste) : tooth_(tooth), f_(tooth.frame()) {
    const Bounds b = local_box(f_, tooth.tooth().bounds());
    above_ = b.max.z + 1e-3;
    beside_ = std::max(std::abs(b.min.x), std::abs(b.max.x)) + 1e-3;
    below_ = local_box(f_, tooth.cavity_bounds()).min.z - 1e-4;
    if (!paste.empty()) paste_.emplace(TriMesh{paste.vertices, paste.triangles});
  }

  // How far along sigma x (sigma = +1 or -1) the intact tooth, or the paste, reaches at (y, z): the
  // first surface met coming in from that side; none where nothing lies there.
  std::optional<real> intact_reach(real sigma, real y, real z) const { return reach(tooth_.tooth(), sigma, y, z); }
  std::optional<real> paste_reach(real sigma, real y, real z) const {
    if (!paste_) return std::nullopt;
    return reach(*paste_, sigma, y, z);
  }

  // The intact tooth's top at (x, y); none off the tooth.
  std::optional<real> intact_top(real x, real y) const {
    const auto t = tooth_.tooth().ray(f_.to_world({x, y, above_}), -f_.z);
    if (!t) return std::nullopt;
    return above_ - *t;
  }
  // The cavity opens at the intact surface here.
  bool opening(real x, real y, real top) const { return tooth_.in_cavity(f_.to_world({x, y, top - kBelowTop})); }
  // The cavity's floor below an opening: where the column leaves the cavity going down, bisected
  // between just under `top` (in it) and the cavity's lowest point (out of it); a cavity's column is
  // in it from the opening down to its floor (its walls flare occlusally: no undercut).
  real floor(real x, real y, real top) const {
    real hi = top - kBelowTop, lo = below_;
    for (int k = 0; k < 40 && hi - lo > 1e-8; ++k) {
      const real mid = 0.5 * (lo + hi);
      (tooth_.in_cavity(f_.to_world({x, y, mid})) ? hi : lo) = mid;
    }
    return 0.5 * (lo + hi);
  }
  // The paste's top at (x, y), looked for from `from` down; none if no paste lies under it.
  std::optional<real> paste_top(real x, real y, real from) const {
    if (!paste_) return std::nullopt;
    const Vec3 o = f_.to_world({x, y, from});
    if (paste_->inside(o)) return from;
    const auto t = paste_->ray(o, -f_.z);
    if (!t) return std::nullopt;
    return from - *t;
  }
  // The restoration's top in an opening: the highest paste within `bridge` of the column (its
  // centre and 16 points on two rings) where it lies above the floor, the floor otherwise. The
  // paste keeps a crevice narrower than a particle from the walls (the SPH gap at a wall,
  // docs/assessment.md "The wall standoff"): a column down it would read the floor.
  real restoration_top(real x, real y, real top, real band_up, real bridge) const {
    return restoration_tops(x, y, top, band_up, bridge).first;
  }
  // The same, and the column's own (the floor or the paste in the column itself, unbridged).
  std::pair<real, real> restoration_tops(real x, real y, real top, real band_up, real bridge) const {
    real own = floor(x, y, top);
    if (const auto p = paste_top(x, y, top + band_up)) own = std::max(own, *p);
    real z = own;
    for (int k = 1; k < 17; ++k) {
      const real r = k <= 8 ? bridge / 2 : bridge;
      const real a = 2 * std::numbers::pi * (k % 8) / 8 + (k > 8 ? std::numbers::pi / 8 : 0);
      if (const auto p = paste_top(x + r * std::cos(a), y + r * std::sin(a), top + band_up)) z = std::max(z, *p);
    }
    return {z, own};
  }
  // The paste lying on the intact surface at (x, y): its height above it (0: none).
  real paste_over(real x, real y, real top, real band_up) const {
    const auto p = paste_top(x, y, top + band_up);
    return p && *p > top ? *p - top : 0;
  }

 private:
  std::optional<real> reach(const MeshDistance& m, real sigma, real y, real z) const {
    const auto t = m.ray(f_.to_world({sigma * beside_, y, z}), f_.x * -sigma);
    if (!t) return std::nullopt;
    return beside_ - *t;
  }

  const PreparedTooth& tooth_;
  ToothFrame f_;
  real above_ = 0;
  real beside_ = 0;
  real below_ = 0;  // under the cavity's lowest point
  std::optional<MeshDistance> paste_;
};

// A length (m), or an area or a volume (m^2, m^3) where the field says so.
void check(const char* field, real v, bool ok) {
  if (!(std::isfinite(v) && ok))
    throw std::invalid_argument(fmt::format(
        "GradeParams::{} is {}: give a finite value in SI units within its range (surface_grade.hpp; 0 where it "
        "takes a default)",
        field, v));
}

real percentile(std::vector<real> v, real q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t k = std::size_t(std::ceil(q * real(v.size()))) - 1;
  return v[std::min(k, v.size() - 1)];
}

// The restoration's heights in columns `step` apart over the cavity's box and `pad` columns around
// it (tooth frame, m): in the opening the restoration's top, on the tooth its top or the paste
// lying on it.
struct HeightMap {
  enum Kind : signed char { opening, tooth, off };
  real x0 = 0, y0 = 0, step = 0;
  int nx = 0, ny = 0;
  std::vector<signed char> kind;
  std::vector<real> intact, top;
  std::vector<real> own;  // the opening's top in the column alone, unbridged (its pits as narrow as they are)
  std::size_t at(int i, int j) const { return std::size_t(i) * std::size_t(ny) + std::size_t(j); }
  real x(int i) const { return x0 + (i + 0.5) * step; }
  real y(int j) const { return y0 + (j + 0.5) * step; }
};

HeightMap height_map(const PreparedTooth& tooth, const Columns& cols, const GradeParams& p, real step, int pad) {
  HeightMap h;
  const Bounds box = local_box(tooth.frame(), tooth.cavity_bounds());
  h.step = step;
  h.x0 = box.min.x - pad * step;
  h.y0 = box.min.y - pad * step;
  h.nx = int(std::ceil((box.max.x - box.min.x) / step)) + 2 * pad;
  h.ny = int(std::ceil((box.max.y - box.min.y) / step)) + 2 * pad;
  const std::size_t n = std::size_t(h.nx) * std::size_t(h.ny);
  h.kind.assign(n, HeightMap::off);
  h.intact.assign(n, 0);
  h.top.assign(n, 0);
  h.own.assign(n, 0);
  const real bridge = p.bridge > 0 ? p.bridge : p.spacing;
  for (int i = 0; i < h.nx; ++i)
    for (int j = 0; j < h.ny; ++j) {
      const real x = h.x(i), y = h.y(j);
      const auto t = cols.intact_top(x, y);
      if (!t) continue;
      const std::size_t c = h.at(i, j);
      h.intact[c] = *t;
      if (cols.opening(x, y, *t)) {
        h.kind[c] = HeightMap::opening;
        std::tie(h.top[c], h.own[c]) = cols.restoration_tops(x, y, *t, p.band_up, bridge);
      } else {
        h.kind[c] = HeightMap::tooth;
        h.top[c] = h.own[c] = *t + cols.paste_over(x, y, *t, p.band_up);
      }
    }
  return h;
}

AnatomicForm anatomic_form(const HeightMap& h, const GradeParams& p) {
  AnatomicForm a;
  a.column_mm = h.step * 1e3;
  a.alpha_max_mm = p.alpha_max * 1e3;
  a.charlie_under_mm = p.charlie_under * 1e3;
  std::vector<real> abs_dev, under;
  real sum = 0, sum2 = 0;
  const real cell_mm2 = a.column_mm * a.column_mm;
  for (int i = 0; i < h.nx; ++i)
    for (int j = 0; j < h.ny; ++j) {
      const std::size_t c = h.at(i, j);
      if (h.kind[c] != HeightMap::opening) continue;
      const real d = (h.top[c] - h.intact[c]) * 1e3;
      a.column_centre_mm.push_back(Vec3{h.x(i), h.y(j), h.intact[c]} * 1e3);
      a.deviation_mm.push_back(d);
      sum += d;
      sum2 += d * d;
      abs_dev.push_back(std::abs(d));
      under.push_back(std::max<real>(0, -d));
      a.max_under_mm = std::max(a.max_under_mm, -d);
      a.max_over_mm = std::max(a.max_over_mm, d);
      if (d < -p.alpha_max * 1e3) a.under_area_mm2 += cell_mm2;
      if (d > p.alpha_max * 1e3) a.over_area_mm2 += cell_mm2;
    }
  a.columns = int(a.deviation_mm.size());
  if (a.columns == 0) {
    a.why_not = "the cavity does not open at the tooth's occlusal surface (no column of the cavity reaches it)";
    return a;
  }
  a.measured = true;
  a.mean_mm = sum / a.columns;
  a.rms_mm = std::sqrt(sum2 / a.columns);
  a.p95_abs_mm = percentile(abs_dev, 0.95);
  a.p95_under_mm = percentile(under, 0.95);
  a.band = a.p95_abs_mm <= p.alpha_max * 1e3 ? 'A' : (a.p95_under_mm > p.charlie_under * 1e3 ? 'C' : 'B');
  return a;
}

// The height map closed (dilated, then eroded) with a disc of `r` columns over the columns on the
// tooth; pits are the opening's columns more than `thr` under it, in 4-connected regions that do not
// reach out of the opening. The columns' own heights, unbridged: a pit narrower than the bridge is
// still a pit, and the crevice the paste keeps from the walls reaches the margin, so is none.
SurfaceVoids surface_voids(const HeightMap& h, const GradeParams& p, real thr) {
  SurfaceVoids v;
  const int r = std::max(1, int(std::lround(p.pit_radius / h.step)));
  v.pit_width_mm = 2 * r * h.step * 1e3;
  v.min_void_mm3 = (p.min_void > 0 ? p.min_void : p.spacing * p.spacing * p.spacing) * 1e9;
  std::vector<std::pair<int, int>> disc;
  for (int di = -r; di <= r; ++di)
    for (int dj = -r; dj <= r; ++dj)
      if (di * di + dj * dj <= r * r) disc.push_back({di, dj});
  auto pass = [&](const std::vector<real>& in, bool dilate) {
    std::vector<real> out(in.size(), 0);
    for (int i = 0; i < h.nx; ++i)
      for (int j = 0; j < h.ny; ++j) {
        if (h.kind[h.at(i, j)] == HeightMap::off) continue;
        real e = in[h.at(i, j)];
        for (const auto& [di, dj] : disc) {
          const int a = i + di, b = j + dj;
          if (a < 0 || b < 0 || a >= h.nx || b >= h.ny || h.kind[h.at(a, b)] == HeightMap::off) continue;
          e = dilate ? std::max(e, in[h.at(a, b)]) : std::min(e, in[h.at(a, b)]);
        }
        out[h.at(i, j)] = e;
      }
    return out;
  };
  const std::vector<real>& top = h.own;
  const std::vector<real> closed = pass(pass(top, true), false);
  bool any = false;
  std::vector<char> seen(top.size(), 0);
  const real cell_mm2 = h.step * h.step * 1e6;
  for (int i = 0; i < h.nx; ++i)
    for (int j = 0; j < h.ny; ++j) {
      const std::size_t c0 = h.at(i, j);
      if (h.kind[c0] != HeightMap::opening) continue;
      any = true;
      if (seen[c0] || closed[c0] - top[c0] <= thr) continue;
      // One pit: its region, its volume under the closed surface, whether it reaches the margin.
      SurfacePit pit;
      bool marginal = false;
      real weight = 0;
      std::vector<std::pair<int, int>> todo = {{i, j}};
      seen[c0] = 1;
      while (!todo.empty()) {
        const auto [a, b] = todo.back();
        todo.pop_back();
        const std::size_t c = h.at(a, b);
        const real d = closed[c] - top[c];
        pit.volume_mm3 += d * 1e3 * cell_mm2;
        pit.depth_mm = std::max(pit.depth_mm, d * 1e3);
        pit.centre_mm += Vec3{h.x(a), h.y(b), top[c]} * (1e3 * d);
        weight += d;
        const int next[4][2] = {{a + 1, b}, {a - 1, b}, {a, b + 1}, {a, b - 1}};
        for (const auto& [u, w] : next) {
          if (u < 0 || w < 0 || u >= h.nx || w >= h.ny || h.kind[h.at(u, w)] != HeightMap::opening) {
            marginal = true;
            continue;
          }
          const std::size_t n = h.at(u, w);
          if (seen[n] || closed[n] - top[n] <= thr) continue;
          seen[n] = 1;
          todo.push_back({u, w});
        }
      }
      if (marginal) continue;  // the margin's gap, graded there
      pit.centre_mm = pit.centre_mm / weight;
      if (pit.volume_mm3 < v.min_void_mm3) {
        ++v.pore_count;
        v.pore_volume_mm3 += pit.volume_mm3;
        continue;
      }
      ++v.count;
      v.volume_mm3 += pit.volume_mm3;
      v.deepest_mm = std::max(v.deepest_mm, pit.depth_mm);
      v.pits.push_back(pit);
    }
  if (!any) {
    v.why_not = "the cavity does not open at the tooth's occlusal surface";
    return v;
  }
  v.measured = true;
  return v;
}

MarginalAdaptation marginal_adaptation(const PreparedTooth& tooth, const Columns& cols, const GradeParams& p,
                                       real step) {
  MarginalAdaptation m;
  const real thr = p.step_threshold > 0 ? p.step_threshold : std::max<real>(0.15e-3, p.spacing / 2);
  const real probe = p.probe > 0 ? p.probe : p.spacing;
  const real min_site = p.min_site > 0 ? p.min_site : p.spacing;
  m.step_threshold_mm = thr * 1e3;
  m.max_sites = p.max_sites;
  m.max_site_mm = p.max_site * 1e3;
  // The region's reach: the cavity's bounds about the axis, and a millimetre.
  const Bounds box = local_box(tooth.frame(), tooth.cavity_bounds());
  const real reach = std::hypot(std::max(std::abs(box.min.x), std::abs(box.max.x)),
                                std::max(std::abs(box.min.y), std::abs(box.max.y))) +
                     1e-3;
  const auto top0 = cols.intact_top(0, 0);
  if (!top0 || !cols.opening(0, 0, *top0)) {
    m.why_not = "the cavity does not open at the occlusal surface around the tooth's long axis";
    return m;
  }
  // 0 in the opening, 1 on the tooth outside it, 2 off the tooth.
  auto where = [&](real x, real y) {
    const auto t = cols.intact_top(x, y);
    if (!t) return 2;
    return cols.opening(x, y, *t) ? 0 : 1;
  };
  const int n = p.margin_samples;
  const real dr = step / 2;
  std::vector<real> gap(std::size_t(n), 0), excess(std::size_t(n), 0);
  real last = 0;  // the last ray's margin: the next starts a few steps inside it where that is open
  for (int k = 0; k < n; ++k) {
    const real th = 2 * std::numbers::pi * k / n;
    const real ux = std::cos(th), uy = std::sin(th);
    real in = std::max<real>(0, last - 4 * dr);
    if (in > 0 && where(in * ux, in * uy) != 0) in = 0;
    real out = in + dr;
    int beyond = 0;
    for (; out <= reach; in = out, out += dr)
      if ((beyond = where(out * ux, out * uy)) != 0) break;
    if (beyond == 2 || out > reach) {  // the opening runs off the tooth's top: a proximal box
      const real r = std::min(in, reach);
      const auto t = cols.intact_top(r * ux, r * uy);
      m.point_mm.push_back(Vec3{r * ux, r * uy, t.value_or(0)} * 1e3);
      m.reading.push_back(3);
      continue;
    }
    for (int b = 0; b < 20; ++b) {  // to a millionth of the step
      const real mid = 0.5 * (in + out);
      (where(mid * ux, mid * uy) == 0 ? in : out) = mid;
    }
    const real r = 0.5 * (in + out);
    last = r;
    m.point_mm.push_back(Vec3{r * ux, r * uy, cols.intact_top(r * ux, r * uy).value_or(0)} * 1e3);
    // Inside: how far the restoration's top falls short of the intact surface.
    const real ri = std::max<real>(0, r - probe);
    if (const auto t = cols.intact_top(ri * ux, ri * uy); t && cols.opening(ri * ux, ri * uy, *t))
      gap[std::size_t(k)] = *t - cols.restoration_top(ri * ux, ri * uy, *t, p.band_up, p.bridge > 0 ? p.bridge : p.spacing);
    // Outside: paste lying on the tooth.
    const real ro = r + probe;
    if (const auto t = cols.intact_top(ro * ux, ro * uy)) excess[std::size_t(k)] = cols.paste_over(ro * ux, ro * uy, *t, p.band_up);
    const real g = gap[std::size_t(k)], e = excess[std::size_t(k)];
    m.reading.push_back(g > thr ? (e > thr && e > g ? 2 : 1) : (e > thr ? 2 : 0));
  }
  // Each point's share of the margin: half of each segment to a graded neighbour.
  std::vector<real> share(std::size_t(n), 0);
  for (int k = 0; k < n; ++k) {
    const int j = (k + 1) % n;
    if (m.reading[std::size_t(k)] == 3) ++m.open_samples;
    if (m.reading[std::size_t(k)] == 3 || m.reading[std::size_t(j)] == 3) continue;
    const real l = norm(m.point_mm[std::size_t(j)] - m.point_mm[std::size_t(k)]);
    share[std::size_t(k)] += l / 2;
    share[std::size_t(j)] += l / 2;
    m.length_mm += l;
  }
  if (m.open_samples == n) {
    m.why_not = "the cavity's outline runs off the tooth's top all round: no occlusal margin";
    return m;
  }
  m.measured = true;
  // Runs of one reading along the closed margin, from a point where the reading changes.
  int start = 0;
  for (int k = 0; k < n; ++k)
    if (m.reading[std::size_t(k)] != m.reading[std::size_t((k + n - 1) % n)]) {
      start = k;
      break;
    }
  for (int done = 0; done < n;) {
    const int kind = m.reading[std::size_t((start + done) % n)];
    MarginDefect d;
    d.kind = kind == 1 ? "gap" : "excess";
    int count = 0;
    Vec3 centre;
    for (; done < n && m.reading[std::size_t((start + done) % n)] == kind; ++done, ++count) {
      const std::size_t k = std::size_t((start + done) % n);
      d.length_mm += share[k];
      d.largest_step_mm = std::max(d.largest_step_mm, (kind == 1 ? gap[k] : excess[k]) * 1e3);
      centre += m.point_mm[k];
    }
    if (kind != 1 && kind != 2) continue;
    d.centre_mm = centre / real(count);
    (kind == 1 ? m.gap_length_mm : m.excess_length_mm) += d.length_mm;
    if (d.length_mm < min_site * 1e3) {
      m.below_resolution_mm += d.length_mm;
      continue;
    }
    m.largest_site_mm = std::max(m.largest_site_mm, d.length_mm);
    m.defects.push_back(d);
  }
  m.passes = int(m.defects.size()) <= p.max_sites && m.largest_site_mm <= p.max_site * 1e3;
  return m;
}

ProximalGrade proximal_grade(const PreparedTooth& tooth, const Columns& cols, const GradeParams& p, real step) {
  ProximalGrade g;
  const CavityParams& c = tooth.params();
  if (c.kind != CavityClass::class_2) {
    g.why_not = "a Class I cavity has no proximal surface";
    return g;
  }
  const real sigma = c.side == ProximalSide::mesial ? 1 : -1;
  g.side = c.side == ProximalSide::mesial ? "mesial" : "distal";
  const real thr = p.step_threshold > 0 ? p.step_threshold : std::max<real>(0.15e-3, p.spacing / 2);
  g.tight_mm = (p.contact_tight > 0 ? p.contact_tight : p.spacing / 2) * 1e3;
  g.open_mm = (p.contact_open > 0 ? p.contact_open : p.spacing / 2 + 0.1e-3) * 1e3;
  g.overhang_threshold_mm = (p.overhang_threshold > 0 ? p.overhang_threshold : thr) * 1e3;
  g.overhang_min_area_mm2 = (p.overhang_min_area > 0 ? p.overhang_min_area : p.spacing * p.spacing) * 1e6;
  // The box's window on the proximal surface: its width, from its gingival floor to a millimetre
  // above the occlusal reference; the neighbour a plane across x at the intact tooth's height of
  // contour in it.
  const real half = c.box_width / 2;
  real contour = -1e9, paste = -1e9;
  std::vector<Vec3> reached;  // (reach, y, z) of the intact tooth
  for (real z = -c.box_depth + step / 2; z < 1e-3; z += step)
    for (real y = -half + step / 2; y < half; y += step) {
      if (const auto r = cols.intact_reach(sigma, y, z)) {
        contour = std::max(contour, *r);
        reached.push_back({*r, y, z});
      }
      if (const auto r = cols.paste_reach(sigma, y, z)) paste = std::max(paste, *r);
    }
  // The height of contour: the farthest reach, the most occlusal of its points within 10 um of it
  // (a flat proximal face touches all along; the contact is where its occlusal end meets the
  // neighbour).
  Vec3 at{0, 0, -1e9};
  for (const Vec3& r : reached)
    if (r.x >= contour - 1e-5 && r.z > at.z) at = {sigma * r.x, r.y, r.z};
  if (contour < -1e8) {
    g.why_not = "no intact proximal surface in the box's window";
    return g;
  }
  g.measured = true;
  g.contact_mm = at * 1e3;
  g.gap_mm = (contour - paste) * 1e3;
  g.contact = g.gap_mm <= g.tight_mm ? "tight" : g.gap_mm <= g.open_mm ? "light" : "open";
  // Below the contact, down to a millimetre under the gingival floor and half a millimetre either
  // side of the box: paste standing beyond the intact contour.
  const real area = step * step * 1e6;
  for (real z = -c.box_depth - 1e-3 + step / 2; z < at.z; z += step)
    for (real y = -half - 0.5e-3 + step / 2; y < half + 0.5e-3; y += step) {
      const auto ri = cols.intact_reach(sigma, y, z), rp = cols.paste_reach(sigma, y, z);
      if (!ri || !rp) continue;
      const real out = (*rp - *ri) * 1e3;
      g.overhang_mm = std::max(g.overhang_mm, out);
      if (out > g.overhang_threshold_mm) g.overhang_area_mm2 += area;
    }
  return g;
}


}  // namespace

SurfaceGrade grade_surface(const PreparedTooth& tooth, const SurfaceMesh& paste, const GradeParams& p) {
  check("spacing", p.spacing, p.spacing > 0);
  check("column", p.column, p.column >= 0);
  check("step_threshold", p.step_threshold, p.step_threshold >= 0);
  check("probe", p.probe, p.probe >= 0);
  check("bridge", p.bridge, p.bridge >= 0);
  check("min_site", p.min_site, p.min_site >= 0);
  check("band_up", p.band_up, p.band_up > 0);
  check("alpha_max", p.alpha_max, p.alpha_max > 0);
  check("charlie_under", p.charlie_under, p.charlie_under > 0);
  check("max_site", p.max_site, p.max_site > 0);
  check("contact_tight", p.contact_tight, p.contact_tight >= 0);
  check("contact_open", p.contact_open, p.contact_open >= 0);
  check("overhang_threshold", p.overhang_threshold, p.overhang_threshold >= 0);
  check("overhang_min_area", p.overhang_min_area, p.overhang_min_area >= 0);
  check("pit_radius", p.pit_radius, p.pit_radius > 0 && p.pit_radius < 5e-3);
  check("min_void", p.min_void, p.min_void >= 0);
  if (p.margin_samples < 16 || p.margin_samples > 100000)
    throw std::invalid_argument(fmt::format("GradeParams::margin_samples is {}: give 16 to 100000", p.margin_samples));
  if (p.max_sites < 0) throw std::invalid_argument("GradeParams::max_sites is negative: give 0 or more");
  const real step = p.column > 0 ? p.column : p.spacing / 3;
  const Columns cols(tooth, paste);
  const HeightMap h = height_map(tooth, cols, p, step, int(std::ceil(p.pit_radius / step)) + 1);
  SurfaceGrade g;
  g.anatomic = anatomic_form(h, p);
  g.voids = surface_voids(h, p, p.step_threshold > 0 ? p.step_threshold : std::max<real>(0.15e-3, p.spacing / 2));
  g.margin = marginal_adaptation(tooth, cols, p, step);
  g.proximal = proximal_grade(tooth, cols, p, step);
  return g;
}

const char* anatomic_band_name(char b) {
  return b == 'A' ? "alpha" : b == 'B' ? "bravo" : b == 'C' ? "charlie" : "none";
}

std::string surface_grade_json(const SurfaceGrade& g) {
  using nlohmann::json;
  json a;
  if (!g.anatomic.measured) {
    a = {{"measured", false}, {"why_not", g.anatomic.why_not}};
  } else {
    const AnatomicForm& f = g.anatomic;
    a = {{"measured", true},          {"band", anatomic_band_name(f.band)},         {"rms_mm", f.rms_mm},
         {"mean_mm", f.mean_mm},      {"max_under_mm", f.max_under_mm},    {"max_over_mm", f.max_over_mm},
         {"p95_abs_mm", f.p95_abs_mm}, {"p95_under_mm", f.p95_under_mm},   {"under_area_mm2", f.under_area_mm2},
         {"over_area_mm2", f.over_area_mm2}, {"columns", f.columns},       {"column_mm", f.column_mm},
         {"alpha_max_mm", f.alpha_max_mm}, {"charlie_under_mm", f.charlie_under_mm}};
  }
  json m;
  if (!g.margin.measured) {
    m = {{"measured", false}, {"why_not", g.margin.why_not}};
  } else {
    const MarginalAdaptation& x = g.margin;
    json sites = json::array();
    for (const MarginDefect& d : x.defects)
      sites.push_back({{"kind", d.kind},
                       {"length_mm", d.length_mm},
                       {"largest_step_mm", d.largest_step_mm},
                       {"centre_mm", {d.centre_mm.x, d.centre_mm.y, d.centre_mm.z}}});
    m = {{"measured", true},
         {"length_mm", x.length_mm},
         {"open_samples", x.open_samples},
         {"samples", x.reading.size()},
         {"gap_length_mm", x.gap_length_mm},
         {"excess_length_mm", x.excess_length_mm},
         {"below_resolution_mm", x.below_resolution_mm},
         {"step_threshold_mm", x.step_threshold_mm},
         {"sites", x.defects.size()},
         {"largest_site_mm", x.largest_site_mm},
         {"passes", x.passes},
         {"max_sites", x.max_sites},
         {"max_site_mm", x.max_site_mm},
         {"defects", sites}};
  }
  json x;
  if (!g.proximal.measured) {
    x = {{"measured", false}, {"why_not", g.proximal.why_not}};
  } else {
    const ProximalGrade& q = g.proximal;
    x = {{"measured", true},
         {"side", q.side},
         {"contact", q.contact},
         {"gap_mm", q.gap_mm},
         {"contact_point_mm", {q.contact_mm.x, q.contact_mm.y, q.contact_mm.z}},
         {"tight_mm", q.tight_mm},
         {"open_mm", q.open_mm},
         {"overhang_mm", q.overhang_mm},
         {"overhang_area_mm2", q.overhang_area_mm2},
         {"overhang_threshold_mm", q.overhang_threshold_mm},
         {"overhang_min_area_mm2", q.overhang_min_area_mm2}};
  }
  json v;
  if (!g.voids.measured) {
    v = {{"measured", false}, {"why_not", g.voids.why_not}};
  } else {
    const SurfaceVoids& sv = g.voids;
    json pits = json::array();
    for (const SurfacePit& q : sv.pits)
      pits.push_back({{"volume_mm3", q.volume_mm3},
                      {"depth_mm", q.depth_mm},
                      {"centre_mm", {q.centre_mm.x, q.centre_mm.y, q.centre_mm.z}}});
    v = {{"measured", true},          {"count", sv.count},
         {"volume_mm3", sv.volume_mm3}, {"deepest_mm", sv.deepest_mm},
         {"pore_count", sv.pore_count}, {"pore_volume_mm3", sv.pore_volume_mm3},
         {"min_void_mm3", sv.min_void_mm3}, {"pit_width_mm", sv.pit_width_mm},
         {"pits", pits}};
  }
  return json{{"anatomic_form", a}, {"marginal_adaptation", m}, {"proximal", x}, {"surface_voids", v}}.dump();
}

std::string surface_grade_report(const SurfaceGrade& g) {
  std::string out;
  const AnatomicForm& a = g.anatomic;
  out += a.measured ? fmt::format("anatomic form against the intact tooth: {} (95% of the opening within {:.2f} mm; "
                                  "RMS {:.2f} mm, mean {:+.2f} mm)\n",
                                  anatomic_band_name(a.band), a.p95_abs_mm, a.rms_mm, a.mean_mm)
                    : fmt::format("anatomic form: not measured ({})\n", a.why_not);
  const MarginalAdaptation& m = g.margin;
  out += m.measured ? fmt::format("margin: {} defect site{} along {:.1f} mm ({:.1f} mm gap, {:.1f} mm excess): {} the "
                                  "rubric (at most {}, none over {:.1f} mm)\n",
                                  m.defects.size(), m.defects.size() == 1 ? "" : "s", m.length_mm, m.gap_length_mm,
                                  m.excess_length_mm, m.passes ? "passes" : "fails", m.max_sites, m.max_site_mm)
                    : fmt::format("margin: not measured ({})\n", m.why_not);
  const SurfaceVoids& v = g.voids;
  if (v.measured)
    out += fmt::format("surface voids (pits open to the surface, narrower than {:.1f} mm): {} ({:.3f} mm^3){}\n",
                       v.pit_width_mm, v.count, v.volume_mm3,
                       v.pore_count > 0 ? fmt::format("; {} smaller, porosity below what the model resolves", v.pore_count)
                                        : "");
  const ProximalGrade& q = g.proximal;
  if (q.measured)
    out += fmt::format("proximal ({}): contact {}, {:.2f} mm {} the intact contour; overhang {:.2f} mm over "
                       "{:.2f} mm^2 ({})\n",
                       q.side, q.contact, std::abs(q.gap_mm), q.gap_mm >= 0 ? "short of" : "beyond",
                       std::max<real>(0, q.overhang_mm), q.overhang_area_mm2,
                       q.overhang_area_mm2 >= q.overhang_min_area_mm2 ? "an overhang" : "none of a particle's cross-section");
  return out;
}

}  // namespace dentsph
