// A block of the scene: a shape sampled on a lattice, with a role, a material and a particle mass
// (docs/scene-format.md, "blocks").
#include <fmt/format.h>

#include <cmath>
#include <tuple>

#include "scene/parse.hpp"

namespace dentsph::scene {

namespace {

std::string show(const Vec3& v) { return fmt::format("[{}, {}, {}]", v.x, v.y, v.z); }

// "min" and "max" of a box or container: min < max on every axis.
std::pair<Vec3, Vec3> read_min_max(const Reader& b) {
  const Vec3 lo = b.vec3("min", "the lower corner [x, y, z] in m");
  const Vec3 hi = b.vec3("max", "the upper corner [x, y, z] in m");
  for (int ax = 0; ax < 3; ++ax)
    if (!(lo[ax] < hi[ax]))
      b.fail(
          "max",
          fmt::format("must exceed min on every axis, got min = {}, max = {}", show(lo), show(hi)),
          "give the upper corner above the lower one");
  return {lo, hi};
}

BoxShape read_box(const Reader& b) {
  const auto [lo, hi] = read_min_max(b);
  return {lo, hi};
}

SphereShape read_sphere(const Reader& b) {
  SphereShape s;
  s.center = b.vec3("center", "the centre [x, y, z] in m");
  s.radius = b.number("radius", "the radius in m", Range::positive);
  return s;
}

LatticeShape read_lattice(const Reader& b) {
  LatticeShape l;
  l.origin = b.vec3("origin", "the first point [x, y, z] in m");
  const std::string_view hint = "the points per axis [nx, ny, nz], positive whole numbers";
  const Json& c = b.array("count", hint);
  if (c.size() != 3)
    b.fail("count", fmt::format("expected an array of 3 whole numbers, got {}", describe(c)),
           fmt::format("give {}", hint));
  for (std::size_t ax = 0; ax < 3; ++ax) {
    const std::string key = fmt::format("count[{}]", ax);
    const real n = b.as_number(c[ax], key, hint, Range::positive);
    if (n != std::floor(n) || n > real(max_block_points))
      b.fail(key, fmt::format("must be a whole number in [1, {}], got {}", max_block_points, n),
             fmt::format("give {}", hint));
    l.count[ax] = std::int64_t(n);
  }
  return l;
}

ContainerShape read_container(const Reader& b, real spacing) {
  ContainerShape c;
  std::tie(c.min, c.max) = read_min_max(b);
  c.layers =
      int(b.integer_or("layers", 2, "the wall thickness in particle layers, e.g. 2", 1, 1000));
  c.open_top = b.boolean_or("open_top", true, "true for a cavity open at the top (+z)");
  for (int ax = 0; ax < 3; ++ax)
    if (container_cells(c.min[ax], c.max[ax], spacing) < 1)
      b.fail("max",
             fmt::format("the inner box is under one spacing ({} m) along axis {}", spacing,
                         "xyz"[ax]),
             "make the inner box at least one spacing wide on every axis");
  return c;
}

// Field names a block of `shape` may have, beyond the common ones.
std::vector<std::string_view> fields_of(std::string_view shape, Role role) {
  std::vector<std::string_view> f = {"shape", "spacing", "material", "mass"};
  if (role != Role::tool) f.insert(f.end(), {"role", "velocity"});
  if (shape == "box") f.insert(f.end(), {"min", "max"});
  if (shape == "sphere") f.insert(f.end(), {"center", "radius"});
  if (shape == "lattice") f.insert(f.end(), {"origin", "count"});
  if (shape == "container") f.insert(f.end(), {"min", "max", "layers", "open_top"});
  return f;
}

Shape read_shape(const Reader& b, std::string_view shape, real spacing) {
  if (shape == "box") return read_box(b);
  if (shape == "sphere") return read_sphere(b);
  if (shape == "lattice") return read_lattice(b);
  return read_container(b, spacing);  // plan_block has refused other names
}

// Spacing: at most h, or a particle has no neighbour inside the kernel support, and at least
// h / 10 (limits.hpp), or the mass sum and the neighbour search take hours.
real read_spacing(const Reader& b, real h) {
  const real s = b.number("spacing", "the lattice spacing in m, about h/2", Range::positive);
  if (const std::string problem = limits::spacing_problem(s, h); !problem.empty())
    b.fail("spacing", problem, limits::spacing_fix(h));
  return s;
}

// Refuses blocks that would give no particles or too many to hold, before they are made.
void check_point_count(const Reader& b, const Shape& shape, real spacing, ParticleBudget* budget) {
  const double n = point_count(shape, spacing);
  if (n < 1) b.fail_here("produces zero particles", "make the shape larger than one spacing");
  if (n > double(max_block_points))
    b.fail_here(fmt::format("would produce {:.3g} particles, over the limit of {} per block", n,
                            max_block_points),
                "use a larger spacing or a smaller shape");
  if (budget) budget->add(b, "", n, n, "use a larger spacing or smaller shapes");
}

}  // namespace

Role parse_role(const Reader& block) {
  const std::string role = block.string("role", "the role: \"material\" or \"boundary\"");
  if (role == "material") return Role::material;
  if (role == "boundary") return Role::boundary;
  if (role == "tool")
    block.fail("role", "tool particles do not go in \"blocks\"",
               "put them in tool.blocks, in the tool's frame");
  block.fail("role", fmt::format("unknown role \"{}\"", role), "use \"material\" or \"boundary\"");
}

BlockPlan plan_block(const Reader& b, const BlockContext& ctx) {
  const std::string shape_name = b.string("shape", "the shape: box, sphere, lattice or container");
  if (shape_name != "box" && shape_name != "sphere" && shape_name != "lattice" &&
      shape_name != "container")
    b.fail("shape", fmt::format("unknown shape \"{}\"", shape_name),
           "use box, sphere, lattice or container");
  b.only(fields_of(shape_name, ctx.role));
  BlockPlan plan;
  plan.spacing = read_spacing(b, ctx.kernel.h);
  plan.shape = read_shape(b, shape_name, plan.spacing);
  check_point_count(b, plan.shape, plan.spacing, ctx.budget);

  ParticleInit& proto = plan.proto;
  proto.role = ctx.role;
  proto.material = resolve_material(b, ctx.materials, ctx.fallback);
  // Default mass: the one that puts an interior particle of this lattice at rest density.
  const real lattice_mass = lattice_particle_mass(proto.material.rho0, plan.spacing, ctx.kernel);
  proto.mass = b.optional_number("mass", "the mass of each particle in kg", Range::positive).value_or(lattice_mass);
  if (!(proto.mass >= lattice_mass / limits::max_mass_factor && proto.mass <= lattice_mass * limits::max_mass_factor))
    b.fail("mass",
           fmt::format("{:.3g} kg is more than {:.0e} times from the mass that puts this lattice at its rest density "
                       "({:.3g} kg)",
                       proto.mass, limits::max_mass_factor, lattice_mass),
           "omit \"mass\" to take the lattice's, or give one near it");
  if (b.has("velocity") && ctx.role != Role::material)
    b.fail("velocity", "only material particles move (boundary particles are static)",
           "remove \"velocity\" from this block");
  proto.vel = b.vec3_or("velocity", {}, "the initial velocity [vx, vy, vz] in m/s");
  return plan;
}

std::vector<ParticleInit> make_block(const BlockPlan& plan) {
  std::vector<ParticleInit> particles;
  const std::vector<Vec3> points = sample(plan.shape, plan.spacing);
  particles.reserve(points.size());
  ParticleInit p = plan.proto;
  for (const Vec3& x : points) {
    p.pos = x;
    particles.push_back(p);
  }
  return particles;
}

std::vector<ParticleInit> make_blocks(const std::vector<BlockPlan>& plans) {
  std::vector<ParticleInit> particles;
  for (const BlockPlan& plan : plans) {
    const std::vector<ParticleInit> ps = make_block(plan);
    particles.insert(particles.end(), ps.begin(), ps.end());
  }
  return particles;
}

}  // namespace dentsph::scene
