// Sizing the iisph solver's scratch for the particles of a State (scratch.hpp): after particles were
// added or removed, so that a step allocates nothing.
#include "solver/scratch.hpp"

namespace dentsph {

void IisphScratch::resize(const State& state, bool with_rheology, bool with_viscous) {
  const std::size_t n = state.size();
  auto size = [](auto& v, std::size_t k) {
    v.resize(k);
    v.shrink_to_fit();
  };
  size(material, state.count(Role::material));
  size(active, n);
  active_count = 0;
  size(pairs, n * kPairStride);
  size(n_material, n);
  size(n_other, n);
  size(grad_sum, n);
  size(diag_x, n);
  size(visc_diag, n);
  size(visc_fixed, n);
  size(div_fixed, n);
  size(normal, n);
  size(v_star, n);
  size(source, n);
  size(tool_force, n);
  size(inv_rho, n);
  size(q, n);
  size(q_viscous, with_viscous ? n : 0);
  with_viscous_pressure = with_viscous;
  size(accel, n);
  size(v_a, n);
  size(cg_p, n);
  size(cg_r, n);
  size(cg_ap, n);
  size(interface_scale, n);
  rheology = with_rheology;
  size(visc_unit, with_rheology ? n * kPairStride : 0);
  size(mu_eff, with_rheology ? n : 0);
  size(visc_block, with_rheology ? n : 0);
  size(partial, n / kSumBlock + 1);
  size(pc_scale, n);
  size(pc_y, n);
  size(pc_g, n);
  size(pc_dir, n);
  size(pc_hp, n);
  size(pc_partial, n / kSumBlock + 1);
  const std::size_t tool_count_now = state.count(Role::tool);
  size(tools, tool_count_now);
  size(tool_list, tool_count_now * kToolStride);
  size(tool_count, tool_count_now);
  size(link_start, n + 1);
  size(link_fill, n);
  size(link_tool, tool_count_now * kToolStride);
}

std::size_t IisphScratch::bytes() const {
  auto b = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  return b(material) + b(active) + b(pairs) + b(n_material) + b(n_other) + b(grad_sum) + b(diag_x) + b(visc_diag) +
         b(visc_fixed) + b(div_fixed) + b(normal) + b(v_star) + b(source) + b(tool_force) + b(inv_rho) + b(q) + b(q_viscous) +
         b(accel) + b(v_a) + b(cg_p) + b(cg_r) + b(cg_ap) + b(interface_scale) + b(visc_unit) + b(mu_eff) + b(visc_block) + b(partial) + b(pc_scale) + b(pc_y) + b(pc_g) +
         b(pc_dir) + b(pc_hp) + b(pc_partial) + b(tools) + b(tool_list) + b(tool_count) +
         b(link_start) + b(link_fill) + b(link_tool);
}

}  // namespace dentsph
