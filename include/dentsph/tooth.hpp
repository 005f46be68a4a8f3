// Tooth geometry for the filling procedure: a checked and repaired closed surface mesh (loaded
// from STL, OBJ or PLY, or the built-in molar crown), its signed distance, the tooth's frame, a
// Class I or Class II cavity carved into it, and the boundary ("ghost") particles that line the
// cavity. Every length is in metres, every volume in m^3; mesh files are read in the units the
// caller names. docs/tooth.md describes what is checked, repaired and sampled.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "dentsph/vec3.hpp"

namespace dentsph {

// ---- meshes ---------------------------------------------------------------------------------

// A mesh that cannot be used. what() reads "<file>: <problem>; <fix>".
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Units of the coordinates in a mesh file (scanners and CAD export millimetres).
enum class MeshUnits { millimetres, metres };

// An axis-aligned box.
struct Bounds {
  Vec3 min, max;  // m
};

// A triangle surface. After load_mesh() / repair_mesh() it is closed, edge- and vertex-manifold,
// one piece, and every triangle is counter-clockwise seen from outside (signed volume > 0).
struct TriMesh {
  std::vector<Vec3> vertices;                           // m
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into vertices

  Bounds bounds() const;
  real volume() const;  // m^3, signed: positive when the triangles face outwards
  real area() const;    // m^2
};

// What repair_mesh() found and changed.
struct MeshReport {
  std::string source;                  // file name, or what built the mesh
  std::size_t triangles_in = 0;        // triangles read
  std::size_t vertices_in = 0;         // vertex records read
  std::size_t merged_vertices = 0;     // records merged into another within the tolerance
  std::size_t dropped_degenerate = 0;  // triangles with two corners at one point
  std::size_t dropped_duplicate = 0;   // triangles on the same three vertices as another
  std::size_t dropped_pieces = 0;      // loose pieces under 1% of the main piece's area
  std::size_t dropped_piece_triangles = 0;
  std::size_t turned_triangles = 0;  // triangles whose winding was reversed
  bool inside_out = false;           // the whole surface faced inwards (most were turned)
  Vec3 extent;                       // m, size of the bounding box
  real volume = 0;                   // m^3
  real area = 0;                     // m^2

  bool repaired() const;
  std::string summary() const;  // one line: counts, what was repaired, size in mm
};

struct LoadedMesh {
  TriMesh mesh;
  MeshReport report;
};

// Reads STL (binary or ASCII), OBJ or PLY through assimp and runs repair_mesh() on it. Throws
// MeshError naming the file when it is missing or unreadable, holds no triangles, or is refused
// by repair_mesh().
LoadedMesh load_mesh(const std::filesystem::path& file, MeshUnits units = MeshUnits::millimetres);

// Checks and repairs a triangle soup (coordinates already in metres); `source` names it in
// messages. Repairs: merges vertices closer than 1e-6 of the bounding-box diagonal, drops
// triangles whose corners merged and repeated triangles, drops loose pieces under 1% of the
// main piece's area, turns triangles to agree with their neighbours and the whole surface
// outwards. Refuses (MeshError): no triangles, non-finite coordinates, several pieces of
// comparable size, boundary edges (open), edges shared by more than two triangles or vertices
// joining separate fans (non-manifold), a surface that cannot be oriented, no enclosed volume,
// and a size outside 3 to 50 mm (a tooth is 5 to 30 mm across: the message suggests the units).
LoadedMesh repair_mesh(TriMesh soup, const std::string& source);

// ---- distance queries -----------------------------------------------------------------------

// The answer to a distance query.
struct SurfacePoint {
  real distance = 0;  // m, signed: negative inside
  Vec3 closest;       // m, the nearest surface point
  Vec3 normal;        // unit gradient of the distance at the query point (outward on the surface)
};

// Signed distance, inside test and ray casts against a closed, outward mesh (as repair_mesh()
// leaves it): a bounding-volume hierarchy for the nearest triangle, and the sign from the
// angle-weighted pseudo-normal of the nearest feature (Baerentzen and Aanaes, IEEE TVCG 11(3),
// 2005), exact for closed manifold meshes. Built once in O(n log n); a query near the surface
// takes about a microsecond for 45,000 triangles. Immutable; copies share the data; queries are
// safe from any number of threads. Throws std::invalid_argument for a mesh without triangles.
class MeshDistance {
 public:
  explicit MeshDistance(TriMesh mesh);

