// carve_cavity(): places the Class I / Class II shape on the occlusal surface, checks that the
// tooth keeps enough wall and floor around it, and measures the tooth removed.
#include <fmt/format.h>

#include <stdexcept>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "tooth/geometry.hpp"
#include "tooth/prepared.hpp"

namespace dentsph {

namespace {

using tooth::CavityShape;
using tooth::RoundedBox;
using tooth::Side;
using tooth::SlantedBox;

constexpr real pi = 3.14159265358979323846;
constexpr real inf = std::numeric_limits<real>::infinity();
// The occlusal reference: the highest occlusal surface point within this radius of the axis
// (one ray down the axis could fall into a fissure).
constexpr real reference_radius = 0.5e-3;  // m
// Finest cell of the volume integration, a third of the material spacing (~0.3 mm); the slab
// estimate below makes its error second order.
constexpr real volume_cell = 0.1e-3;  // m

[[noreturn]] void refuse(const std::string& problem, const std::string& fix) {
  throw CavityError(fmt::format("cavity does not fit: {}; {}", problem, fix));
}
[[noreturn]] void bad_param(const std::string& name, real value_mm, const std::string& need) {
  throw CavityError(fmt::format("cavity parameter {} = {:.4g} mm: {}", name, value_mm, need));
}

std::string mm3(const Vec3& p) {
  return fmt::format("({:.2f}, {:.2f}, {:.2f}) mm", p.x * 1e3, p.y * 1e3, p.z * 1e3);
}

// Local bounds of the tooth in a frame.
Bounds local_bounds(const TriMesh& mesh, const ToothFrame& f) {
  Bounds b{{inf, inf, inf}, {-inf, -inf, -inf}};
  for (const Vec3& v : mesh.vertices) {
    const Vec3 l = f.to_local(v);
    b.min = vmin(b.min, l);
    b.max = vmax(b.max, l);
  }
  return b;
}

// Tooth left along a ray from a point of a wall or floor (frame coordinates): 0 when the
// point is not in the tooth.
real thickness(const MeshDistance& tooth, const ToothFrame& f, const Vec3& local,
               const Vec3& local_dir) {
  const Vec3 p = f.to_world(local);
  if (!tooth.inside(p)) return 0;
  const Vec3 d = f.x * local_dir.x + f.y * local_dir.y + f.z * local_dir.z;
  return tooth.ray(p, d).value_or(0);
}

// One checked surface of the preparation: points on it, and the direction to measure in.
struct Probe {
  std::string name;
  std::vector<Vec3> points;  // frame coordinates
  Vec3 direction;            // frame coordinates, unit, out of the cavity into the tooth
  bool floor = false;
};

// Evenly spaced values in [a, b], at most `step` apart, ends included.
std::vector<real> steps(real a, real b, real step) {
  if (b <= a) return {0.5 * (a + b)};
  const int n = std::max(1, int(std::ceil((b - a) / step)));
  std::vector<real> v;
  for (int i = 0; i <= n; ++i) v.push_back(a + (b - a) * i / n);
  return v;
}

void check_params(const CavityParams& p) {
  // Absurd magnitudes first, with a short message (a width of 1e308 m otherwise reached the fit
  // checks, which printed 310-digit coordinates).
  const std::pair<const char*, real> lengths[] = {
      {"width", p.width},         {"length", p.length},       {"depth", p.depth},
      {"rounding", p.rounding},   {"min_wall", p.min_wall},   {"min_floor", p.min_floor},
      {"box_width", p.box_width}, {"box_depth", p.box_depth}, {"box_axial_depth", p.box_axial_depth}};
  for (const auto& [name, v] : lengths)
    if (std::isfinite(v) && std::abs(v) >= max_cavity_length)
      bad_param(name, v * 1e3, fmt::format("must be under {:.0f} mm (no tooth is that large)", max_cavity_length * 1e3));
  auto positive = [](const char* name, real v) {
    if (!(v > 0) || !std::isfinite(v)) bad_param(name, v * 1e3, "must be > 0");
  };
  positive("width", p.width);
  positive("length", p.length);
  positive("depth", p.depth);
  if (!(p.taper_deg >= 0 && p.taper_deg < 30))
    throw CavityError(fmt::format(
        "cavity parameter taper_deg = {}: must be in [0, 30) degrees (occlusal divergence of "
        "each wall; 2 to 8 is usual)",
        p.taper_deg));
  if (!(p.rounding >= 0)) bad_param("rounding", p.rounding * 1e3, "must be >= 0");
  if (!(p.min_wall >= 0)) bad_param("min_wall", p.min_wall * 1e3, "must be >= 0");
  if (!(p.min_floor >= 0)) bad_param("min_floor", p.min_floor * 1e3, "must be >= 0");
  if (p.kind == CavityClass::class_2) {
    positive("box_width", p.box_width);
    positive("box_axial_depth", p.box_axial_depth);
    if (!(p.box_depth >= p.depth))
      bad_param("box_depth", p.box_depth * 1e3,
                fmt::format("the gingival floor must lie at least as deep as the pulpal floor "
                            "(depth = {:.4g} mm)",
                            p.depth * 1e3));
  }
}

// Volume of {cavity} and {tooth} by adaptive octree cells: both distances are 1-Lipschitz, so a
// cell whose centre is farther than its half-diagonal from a surface lies wholly on one side.
struct VolumeIntegrator {
  const CavityShape& shape;
  const MeshDistance& tooth;
  const ToothFrame& frame;
  real volume = 0;
  Bounds hit{{inf, inf, inf}, {-inf, -inf, -inf}};

