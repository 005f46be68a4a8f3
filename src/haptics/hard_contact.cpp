// HardContact (dentsph/contact.hpp): the god-object proxy of the instrument against the rigid
// surfaces, with Coulomb friction, one haptic tick at a time.
//
// Each tick the proxy moves from where it was towards the device in steps short enough that no
// sphere of the instrument passes through a surface (a third of the smallest radius), and after
// each step every sphere inside a surface is pushed out along the surface's normal (a few passes:
// the corners of a cavity push along two or three normals). That is the frictionless proxy: the
// point of the surface nearest the device that the instrument reaches by sliding. Friction then
// holds the proxy where it was while the device's pull along the surface is inside the cone
// (|tangential| <= mu |normal|), and lets it slide to the cone's edge otherwise, so the tangential
// force never exceeds mu times the normal force. The hand feels k (proxy - device) and a damper
// along the normal that grows with the depth (no step at first contact) and never pulls.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "dentsph/contact.hpp"

namespace dentsph {

namespace {
constexpr int kPasses = 4;
constexpr int kMaxSteps = 64;
}  // namespace

HardContact::HardContact(const ContactParams& p, double scale, std::size_t max_spheres) : p_(p), scale_(scale) {
  if (!(p.stiffness_N_per_m > 0) || !(p.damping_N_s_per_m >= 0) || !(p.friction >= 0) || !(p.damping_depth_m > 0) ||
      !std::isfinite(p.stiffness_N_per_m + p.damping_N_s_per_m + p.friction + p.damping_depth_m) || !(scale > 0) ||
      !std::isfinite(scale))
    throw std::invalid_argument(
        "hard contact: stiffness and the damping's depth must be positive, damping and friction non-negative, the "
        "workspace scale positive, all finite");
  offset_.reserve(max_spheres);
  radius_.reserve(max_spheres);
  active_.reserve(max_spheres);
}

void HardContact::reset(const Vec3& position) {
  proxy_ = position;
  started_ = true;
  ignore_tooth_ = ignore_particles_ = false;
  res_ = {};
  res_.proxy = position;
}

real HardContact::project(const ContactField& field, Vec3& g, Vec3& normal, Vec3& contact_point) {
  for (int pass = 0; pass < kPasses; ++pass) {
    bool moved = false;
    for (std::uint32_t i : active_) {
      const ContactField::Sample s = field.sample(g + offset_[i], !ignore_tooth_, !ignore_particles_);
      const real c = s.distance - radius_[i];
      if (c < 0 && s.normal != Vec3{}) {
        g += s.normal * -c;
        moved = true;
      }
    }
    if (!moved) break;
  }
  // The spheres resting on a surface (within a fiftieth of their radius): their mean normal and
  // where they touch.
  Vec3 nsum, csum;
  int touching = 0;
  real deepest = 0;
  for (std::uint32_t i : active_) {
    const ContactField::Sample s = field.sample(g + offset_[i], !ignore_tooth_, !ignore_particles_);
    const real c = s.distance - radius_[i];
    if (c < 0.02 * radius_[i] && s.normal != Vec3{}) {
      nsum += s.normal;
      csum += g + offset_[i] - s.normal * radius_[i];
      ++touching;
      deepest = std::max(deepest, -c);
    }
  }
  const real len = norm(nsum);
  normal = touching > 0 && len > 0 ? nsum / len : Vec3{};
  contact_point = touching > 0 ? csum / real(touching) : g;
  return touching > 0 ? deepest : -1;
}

const ContactResult& HardContact::update(const ContactField& field, const ContactShape& shape, const Vec3& target,
                                         const Quat& q, const Vec3& device_velocity) {
  if (!is_finite(target)) {  // a device pose that is not a position: the proxy stays, no force
    res_ = {};
    res_.proxy = proxy_;
    return res_;
  }
  if (!started_) reset(target);
  const std::size_t n = std::min(shape.spheres.size(), offset_.capacity());
  offset_.resize(n);  // within the capacity reserved: no allocation
  radius_.resize(n);
  min_radius_ = 1e30;
  for (std::size_t i = 0; i < n; ++i) {
    offset_[i] = q.rotate(shape.spheres[i].centre);
    radius_[i] = shape.spheres[i].radius;
    min_radius_ = std::min(min_radius_, radius_[i]);
  }
  const Vec3 from = proxy_;
  const real move = norm(target - from);
  const Vec3 was_normal = res_.touching ? res_.normal : Vec3{};
  res_ = {};
  // Nothing within reach of the instrument's bounding sphere along the whole move: free.
  const ContactField::Sample around = field.sample(from + q.rotate(shape.centre));
  if (n == 0 || around.distance - shape.bound > move + min_radius_) {
    proxy_ = target;
    ignore_tooth_ = ignore_particles_ = false;
    res_.proxy = proxy_;
    return res_;
  }
  // The spheres that may touch on the way, and whether the proxy is inside a surface already (one
  // that appeared around it: set paste; or the device's first pose): that surface does not hold
  // it until it is out.
  active_.clear();
  bool in_tooth = false, in_particles = false, out_tooth = true, out_particles = true;
  const real tolerance = 0.25 * min_radius_;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 p = from + offset_[i];
    const ContactField::Sample st = field.sample(p, true, false), sp = field.sample(p, false, true);
    const real ct = st.distance - radius_[i], cp = sp.distance - radius_[i];
    if (std::min(ct, cp) < move + min_radius_) active_.push_back(std::uint32_t(i));
    // Only a sampled distance (one with a normal) says the sphere is inside: outside a grid the
    // field is a lower bound (the distance to the grid's box), not a penetration.
    const bool sampled_t = st.normal != Vec3{}, sampled_p = sp.normal != Vec3{};
    in_tooth = in_tooth || (sampled_t && ct < -tolerance);
    in_particles = in_particles || (sampled_p && cp < -tolerance);
    out_tooth = out_tooth && (ct >= 0 || !sampled_t);
    out_particles = out_particles && (cp >= 0 || !sampled_p);
  }
  ignore_tooth_ = ignore_tooth_ ? !out_tooth : in_tooth;
  ignore_particles_ = ignore_particles_ ? !out_particles : in_particles;

