// The report's pictures of a filling: a section through the middle of the cavity (mesio-distal,
// seen from the buccal or lingual side) and the tooth seen from above, each drawn with the
// tooth's surface (its mesh and the cavity's walls) and the particles as lit spheres in the
// colour a function gives each one (by role today; another colouring, such as a degree of
// conversion, is another function), or the paste as its surface (dentsph/surface.hpp), cut by the
// section where it crosses it. Voids may be marked with rings; a 1 mm scale bar sits in the lower
// left corner.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "dentsph/state.hpp"
#include "dentsph/surface.hpp"
#include "dentsph/tooth.hpp"
#include "report/raster.hpp"

namespace dentsph::report {

// The colour of particle i, or none to leave it out of the picture.
using ParticleColour = std::function<std::optional<Rgb>(std::size_t i)>;

// Paste blue and tool orange (the project's role colours); boundary particles are left out, the
// tooth's surface stands for them; paste too when `paste` is false (its surface stands for it).
ParticleColour colour_by_role(std::span<const Role> roles, bool paste = true);

struct PictureOptions {
  double spacing = default_tooth_spacing;  // m, the paste's spacing: spheres of half of it
  int width = 720;                         // pixels of each picture's width
  std::vector<Vec3> markers;               // world points ringed in red (void centres)
  std::vector<double> marker_radii;        // m, one per marker (0 or missing: a small ring)
  // The paste's surface, drawn in the paste's colour (its section a darker shade); null: none.
  const SurfaceMesh* paste_surface = nullptr;
};

// The colours the pictures use, for tests and the report's legend.
inline constexpr Rgb kEnamel = {236, 228, 208};
inline constexpr Rgb kDentine = {214, 184, 140};  // the section's cut face
inline constexpr Rgb kBackground = {250, 250, 250};
inline constexpr Rgb kMarker = {220, 30, 30};
inline constexpr Rgb kPasteSection = {40, 80, 170};  // the paste surface's cut face

struct ToothPictures {
  Canvas cut;  // the section through the cavity's middle, the near half removed
  Canvas top;  // from above, along the tooth's long axis
  double px_per_mm = 0;
};

// Draws both pictures of `positions` (world, m) around `tooth`.
ToothPictures draw_tooth_pictures(const PreparedTooth& tooth, std::span<const Vec3> positions,
                                  const ParticleColour& colour, const PictureOptions& options);

// The file names the run folder holds them under: the paste as a surface, and as particles.
inline constexpr const char* kCutPicture = "tooth_cut.png";
inline constexpr const char* kTopPicture = "tooth_top.png";
inline constexpr const char* kCutParticlesPicture = "tooth_cut_particles.png";
inline constexpr const char* kTopParticlesPicture = "tooth_top_particles.png";

// Draws and writes DIR/tooth_cut.png and DIR/tooth_top.png (or, with `particles`, their
// _particles.png pair). Throws std::runtime_error naming a file that cannot be written.
void write_tooth_pictures(const std::filesystem::path& dir, const PreparedTooth& tooth,
                          std::span<const Vec3> positions, const ParticleColour& colour,
                          const PictureOptions& options, bool particles = false);

}  // namespace dentsph::report
