// The filling graded as a tutor grades a restoration's surface (docs/assessment.md, "The surface
// graded"): its anatomic form against the intact tooth and its marginal adaptation along the
// cavity's occlusal margin, each measured on the paste's surface (surface.hpp) and the prepared
// tooth. The USPHS (Ryge) criteria they follow are qualitative; the numbers that turn them into
// bands and defects are dentsph's and documented there. Lengths in metres unless a name says mm.
#pragma once

#include <string>
#include <vector>

#include "dentsph/surface.hpp"
#include "dentsph/tooth.hpp"
#include "dentsph/vec3.hpp"

namespace dentsph {

struct GradeParams {
  real spacing = default_tooth_spacing;  // m, the paste's particle spacing (what the model resolves)
  real column = 0;          // m, the anatomic form's column spacing; 0: spacing / 3 (the surface's voxel)
  real step_threshold = 0;  // m, a step at the margin read as a defect; 0: the larger of 0.15 mm and spacing / 2
  real probe = 0;           // m, how far inside and outside the margin the step is read; 0: spacing
  real min_site = 0;        // m, a defect shorter along the margin is below what the model resolves; 0: spacing
  // m, the restoration's top in a column is the highest paste within this of it, so that the crevice
  // narrower than a particle that the paste keeps from a wall is not read as a gap; 0: spacing
  real bridge = 0;
  int margin_samples = 720;  // points on the margin, at equal angles about the long axis
  real band_up = 2e-3;      // m, paste higher than this above the intact surface is not the restoration's
  // The anatomic form's bands (USPHS alpha / bravo / charlie), on the 95th percentile of the
  // columns' deviation: alpha within alpha_max either way, charlie an under-contour deeper than
  // charlie_under, bravo between.
  real alpha_max = 0.25e-3;
  real charlie_under = 1e-3;
  // The preclinical rubric's marginal rule: more than max_sites defect sites, or any longer than
  // max_site, fails.
  int max_sites = 3;
  real max_site = 1e-3;
  // A Class II's proximal contact, with the neighbour taken where the intact tooth's proximal
  // contour stood (no neighbouring tooth in the scene): tight where the restoration's proximal
  // surface reaches within contact_tight of it, light within contact_open, open beyond; 0: half a
  // spacing (the paste's standoff from the matrix band) and that plus 0.1 mm.
  real contact_tight = 0;
  real contact_open = 0;
  // Paste standing more than this beyond the intact contour below the contact is an overhang; 0:
  // step_threshold's value. One over less than overhang_min_area is below what the model resolves;
  // 0: a particle's cross-section, spacing^2 (m^2).
  real overhang_threshold = 0;
  real overhang_min_area = 0;
  // Surface voids: pits in the restoration's surface narrower than twice pit_radius (m), found by
  // closing its height map with a disc of that radius; one whose volume is under min_void (m^3; 0:
  // spacing^3, a particle's volume) is porosity below what the model resolves.
  real pit_radius = 0.5e-3;
  real min_void = 0;
};

// The restoration's occlusal surface against the intact tooth's, column by column along the long
// axis over the cavity's opening: deviation = the restoration's top (the highest paste within
// GradeParams::bridge of the column, or the cavity's floor where there is none) minus the intact
// tooth's top; < 0 under-contoured.
struct AnatomicForm {
  bool measured = false;
  std::string why_not;          // when not measured: what is missing
  int columns = 0;              // columns over the opening
  real column_mm = 0;           // their spacing
  real rms_mm = 0;              // root mean square deviation
  real mean_mm = 0;             // mean deviation (< 0: under-filled on the whole)
  real max_under_mm = 0;        // deepest under-contour (>= 0)
  real max_over_mm = 0;         // highest over-contour (>= 0)
  real p95_abs_mm = 0;          // 95th percentile of |deviation|
  real p95_under_mm = 0;        // 95th percentile of the under-contour (>= 0)
  real under_area_mm2 = 0;      // area of the opening under-contoured by more than alpha_max
  real over_area_mm2 = 0;       // ... over-contoured by more than alpha_max
  char band = '-';              // 'A' alpha, 'B' bravo, 'C' charlie ('-' when not measured)
  real alpha_max_mm = 0, charlie_under_mm = 0;  // the bands' limits (GradeParams)
  // Each column, for a picture: its centre in the tooth frame (mm, z on the intact surface) and its
  // deviation (mm).
  std::vector<Vec3> column_centre_mm;
  std::vector<real> deviation_mm;
};

// One defect site: a run of the margin where the paste falls short of the tooth's surface (a gap,
// where an explorer catches) or laps over it (an excess).
struct MarginDefect {
  std::string kind;        // "gap" or "excess"
  real length_mm = 0;      // along the margin
  real largest_step_mm = 0;
  Vec3 centre_mm;          // mean of its margin points, tooth frame
};

// The cavity's occlusal margin, where the cavity meets the intact surface, sampled as a closed
// curve about the long axis; a Class II's proximal opening (where the cavity runs off the tooth's
// top) is counted apart, not graded here.
struct MarginalAdaptation {
  bool measured = false;
  std::string why_not;
  real length_mm = 0;           // the occlusal margin's length
  int open_samples = 0;         // a Class II's samples where the cavity runs off the tooth's top (not graded)
  real gap_length_mm = 0;       // within defect sites of each kind
  real excess_length_mm = 0;
  real below_resolution_mm = 0; // defect runs shorter than min_site, not counted as sites
  real step_threshold_mm = 0;
  std::vector<MarginDefect> defects;  // the sites, along the margin
  real largest_site_mm = 0;
  bool passes = false;          // the rubric: at most max_sites sites, none longer than max_site
  int max_sites = 0;            // the rubric's limits (GradeParams)
  real max_site_mm = 0;
  // The margin's points (tooth frame, mm) and each one's reading: 0 sound, 1 gap, 2 excess, 3 open.
  std::vector<Vec3> point_mm;
  std::vector<int> reading;
};

// A Class II's proximal surface (frame x towards the box's side): its contact at the intact tooth's
// height of contour, and paste standing out beyond the intact contour below it (an overhang over
// the gingival margin).
struct ProximalGrade {
  bool measured = false;
  std::string why_not;        // a Class I: no proximal surface
  std::string side;           // "mesial" or "distal"
  Vec3 contact_mm;            // the intact tooth's height of contour in the box's window, tooth frame
  real gap_mm = 0;            // the intact contour's reach minus the restoration's there (> 0: short)
  std::string contact;        // "tight", "light" or "open"
  real tight_mm = 0, open_mm = 0;  // the thresholds (GradeParams)
  real overhang_mm = 0;       // the most paste stands beyond the intact contour below the contact
  real overhang_area_mm2 = 0; // the proximal window's area where it stands beyond it by the threshold
  real overhang_threshold_mm = 0;
  real overhang_min_area_mm2 = 0;  // an overhang is judged from this area on
};

// A void open to the surface: a pit in the restoration's top, away from the margin (a pit that
// reaches the margin is the margin's gap).
struct SurfacePit {
  Vec3 centre_mm;        // tooth frame, on the surface
  real volume_mm3 = 0;   // below the closed surface
  real depth_mm = 0;     // the deepest
};

// Voids open to the surface, apart from the enclosed ones the assessment counts: the restoration's
// height map (its top over the opening, the tooth's or the paste on it around) closed with a disc
// of pit_radius; where it lies more than the margin's step threshold under its closing, a pit.
struct SurfaceVoids {
  bool measured = false;
  std::string why_not;
  int count = 0;                // pits of at least min_void_mm3
  real volume_mm3 = 0;          // their volume
  real deepest_mm = 0;
  int pore_count = 0;           // smaller pits: porosity below what the model resolves
  real pore_volume_mm3 = 0;
  real min_void_mm3 = 0;
  real pit_width_mm = 0;        // the widest pit found: twice pit_radius
  std::vector<SurfacePit> pits; // those counted
};

struct SurfaceGrade {
  AnatomicForm anatomic;
  MarginalAdaptation margin;
  ProximalGrade proximal;
  SurfaceVoids voids;
};

// Grades `paste` (the paste's surface, world m) against `tooth`. An empty surface grades the empty
// cavity (everything under-contoured, the margin all gap). Throws std::invalid_argument naming the
// field for parameters out of range (a spacing or threshold not positive and finite, fewer than
// 16 margin samples).
SurfaceGrade grade_surface(const PreparedTooth& tooth, const SurfaceMesh& paste, const GradeParams& params = {});

// The summary's "grading" section (docs/outputs.md): the figures and verdicts, without the
// per-column and per-point lists.
std::string surface_grade_json(const SurfaceGrade& g);

// "alpha", "bravo", "charlie" for AnatomicForm::band 'A', 'B', 'C' ("none" otherwise).
const char* anatomic_band_name(char band);

// Its lines for a person (the run's report on the console), each ending in a newline.
std::string surface_grade_report(const SurfaceGrade& g);

}  // namespace dentsph
