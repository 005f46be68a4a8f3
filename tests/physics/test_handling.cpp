// The presets' virtual handling tests (include/dentsph/handling.hpp; docs/model.md, "Handling
// tests"), each figure beside its published range:
// - rheometer: the flow curve of each preset in a parallel-plate rheometer calibrated with a
//   Newtonian standard; its viscosity at 10 /s inside the published range (a calibration: the
//   presets were chosen there), the flowable's over the universal's inside Lee, Son & Um 2003's
//   0.04 to 0.56 (not fitted), the law's flow index read back, and packable > universal > flowable;
//   in oscillation at 10 rad/s the complex viscosity in the published range and the phase angle a
//   liquid's, 90 degrees (a departure: the model has no elasticity).
// - slump: 10 s on glass (Lee et al. 2010); the flowable slumps, the pastes with a yield stress
//   hold their shape, in the order of their viscosity.
// The result's JSON and plots are tested through the program (tests/unit/test_cli.cpp,
// tests/report/test_report_browser.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "dentsph/handling.hpp"
#include "physics/rheology.hpp"

namespace dentsph {
namespace {

HandlingRunOptions two_threads() {
  HandlingRunOptions run;
  run.threads = 2;
  return run;
}

// Three close rates around 10 /s: the viscosity there and the slope of the torque (the slope by
// finite differences: close rates, so that the flowable's plateau, which ends at 10 /s, bends it little).
const HandlingResult& rheometer(const std::string& name) {
  static std::map<std::string, HandlingResult> done;
  auto it = done.find(name);
  if (it == done.end()) {
    RheometerOptions o;
    o.run = two_threads();
    o.shear_rates = {8, 10, 12.5};
    it = done.emplace(name, rheometer_test(paste_preset(name), o)).first;
    std::printf("%s", handling_report(it->second).c_str());
  }
  return it->second;
}

// The complex viscosity a parallel-plate rheometer reads from a paste of flow law `m` (no
// elasticity) oscillated to rim strain gamma0 at omega, from the law itself: the torque's first
// harmonic, T(t) = 2 pi R^3 int_0^1 tau(rho gamma0 omega cos wt) rho^2 drho, read as
// |eta*| = 2 B / (pi R^3 gamma0 omega) (B its cos coefficient; a purely viscous law has no sin
// term), by the midpoint rule over the radius and a period.
real law_complex_viscosity(const Material& m, real gamma0, real omega) {
  constexpr int nr = 400, nt = 400;
  constexpr real pi = 3.14159265358979323846;
  real sum = 0;
  for (int k = 0; k < nt; ++k) {
    const real c = std::cos(2 * pi * (k + 0.5) / nt);
    for (int q = 0; q < nr; ++q) {
      const real rho = (q + 0.5) / nr, rate = rho * gamma0 * omega * c;
      const real tau = rate == 0 ? 0 : rheology::effective_viscosity(m, std::abs(rate)) * rate;
      sum += tau * rho * rho * c;
    }
  }
  const real harmonic = 2 * sum / (real(nr) * nt);  // (2 / P) int_P int_0^1 tau rho^2 cos
  return 4 * harmonic / (gamma0 * omega);
}

const HandlingResult& slump(const std::string& name) {
  static std::map<std::string, HandlingResult> done;
  auto it = done.find(name);
  if (it == done.end()) {
    SlumpOptions o;
    o.run = two_threads();
    it = done.emplace(name, slump_test(paste_preset(name), o)).first;
    std::printf("%s", handling_report(it->second).c_str());
  }
  return it->second;
}

// Each preset's viscosity at 10 /s read back within 3% of its law (the rig is calibrated) and in
// its published range, its shear thinning read back, and the order packable > universal >
// flowable, the flowable's ratio to the universal inside Lee 2003's range (not fitted). Measured
// (2026-11-27, with the viscous pressure): flowable 1,669, universal 5,352, packable 11,590,
// amalgam 43,460 Pa s at 10 /s (the laws' 1,700, 5,300, 11,400, 43,000); the rig's constant 1.158
// (the amalgam's 1.112). One test for the four presets: each rheometer runs once.
TEST(Rheometer, EachPresetReadsItsLawInItsPublishedRangeAndInOrder) {
  for (const std::string name : {"flowable", "universal", "packable", "amalgam"}) {
    SCOPED_TRACE(name);
    const PastePreset preset = paste_preset(name);
    const HandlingResult& r = rheometer(name);
    const HandlingFigure& eta = r.figure("viscosity at 10 /s");
    EXPECT_NEAR(eta.value, rheology::effective_viscosity(preset.paste, 10), 0.03 * eta.value)
        << "the calibrated rheometer reads the preset's law";
    if (preset.published_high > 0) {
      ASSERT_TRUE(eta.range.has_value());
      EXPECT_TRUE(eta.in_range()) << eta.value << " against " << (*eta.range)[0] << " to " << (*eta.range)[1];
    } else {
      EXPECT_FALSE(eta.range.has_value()) << "no published range: none is claimed";
    }
    // The law's shear thinning, read back between 10 and 12.5 /s: the slope of its stress there (a
    // yield stress lowers it below the flow index); not the flowable's, whose plateau ends at 10 /s.
    if (preset.paste.max_viscosity >= 1e6) {
      const real slope = std::log(rheology::effective_viscosity(preset.paste, 12.5) * 12.5 /
                                  (rheology::effective_viscosity(preset.paste, 10) * 10)) /
                         std::log(1.25);
      EXPECT_NEAR(r.figure("flow index").value, slope, 0.05) << "the law's shear thinning, read back";
    }
    EXPECT_GT(r.figure("rig constant").value, 1.0) << "the disc's rim reads high (1.11 to 1.14 in the Couette tests)";
    EXPECT_LT(r.figure("rig constant").value, 1.25);
    ASSERT_EQ(r.curves.size(), 2u);
    EXPECT_EQ(r.curves[0].series[0].x.size(), 3u);
    // In oscillation at 10 rad/s: the complex viscosity in the published range where there is one,
    // and the phase angle of a liquid (the model has no elasticity: the departure from Lee 2003's 31
    // to 78 degrees, which the figure's range shows).
    const HandlingFigure& complex = r.figure("complex viscosity at 10 rad/s");
    EXPECT_NEAR(complex.value, law_complex_viscosity(preset.paste, 1, 10), 0.03 * complex.value)
        << "the calibrated rheometer reads the law's first harmonic";
    if (preset.published_high > 0) {
      EXPECT_TRUE(complex.in_range()) << complex.value;
    }
    const HandlingFigure& phase = r.figure("phase angle at 10 rad/s");
    EXPECT_NEAR(phase.value, 90, 2) << "a liquid's stress is in phase with its strain rate";
    ASSERT_TRUE(phase.range.has_value());
    EXPECT_FALSE(phase.in_range()) << "the departure is shown against the published range";
    EXPECT_GT(r.curves[1].series[1].x.size(), 50u) << "the last cycle's stress, sampled";
  }
  // The law's first harmonic of a Newtonian liquid (the flowable's plateau, 1,700 Pa s, holds to
  // 10 /s) is its viscosity, G'' = omega mu: the quadrature above checked.
  EXPECT_NEAR(law_complex_viscosity(paste_preset("flowable").paste, 1, 10), 1700, 1);
  const real flowable = rheometer("flowable").figure("viscosity at 10 /s").value;
  const real universal = rheometer("universal").figure("viscosity at 10 /s").value;
  const real packable = rheometer("packable").figure("viscosity at 10 /s").value;
  EXPECT_GT(packable, universal);
  EXPECT_GT(universal, flowable);
  const HandlingFigure& ratio = rheometer("flowable").figure("viscosity over a conventional composite's");
  ASSERT_TRUE(ratio.range.has_value());
  EXPECT_TRUE(ratio.in_range()) << ratio.value << ": flowables 0.04 to 0.56 of Z-100 (Lee, Son & Um 2003)";
  EXPECT_NEAR(ratio.value, flowable / universal, 0.03 * ratio.value);
}

// Measured (2026-11-27, a 3 mm cylinder, 690 particles, with the viscous pressure): the flowable
// keeps 0.975 of its height (aspect ratio 1.006 to 0.966; a 1.7 kPa s paste spreads slowly at this
// size), and warmed to 37 C less; universal and packable 1.0000, at rest (under 1e-4 mm/s).
TEST(Slump, TheFlowableSlumpsThePastesWithAYieldStressHoldTheirShape) {
  const HandlingResult &flowable = slump("flowable"), &universal = slump("universal"), &packable = slump("packable");
  const real f = flowable.figure("height kept").value, u = universal.figure("height kept").value,
             p = packable.figure("height kept").value;
  EXPECT_LT(f, 0.99) << "the flowable slumps";
  EXPECT_GT(flowable.figure("fastest particle at the end").value, 1e-3) << "mm/s: and is still slumping at 10 s";
  EXPECT_GT(u, 0.995) << "the universal holds its shape";
  EXPECT_GT(p, 0.995) << "the packable holds its shape";
  EXPECT_LT(universal.figure("fastest particle at the end").value, 1e-3) << "mm/s: at rest";
  EXPECT_LT(flowable.figure("aspect ratio after 10 s").value, universal.figure("aspect ratio after 10 s").value);
  EXPECT_LE(universal.figure("aspect ratio after 10 s").value, packable.figure("aspect ratio after 10 s").value + 0.005);
  EXPECT_NEAR(flowable.figure("aspect ratio at the start").value, 1.0, 0.02) << "as tall as it is wide";
  // The flowable warmed to the mouth's 37 C (0.59 of its viscosity) slumps more than at 23 C.
  SlumpOptions o;
  o.run = two_threads();
  const HandlingResult warm = slump_test(paste_preset("flowable", 37), o);
  EXPECT_LT(warm.figure("height kept").value, f - 0.005);
}

}  // namespace
}  // namespace dentsph

