// The cure laws and the mapping from conversion to the paste's parameters (src/cure/material.cpp),
// the cure model's checks, and setting without light (the amalgam preset).
#include <gtest/gtest.h>

#include <cmath>

#include "dentsph/cure.hpp"
#include "support/cure_scenes.hpp"

namespace dentsph::testing {
namespace {

constexpr real mm = 1e-3, J_cm2 = J_per_m2_per_J_per_cm2;

TEST(CureLaw, ConversionRisesWithDoseTowardsItsMaximum) {
  const CureMaterial m = cure_material_preset("composite");
  EXPECT_EQ(conversion_from_dose(m, 0), 0);
  EXPECT_NEAR(conversion_from_dose(m, 1 * J_cm2), m.alpha_max * (1 - std::exp(-1.0)), 1e-12);
  EXPECT_NEAR(conversion_from_dose(m, 16 * J_cm2), m.alpha_max, 1e-6 * m.alpha_max);
  real last = 0;
  for (real h = 0.1; h < 30; h *= 1.5) {
    const real a = conversion_from_dose(m, h * J_cm2);
    EXPECT_GT(a, last);
    EXPECT_LE(a, m.alpha_max);
    last = a;
  }
  EXPECT_EQ(conversion_from_dose(cure_material_preset("amalgam"), 16 * J_cm2), 0) << "amalgam ignores the light";
}

// The rule the constants are chosen for: with 1.15 per mm and H_c = 1 J/cm^2, 16 J/cm^2 at the top
// leaves 0.8 of the top's conversion at about 2 mm (Beer-Lambert with the uncured coefficient).
TEST(CureLaw, SixteenJoulesCureTwoMillimetres) {
  const CureMaterial m = cure_material_preset("composite");
  EXPECT_DOUBLE_EQ(m.attenuation_uncured, 1150);
  auto ratio = [&](real top_J_cm2, real depth) {
    return conversion_from_dose(m, top_J_cm2 * J_cm2 * std::exp(-m.attenuation_uncured * depth)) /
           conversion_from_dose(m, top_J_cm2 * J_cm2);
  };
  EXPECT_NEAR(ratio(16, 2 * mm), 0.80, 0.02);
  EXPECT_LT(ratio(20, 4 * mm), 0.25) << "the base of a 4 mm increment";
  EXPECT_GT(ratio(20, 2 * mm), 0.85);
}

TEST(CureLaw, AmalgamSetsAfterItsWorkingTime) {
  const CureMaterial m = cure_material_preset("amalgam");
  EXPECT_EQ(conversion_from_age(m, 0.5 * m.working_time), 0);
  EXPECT_NEAR(conversion_from_age(m, m.working_time + m.set_time_constant), 1 - std::exp(-1.0), 1e-12);
  EXPECT_EQ(conversion_from_age(cure_material_preset("composite"), 1e4), 0) << "a composite needs light";
  // Its gel point's age, the inverse of the law at alpha_gel: 346 s for the preset.
  EXPECT_NEAR(conversion_from_age(m, gel_age(m)), m.alpha_gel, 1e-12);
  EXPECT_NEAR(gel_age(m), 180 + 240 * std::log(2.0), 1e-9);
  EXPECT_TRUE(std::isinf(gel_age(cure_material_preset("composite")))) << "a composite never gels by itself";
}

TEST(CureLaw, ConversionStiffensThePasteAndShrinksIt) {
  const CureMaterial m = cure_material_preset("composite");
  const Material u = kPaste;
  const Material at0 = cured_parameters(m, u, 0, 1e9);
  EXPECT_EQ(at0.mu, u.mu);
  EXPECT_EQ(at0.Ka, u.Ka);
  EXPECT_EQ(at0.rho0, u.rho0);
  const Material gel = cured_parameters(m, u, m.alpha_gel, 1e9);
  EXPECT_NEAR(gel.mu, u.mu * m.viscosity_factor_at_gel, 1e-12);
  EXPECT_NEAR(gel.Ka, u.Ka * m.adhesion_factor_at_gel, 1e-12);
  const Material half = cured_parameters(m, u, 0.5 * m.alpha_gel, 1e9);
  EXPECT_NEAR(half.mu, u.mu * std::sqrt(m.viscosity_factor_at_gel), 1e-12) << "geometric in alpha / alpha_gel";
  const Material full = cured_parameters(m, u, m.alpha_max, 1e9);
  EXPECT_NEAR(full.rho0, u.rho0 / (1 - m.shrinkage), 1e-9) << "mass kept, volume down by the shrinkage";
  EXPECT_EQ(full.Kp, u.Kp);
  // The time step's limit caps the viscosity, and never lowers it below the uncured value.
  EXPECT_DOUBLE_EQ(cured_parameters(m, u, m.alpha_max, 1.5).mu, 1.5);
  EXPECT_DOUBLE_EQ(cured_parameters(m, u, m.alpha_max, 0.1).mu, u.mu);
}

TEST(CureModel, ViscosityLimitComesFromTheTimeStep) {
  const real s = 0.3 * mm;
  Model model = cure_model(s, {0, 0, 0}, {3 * mm, 3 * mm, 3 * mm}, 5e-5);
  const CureModel cm = make_cure_model(model, cure_material_preset("composite"), s, kPaste);
  const real h = 2 * s;
  // Half the bulk's viscous limit: at 0.8 of it a pair of surface particles (a third of the rest
  // density) oscillated unstably and flung paste out of a cured filling (src/cure/cure_step.cpp).
  EXPECT_NEAR(cm.viscosity_limit, 0.5 * 0.125 * h * h * kPaste.rho0 / 5e-5, 1e-12);
  EXPECT_NEAR(cm.shrink_tolerance, 0.01 * s, 1e-15);
  CureMaterial bad = cure_material_preset("composite");
  bad.alpha_gel = 2 * bad.alpha_max;
  EXPECT_THROW(make_cure_model(model, bad, s, kPaste), std::invalid_argument);
  EXPECT_THROW(make_cure_model(model, cure_material_preset("composite"), 0, kPaste), std::invalid_argument);
  try {
    cure_material_preset("glass ionomer");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("composite, amalgam"), std::string::npos) << e.what();
  }
}

// Setting without light: nothing during the working time, then the degree of set rises and the paste
// becomes rigid at half of it, t_w + tau ln 2 after it was mixed. At dt = 10 us, whose viscous limit
// leaves the viscosity room to rise (at the dental scenes' 50 us the cap, 0.9 Pa s, is under the
// paste's own 1 Pa s: it stays, tested below).
TEST(CureSetting, AmalgamBecomesRigidAfterItsWorkingTime) {
  const real s = 0.3 * mm;
  Model model = cure_model(s, {-1 * mm, -1 * mm, -1 * mm}, {3 * mm, 3 * mm, 3 * mm}, 1e-5);
  State st;
  add_paste_layers(model, st, s, 4, 4, 0, 3);
  const CureMaterial am = cure_material_preset("amalgam");
  const CureModel cm = make_cure_model(model, am, s, kPaste);
  const real t_rigid = am.working_time + am.set_time_constant * std::log(2.0);
  cure_at_rest(cm, st, std::nullopt, am.working_time - 1, 1.0);
  EXPECT_EQ(st.cure.alpha[0], 0);
  EXPECT_EQ(st.count(Role::boundary), 0u);
  EXPECT_EQ(st.mu[0], kPaste.mu);
  cure_at_rest(cm, st, std::nullopt, t_rigid - 2 - st.time, 1.0);  // just before
  EXPECT_GT(st.cure.alpha[0], 0.45);
  EXPECT_EQ(st.count(Role::boundary), 0u);
  EXPECT_GT(st.mu[0], kPaste.mu) << "stiffer as it sets";
  EXPECT_DOUBLE_EQ(st.mu[0], cured_parameters(am, kPaste, st.cure.alpha[0], cm.viscosity_limit).mu);
  const CureModel at_50us = make_cure_model(cure_model(s, {-1 * mm, -1 * mm, -1 * mm}, {3 * mm, 3 * mm, 3 * mm}, 5e-5), am, s, kPaste);
  EXPECT_EQ(cured_parameters(am, kPaste, st.cure.alpha[0], at_50us.viscosity_limit).mu, kPaste.mu)
      << "the paper's step at 50 us cannot carry a higher viscosity at the paste's surface";
  cure_at_rest(cm, st, std::nullopt, 4, 1.0);  // just after
  EXPECT_EQ(st.count(Role::boundary), st.size()) << "set: rigid";
  // A light changes nothing: the conversion is the age's.
  const real before = st.cure.alpha[0];
  cure_at_rest(cm, st, light_above({0.6 * mm, 0.6 * mm, 2 * mm}), 1, 1.0);
  EXPECT_NEAR(st.cure.alpha[0], conversion_from_age(am, st.time), 1e-12);
  EXPECT_GT(st.cure.alpha[0], before);
}

}  // namespace
}  // namespace dentsph::testing
