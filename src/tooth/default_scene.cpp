// Lined teeth: the tooth a ToothSpec names (the built-in crown or a scan, its frame found or
// given), the cavity carved, its lining sampled; the built-in scene's geometry is the default
// spec's.
#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <stdexcept>

#include "dentsph/tooth.hpp"

namespace dentsph {

namespace {

Vec3 checked_direction(const Vec3& v, const char* what) {
  if (!is_finite(v) || norm(v) == 0)
    throw ToothAxisError(
        fmt::format("{} ({}, {}, {}) is not a direction; give a finite, non-zero vector", what, v.x, v.y, v.z));
  return v / norm(v);
}

// The frame `found` turned to the given long axis and mesial direction (either may be absent).
ToothFrame given_frame(const ToothFrame& found, const ToothSpec& spec) {
  if (!spec.long_axis && !spec.mesial) return found;
  const Vec3 z = spec.long_axis ? checked_direction(*spec.long_axis, "the long axis") : found.z;
  Vec3 hint = spec.mesial ? checked_direction(*spec.mesial, "the mesial direction") : found.x;
  const real off_axis = norm(hint - z * dot(hint, z));
  if (off_axis < std::sin(10.0 * M_PI / 180)) {
    if (spec.mesial)
      throw ToothAxisError(fmt::format(
          "the mesial direction ({}, {}, {}) lies within 10 degrees of the long axis; give a direction across "
          "the tooth, towards its mesial surface",
          spec.mesial->x, spec.mesial->y, spec.mesial->z));
    hint = found.y;  // the found mesio-distal axis lies along the given long axis: take the other one
  }
  return make_tooth_frame(found.origin, z, hint);
}

}  // namespace

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

std::string tooth_name(const ToothSpec& spec) {
  return spec.mesh.empty() ? std::string("the built-in crown") : spec.mesh.string();
}

ToothScene prepare_tooth(const ToothSpec& spec) {
  TriMesh mesh;
  ToothFrame found;
  if (spec.mesh.empty()) {
    MolarCrown crown = molar_crown();
    mesh = std::move(crown.mesh);
    found = crown.frame;
  } else {
    mesh = load_mesh(spec.mesh, spec.units).mesh;
    found = find_tooth_frame(mesh);
  }
  const ToothFrame frame = given_frame(found, spec);
  std::optional<PreparedTooth> carved;
  try {
    carved = carve_cavity(MeshDistance(std::move(mesh)), frame, spec.cavity);
  } catch (const CavityError& e) {
    throw CavityError(fmt::format("{}: {}", tooth_name(spec), e.what()));  // which tooth
  }
  return line_tooth(std::move(*carved));
}

ToothScene default_tooth_scene() { return prepare_tooth(ToothSpec{}); }

ToothScene tooth_scene_from_mesh(const std::filesystem::path& mesh_file, const CavityParams& cavity) {
  ToothSpec spec;
  spec.mesh = mesh_file;
  spec.cavity = cavity;
  return prepare_tooth(spec);
}

}  // namespace dentsph