namespace dentsph {
namespace {

// The packing test with the 3 mm probe, held 0.25 s (the stress falls at once when the probe stops).
const HandlingResult& packing(const std::string& name) {
  static std::map<std::string, HandlingResult> done;
  auto it = done.find(name);
  if (it == done.end()) {
    PackingOptions o;
    o.run.threads = 2;
    o.probe_diameters = {3e-3};
    o.hold = 0.25;
    it = done.emplace(name, packing_test(paste_preset(name), o)).first;
    std::printf("%s", handling_report(it->second).c_str());
  }
  return it->second;
}

// The yield stresses of universal and packable were fitted to put this peak inside the published
// 0.12 to 4.21 MPa (a calibration; measured 0.546 and 1.81 MPa with the viscous pressure, 0.63 and
// 1.10 MPa before); the flowable, which must slump, has none and its viscosity alone gives less
// than the range's low end (a departure, held: 0.014 MPa). Once the probe stops the stress relaxes,
// as the published stress does over the hold; the pastes with a yield stress keep a part of it
// (held below their yield stress, the paste under the probe cannot flow back: measured 0.68 and
// 0.70 of the peak 0.25 s on, 0.18 and 0.14 after the command's 10 s), the flowable little (0.067).
// Before the presets kept their volume (the viscous pressure) the stress fell at once, to under
// 0.1% of the peak: the paste gave way by compressing.
TEST(Packing, ThePeakStressRisesFromFlowableToPackableAndTheFittedPastesAreInRange) {
  const HandlingFigure &f = packing("flowable").figure("peak stress, 3 mm probe"),
                       &u = packing("universal").figure("peak stress, 3 mm probe"),
                       &p = packing("packable").figure("peak stress, 3 mm probe");
  EXPECT_LT(f.value, u.value);
  EXPECT_LT(u.value, p.value);
  EXPECT_TRUE(u.in_range()) << u.value << " MPa";
  EXPECT_TRUE(p.in_range()) << p.value << " MPa";
  EXPECT_LT(f.value, 0.12) << "the flowable below the published range: a departure";
  auto after_hold = [](const char* name) {
    return packing(name).figure("stress after the hold over the peak, 3 mm probe").value;
  };
  EXPECT_LT(after_hold("flowable"), 0.2) << "the flowable relaxes";
  for (const char* name : {"universal", "packable"}) {
    EXPECT_LT(after_hold(name), 0.9) << name << ": the stress relaxes once the probe stops";
    EXPECT_GT(after_hold(name), 0.3) << name << ": a paste with a yield stress keeps a part of it";
    EXPECT_GT(after_hold(name), 3 * after_hold("flowable")) << name;
  }
}

}  // namespace
}  // namespace dentsph