  const TriMesh& mesh() const;
  Bounds bounds() const;
  SurfacePoint query(const Vec3& p) const;
  real signed_distance(const Vec3& p) const { return query(p).distance; }
  bool inside(const Vec3& p) const { return query(p).distance < 0; }
  // Distance along the unit `direction` from `origin` to the first surface crossing beyond
  // t_min (m), if any.
  std::optional<real> ray(const Vec3& origin, const Vec3& direction, real t_min = 1e-9) const;

  struct Impl;

 private:
  std::shared_ptr<const Impl> impl_;
};

// ---- tooth frame ----------------------------------------------------------------------------

// A right-handed orthonormal frame on the tooth. z is the long axis pointing to the occlusal
// (biting) surface; x is the mesio-distal axis; y = z x x the bucco-lingual axis.
struct ToothFrame {
  Vec3 origin;  // m, a point on the long axis
  Vec3 x, y, z;

  Vec3 to_local(const Vec3& world) const;  // m
  Vec3 to_world(const Vec3& local) const;  // m
};

// A frame from a long axis and a mesio-distal hint (made orthogonal to the axis).
ToothFrame make_tooth_frame(const Vec3& origin, const Vec3& long_axis, const Vec3& mesial_hint);

// The frame found from the mesh: origin at the volume centroid, z along the longest principal
// axis of the solid (the root-crown axis of a tooth with its roots), pointing to the end with
// the larger cross-sections (the crown), x along the second principal axis (mesio-distal for a
// two-rooted molar; its sign cannot be told from one tooth, so it is made deterministic, not
// anatomical). A crown without roots is wider than tall: give its frame instead.
ToothFrame find_tooth_frame(const TriMesh& mesh);

// ---- cavity ---------------------------------------------------------------------------------

// A cavity that does not fit the tooth, or parameters that describe no cavity.
// what() gives the reason with the numbers and what to change.
class CavityError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class CavityClass {
  class_1,  // occlusal box only
  class_2,  // occlusal box and one proximal box
};
// Side of the Class II box: mesial is the frame's +x, distal its -x.
enum class ProximalSide { mesial, distal };

// The preparation, in the tooth frame with z = 0 at the occlusal reference: the highest point
// of the occlusal surface within 0.5 mm of the long axis. The outline is measured at z = 0; the
// walls diverge occlusally by `taper_deg` each, so the outline grows where the cusps rise
// above z = 0. Every internal line and point angle is rounded with `rounding`. Defaults: the
// built-in scene's Class I.
// The largest length a cavity parameter may have (m): no tooth is larger than about 15 mm, so a
// larger one is a mistake of units or a typo, refused before anything is carved.
inline constexpr real max_cavity_length = 50e-3;

struct CavityParams {
  CavityClass kind = CavityClass::class_1;
  real width = 3.0e-3;     // m, bucco-lingual (frame y) outline of the occlusal box at z = 0
  real length = 5.0e-3;    // m, mesio-distal (frame x) outline of the occlusal box at z = 0
  real depth = 2.0e-3;     // m, pulpal floor below z = 0
  real taper_deg = 5;      // degrees, occlusal divergence of each wall from the long axis
  real rounding = 0.5e-3;  // m, radius of internal line and point angles

