// Instruments and increments as particle clusters (include/dentsph/tools.hpp).
#include "dentsph/tools.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "dentsph/limits.hpp"
#include "dentsph/solver.hpp"
#include "physics/kernels.hpp"

namespace dentsph {

namespace {

// Fibonacci lattice: one particle per spacing^2 of a sphere of radius R, centred `centre_z` above the tip.
void sphere_shell(ToolShape& t, real R, real centre_z, real spacing) {
  const int count = std::max(4, int(std::lround(4 * kernels::pi * R * R / (spacing * spacing))));
  const real golden = kernels::pi * (3 - std::sqrt(5.0));
  for (int q = 0; q < count; ++q) {
    const real z = 1 - 2 * (q + 0.5) / count, r = std::sqrt(1 - z * z);
    t.points.push_back({R * r * std::cos(golden * q), R * r * std::sin(golden * q), centre_z + R * z});
  }
}

}  // namespace

ToolShape ball_burnisher(real diameter, real spacing, int layers) {
  const real R = 0.5 * diameter;
  ToolShape t{"ball_burnisher", {}};
  sphere_shell(t, R, R, spacing);
  if (layers >= 2) {
    // Shells a spacing apart inwards while they are larger than half a spacing, then the centre.
    real inner = R - spacing;
    for (int k = 1; k < layers && inner > 0.5 * spacing; ++k, inner -= spacing) sphere_shell(t, inner, R, spacing);
    t.points.push_back({0, 0, R});
  }
  return t;
}

namespace {

// A solid cylinder on a lattice; `face_offset(i, j)` sets back the face row of lattice column i.
template <class FaceOffset>
ToolShape cylinder(const char* name, real diameter, real length, real spacing, FaceOffset&& face_offset) {
  const real R = 0.5 * diameter;
  const int n = int(std::floor(R / spacing));
  const int layers = std::max(1, int(std::lround(length / spacing)) + 1);
  ToolShape t{name, {}};
  for (int k = 0; k < layers; ++k)
    for (int j = -n; j <= n; ++j)
      for (int i = -n; i <= n; ++i) {
        const real x = i * spacing, y = j * spacing;
        if (x * x + y * y > R * R * (1 + 1e-9)) continue;
        t.points.push_back({x, y, k * spacing + (k == 0 ? face_offset(i) : 0)});
      }
  return t;
}

}  // namespace

ToolShape flat_plugger(real diameter, real length, real spacing) {
  return cylinder("flat_plugger", diameter, length, spacing, [](int) { return real(0); });
}

ToolShape condenser(real diameter, real length, real spacing) {
  return cylinder("condenser", diameter, length, spacing, [&](int i) { return (i % 2 ? spacing / 3 : real(0)); });
}

const std::vector<std::string>& instrument_names() {
  static const std::vector<std::string> names = {"ball_burnisher", "flat_plugger", "condenser"};
  return names;
}

int instrument_layers(Solver solver) { return solver_properties(solver).instrument_layers(); }

ToolShape tool_by_name(const std::string& name, real spacing, Solver solver) {
  // Default sizes in spacings: the paper's 42-particle ball at 0.3 mm is 1.1 mm across.
  if (name == "ball_burnisher") return ball_burnisher(3.65 * spacing, spacing, instrument_layers(solver));
  if (name == "flat_plugger") return flat_plugger(5 * spacing, 3 * spacing, spacing);
  if (name == "condenser") return condenser(3 * spacing, 3 * spacing, spacing);
  throw std::invalid_argument(fmt::format("unknown tool \"{}\"; known: {}", name, fmt::join(instrument_names(), ", ")));
}

std::vector<ParticleInit> tool_particles(const ToolShape& shape, real mass, const Material& material,
                                         MaterialIndex index) {
  std::vector<ParticleInit> ps;
  for (const Vec3& p : shape.points) ps.push_back(make_particle(Role::tool, p, mass, material, {}, index));
  return ps;
}

void replace_tool_particles(State& state, const Model& model, const std::vector<ParticleInit>& particles) {
  // The new tool's material checked before the old tool goes (add_particles refuses one the table lacks).
  for (const ParticleInit& p : particles)
    if (p.material_index == kNoMaterial ? !model.materials.find(p.material) : p.material_index >= model.materials.size())
      throw std::invalid_argument(fmt::format(
          "switch_tool: the instrument's material (mu {}, Kp {}, rho0 {}, Ka {}) is not in the Model's material table; "
          "add it (Model::materials.add) and name it",
          p.material.mu, p.material.Kp, p.material.rho0, p.material.Ka));
  std::vector<std::uint8_t> remove(state.size(), 0);
  for (std::uint32_t i = 0; i < state.size(); ++i) remove[i] = state.role[i] == Role::tool;
  state.remove_particles(model, remove);
  state.add_particles(model, particles);  // at tool_pose_applied
}

void switch_tool(State& state, const Model& model, const ToolShape& shape, real mass, const Material& material,
                 MaterialIndex index) {
  replace_tool_particles(state, model, tool_particles(shape, mass, material, index));
}

double increment_points_bound(real volume, real spacing) {
  if (!std::isfinite(volume) || !(volume > 0) || !std::isfinite(spacing) || !(spacing > 0))
    return std::numeric_limits<double>::infinity();
  const double R = std::cbrt(3 * double(volume) / (4 * kernels::pi)) + double(spacing);
  return 4.0 / 3.0 * kernels::pi * (R / double(spacing)) * (R / double(spacing)) * (R / double(spacing));
}

std::vector<ParticleInit> material_increment(const Vec3& centre, real volume, real spacing, real mass,
                                             const Material& material, MaterialIndex index) {
  if (const double bound = increment_points_bound(volume, spacing); !(bound <= double(limits::max_particles)))
    throw std::invalid_argument(fmt::format(
        "material_increment: {:.3g} m^3 at a spacing of {:.3g} m is up to {:.3g} particles, over the limit of {}",
        volume, spacing, bound, limits::max_particles));
  const real R = std::cbrt(3 * volume / (4 * kernels::pi));
  const int n = int(std::ceil(R / spacing));
  std::vector<ParticleInit> ps;
  auto add = [&](const Vec3& p) { ps.push_back(make_particle(Role::material, p, mass, material, {}, index)); };
  for (int k = -n; k <= n; ++k)
    for (int j = -n; j <= n; ++j)
      for (int i = -n; i <= n; ++i) {
        const Vec3 d{i * spacing, j * spacing, k * spacing};
        if (norm2(d) <= R * R) add(centre + d);
      }
  if (ps.empty()) add(centre);
  return ps;
}

}  // namespace dentsph