  const real still2 = 1e-6 * min_radius_ * min_radius_;  // (a thousandth of a radius)^2
  // Static friction first: a proxy that rested on a surface stays where it is while the device's
  // pull along that surface is inside the friction cone (one projection: a hand holding still on
  // the tooth, or pressing into it, costs no more).
  if (was_normal != Vec3{}) {
    Vec3 h = from, hn, hc;
    if (project(field, h, hn, hc) >= 0 && norm2(h - from) <= still2) {
      const real depth = dot(h - target, hn);
      Vec3 pull = target - h;
      pull -= hn * dot(pull, hn);
      if (depth > 0 && norm(pull) <= p_.friction * depth) {
        res_.touching = true;
        res_.normal = hn;
        return finish(h, hc, target, device_velocity);
      }
    }
  }
  // The frictionless proxy: from where it was to the device, in steps, pushed out after each. A
  // step does not push into the surface touched (the last step's normal, or the last tick's): its
  // part along the surface is all the proxy can move, and once that is nothing the proxy rests
  // (a hand pressing into the tooth costs one projection a step it moves, not one a step).
  const int steps = std::clamp(int(std::ceil(move / (min_radius_ / 3))), 1, kMaxSteps);
  Vec3 g = from, normal = was_normal, contact;
  real deepest = -1;
  for (int s = 0; s < steps; ++s) {
    Vec3 d = (target - g) / real(steps - s);
    const real into = dot(d, normal);
    if (into < 0) d -= normal * into;
    if (s > 0 && norm2(d) < still2) break;
    g += d;
    deepest = project(field, g, normal, contact);
  }
  const real depth = deepest >= 0 ? dot(g - target, normal) : 0;  // scene m behind the surface
  if (deepest >= 0 && depth > 0) {
    // Friction: the proxy stays where it was while the pull along the surface is within the cone.
    Vec3 t = from - g;
    t -= normal * dot(t, normal);
    const real limit = p_.friction * depth, slip = norm(t);
    res_.sliding = slip > limit * (1 + 1e-6);  // at the cone's edge a still hand stays
    Vec3 held = g + (res_.sliding ? t * (limit / slip) : t), held_normal, held_contact;
    if (project(field, held, held_normal, held_contact) >= 0) {
      g = held;
      contact = held_contact;
    }
    res_.touching = true;
    res_.normal = normal;
  }
  return finish(g, contact, target, device_velocity);
}

const ContactResult& HardContact::finish(const Vec3& g, const Vec3& contact, const Vec3& target,
                                         const Vec3& device_velocity) {
  proxy_ = g;
  res_.proxy = g;
  if (res_.touching) {
    const Vec3 normal = res_.normal;
    const Vec3 d = (g - target) / scale_;  // device m
    Vec3 f = d * p_.stiffness_N_per_m;
    res_.depth_m = std::max<real>(0, dot(d, normal));
    const double ramp = std::min(1.0, res_.depth_m / p_.damping_depth_m);
    f += normal * (-p_.damping_N_s_per_m * ramp * dot(device_velocity, normal));
    const real fn = dot(f, normal);
    if (fn < 0) f -= normal * fn;  // the damper never pulls the hand into the surface
    res_.force_N = f;
    res_.torque_N_m = cross((contact - g) / scale_, f);
  }
  return res_;
}

}  // namespace dentsph
