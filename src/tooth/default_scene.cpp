// The built-in scene's geometry: the procedural crown, the default Class I cavity, its lining.
#include "dentsph/tooth.hpp"

namespace dentsph {

ToothScene default_tooth_scene() {
  const MolarCrown crown = molar_crown();
  PreparedTooth tooth = carve_cavity(MeshDistance(crown.mesh), crown.frame, CavityParams{});
  BoundaryParams bp;
  bp.spacing = default_tooth_spacing;
  BoundarySamples boundary = sample_boundary(tooth, bp);
  return {std::move(tooth), std::move(boundary)};
}

}  // namespace dentsph
