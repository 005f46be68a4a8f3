// ContactField and the instrument's contact shape (dentsph/contact.hpp): the signed distance to
// what is rigid in a dental scene, and the spheres the hard contact keeps out of it.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "dentsph/contact.hpp"
#include "dentsph/scene.hpp"
#include "dentsph/state.hpp"

namespace dentsph {

namespace {
constexpr std::int64_t kMaxCorners = 16'000'000;
constexpr real kSupportRadii = 4;  // Zhu & Bridson's kernel support, in particle radii
}  // namespace

void ContactShape::finish_bound() {
  Vec3 lo{1e30, 1e30, 1e30}, hi = -lo;
  for (const ContactSphere& s : spheres) {
    lo = vmin(lo, s.centre);
    hi = vmax(hi, s.centre);
  }
  centre = spheres.empty() ? Vec3{} : (lo + hi) * 0.5;
  bound = 0;
  for (const ContactSphere& s : spheres) bound = std::max(bound, norm(s.centre - centre) + s.radius);
}

ContactShape instrument_contact_shape(std::span<const Vec3> points, real spacing, real shank_length, real shank_radius) {
  ContactShape shape;
  const real r = 0.5 * spacing;
  real top = 0;
  for (const Vec3& p : points) {
    shape.spheres.push_back({p, r});
    top = std::max(top, p.z);
  }
  if (shank_radius > 0 && !points.empty()) {
    // From inside the working end (its top less the shank's radius) up the handle.
    const real step = 0.25 * shank_radius;
    for (real z = std::max<real>(0, top - shank_radius); z <= shank_length; z += step)
      shape.spheres.push_back({{0, 0, z}, shank_radius});
  }
  shape.finish_bound();
  return shape;
}

real instrument_contact_spacing(const Scene& scene) {
  if (scene.instrument_spacing > 0) return scene.instrument_spacing;
  return scene.material_spacing > 0 ? scene.material_spacing : 0.5 * scene.model.kernel.h;
}

void tool_anchors(const State& state, std::vector<Vec3>& out) {
  out.clear();
  for (std::uint32_t i = 0; i < state.size(); ++i)
    if (state.role[i] == Role::tool) out.push_back(state.anchor[i]);
}

ContactShape instrument_contact_shape(const Scene& scene, const State& state) {
  std::vector<Vec3> points;
  tool_anchors(state, points);
  return instrument_contact_shape(points, instrument_contact_spacing(scene));
}

namespace {
bool set_paste(const State& s, std::uint32_t i) {
  const std::uint32_t id = s.id[i];
  return s.role[i] == Role::boundary && id < s.cure.rigid.size() && s.cure.rigid[id];
}
}  // namespace

RigidWatch::RigidWatch(std::vector<Vec3> band, real tolerance)
    : band_(std::move(band)), tolerance2_(tolerance * tolerance) {}

bool RigidWatch::changed(const State& s) {
  // The anchors change only when the instrument is switched: an exact sum tells them apart.
  double tool_signature = 0;
  std::size_t set_count = 0;
  bool moved = first_;
  for (std::uint32_t i = 0; i < s.size(); ++i) {
    if (s.role[i] == Role::tool) {
      tool_signature += 7 * s.anchor[i].x + 11 * s.anchor[i].y + 13 * s.anchor[i].z + 1;
    } else if (set_paste(s, i)) {
      ++set_count;
      const std::uint32_t id = s.id[i];
      moved = moved || id >= built_.size() || !(norm2(s.pos[i] - built_[id]) <= tolerance2_);
    }
  }
  if (!moved && set_count == set_count_ && tool_signature == tool_signature_) return false;
  constexpr real nan = std::numeric_limits<real>::quiet_NaN();
  built_.assign(s.cure.rigid.size(), Vec3{nan, nan, nan});
  for (std::uint32_t i = 0; i < s.size(); ++i)
    if (set_paste(s, i)) built_[s.id[i]] = s.pos[i];
  rigid_particles(s, band_, particles_);
  tool_anchors(s, tool_);
  set_count_ = set_count;
  tool_signature_ = tool_signature;
  first_ = false;
  return true;
}

ContactField::ContactField(std::shared_ptr<const WallField> tooth, Vec3 lo, Vec3 hi, real cell, real particle_radius)
    : tooth_(std::move(tooth)), origin_(lo), cell_(cell), inv_cell_(1 / cell), radius_(particle_radius) {
  if (!(cell > 0) || !std::isfinite(cell) || !(particle_radius > 0) || !std::isfinite(particle_radius))
    throw std::invalid_argument(fmt::format("contact field: cell {} m and particle radius {} m must be positive", cell,
                                            particle_radius));
  std::int64_t total = 1;
  for (int a = 0; a < 3; ++a) {
    const real span = hi[a] - lo[a];
    if (!(span > 0) || !std::isfinite(span)) throw std::invalid_argument("contact field: the box is empty");
    const real n = std::ceil(span / cell) + 1;
    if (!(n <= real(kMaxCorners))) throw std::invalid_argument("contact field: too many corners; use larger cells");
    n_[a] = int(n);
    total *= n_[a];
    if (total > kMaxCorners) throw std::invalid_argument("contact field: too many corners; use larger cells");
  }
  hi_ = origin_ + Vec3{real(n_[0] - 1), real(n_[1] - 1), real(n_[2] - 1)} * cell_;
  far_ = (kSupportRadii - 1) * radius_;  // no particle within the support: the surface is farther than this
  phi_.assign(std::size_t(total), float(far_));
}

void ContactField::set_particles(std::span<const Vec3> points) {
  if (phi_.empty()) return;
  std::fill(phi_.begin(), phi_.end(), float(far_));
  particles_ = 0;
  const real support = kSupportRadii * radius_, support2 = support * support;
  // The particles in buckets of the support's size over the grid's box grown by the support.
  const Vec3 lo = origin_ - Vec3{support, support, support};
  int nb[3];
  for (int a = 0; a < 3; ++a) nb[a] = int(std::ceil((real(n_[a] - 1) * cell_ + 2 * support) / support)) + 1;
  const std::size_t buckets = std::size_t(nb[0]) * nb[1] * nb[2];
  std::vector<std::uint32_t> start(buckets + 1, 0), order;
  std::vector<std::size_t> bucket_of(points.size(), buckets);
  Vec3 plo{1e30, 1e30, 1e30}, phi = -plo;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    if (!is_finite(p)) continue;
    int c[3];
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      const real f = std::floor((p[a] - lo[a]) / support);
      inside = inside && f >= 0 && f < nb[a];
      c[a] = inside ? int(f) : 0;
    }
    if (!inside) continue;
    bucket_of[i] = (std::size_t(c[2]) * nb[1] + c[1]) * nb[0] + c[0];
    ++start[bucket_of[i] + 1];
    plo = vmin(plo, p);
    phi = vmax(phi, p);
    ++particles_;
  }
  if (particles_ == 0) return;
  for (std::size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  order.resize(particles_);
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < points.size(); ++i)
      if (bucket_of[i] < buckets) order[fill[bucket_of[i]]++] = std::uint32_t(i);
  }
  // Every corner within the support of some particle: Zhu & Bridson's surface, phi = |x - xbar| - r,
  // xbar the particles' mean weighted by (1 - d^2 / R^2)^3.
  int c0[3], c1[3];
  for (int a = 0; a < 3; ++a) {
    c0[a] = std::clamp(int(std::floor((plo[a] - support - origin_[a]) * inv_cell_)), 0, n_[a] - 1);
    c1[a] = std::clamp(int(std::ceil((phi[a] + support - origin_[a]) * inv_cell_)), 0, n_[a] - 1);
  }
  for (int k = c0[2]; k <= c1[2]; ++k)
    for (int j = c0[1]; j <= c1[1]; ++j)
      for (int i = c0[0]; i <= c1[0]; ++i) {
        const Vec3 x = origin_ + Vec3{real(i) * cell_, real(j) * cell_, real(k) * cell_};
        int b[3];
        for (int a = 0; a < 3; ++a) b[a] = int((x[a] - lo[a]) / support);
        real wsum = 0;
        Vec3 mean;
        for (int bz = std::max(0, b[2] - 1); bz <= std::min(nb[2] - 1, b[2] + 1); ++bz)
          for (int by = std::max(0, b[1] - 1); by <= std::min(nb[1] - 1, b[1] + 1); ++by)
            for (int bx = std::max(0, b[0] - 1); bx <= std::min(nb[0] - 1, b[0] + 1); ++bx) {
              const std::size_t bi = (std::size_t(bz) * nb[1] + by) * nb[0] + bx;
              for (std::uint32_t q = start[bi]; q < start[bi + 1]; ++q) {
                const Vec3& p = points[order[q]];
                const real d2 = norm2(x - p);
                if (d2 >= support2) continue;
                const real u = 1 - d2 / support2, w = u * u * u;
                wsum += w;
                mean += p * w;
              }
            }
        if (wsum > 0)
          phi_[(std::size_t(k) * n_[1] + j) * n_[0] + i] = float(std::min(far_, norm(x - mean / wsum) - radius_));
      }
}