namespace dentsph {
namespace {

// The tack test's pull at the protocol's speeds, pressed 0.2 s here (1 s in the protocol).
HandlingResult tack(const std::string& name, std::vector<real> speeds, const std::string& instrument = "steel") {
  TackOptions o;
  o.run.threads = 2;
  o.run.instrument = instrument;
  o.speeds = std::move(speeds);
  o.press_time = 0.2;
  o.pull_distance = 1e-3;  // past the separation (under 0.5 mm)
  HandlingResult r = tack_test(paste_preset(name), o);
  std::printf("%s", handling_report(r).c_str());
  return r;
}

// The universal paste on a steel probe at the slowest and fastest of the protocol's speeds. Its
// contact with steel carries 50 kPa (the interface strength, fitted to put this peak in the
// published 0.47 to 3.68 N: a calibration); the work of separation, predicted, lies in the
// published 0.11 to 2.84 N mm and rises with the speed; the peak does not (a departure, held: the
// contact is rigid-plastic, where a real paste's pull rises with the speed). Measured (the test's
// runs, with the viscous pressure): 2.085 and 2.08 N, work 0.553 and 0.574 N mm at 2 and 8 mm/s
// (the command's defaults: 2.06 to 2.10 N, 0.58 to 0.60 N mm). Before the interface had a
// strength the no-slip coupling pulled 3.75 to 4.85 N (over the range), the same with Ka 0, 10 or
// 50 Pa. A non-stick coated probe (10 kPa, assumed) pulls a fifth of steel's (measured 0.385 N,
// work 0.105 N mm).
TEST(Tack, TheInterfaceStrengthHoldsThePullInRangeAndTheWorkRisesWithTheSpeed) {
  const HandlingResult r = tack("universal", {2e-3, 8e-3});
  const HandlingFigure &slow = r.figure("peak tack force at 2 mm/s"), &fast = r.figure("peak tack force at 8 mm/s");
  const HandlingFigure &w_slow = r.figure("work of separation at 2 mm/s"), &w_fast = r.figure("work of separation at 8 mm/s");
  EXPECT_TRUE(slow.in_range()) << slow.value << " N";
  EXPECT_TRUE(fast.in_range()) << fast.value << " N";
  EXPECT_NEAR(fast.value, slow.value, 0.05 * slow.value) << "the departure: a rigid-plastic contact, no rise with speed";
  EXPECT_GT(w_fast.value, w_slow.value) << "the work rises with the speed";
  EXPECT_TRUE(w_slow.in_range()) << w_slow.value << " N mm";
  EXPECT_TRUE(w_fast.in_range()) << w_fast.value << " N mm";
  ASSERT_EQ(r.curves.size(), 1u);
  ASSERT_EQ(r.curves[0].series.size(), 2u);
  EXPECT_GT(r.curves[0].series[0].y.size(), 10u) << "the pull's curve";

  const real coated = tack("universal", {8e-3}, "coated").figure("peak tack force at 8 mm/s").value;
  EXPECT_GT(coated, 0.1 * fast.value) << "a coated probe still holds some paste";
  EXPECT_LT(coated, 0.3 * fast.value) << "a non-stick coating pulls far less than steel";
}

// The packable pulled 13 N with an unlimited contact (3.6 times the published top): its contact's
// strength holds it in range. The flowable never reaches its contact's strength: its pull is its
// viscous resistance, in proportion to the speed (measured 0.233 and 0.911 N at 2 and 8 mm/s with
// the viscous pressure, 0.36 and 1.51 N without; the slowest under the published 0.47 N: a
// departure, held). The packable pulls 1.935 N.
TEST(Tack, ThePackableIsHeldInRangeAndTheFlowablesPullRisesWithTheSpeed) {
  const HandlingFigure packable = tack("packable", {2e-3}).figure("peak tack force at 2 mm/s");
  EXPECT_TRUE(packable.in_range()) << packable.value << " N";
  const HandlingResult flowable = tack("flowable", {2e-3, 8e-3});
  const real slow = flowable.figure("peak tack force at 2 mm/s").value, fast = flowable.figure("peak tack force at 8 mm/s").value;
  EXPECT_GT(fast, 3 * slow) << "a viscous pull, about in proportion to the speed";
  EXPECT_TRUE(flowable.figure("peak tack force at 8 mm/s").in_range()) << fast << " N";
  EXPECT_GT(slow, 0.2) << "N";
  EXPECT_LT(slow, 0.47) << "N: the slowest under the published range, held";
  EXPECT_TRUE(flowable.figure("work of separation at 8 mm/s").in_range());
}

}  // namespace
}  // namespace dentsph

