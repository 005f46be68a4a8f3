// The grid step, in the paper's order (section 3.2).
#include "dentsph/step.hpp"
#include "step/stages.hpp"

namespace dentsph {

void step(const Model& model, State& state) {
  stages::compute_cell_keys(model, state);   // 1. broad phase
  stages::sort_by_cell(model, state);        // 2. sort, cell ranges
  stages::reorder(state);                    //    and reorder
  stages::compute_density(model, state);     // 3. density
  stages::compute_pressure(state);           // 4. pressure
  stages::compute_forces(model, state);      // 5. forces, and bond hysteresis of moving particles
  stages::update_boundary_bonds(model, state);  //  bond hysteresis of boundary particles
  stages::compute_tool_wrench(state);        //    force and torque on the tool
  stages::integrate(model, state);           // 6. integration
}

}  // namespace dentsph