ContactField::Sample ContactField::sample(const Vec3& p, bool tooth, bool particles) const {
  Sample s;
  real d;
  Vec3 g;
  // Each part: sampled in its grid, else the distance to its box, a lower bound.
  const auto take = [&](real distance, const Vec3& gradient, bool is_tooth) {
    if (!(distance < s.distance)) return;
    s.distance = distance;
    s.normal = gradient;
    s.tooth = is_tooth;
  };
  if (tooth && tooth_) {
    if (tooth_->sample(p, d, g)) take(d, g, true);
    else take(box_distance(p, tooth_->lo(), tooth_->hi()), {}, true);
  }
  if (particles && !phi_.empty()) {
    if (sample_grid(phi_, n_, origin_, inv_cell_, p, d, g)) take(d, g, false);
    else take(box_distance(p, origin_, hi_), {}, false);
  }
  const real len = norm(s.normal);
  s.normal = len > 0 ? s.normal / len : Vec3{};
  return s;
}

std::vector<Vec3> scene_rigid_band(const Scene& scene) {
  std::vector<Vec3> band;
  if (!scene.tooth) return band;
  const real off = 0.25 * scene.material_spacing;
  for (const ParticleInit& p : scene.particles)
    if (p.role == Role::boundary && scene.tooth->distance(p.pos).distance > off) band.push_back(p.pos);
  return band;
}