namespace dentsph {
namespace {

// The condensation test on the amalgam. Its yield stress was fitted (230 kPa) to put the 1.8 mm
// plugger's peak at the 4.1 MPa (10.4 N) practitioners condense with (a calibration: measured
// 4.045 MPa, 10.3 N with the viscous pressure; fitted at 690 kPa without it, where the paste gave
// way by compressing, and at 590 kPa before the instrument's slip entered the shear rate); the
// 1.15 mm plugger's is a prediction: in the published 4 to 9 MPa, and above the larger plugger's,
// as practitioners' are (9.1 against 4.1 MPa), though at 4.71 MPa well under their 9.1 (a
// departure: a hand pushes harder than the paste needs). A conventional composite resists far
// less. Converged in the spacing before the first fit: 4.47, 4.14, 4.36 MPa (1.15 mm) and 3.49,
// 3.34, 3.30 MPa (1.8 mm) at 0.15, 0.1 and 0.075 mm.
TEST(Condensation, TheAmalgamsFittedPluggerReadsItsStressAndTheSmallerOneIsInRange) {
  CondensationOptions o;
  o.run.threads = 2;
  o.ages.clear();  // the working window: the next test
  const HandlingResult r = condensation_test(paste_preset("amalgam"), o);
  std::printf("%s", handling_report(r).c_str());
  const HandlingFigure &small = r.figure("peak stress, 1.15 mm plugger"), &large = r.figure("peak stress, 1.8 mm plugger");
  EXPECT_NEAR(large.value, 4.1, 0.05 * 4.1) << "the fit: the 1.8 mm plugger at the practitioners' 10.4 N";
  EXPECT_NEAR(r.figure("peak force, 1.8 mm plugger").value, large.value * 1e6 * 0.25 * 3.14159265 * 1.8e-3 * 1.8e-3,
              1e-6);
  EXPECT_TRUE(small.in_range()) << small.value << " MPa: predicted, not fitted";
  EXPECT_GT(small.value, large.value) << "the smaller plugger needs the higher stress";
  EXPECT_LT(small.value, 9.1 * 0.7) << "MPa: the departure below the practitioners' 9.1, held";
  ASSERT_EQ(r.curves.size(), 1u);
  ASSERT_EQ(r.curves[0].series.size(), 2u);
  EXPECT_GT(r.curves[0].series[1].x.back(), 0.45) << "mm: the plugger went half the increment in";

  o.plugger_diameters = {1.8e-3};
  o.spacing = 0.15e-3;
  const real composite = condensation_test(paste_preset("universal"), o).figure("peak stress, 1.8 mm plugger").value;
  EXPECT_LT(composite, 0.5 * large.value) << "MPa: a conventional composite is not condensed like an amalgam";
}

// The amalgam's working window (docs/model.md, "Handling tests"): condensed at its ages since mixing,
// its stress holds through its working time (180 s, the cure preset's: set from the published
// "about 3 minutes", a calibration) and rises as it sets, until it sets rigid at its gel point
// (346 s); the age at which the stress has doubled is the working time read off the test. A
// composite, which does not set by itself, has no window. At 0.15 mm spacing (the fitted figure is
// the 0.1 mm test's above).
TEST(Condensation, TheAmalgamHoldsItsStressThroughItsWorkingTimeAndStiffensAsItSets) {
  CondensationOptions o;
  o.run.threads = 2;
  o.spacing = 0.15e-3;
  o.plugger_diameters = {1.8e-3};
  o.ages = {0, 170, 240, 330, 400};
  const HandlingResult r = condensation_test(paste_preset("amalgam"), o);
  std::printf("%s", handling_report(r).c_str());
  auto at = [&](int age) { return r.figure(fmt::format("peak stress {} s after mixing, 1.8 mm plugger", age)).value; };
  EXPECT_EQ(at(0), r.figure("peak stress, 1.8 mm plugger").value) << "the fresh paste is the one condensed above";
  EXPECT_EQ(at(170), at(0)) << "within its working time the paste has not changed";
  EXPECT_GT(at(240), 1.5 * at(0)) << "setting, it resists more";
  EXPECT_GT(at(330), 1.5 * at(240));
  EXPECT_THROW((void)r.figure("peak stress 400 s after mixing, 1.8 mm plugger"), std::out_of_range)
      << "past its gel point (346 s) the paste is set: not condensed";
  const real working = r.figure("working time: the condensing stress doubled").value;
  EXPECT_GT(working, 180);
  EXPECT_LT(working, 240);
  ASSERT_EQ(r.curves.size(), 2u);
  EXPECT_EQ(r.curves[1].file, "condensation_window");
  EXPECT_EQ(r.curves[1].series[0].x.size(), 4u);

  o.ages = {0, 240};
  const HandlingResult composite = condensation_test(paste_preset("universal"), o);
  EXPECT_EQ(composite.curves.size(), 1u) << "a composite sets by light, not by itself: no window";
}

}  // namespace
}  // namespace dentsph