  void cell(const Vec3& c, real half, int levels) {
    const real reach = half * std::sqrt(real(3));
    const real dc = shape.distance(c).distance;
    if (dc > reach) return;
    const real g = std::fmax(dc, tooth.signed_distance(frame.to_world(c)));
    if (g > reach) return;
    if (g < -reach || levels == 0) {
      // A finest cell counts the part of it behind the plane at distance g from its centre (as
      // if the cube were a slab across the normal): exact for faces parallel to the cell's,
      // and unbiased for others, where the midpoint rule would be off by up to half a cell.
      const real side = 2 * half;
      const real inside = std::clamp(0.5 - g / side, 0.0, 1.0);
      if (inside <= 0) return;
      volume += inside * side * side * side;
      hit.min = vmin(hit.min, c - Vec3{half, half, half});
      hit.max = vmax(hit.max, c + Vec3{half, half, half});
      return;
    }
    const real q = half / 2;
    for (int k = 0; k < 8; ++k)
      cell(c + Vec3{k & 1 ? q : -q, k & 2 ? q : -q, k & 4 ? q : -q}, q, levels - 1);
  }
};

// The frame moved to the occlusal reference: rays down the axis from above the tooth, at the axis
// and around it; the highest hit is z = 0.
ToothFrame occlusal_frame(const MeshDistance& tooth, const ToothFrame& given) {
  const Bounds tb = local_bounds(tooth.mesh(), given);
  const real start = tb.max.z + 1e-3;
  real top = -inf;
  bool axis_hit = false;
  for (int k = -1; k < 8; ++k) {
    const real ox = k < 0 ? 0 : reference_radius * std::cos(2 * pi * k / 8);
    const real oy = k < 0 ? 0 : reference_radius * std::sin(2 * pi * k / 8);
    if (auto t = tooth.ray(given.to_world({ox, oy, start}), -given.z)) {
      top = std::fmax(top, start - *t);
      axis_hit |= k < 0;
    }
  }
  if (!axis_hit)
    refuse("the long axis does not meet the tooth's occlusal surface",
           "check the tooth frame: its origin and z axis must pass through the crown");
  ToothFrame f = given;
  f.origin = given.to_world({0, 0, top});
  return f;
}

// The preparation's outline in the frame (z = 0 at the reference, walls diverging occlusally by
// the taper), in "xi" = sigma x, where the proximal side is +xi.
struct Outline {
  real t = 0;             // the taper's tangent
  real sigma = 1;         // +1: the proximal box mesial (+x); -1: distal
  bool class2 = false;
  real xi_axial = 0;      // the proximal box's axial wall at the gingival floor (Class II)
  // Converts a [lo, hi] xi range to x sides.
  std::pair<Side, Side> x_sides(Side xi_lo, Side xi_hi) const {
    if (sigma > 0) return {xi_lo, xi_hi};
    return {Side{-xi_hi.a, -xi_hi.slope}, Side{-xi_lo.a, -xi_lo.slope}};
  }
};

// The occlusal box and, for a Class II, the proximal box, added to `shape` (`lb`: the tooth's
// bounds in the frame). Refuses a gingival floor below the tooth or an axial wall past the axis.
Outline cavity_boxes(const MeshDistance& tooth, const ToothFrame& f, const Bounds& lb, const CavityParams& p,
                     CavityShape& shape) {
  Outline o;
  o.t = std::tan(p.taper_deg * pi / 180);
  o.sigma = p.side == ProximalSide::mesial ? 1 : -1;
  o.class2 = p.kind == CavityClass::class_2;
  const real t = o.t;
  const real z_top = lb.max.z + p.rounding + 1e-3;  // above every cusp: no top rounding in tooth
  const real xi_out = std::fmax(lb.max.x, -lb.min.x) + p.rounding + 1e-3;  // beyond the tooth
  {
    SlantedBox occlusal;
    const Side far{-p.length / 2, -t};
    const Side near = o.class2 ? Side{xi_out, 0} : Side{p.length / 2, t};
    std::tie(occlusal.x_lo, occlusal.x_hi) = o.x_sides(far, near);
    occlusal.y_lo = {-p.width / 2, -t};
    occlusal.y_hi = {p.width / 2, t};
    occlusal.z_lo = -p.depth;
    occlusal.z_hi = z_top;
    shape.boxes.emplace_back(occlusal, p.rounding, "occlusal box");
  }
  if (!o.class2) return o;
  // The axial wall stands box_axial_depth inside the proximal surface at the gingival floor.
  const Vec3 floor_centre{0, 0, -p.box_depth};
  if (!tooth.inside(f.to_world(floor_centre)))
    refuse(fmt::format("the gingival floor, {:.2f} mm below the occlusal reference, lies below "
                       "the tooth on its axis",
                       p.box_depth * 1e3),
           "reduce box_depth");
  const real to_surface = tooth.ray(f.to_world(floor_centre), f.x * o.sigma).value_or(0);  // m along +xi
  o.xi_axial = to_surface - p.box_axial_depth;
  if (o.xi_axial < 0)
    refuse(fmt::format("the proximal surface is {:.2f} mm from the axis at the gingival floor, "
                       "so an axial depth of {:.2f} mm reaches past the long axis",
                       to_surface * 1e3, p.box_axial_depth * 1e3),
           "reduce box_axial_depth");
  SlantedBox box;
  std::tie(box.x_lo, box.x_hi) = o.x_sides(Side{o.xi_axial - t * p.box_depth, -t}, Side{xi_out, 0});
  box.y_lo = {-p.box_width / 2, -t};
  box.y_hi = {p.box_width / 2, t};
  box.z_lo = -p.box_depth;
  box.z_hi = z_top;
  shape.boxes.emplace_back(box, p.rounding, "proximal box");
  return o;
}

// The surfaces the fit is checked on: horizontal rays from the walls and vertical rays from the
// floors, inside the part of each wall the rounding leaves flat, from the floor up to a third of
// the depth below the reference (higher up the occlusal surface itself may dip below z = 0 in a
// groove).
std::vector<Probe> fit_probes(const Outline& o, const CavityParams& p) {
  const real t = o.t, sigma = o.sigma, r = p.rounding, step = 0.4e-3;
  auto wall_heights = [&](real floor_depth) {
    return steps(-floor_depth + r, std::fmin(-floor_depth / 3, -floor_depth + r), step);
  };
  std::vector<Probe> probes;
  const std::string prox = p.side == ProximalSide::mesial ? "mesial (+x)" : "distal (-x)";
  const real xi_far = -p.length / 2;
  const real xi_near = o.class2 ? o.xi_axial : p.length / 2;
  for (real side : {-1.0, 1.0}) {
    Probe wall{fmt::format("{} side wall of the occlusal box", side > 0 ? "+y" : "-y"), {}, {0, side, 0}};
    for (real z : wall_heights(p.depth))
      for (real xi : steps(xi_far + r, xi_near - r, step)) wall.points.push_back({sigma * xi, side * (p.width / 2 + t * z), z});
    probes.push_back(std::move(wall));
  }
  auto end_wall = [&](real xi_sign) {
    const std::string name = sigma * xi_sign > 0 ? "mesial (+x)" : "distal (-x)";
    Probe wall{name + " end wall of the occlusal box", {}, {sigma * xi_sign, 0, 0}};
    for (real z : wall_heights(p.depth))
      for (real y : steps(-p.width / 2 + r, p.width / 2 - r, step))
        wall.points.push_back({sigma * xi_sign * (p.length / 2 + t * z), y, z});
    probes.push_back(std::move(wall));
  };
  end_wall(-1);
  if (!o.class2) end_wall(1);
  Probe floor{"pulpal floor", {}, {0, 0, -1}, true};
  const real half_w = p.width / 2 - t * p.depth - r;
  for (real xi : steps(xi_far + r, xi_near - r, step))
    for (real y : steps(-half_w, half_w, step)) floor.points.push_back({sigma * xi, y, -p.depth});
  probes.push_back(std::move(floor));
  if (!o.class2) return probes;
  // Beside the box, at its axial wall (nearer the proximal surface the walls thin out as the
  // crown's contour curves in: that is where the box is meant to break through).
  for (real side : {-1.0, 1.0}) {
    Probe wall{fmt::format("{} side wall of the {} box", side > 0 ? "+y" : "-y", prox), {}, {0, side, 0}};
    for (real z : steps(-p.box_depth + r, -p.depth, step))
      wall.points.push_back({sigma * (o.xi_axial - t * (p.box_depth + z) + r), side * (p.box_width / 2 + t * z), z});
    probes.push_back(std::move(wall));
  }
  Probe gingival{"gingival floor", {}, {0, 0, -1}, true};
  const real box_half_w = p.box_width / 2 - t * p.box_depth - r;
  for (real xi : steps(o.xi_axial + r, o.xi_axial + std::fmax(r, p.box_axial_depth / 2), step))
    for (real y : steps(-box_half_w, box_half_w, step)) gingival.points.push_back({sigma * xi, y, -p.box_depth});
  probes.push_back(std::move(gingival));
  return probes;
}

// The thinnest tooth left beside the walls and under the floors, into `report`; refuses the first
// surface that leaves less than min_wall or min_floor, naming it and where.
void check_fit(const MeshDistance& tooth, const ToothFrame& f, const std::vector<Probe>& probes, const CavityParams& p,
               CavityReport& report) {
  report.min_wall = inf;
  report.min_floor = inf;
  for (const Probe& probe : probes) {
    real least = inf;
    Vec3 where;
    for (const Vec3& q : probe.points) {
      const real th = thickness(tooth, f, q, probe.direction);
      if (th < least) least = th, where = q;
    }
    real& keep = probe.floor ? report.min_floor : report.min_wall;
    keep = std::fmin(keep, least);
    const real need = probe.floor ? p.min_floor : p.min_wall;
    if (least >= need) continue;
    const std::string what = least == 0 ? "lies outside the tooth" : "leaves too little tooth";
    if (probe.floor)
      refuse(fmt::format("the {} {} at {} (frame coordinates): {:.2f} mm below it, {:.2f} mm "
                         "required (min_floor)",
                         probe.name, what, mm3(where), least * 1e3, need * 1e3),
             "make the cavity shallower");
    refuse(fmt::format("the {} {} at {} (frame coordinates): {:.2f} mm of tooth beside it, "
                       "{:.2f} mm required (min_wall){}",
                       probe.name, what, mm3(where), least * 1e3, need * 1e3,
                       least == 0 ? ": the outline runs off the crown" : ""),
           "make the outline narrower or shorter, or the cavity shallower");
  }
}

// The tooth the shape removes, by octree cells of root size 8 finest cells over the shape's bounds
// within the tooth's (`lb`): its volume and the box of the cells that count (frame coordinates).
VolumeIntegrator removed_tooth(const CavityShape& shape, const MeshDistance& tooth, const ToothFrame& f, const Bounds& lb) {
  Bounds cb = shape.bounds();
  cb.min = vmax(cb.min, lb.min);
  cb.max = vmin(cb.max, lb.max);
  VolumeIntegrator vi{shape, tooth, f};
  constexpr int levels = 3;
  const real root = volume_cell * (1 << levels);
  const auto cells = [&](real lo, real hi) { return int(std::ceil((hi - lo) / root)); };
  const int nx = cells(cb.min.x, cb.max.x), ny = cells(cb.min.y, cb.max.y), nz = cells(cb.min.z, cb.max.z);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) vi.cell(cb.min + Vec3{i + 0.5, j + 0.5, k + 0.5} * root, root / 2, levels);
  if (!(vi.volume > 0)) refuse("it removes no tooth", "check the frame: the cavity must sit on the occlusal surface");
  return vi;
}

}  // namespace

