// The assessment of cure (src/cure/assessment.cpp) on paste whose conversion is set by hand: the
// numbers per increment, the message, the JSON.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "dentsph/cure_assessment.hpp"
#include "dentsph/layer_thickness.hpp"
#include "support/cure_scenes.hpp"

namespace dentsph::testing {
namespace {

constexpr real mm = 1e-3;

// A paste that sets by itself (the amalgam's cure): no light cures it, so none of it is called
// under-cured; the message says how much has set and when the rest will.
TEST(CureAssessment, APasteThatSetsByItselfIsNotUnderCuredByTheLight) {
  const real s = 0.2 * mm;
  Model model = cure_model(s, {-1 * mm, -1 * mm, -1 * mm}, {3 * mm, 3 * mm, 7 * mm});
  State st;
  add_paste_layers(model, st, s, 5, 5, 0, 10);  // 250 particles, 2 mm
  const CureModel cm = make_cure_model(model, cure_material_preset("amalgam"), s, kPaste);
  for (std::uint32_t id = 0; id < 50; ++id) st.cure.rigid[id] = 1;  // a fifth set
  const CureAssessment a = assess_cure(cm, st, {0, 0, 1});
  ASSERT_EQ(a.increments.size(), 1u);
  EXPECT_EQ(a.under_cured_volume, 0);
  const real volume = st.mass[0] / kPaste.rho0 / (mm * mm * mm);  // mm3 a particle
  EXPECT_NE(a.message.find(fmt::format("sets by itself (amalgam), not by light: {:.2f} of {:.2f} mm3 set", 50 * volume,
                                       250 * volume)),
            std::string::npos)
      << a.message;
  EXPECT_NE(a.message.find("rigid 346 s after"), std::string::npos) << a.message;
  EXPECT_NE(a.increments[0].message.find("sets by itself"), std::string::npos) << a.increments[0].message;
}

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
  EXPECT_NEAR(two.under_cured_column_thickness, 3.6 * mm, 1e-9) << "down to its base, within its thickness";
  EXPECT_EQ(two.message.find("where it is up to"), std::string::npos) << "no deeper than its (median) thickness";
  EXPECT_NEAR(a.under_cured_volume, (18 - adequate) * 25 * st.mass[0] / kPaste.rho0, 1e-12) << "volume m / rho0";
  EXPECT_NE(two.message.find("increment 2 is 3.60 mm thick: its base received 0.48 J/cm2"), std::string::npos) << two.message;
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

// Under-cured paste deeper than the increment's (median) thickness lies where it is thicker: the
// message says how thick it is there. One increment 2 mm thick in three of its columns and 3 mm in
// the fourth, its lowest layer under-cured.
TEST(CureAssessment, UnderCuredPasteBelowTheMedianSaysHowThickTheIncrementIsThere) {
  const real s = 0.2 * mm;
  Model model = cure_model(s, {-1 * mm, -1 * mm, -1 * mm}, {3 * mm, 3 * mm, 7 * mm});
  State st;
  add_paste_layers(model, st, s, 4, 4, 0, 10);       // four columns of 2 mm
  add_paste_layers(model, st, s, 2, 2, 2 * mm, 5);   // one of them 1 mm taller
  const CureModel cm = make_cure_model(model, cure_material_preset("composite"), s, kPaste);
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    const std::uint32_t id = st.id[i];
    st.cure.increment[id] = 1;
    st.cure.dose[id] = 1e5;
    st.cure.alpha[id] = st.pos[i].z < s ? 0.3 : 0.7;  // the lowest layer under the 0.8 criterion
  }
  const CureAssessment a = assess_cure(cm, st, {0, 0, 1});
  ASSERT_EQ(a.increments.size(), 1u);
  const IncrementCure& r = a.increments[0];
  EXPECT_NEAR(r.thickness, 2 * mm, 1e-9);
  EXPECT_NEAR(r.thickness_p90, 3 * mm, 1e-9);
  EXPECT_NEAR(r.under_cured_from, 1.8 * mm, 1e-9);
  EXPECT_NEAR(r.under_cured_to, 3 * mm, 1e-9) << "the tall column's lowest layer";
  EXPECT_NEAR(r.under_cured_column_thickness, 3 * mm, 1e-9);
  EXPECT_NE(r.message.find("increment 1 is 2.00 mm thick"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("from 1.80 mm below its top down to 3.00 mm, where it is up to 3.00 mm thick"), std::string::npos)
      << r.message;
  const nlohmann::json j = nlohmann::json::parse(cure_assessment_json(a));
  EXPECT_NEAR(j["increments"][0]["thickness_p90_mm"].get<double>(), 3.0, 1e-9);
  EXPECT_NEAR(j["increments"][0]["under_cured_column_thickness_mm"].get<double>(), 3.0, 1e-9);
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

namespace dentsph::testing {
namespace {

// layer_thickness(), the one definition of an increment's thickness: a lattice block's layers, a
// block whose edge columns the paste half covers, a gap inside it and a film drawn up a wall.
TEST(LayerThickness, IsThePastesVolumeOverTheAreaItCoversInEachColumn) {
  const real s = 0.3 * mm;
  auto block = [&](int nx, int ny, int nz) {
    std::vector<Vec3> p;
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) p.push_back(Vec3{i + 0.5, j + 0.5, k + 0.5} * s);
    return p;
  };
  // 4 x 4 cells, 10 layers: four full columns, each 10 s; every depth inside its column.
  const LayerThickness full = layer_thickness(block(4, 4, 10), {0, 0, 1}, s);
  EXPECT_EQ(full.column_particles.size(), 4u);
  EXPECT_NEAR(full.median, 10 * s, 1e-12);
  EXPECT_NEAR(full.p90, 10 * s, 1e-12);
  const std::vector<Vec3> five = block(5, 5, 10);
  // 5 x 5: the edge columns hold half or a quarter of a full one's paste over as much less area.
  const LayerThickness edges = layer_thickness(five, {0, 0, 1}, s);
  EXPECT_EQ(edges.column_particles.size(), 9u);
  EXPECT_NEAR(edges.median, 10 * s, 1e-12) << "a column the paste half covers is not half as thick";
  for (std::size_t i = 0; i < five.size(); ++i) {
    const real top_down = (10 - 0.5) * s - five[i].z;  // from the top layer's centre
    EXPECT_NEAR(edges.depth[i], std::floor(top_down / s + 1e-9) * s, s) << i;
    EXPECT_LT(edges.depth[i], edges.column_thickness(edges.column[i])) << i;
  }
  // A layer missing in the middle: 9 layers of paste, not the 10 its extent spans.
  std::vector<Vec3> gap;
  for (const Vec3& p : block(4, 4, 10))
    if (std::abs(p.z - 4.5 * s) > 1e-9) gap.push_back(p);
  EXPECT_NEAR(layer_thickness(gap, {0, 0, 1}, s).median, 9 * s, 1e-12);
  // A film one particle thick drawn 20 spacings up a wall: the wall's columns are thicker (the
  // 90th percentile shows them), the median is not.
  std::vector<Vec3> film = block(8, 8, 5);
  for (int k = 5; k < 25; ++k)
    for (int j = 0; j < 8; ++j) film.push_back(Vec3{0.5, j + 0.5, k + 0.5} * s);
  const LayerThickness drawn = layer_thickness(film, {0, 0, 1}, s);
  EXPECT_NEAR(drawn.median, 5 * s, 1e-12);
  EXPECT_GT(drawn.p90, 5 * s);
  // Measured along any `up`: the same block on its side.
  std::vector<Vec3> side;
  for (const Vec3& p : block(4, 4, 10)) side.push_back(Vec3{p.z, p.y, p.x});
  EXPECT_NEAR(layer_thickness(side, {1, 0, 0}, s).median, 10 * s, 1e-12);
  EXPECT_EQ(layer_thickness({}, {0, 0, 1}, s).median, 0);
}

}  // namespace
}  // namespace dentsph::testing