  // Class II: a proximal box through the mesial or distal surface. The occlusal box then runs
  // on through the marginal ridge of that side into the box (as the isthmus of an MO or DO
  // preparation does), and length / 2 is how far it reaches the other way from the axis.
  ProximalSide side = ProximalSide::mesial;
  real box_width = 3.0e-3;        // m, bucco-lingual width at z = 0
  real box_depth = 3.5e-3;        // m, gingival floor below z = 0 (at least `depth`)
  real box_axial_depth = 1.5e-3;  // m, axial wall inside the proximal surface, measured along
                                  // x from the axis at the height of the gingival floor

  // Fit: what must remain of the tooth.
  real min_wall = 1.0e-3;   // m, beside every wall, measured horizontally outwards
  real min_floor = 1.0e-3;  // m, below the floors, measured down the long axis
};

// What carve_cavity() measured.
struct CavityReport {
  Vec3 occlusal_point;          // m, world: frame origin at the occlusal reference
  real min_wall = 0;            // m, thinnest wall left (over the checked walls)
  real min_floor = 0;           // m, thinnest floor left
  real cavity_volume = 0;       // m^3, tooth removed
  std::string summary() const;  // one line, mm and mm^3
};

// A tooth with a cavity carved into it. Immutable; copies share the data.
class PreparedTooth {
 public:
  const MeshDistance& tooth() const;
  const ToothFrame& frame() const;  // origin at the occlusal reference
  const CavityParams& params() const;
  const CavityReport& report() const;

  // Signed distance to the cavity's shape (unclipped: it reaches above the occlusal surface
  // and, for Class II, through the proximal surface), negative inside.
  SurfacePoint cavity_distance(const Vec3& p) const;
  // Signed distance to the prepared tooth (tooth minus cavity), negative inside it. Exact
  // inside the prepared tooth, a lower bound outside.
  SurfacePoint distance(const Vec3& p) const;
  // Inside the removed tooth: in the cavity's shape and in the original tooth.
  bool in_cavity(const Vec3& p) const;
  // Class II: signed distance to the proximal box's own shape (unclipped). Throws
  // std::logic_error for a Class I cavity.
  real proximal_box_distance(const Vec3& p) const;
  real cavity_volume() const { return report().cavity_volume; }  // m^3
  Bounds cavity_bounds() const;  // m, world box holding every point where in_cavity() is true

  struct Impl;
  explicit PreparedTooth(std::shared_ptr<const Impl> impl);

