// The hard contact's test bench: the built-in crown's contact field and ball burnisher, a slab of
// set paste on its cavity floor, and a press at 1 kHz ticks with its energy bookkeeping.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "dentsph/contact.hpp"
#include "dentsph/dental.hpp"
#include "dentsph/haptics/device.hpp"
#include "dentsph/haptics/replay.hpp"
#include "dentsph/tools.hpp"

namespace dentsph::testing {

inline double angle_deg(const Vec3& a, const Vec3& b) {
  const double c = dot(a, b) / (norm(a) * norm(b));
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180 / std::numbers::pi;
}

struct ContactBench {
  Scene scene;
  ContactField field;
  ContactShape shape;
  real spacing = 0;
  const PreparedTooth& tooth() const { return *scene.tooth; }

  static const ContactBench& get() {
    static const ContactBench b = [] {
      ContactBench c;
      c.scene = default_dental_scene();
      c.spacing = c.scene.material_spacing;
      c.field = scene_contact_field(c.scene);
      const ToolShape ball = tool_by_name("ball_burnisher", c.spacing, Solver::iisph);
      c.shape = instrument_contact_shape(ball.points, c.spacing);
      return c;
    }();
    return b;
  }

  // Set paste: three layers of particles a spacing apart on the cavity floor, clear of its walls,
  // in `field`; returns the top layer's height in the tooth frame (m).
  real set_slab(ContactField& f) const {
    const ToothFrame& fr = tooth().frame();
    std::vector<Vec3> pts;
    const real top = -1.25e-3;
    for (real z = top - 2 * spacing; z <= top + 1e-9; z += spacing)
      for (real y = -3e-3; y <= 3e-3; y += spacing)
        for (real x = -3e-3; x <= 3e-3; x += spacing) {
          const Vec3 p = fr.to_world({x, y, z});
          if (tooth().in_cavity(p) && tooth().distance(p).distance > 0.5 * spacing) pts.push_back(p);
        }
    f.set_particles(pts);
    return top;
  }
};

struct PressRun {
  bool touched = false;
  ContactResult held, released;
  Vec3 device;                  // m, scene: where the device held
  Vec3 surface_normal;          // the surface's own normal where the proxy touches
  double clearance = 1;         // m: the instrument's nearest sphere's distance to the surface
  double energy_to_hand_J = 0;  // sum of F . v dt over the press and the release
  double work_in_J = 0;         // the hand's work pressing in (positive)
  double max_force_step_N = 0;
};

// From `start`, the device moves along `dir` at `speed` (m/s; ticks of 1 ms) until the instrument
// touches, then along the touched surface's inward normal `depth` further, holds 50 ms, and (with
// `release`) goes back out the way it came. The surface is `exact` (the tooth's distance) or, where
// that is farther, the field's particles.
inline PressRun press(HardContact& c, const ContactField& field, const ContactShape& shape, const Vec3& start,
                      const Vec3& dir, real depth, real speed, bool release = true,
                      const PreparedTooth* exact = nullptr) {
  PressRun run;
  const double dt = 1e-3;
  const real step = speed * dt;
  Vec3 x = start, last_force;
  c.reset(start);
  auto tick = [&](const Vec3& v, bool pressing) {
    x += v * dt;
    const ContactResult& r = c.update(field, shape, x, {}, v);
    const double p = dot(r.force_N, v) * dt;
    run.energy_to_hand_J += p;
    if (pressing) run.work_in_J -= p;
    run.max_force_step_N = std::max(run.max_force_step_N, norm(r.force_N - last_force));
    last_force = r.force_N;
    return r;
  };
  Vec3 n;
  for (int k = 0; k < 20000 && !run.touched; ++k) {
    const ContactResult& r = tick(dir * speed, true);
    if (r.touching) run.touched = true, n = r.normal;
  }
  if (!run.touched) return run;
  const int in = int(std::lround(depth / step));
  for (int k = 0; k < in; ++k) tick(-n * speed, true);
  for (int k = 0; k < 50; ++k) run.held = tick({}, false);
  run.device = x;
  // The instrument's distance to the surface and the normal there.
  run.clearance = 1;
  for (const ContactSphere& s : shape.spheres) {
    const Vec3 p = run.held.proxy + s.centre;
    ContactField::Sample fs = field.sample(p);
    double d = fs.distance;
    Vec3 normal = fs.normal;
    if (exact && fs.tooth) {
      const SurfacePoint sp = exact->distance(p);
      d = sp.distance, normal = sp.normal;
    } else if (normal == Vec3{}) {
      continue;  // outside the field's grids: a lower bound, no surface here
    }
    if (d - s.radius < run.clearance) run.clearance = d - s.radius, run.surface_normal = normal;
  }
  if (release) {
    for (int k = 0; k < in + 100; ++k) run.released = tick(n * speed, false);
  }
  return run;
}

}  // namespace dentsph::testing
