// Hand instruments as particle clusters, in the tool frame (tip at the origin, handle along +z),
// and increments of filling material. The tool's particles follow the device pose as a rigid
// transform (State::tool_pose).
#pragma once

#include <string>
#include <vector>

#include "dentsph/model.hpp"
#include "dentsph/state.hpp"

namespace dentsph {

struct ToolShape {
  std::string name;
  std::vector<Vec3> points;  // m, tool frame
};

// A ball burnisher: particles evenly on a sphere of `diameter` (a Fibonacci lattice with about
// one particle per spacing^2 of surface), centred `diameter / 2` above the tip. The paper's tool
// is about 42 particles: diameter 1.1 mm at 0.3 mm spacing. `layers` >= 2 adds shells a spacing
// apart inwards (while larger than half a spacing) and a particle at the centre: 42 + 9 + 1 at
// the paper's size.
ToolShape ball_burnisher(real diameter, real spacing, int layers = 1);
// A flat plugger: a solid cylinder of `diameter` and `length` on a lattice, its flat face the tip.
ToolShape flat_plugger(real diameter, real length, real spacing);
// A condenser: a plugger whose face is serrated (alternate rows of the face set back by a third
// of a spacing) to grip the paste.
ToolShape condenser(real diameter, real length, real spacing);
// The names tool_by_name knows, in a fixed order (a recording names a switched tool by its
// position here: new instruments go at the end).
const std::vector<std::string>& instrument_names();
// The layers of particles an instrument's walls have for a solver (StepSolver::instrument_layers):
// the iisph solver's walls need two (docs/model.md, "What changes in the paper's model"), the
// paper's ball is one shell.
int instrument_layers(Solver solver);
// A tool by name ("ball_burnisher", "flat_plugger", "condenser") with its default size for a
// material spacing, as `solver` runs it (the ball burnisher has instrument_layers(solver) layers;
// the plugger and the condenser are solid); throws std::invalid_argument naming the known tools
// otherwise.
ToolShape tool_by_name(const std::string& name, real spacing, Solver solver);

// The particles of an instrument (tool frame) with the given mass and material.
// `index`: the material's entry of Model::materials (kNoMaterial: found by its values).
std::vector<ParticleInit> tool_particles(const ToolShape& shape, real mass, const Material& material,
                                         MaterialIndex index = kNoMaterial);
// Replaces the tool particles of `state` (between steps) by `particles` (tool frame), placed at
// the current tool pose.
void replace_tool_particles(State& state, const Model& model, const std::vector<ParticleInit>& particles);
// Replaces the tool particles of `state` by `shape`'s (between steps), placed at the current
// tool pose, with the given mass and material.
void switch_tool(State& state, const Model& model, const ToolShape& shape, real mass, const Material& material,
                 MaterialIndex index = kNoMaterial);

// An increment of material: lattice points of `spacing` in a sphere of the given volume (m^3)
// around `centre`, at least one particle. Throws std::invalid_argument, before making any, when
// increment_points_bound is over limits::max_particles or the volume or spacing is not finite and
// positive.
std::vector<ParticleInit> material_increment(const Vec3& centre, real volume, real spacing, real mass,
                                             const Material& material, MaterialIndex index = kNoMaterial);
// At least the number of particles material_increment makes for `volume` and `spacing` (every
// lattice point within R of the centre owns a cube of the lattice inside R + s: 4/3 pi (R + s)^3 /
// s^3); infinity for a volume or spacing that is not finite and positive.
double increment_points_bound(real volume, real spacing);

}  // namespace dentsph
