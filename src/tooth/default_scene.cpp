// The built-in scene's geometry: the procedural crown, the default Class I cavity, its lining.
#include <optional>

#include "dentsph/tooth.hpp"

namespace dentsph {

ToothScene line_tooth(PreparedTooth tooth, real spacing) {
  BoundaryParams bp;
  bp.spacing = spacing;
  BoundarySamples boundary = sample_boundary(tooth, bp);
  if (tooth.params().kind == CavityClass::class_2) {
    const BoundarySamples band = matrix_band(tooth, bp.spacing);
    boundary.points.insert(boundary.points.end(), band.points.begin(), band.points.end());
    boundary.layer.insert(boundary.layer.end(), band.layer.begin(), band.layer.end());
  }
  return {std::move(tooth), std::move(boundary)};
}

ToothScene default_tooth_scene() {
  const MolarCrown crown = molar_crown();
  return line_tooth(carve_cavity(MeshDistance(crown.mesh), crown.frame, CavityParams{}));
}

ToothScene tooth_scene_from_mesh(const std::filesystem::path& mesh_file, const CavityParams& cavity) {
  const LoadedMesh loaded = load_mesh(mesh_file);
  std::optional<PreparedTooth> carved;
  try {
    carved = carve_cavity(MeshDistance(loaded.mesh), find_tooth_frame(loaded.mesh), cavity);
  } catch (const CavityError& e) {
    throw CavityError(mesh_file.string() + ": " + e.what());  // which tooth
  }
  return line_tooth(std::move(*carved));
}

}  // namespace dentsph
