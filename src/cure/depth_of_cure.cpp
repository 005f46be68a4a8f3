// The virtual ISO 4049 depth-of-cure test (include/dentsph/depth_of_cure.hpp): the paste in the
// mould is at rest, so it is cured by cure_between_steps alone (no step between the updates), with
// the mould's steel walls beside the beam, not in it (the light is collimated along the axis).
#include "dentsph/depth_of_cure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "dentsph/cure.hpp"
#include "dentsph/limits.hpp"
#include "dentsph/scene.hpp"

namespace dentsph {

namespace {

constexpr real mm = 1e-3;

void check_positive(real v, const char* what) {
  if (!(v > 0)) throw std::invalid_argument(fmt::format("depth of cure: {} must be > 0, got {}", what, v));
}

}  // namespace

DepthOfCureResult depth_of_cure_test(const DepthOfCureOptions& o) {
  DepthOfCureResult r;
  r.material = cure_material_preset(o.material);
  r.published = published_depth_of_cure(o.material);
  if (!r.material.light_cured)
    throw std::invalid_argument(fmt::format(
        "material \"{}\" sets by itself, not by light: the depth of cure is a test of light-cured materials", o.material));
  check_positive(o.irradiance, "the irradiance");
  check_positive(o.exposure_time, "the exposure time");
  check_positive(o.mould_diameter, "the mould's diameter");
  check_positive(o.mould_length, "the mould's length");
  check_positive(o.spacing, "the spacing");
  check_positive(o.cure_dt, "the cure update's dt");

  // The paste: lattice sites in the mould, its top layer's centres half a spacing below z = 0.
  const real s = o.spacing, R = 0.5 * o.mould_diameter;
  const int across = int(std::floor(R / s)), layers = std::max(1, int(std::lround(o.mould_length / s)));
  // One layer's sites (x, y), and the whole mould counted from them before anything is made: a fine
  // spacing in a long mould (0.02 mm in 50 mm: 78 million particles) is refused instead of
  // allocating until the machine runs out.
  std::vector<std::array<real, 2>> layer;
  for (int j = -across; j <= across; ++j)
    for (int i = -across; i <= across; ++i) {
      const real x = (i + 0.5) * s, y = (j + 0.5) * s;
      if (x * x + y * y <= R * R) layer.push_back({x, y});
    }
  ModelParams p;
  const double count = double(layer.size()) * layers;
  const std::string memory = count <= double(limits::max_particles)
                                 ? limits::memory_problem(0, std::uint64_t(count), p.max_bonds_per_particle, false,
                                                          limits::memory_limit_bytes())
                                 : std::string();
  if (count > double(limits::max_particles) || !memory.empty())
    throw std::invalid_argument(fmt::format(
        "depth of cure: a mould {:.3g} mm across and {:.3g} mm long at a spacing of {:.3g} mm holds {:.3g} particles, "
        "{}: give a coarser spacing (--spacing) or a shorter mould (--mould-length)",
        o.mould_diameter / mm, o.mould_length / mm, s / mm, count,
        memory.empty() ? fmt::format("over the limit of {}", limits::max_particles) : memory));
  p.dt = 1e-5;
  set_lattice_spacing(p, s);
  p.domain_min = {-R - 2 * s, -R - 2 * s, -o.mould_length - 2 * s};
  p.domain_max = {R + 2 * s, R + 2 * s, 2 * s};
  Model model = make_model(p);  // its material table grows with the paste (add_particles)
  const Material paste{1.0, 10, 2000, 50};
  const real mass = lattice_particle_mass(paste.rho0, s, model.kernel);
  std::vector<ParticleInit> ps;
  ps.reserve(std::size_t(count));
  for (int k = 0; k < layers; ++k)
    for (const auto& [x, y] : layer) ps.push_back(make_particle(Role::material, {x, y, -(k + 0.5) * s}, mass, paste));
  State state;
  state.add_particles(model, ps);
  r.particles = state.size();

  const CureModel cure = make_cure_model(model, r.material, s, paste);
  CuringLight light;
  light.tip = {0, 0, 0};
  light.direction = {0, 0, -1};
  light.diameter = o.light_diameter;
  light.irradiance = o.irradiance;
  const auto updates = std::max<long>(1, std::lround(o.exposure_time / o.cure_dt));
  const real dt = o.exposure_time / real(updates);
  for (long u = 0; u < updates; ++u) {
    state.time += dt;
    cure_between_steps(cure, state, light, dt);
  }
  // Scrape: what has not set goes; the set cylinder's length runs from the paste's top (z = 0)
  // to the lowest set particle's lower face.
  real lowest = 0, top_dose = 0;
  std::uint32_t top = 0;
  for (std::uint32_t i = 0; i < state.size(); ++i) {
    const std::uint32_t id = state.id[i];
    if (state.cure.rigid[id])
      lowest = std::min(lowest, state.pos[i].z - 0.5 * s);
    else
      ++r.scraped;
    if (state.pos[i].z > -s) top_dose += state.cure.dose[id], ++top;
  }
  r.cured_length = -lowest;
  r.depth = 0.5 * r.cured_length;
  r.top_dose = top > 0 ? top_dose / top : 0;
  r.set_to_bottom = r.scraped == 0;
  return r;
}

std::string depth_of_cure_report(const DepthOfCureOptions& o, const DepthOfCureResult& r) {
  std::string out = fmt::format(
      "ISO 4049 depth of cure, {} ({} particles at {:.2g} mm in a mould {:.1f} mm across and {:.1f} mm long)\n"
      "  light: {:.0f} mW/cm2 for {:.3g} s ({:.3g} J/cm2 at the window; the top layer received {:.3g} J/cm2)\n"
      "  cured length after scraping: {:.2f} mm ({} particles scraped away)\n"
      "  depth of cure: {:.2f} mm\n",
      r.material.name, r.particles, o.spacing / mm, o.mould_diameter / mm, o.mould_length / mm,
      o.irradiance / W_per_m2_per_mW_per_cm2, o.exposure_time, o.irradiance * o.exposure_time / J_per_m2_per_J_per_cm2,
      r.top_dose / J_per_m2_per_J_per_cm2, r.cured_length / mm, r.scraped, r.depth / mm);
  if (r.set_to_bottom)
    out += "  the whole mould set: its length limited the result, not the light; give a longer mould\n";
  if (r.published.depth > 0)
    out += fmt::format("  published: {:.2f} mm at {:.0f} mW/cm2 for {:.3g} s ({:+.0f}%): {}\n", r.published.depth / mm,
                       r.published.irradiance / W_per_m2_per_mW_per_cm2, r.published.exposure_time,
                       100 * (r.depth / r.published.depth - 1), r.published.source);
  return out;
}

}  // namespace dentsph
