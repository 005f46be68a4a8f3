// The stages of one step (docs/model.md, "One step"), one file each. paper_step.cpp calls them in the
// paper's order; brute_force.cpp replaces the grid stages by all-pairs loops.
#pragma once

#include "dentsph/model.hpp"
#include "dentsph/state.hpp"

namespace dentsph::stages {

// 1. Broad phase: the grid cell key of every particle (hash.cpp).
void compute_cell_keys(const Model& model, State& state, int threads);
// 2a. Counting radix sort of the particles by cell key, and each cell's range (sort.cpp).
void sort_by_cell(const Model& model, State& state);
// 2b. Reorder every particle array into cell order; refresh index_of_id and the material cache
// from model.materials (reorder.cpp). With keep_pressure, State::pressure too (a solver whose next
// pressure solve starts from the last one's).
void reorder(const Model& model, State& state, int threads, bool keep_pressure = false);
// 3. Density: over the 27 neighbouring cells, building each moving particle's neighbour list
// (radius h + skin), or, between rebuilds, over those lists (density.cpp); each particle's
// pressure (stage 4, pressure_stage.hpp) as soon as its density is known.
void compute_density(const Model& model, State& state, int threads, bool build_lists);
// Neighbour-list bookkeeping (neighbour_lists.cpp): whether this step must sort and rebuild, and
// the positions remembered at a rebuild (with a skin only).
// With tool_listed false the tool particles are left out (a solver that finds the tool's
// neighbours itself every step: the iisph solver, solver/tool_pairs.cpp).
bool lists_need_rebuild(const Model& model, const State& state, int threads, bool tool_listed = true);
void remember_build_positions(State& state, int threads);
// The boundary-boundary part of boundary particles' density, once (density.cpp).
void compute_static_density(const Model& model, State& state);
// 5. Pressure, viscosity and adhesion force densities; moving particles' bond hysteresis on the
// distances this pass computes anyway (forces.cpp).
void compute_forces(const Model& model, State& state, int threads);
// Wrench of the particles on the tool, from the forces of this step (tool_wrench.cpp).
void compute_tool_wrench(State& state);
// 6. Semi-implicit Euler for material; the tool moves to its pose (integrate.cpp).
void integrate(const Model& model, State& state, int threads);
// The end of every step, whichever solver took it: the largest acceleration and speed of the
// material (from their squares), its non-finite particles, the tool at its pose, the clock advanced.
void close_step(State& state, real a2max, real v2max, std::uint64_t non_finite, real dt);

// The all-pairs versions of the neighbour stages (brute_force.cpp), and its stage 4 as a pass of
// its own over all particles (the grid step applies pressure_stage.hpp inside its density pass).
void update_bonds_all_pairs(const Model& model, State& state);
void compute_density_all_pairs(const Model& model, State& state);
void compute_pressure_all_pairs(State& state);
void compute_forces_all_pairs(const Model& model, State& state);

}  // namespace dentsph::stages
