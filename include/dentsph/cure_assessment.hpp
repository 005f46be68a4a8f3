// The assessment of cure (docs/assessment.md, "Cure"): per increment of paste (the particles one
// dispense placed), its thickness, the radiant exposure at its top and base, the share adequately
// cured (conversion at least `criterion` of its top's: bottom/top 0.8 is the usual criterion) and
// where the under-cured paste lies; overall, the under-cured volume; as JSON for summary.json and
// as text for the report, with a plain message per increment.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "dentsph/cure.hpp"

namespace dentsph {

struct IncrementCure {
  int index = 0;                   // 0: the scene's own paste; k: the k-th increment dispensed
  std::uint32_t particles = 0;
  real thickness = 0;              // m, along `up`: the median over its columns (layer_thickness.hpp:
                                   // each column's paste volume over its area)
  real thickness_p90 = 0;          // m, the 90th percentile over its columns: its thickest part
  real top_dose = 0, base_dose = 0;    // J/m^2, mean over its columns' top and base layers (a spacing deep)
  real top_alpha = 0, base_alpha = 0;  // mean conversion of the same layers
  real adequate_fraction = 0;      // share of its particles with alpha >= criterion * top_alpha
  real under_cured_volume = 0;     // m^3
  // Where its under-cured paste lies: from `under_cured_from` to `under_cured_to` below its top (m),
  // each a depth in its column as layer_thickness.hpp measures it (so within its column's
  // thickness); both 0 when there is none.
  real under_cured_from = 0, under_cured_to = 0;
  real under_cured_column_thickness = 0;  // m, the thickest column holding under-cured paste (0: none)
  std::string message;             // e.g. "increment 2 is 3.6 mm thick: its base received ..."
};

struct CureAssessment {
  real criterion = 0.8;
  std::vector<IncrementCure> increments;  // those with paste, in increment order
  real paste_volume = 0;                  // m^3
  real under_cured_volume = 0;            // m^3
  std::string message;                    // one line over all increments
  std::uint32_t left_out = 0;             // paste particles above the ceiling or below the floor (not assessed)
};

// Assesses the paste of `state` (cure.curable particles) by increment; `up` points from the cavity's
// floor towards its opening (the tooth's long axis; thickness and depth are measured along it).
// Paste higher than `ceiling` or lower than `floor` (m, along `up`: dot(position, up / |up|)) is
// left out and counted (left_out): paste drawn up on the instrument, out of the light, or thrown
// out of the cavity and fallen past it, is no part of the filling (an increment's thickness would
// otherwise reach down to where a lost particle has fallen).
CureAssessment assess_cure(const CureModel& cure, const State& state, const Vec3& up, real criterion = 0.8,
                           real ceiling = std::numeric_limits<real>::infinity(),
                           real floor = -std::numeric_limits<real>::infinity());
// As a JSON object (summary.json's "cure"): mm, J/cm^2, mm^3.
std::string cure_assessment_json(const CureAssessment& a);
// As text for the report: the overall line and one line per increment.
std::string cure_assessment_report(const CureAssessment& a);

}  // namespace dentsph
