// The slump test (include/dentsph/handling.hpp; docs/model.md, "Handling tests"): Lee, Min, Kim &
// Ferracane (Dent Mater 2010) extruded a fixed volume of each composite onto a glass slide, let it
// slump for 10 s at 25 C and light-cured it; the aspect ratio height / diameter of the cone or dome
// measured its slumping tendency, which fell as the paste's complex modulus rose. Here the fixed
// volume is a cylinder as tall as it is wide, set down on a no-slip plate (the glass: the paste
// sticks to it) and let go under gravity; the iisph solver steps it with the velocity limit's
// substeps where it flows fast.
#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "dentsph/handling.hpp"
#include "dentsph/scene.hpp"
#include "handling/rig.hpp"

namespace dentsph {

namespace {

// The paste's height on the axis (the highest particle within two spacings of it, plus half a
// spacing) and its diameter (twice the farthest particle's distance from the axis, plus a spacing).
struct Shape {
  real height = 0, diameter = 0;
};

Shape shape(const State& st, real s) {
  Shape sh;
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    if (st.role[i] != Role::material) continue;
    const real r = std::hypot(st.pos[i].x, st.pos[i].y);
    if (r < 2 * s) sh.height = std::max(sh.height, st.pos[i].z + 0.5 * s);
    sh.diameter = std::max(sh.diameter, 2 * r + s);
  }
  return sh;
}

}  // namespace

HandlingResult slump_test(const PastePreset& preset, const SlumpOptions& o) {
  if (!(o.diameter > 4 * o.spacing) || !(o.duration > 0) || !(o.dt > 0) || !(o.spacing > 0))
    throw std::invalid_argument("slump: the spacing, duration and dt must be > 0 and the diameter over 4 spacings");
  const real s = o.spacing;
  const int nr = int(std::lround(0.5 * o.diameter / s)), nz = int(std::lround(o.diameter / s));
  const int plate = 3 * nr + 4;  // room for the flowable's spread
  const real L = plate + 4;
  ModelParams p = handling::rig_params(s, Vec3{-L, -L, -6} * s, Vec3{L, L, nz + 8.0} * s, o.dt, Vec3{0, 0, -9.81});
  Model model = make_model(p);
  const Material& paste = preset.paste;
  const Material glass = handling::wall_beside(paste);
  const real m = lattice_particle_mass(paste.rho0, s, model.kernel);
  std::vector<ParticleInit> ps;
  for (int k = -2; k < nz; ++k)
    for (int j = -plate; j <= plate; ++j)
      for (int i = -plate; i <= plate; ++i) {
        const Vec3 x{i * s, j * s, (k + 0.5) * s};
        const real r = std::hypot(x.x, x.y);
        if (k < 0 && r <= plate * s) ps.push_back(make_particle(Role::boundary, x, m, glass));
        if (k >= 0 && r < nr * s) ps.push_back(make_particle(Role::material, x, m, paste));
      }
  State st;
  st.add_particles(model, ps);

  const Shape start = shape(st, s);
  std::vector<real> t{0}, aspect{start.height / start.diameter};
  real next_sample = 0.1;
  while (st.time < o.duration - 0.5 * o.dt) {
    handling::rig_step(model, st, o.run, "slump");
    if (st.time >= next_sample - 1e-9) {
      const Shape now = shape(st, s);
      t.push_back(st.time);
      aspect.push_back(now.height / now.diameter);
      next_sample += 0.1;
      if (o.run.progress && std::lround(st.time * 10) % 10 == 0)
        o.run.progress(fmt::format("slump: {} at {:.1f} s: aspect ratio {:.3f}", preset.name, st.time, aspect.back()));
    }
  }
  const Shape end = shape(st, s);

  HandlingResult r = handling::result_of("slump", preset);
  r.figures.push_back({fmt::format("aspect ratio after {:g} s", o.duration), end.height / end.diameter, "", std::nullopt,
                       "Lee, Min, Kim & Ferracane (Dent Mater 2010): the aspect ratio falls as the paste slumps more; "
                       "their ranking (slumping resistance rising with the complex modulus) is the published "
                       "figure, not a range for this volume"});
  r.figures.push_back({"aspect ratio at the start", start.height / start.diameter, "", std::nullopt,
                       "the cylinder as set down"});
  r.figures.push_back({"height kept", end.height / start.height, "", std::nullopt,
                       fmt::format("the height after {:g} s over the height at the start", o.duration)});
  r.figures.push_back({"fastest particle at the end", st.diagnostics.max_speed * 1e3, "mm/s", std::nullopt,
                       "still slumping where above about 0.01 mm/s"});
  HandlingCurve curve;
  curve.file = "slump";
  curve.title = fmt::format("Slump on glass: {} at {:g} C", preset.name, preset.temperature_c);
  curve.x_label = "time (s)";
  curve.y_label = "aspect ratio, height / diameter";
  curve.series.push_back({"virtual slump", t, aspect, false});
  r.curves.push_back(curve);
  r.notes.push_back(fmt::format("a cylinder {:.2f} mm across and {:.2f} mm tall ({} particles {:.2f} mm apart) on a "
                                "no-slip plate, {:g} s under gravity",
                                start.diameter * 1e3, start.height * 1e3,
                                std::count(st.role.begin(), st.role.end(), Role::material), s * 1e3, o.duration));
  return r;
}

}  // namespace dentsph