 private:
  std::shared_ptr<const Impl> impl_;
};

// Carves the cavity, centred on the long axis at the occlusal reference. Throws CavityError
// when the parameters are out of range, a wall or floor would leave less than min_wall /
// min_floor (including an outline that runs off the crown), or the Class II box does not meet
// the occlusal box.
PreparedTooth carve_cavity(const MeshDistance& tooth, const ToothFrame& frame,
                           const CavityParams& params = {});

// ---- boundary particles ---------------------------------------------------------------------

struct BoundaryParams {
  real spacing = 0;  // m, distance between neighbouring particles: the material spacing
  int layers = 2;    // layers into the tooth, `spacing` apart; the first on the surface
  real margin = 0;   // m, band of occlusal surface kept around the outline; 0: 2 spacings
};

// Points on the prepared surface where it bounds the cavity (walls and floors) or lies within
// `margin` of it (the occlusal surface around the outline, and for Class II the proximal
// surface around the box), and the same surface offset `spacing` deeper per layer. Each layer
// is a maximal Poisson-disk set: no two points closer than 0.9 spacing. The first layer's holes
// (wherever a surface point is more than 0.7 spacing from every point) are closed by a point
// 0.75 spacing under the hole (labelled layer 0), so every surface point is within 0.9 spacing
// of a first-layer point.
struct BoundarySamples {
  std::vector<Vec3> points;  // m, world
  std::vector<int> layer;    // 0 on the surface (and under its holes), 1 one spacing deeper, ...
  real spacing = 0;          // m
};

BoundarySamples sample_boundary(const PreparedTooth& tooth, const BoundaryParams& params);

// A matrix band for a Class II cavity: two layers of boundary particles on the tooth's original
// contour where the proximal box cut it away (and one spacing outside it), up to where the
// contour turns to face the occlusal side, and `2 spacing` beyond the box's outline. Like the
// metal strip a dentist wraps round the tooth, it closes the box so that it can be filled.
// Throws std::invalid_argument for a Class I cavity.
BoundarySamples matrix_band(const PreparedTooth& tooth, real spacing);

// ---- built-in molar ---------------------------------------------------------------------------

// A procedurally generated lower molar crown (no roots): a rounded box footprint bulging at the
// height of contour, four cusps around a central fossa, a flat cervical base at z = 0, centred
// on the z axis, mesio-distal along x. Sized like a first molar.
struct MolarCrownParams {
  real length = 11.0e-3;      // m, mesio-distal (x)
  real width = 10.0e-3;       // m, bucco-lingual (y)
  real height = 7.0e-3;       // m, base to cusp tips
  real cusp_height = 1.8e-3;  // m, cusp tips above the central fossa
  int resolution = 96;        // segments around; latitude rings are half as many
};

struct MolarCrown {
  TriMesh mesh;       // passed through repair_mesh()
  MeshReport report;  // nothing repaired
  ToothFrame frame;   // origin at the centre of the base, z up, x mesio-distal
};

MolarCrown molar_crown(const MolarCrownParams& params = {});

// The material spacing the built-in scene is sized for (about 1600 material particles fill its
// cavity, about 1400 boundary particles line it).
inline constexpr real default_tooth_spacing = 0.3e-3;  // m

// A prepared tooth and the boundary particles that line it.
struct ToothScene {
  PreparedTooth tooth;
  BoundarySamples boundary;
};
// The built-in scene's geometry, needing no file: molar_crown() with the default Class I
// cavity, lined at default_tooth_spacing (prepare_tooth() of the default ToothSpec).
ToothScene default_tooth_scene();

// A carved tooth lined at `spacing` (sample_boundary() with two layers; a Class II with its
// matrix_band() too).
ToothScene line_tooth(PreparedTooth tooth, real spacing = default_tooth_spacing);

// Which tooth, how it is oriented and which cavity is carved into it (the command line's and
// dental scene files' choice, include/dentsph/dental.hpp).
struct ToothSpec {
  std::filesystem::path mesh;     // STL, OBJ or PLY; empty: the built-in crown
  MeshUnits units = MeshUnits::millimetres;  // of the mesh file's coordinates
  CavityParams cavity;            // the preparation; default: the built-in Class I
  std::optional<Vec3> long_axis;  // towards the crown, in the mesh's coordinates; none: found
                                  // from the mesh (the built-in crown: its own, +z)
  std::optional<Vec3> mesial;     // towards mesial (the Class II side "mesial"), made orthogonal
                                  // to the axis; none: the found frame's mesio-distal axis
};

// "the built-in crown" or the mesh file's name.
std::string tooth_name(const ToothSpec& spec);

// The tooth of `spec` loaded (or built), its frame found or made from the given axes, the cavity
// carved and lined at default_tooth_spacing (a Class II with its matrix band): the one path every
// lined tooth takes. Throws MeshError, CavityError (its reason after the tooth's name) and
// ToothAxisError (an axis that is zero or not finite, a mesial direction along the long axis).
ToothScene prepare_tooth(const ToothSpec& spec);

// ToothSpec's long axis or mesial direction describes no frame; what() says which and the fix.
class ToothAxisError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// A scanned tooth's scene: prepare_tooth() of the mesh (mm) with its frame found. Throws
// MeshError or CavityError with the reason.
ToothScene tooth_scene_from_mesh(const std::filesystem::path& mesh_file, const CavityParams& cavity = {});

}  // namespace dentsph