std::string CavityReport::summary() const {
  return fmt::format(
      "occlusal reference at {}; thinnest wall {:.2f} mm, thinnest floor {:.2f} mm; tooth "
      "removed {:.2f} mm^3",
      mm3(occlusal_point), min_wall * 1e3, min_floor * 1e3, cavity_volume * 1e9);
}

PreparedTooth carve_cavity(const MeshDistance& tooth, const ToothFrame& given,
                           const CavityParams& p) {
  check_params(p);
  auto impl =
      std::make_shared<PreparedTooth::Impl>(PreparedTooth::Impl{tooth, given, p, {}, {}, {}, {}});
  const ToothFrame& f = impl->frame = occlusal_frame(tooth, given);
  const Bounds lb = local_bounds(tooth.mesh(), f);
  const Outline outline = cavity_boxes(tooth, f, lb, p, impl->shape);
  check_fit(tooth, f, fit_probes(outline, p), p, impl->report);
  const VolumeIntegrator removed = removed_tooth(impl->shape, tooth, f, lb);
  impl->report.cavity_volume = removed.volume;
  impl->report.occlusal_point = f.origin;
  impl->cavity_local = removed.hit;
  impl->cavity_world = tooth::box_of_corners(removed.hit, [&f](const Vec3& p) { return f.to_world(p); });
  return PreparedTooth(std::move(impl));
}