ContactField scene_contact_field(const Scene& scene) {
  if (!scene.tooth || !(scene.material_spacing > 0)) return {};
  std::shared_ptr<const WallField> tooth = tooth_wall_field(scene, true);
  Vec3 lo{1e30, 1e30, 1e30}, hi = -lo;
  for (const ParticleInit& p : scene.particles)
    if (p.role == Role::boundary) {
      lo = vmin(lo, p.pos);
      hi = vmax(hi, p.pos);
    }
  if (!(lo.x <= hi.x)) return {};
  const real pad = 2e-3;
  lo = lo - Vec3{pad, pad, pad};
  hi = hi + Vec3{pad, pad, pad};
  if (scene.model.domain_min.x < scene.model.domain_max.x) {
    lo = vmax(lo, scene.model.domain_min);
    hi = vmin(hi, scene.model.domain_max);
  }
  const real s = scene.material_spacing;
  ContactField field(std::move(tooth), lo, hi, 0.5 * s, 0.5 * s);
  field.set_particles(scene_rigid_band(scene));
  return field;
}

void rigid_particles(const State& state, std::span<const Vec3> band, std::vector<Vec3>& out) {
  out.assign(band.begin(), band.end());
  for (std::uint32_t i = 0; i < state.size(); ++i)
    if (set_paste(state, i)) out.push_back(state.pos[i]);
}

}  // namespace dentsph
