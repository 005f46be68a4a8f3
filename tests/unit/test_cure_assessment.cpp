// The assessment of cure (src/cure/assessment.cpp) on paste whose conversion is set by hand: the
// numbers per increment, the message, the JSON.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "dentsph/cure_assessment.hpp"
#include "support/cure_scenes.hpp"

namespace dentsph::testing {
namespace {

constexpr real mm = 1e-3;

TEST(CureAssessment, PerIncrementThicknessDoseAndUnderCuredShare) {
  const real s = 0.2 * mm;
  Model model = cure_model(s, {-1 * mm, -1 * mm, -1 * mm}, {3 * mm, 3 * mm, 7 * mm});
  State st;
  add_paste_layers(model, st, s, 5, 5, 0, 10);        // increment 1: 2 mm
  add_paste_layers(model, st, s, 5, 5, 2 * mm, 18);   // increment 2: 3.6 mm on it
  const CureModel cm = make_cure_model(model, cure_material_preset("composite"), s, kPaste);
  // Conversion from dose, the dose falling by e per mm below each increment's top.
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    const std::uint32_t id = st.id[i];
    const real top = st.cure.increment[id] == 1 ? 2 * mm : 5.6 * mm;
    st.cure.dose[id] = 16e4 * std::exp(-(top - st.pos[i].z) / mm);
    st.cure.alpha[id] = conversion_from_dose(cm.paste, st.cure.dose[id]);
  }
  const CureAssessment a = assess_cure(cm, st, {0, 0, 1});
  ASSERT_EQ(a.increments.size(), 2u);
  const IncrementCure& one = a.increments[0];
  const IncrementCure& two = a.increments[1];
  EXPECT_EQ(one.index, 1);
  EXPECT_EQ(one.particles, 250u);
  EXPECT_NEAR(one.thickness, 2 * mm, 1e-12);
  EXPECT_NEAR(two.thickness, 3.6 * mm, 1e-12);
  EXPECT_NEAR(two.top_dose, 16e4 * std::exp(-0.1), 1e-6);
  EXPECT_NEAR(two.base_dose, 16e4 * std::exp(-3.5), 1e-6);
  // Under-cured: alpha below 0.8 of the top's layer by layer (about 2.3 mm below the top here).
  int adequate = 0;
  for (int k = 0; k < 18; ++k) {
    const real depth = (k + 0.5) * s;
    adequate += conversion_from_dose(cm.paste, 16e4 * std::exp(-depth / mm)) >= 0.8 * two.top_alpha;
  }
  EXPECT_NEAR(two.adequate_fraction, adequate / 18.0, 1e-12);
  EXPECT_LT(two.adequate_fraction, 0.75);
  EXPECT_NEAR(one.adequate_fraction, 1.0, 1e-12) << "2 mm at 16 J/cm2 with e per mm: 0.86 at the base";
  EXPECT_NEAR(two.under_cured_from, (adequate) * s, 1e-9);
  EXPECT_NEAR(two.under_cured_to, 3.6 * mm, 1e-9);
  EXPECT_NEAR(a.under_cured_volume, (18 - adequate) * 25 * st.mass[0] / kPaste.rho0, 1e-12) << "volume m / rho0";
  EXPECT_NE(two.message.find("increment 2 is 3.6 mm thick: its base received 0.48 J/cm2"), std::string::npos) << two.message;
  EXPECT_NE(two.message.find("% of it is under-cured"), std::string::npos) << two.message;
  EXPECT_NE(one.message.find("adequately cured"), std::string::npos) << one.message;
  EXPECT_NE(a.message.find("1 of 2 increments"), std::string::npos) << a.message;

  const nlohmann::json j = nlohmann::json::parse(cure_assessment_json(a));
  EXPECT_EQ(j["increments"].size(), 2u);
  EXPECT_NEAR(j["increments"][1]["thickness_mm"].get<double>(), 3.6, 1e-9);
  EXPECT_NEAR(j["increments"][1]["base_dose_J_per_cm2"].get<double>(), 16 * std::exp(-3.5), 1e-9);
  EXPECT_NEAR(j["under_cured_volume_mm3"].get<double>(), a.under_cured_volume / 1e-9, 1e-9);
  EXPECT_NE(cure_assessment_report(a).find(two.message), std::string::npos);
  EXPECT_EQ(a.left_out, 0u);

  // Paste drawn up on the instrument, above the ceiling and out of the light, is left out: the
  // increment's top and thickness are those of the paste below it.
  State drawn = st;
  const std::uint32_t top_id = st.size() - 1;  // increment 2's highest particle
  drawn.pos[drawn.index_of_id[top_id]].z = 9 * mm;
  drawn.cure.dose[top_id] = 0;
  drawn.cure.alpha[top_id] = 0;
  const CureAssessment with = assess_cure(cm, drawn, {0, 0, 1});
  EXPECT_NEAR(with.increments[1].thickness, 3.6 * mm, 1e-12)
      << "one tall column (paste drawn up, or a film up a wall) leaves the median column's thickness alone";
  const CureAssessment without = assess_cure(cm, drawn, {0, 0, 1}, 0.8, 6 * mm);
  EXPECT_EQ(without.left_out, 1u);
  EXPECT_EQ(without.increments[1].particles, two.particles - 1);
  EXPECT_NEAR(without.increments[1].thickness, 3.6 * mm, 1e-12);
  EXPECT_NEAR(without.increments[1].top_dose, two.top_dose, 0.01 * two.top_dose)
      << "the top layer is the paste's (its column one particle lower), not the drawn particle's";
  EXPECT_NEAR(without.increments[1].adequate_fraction, two.adequate_fraction, 0.01);
  EXPECT_EQ(nlohmann::json::parse(cure_assessment_json(without))["left_out_particles"].get<int>(), 1);

  // Paste thrown out and fallen far below the cavity (a lost particle) is left out below the floor:
  // with it, its column would reach 5 m down (as a cured run's report once said of the increment).
  State fallen = st;
  fallen.pos[fallen.index_of_id[0]].z = -5.0;  // increment 1's first particle
  const CureAssessment deep = assess_cure(cm, fallen, {0, 0, 1});
  EXPECT_NEAR(deep.increments[0].thickness, one.thickness, 1e-12) << "the median column is not the fallen one's";
  const CureAssessment kept = assess_cure(cm, fallen, {0, 0, 1}, 0.8, 6 * mm, -1 * mm);
  EXPECT_EQ(kept.left_out, 1u);
  EXPECT_EQ(kept.increments[0].particles, one.particles - 1);
  EXPECT_NEAR(kept.increments[0].thickness, one.thickness, 1e-12);
  EXPECT_NEAR(kept.increments[0].base_dose, one.base_dose, 1e-6);
}

TEST(CureAssessment, PasteNoLightReachedIsSaidSo) {
  const real s = 0.2 * mm;
  Model model = cure_model(s, {-1 * mm, -1 * mm, -1 * mm}, {3 * mm, 3 * mm, 3 * mm});
  State st;
  add_paste_layers(model, st, s, 5, 5, 0, 5);
  const CureModel cm = make_cure_model(model, cure_material_preset("composite"), s, kPaste);
  const CureAssessment a = assess_cure(cm, st, {0, 0, 1});
  ASSERT_EQ(a.increments.size(), 1u);
  EXPECT_EQ(a.increments[0].adequate_fraction, 0);
  EXPECT_NE(a.increments[0].message.find("was not cured"), std::string::npos) << a.increments[0].message;
}

}  // namespace
}  // namespace dentsph::testing