PreparedTooth::PreparedTooth(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}

const MeshDistance& PreparedTooth::tooth() const { return impl_->tooth; }
const ToothFrame& PreparedTooth::frame() const { return impl_->frame; }
const CavityParams& PreparedTooth::params() const { return impl_->params; }
const CavityReport& PreparedTooth::report() const { return impl_->report; }
Bounds PreparedTooth::cavity_bounds() const { return impl_->cavity_world; }

SurfacePoint PreparedTooth::cavity_distance(const Vec3& p) const {
  const ToothFrame& f = impl_->frame;
  const auto s = impl_->shape.distance(f.to_local(p));
  const Vec3 g = f.x * s.gradient.x + f.y * s.gradient.y + f.z * s.gradient.z;
  return {s.distance, p - g * s.distance, g};
}

SurfacePoint PreparedTooth::distance(const Vec3& p) const {
  const SurfacePoint t = impl_->tooth.query(p);
  SurfacePoint c = cavity_distance(p);
  if (t.distance >= -c.distance) return t;
  // Outside the cavity's complement the distance is the cavity's, with the sign turned.
  c.distance = -c.distance;
  c.normal = -c.normal;
  return c;
}

real PreparedTooth::proximal_box_distance(const Vec3& p) const {
  if (impl_->shape.boxes.size() < 2) throw std::logic_error("proximal_box_distance: a Class I cavity has no proximal box");
  return impl_->shape.boxes[1].distance(impl_->frame.to_local(p)).distance;
}

bool PreparedTooth::in_cavity(const Vec3& p) const {
  return cavity_distance(p).distance < 0 && impl_->tooth.signed_distance(p) < 0;
}

}  // namespace dentsph
