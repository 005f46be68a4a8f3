// The curing light's transport (src/cure/light_transport.cpp) against Beer-Lambert.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "dentsph/cure.hpp"
#include "support/cure_scenes.hpp"

namespace dentsph::testing {
namespace {

constexpr real mm = 1e-3;

// A composite whose attenuation does not change as it cures, so that Beer-Lambert is exact.
CureMaterial constant_attenuation(real per_mm) {
  CureMaterial m = cure_material_preset("composite");
  m.attenuation_uncured = m.attenuation_cured = per_mm / mm;
  return m;
}

TEST(CureLight, SlabFollowsBeerLambert) {
  const real s = 0.1 * mm;
  const int nx = 40, layers = 60;
  Model model = cure_model(s, {-1 * mm, -1 * mm, -1 * mm}, {5 * mm, 5 * mm, 7 * mm});
  State st;
  add_paste_layers(model, st, s, nx, nx, 0, layers);
  const CureModel cm = make_cure_model(model, constant_attenuation(1.15), s, kPaste);
  const CuringLight light = light_above({2 * mm, 2 * mm, layers * s + 1 * mm});
  compute_irradiance(cm, st, light);
  // Each layer's mean over the middle of the slab: E0 exp(-mu depth), depth from the top face.
  std::map<int, std::pair<real, int>> by_layer;
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    const Vec3 p = st.pos[i];
    if (std::abs(p.x - 2 * mm) > 1 * mm || std::abs(p.y - 2 * mm) > 1 * mm) continue;
    auto& [sum, n] = by_layer[int(std::lround((layers * s - p.z) / s - 0.5))];
    sum += st.cure.irradiance[st.id[i]], ++n;
  }
  for (const auto& [k, v] : by_layer) {
    const real depth = (k + 0.5) * s;
    const real expected = light.irradiance * std::exp(-1.15 * depth / mm);
    EXPECT_NEAR(v.first / v.second / expected, 1.0, 0.01) << "layer " << k << " at " << depth / mm << " mm";
  }
}

}  // namespace
}  // namespace dentsph::testing

namespace dentsph::testing {
namespace {

// Mean irradiance of the paste particles whose position passes `keep`.
template <class Keep>
real mean_irradiance(const State& st, Keep&& keep) {
  real sum = 0;
  int n = 0;
  for (std::uint32_t i = 0; i < st.size(); ++i)
    if (st.cure.curable[st.id[i]] && keep(st.pos[i])) sum += st.cure.irradiance[st.id[i]], ++n;
  EXPECT_GT(n, 0);
  return n ? sum / n : 0;
}

// A beam 30 degrees off the slab's normal crosses depth / cos 30 of paste to reach a depth.
TEST(CureLight, TiltedBeamCrossesTheSlantPath) {
  const real s = 0.1 * mm;
  const int nx = 80, layers = 20;
  Model model = cure_model(s, {-1 * mm, -1 * mm, -1 * mm}, {9 * mm, 9 * mm, 4 * mm});
  State st;
  add_paste_layers(model, st, s, nx, nx, 0, layers);
  const CureModel cm = make_cure_model(model, constant_attenuation(1.15), s, kPaste);
  const real theta = 30 * 3.14159265358979 / 180;
  CuringLight light = light_above({4 * mm, 4 * mm, 3 * mm}, 1000, 20 * mm);
  light.direction = {std::sin(theta), 0, -std::cos(theta)};
  compute_irradiance(cm, st, light);
  // Within 5%, except within four cells of the slab's far face, where the grid smooths the face
  // across the slant columns: up to 11% more light there (docs/model.md, "Curing").
  for (int k = 0; k < layers; ++k) {
    const real z = (k + 0.5) * s;  // height of layer k; its depth below the top face:
    const real depth = layers * s - z;
    const real e = mean_irradiance(st, [&](const Vec3& p) {
      return std::abs(p.z - z) < 0.1 * s && std::abs(p.x - 4 * mm) < 1.5 * mm && std::abs(p.y - 4 * mm) < 1.5 * mm;
    });
    const real ratio = e / (light.irradiance * std::exp(-1.15 * depth / mm / std::cos(theta)));
    if (z > 4 * s) {
      EXPECT_NEAR(ratio, 1.0, 0.05) << "depth " << depth / mm;
    } else {
      EXPECT_GT(ratio, 1.0) << "depth " << depth / mm;
      EXPECT_LT(ratio, 1.11) << "depth " << depth / mm;
    }
  }
}

TEST(CureLight, NothingOutsideTheBeamOrBehindTheWindow) {
  const real s = 0.2 * mm;
  Model model = cure_model(s, {-1 * mm, -1 * mm, -1 * mm}, {9 * mm, 9 * mm, 3 * mm});
  State st;
  add_paste_layers(model, st, s, 40, 40, 0, 5);  // 8 x 8 mm, 1 mm thick
  const CureModel cm = make_cure_model(model, cure_material_preset("composite"), s, kPaste);
  // A 4 mm window over the middle: lit within 2 mm of its axis, dark beyond.
  EXPECT_GT(compute_irradiance(cm, st, light_above({4 * mm, 4 * mm, 2 * mm}, 1000, 4 * mm)), 0u);
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    const real r = std::hypot(st.pos[i].x - 4 * mm, st.pos[i].y - 4 * mm);
    if (r > 2 * mm) {
      EXPECT_EQ(st.cure.irradiance[st.id[i]], 0) << r / mm;
    } else if (r < 1.9 * mm) {
      EXPECT_GT(st.cure.irradiance[st.id[i]], 0) << r / mm;
    }
  }
  // The window half way down the slab: the paste above it is behind the window.
  compute_irradiance(cm, st, light_above({4 * mm, 4 * mm, 0.5 * mm}, 1000, 10 * mm));
  for (std::uint32_t i = 0; i < st.size(); ++i)
    if (st.pos[i].z > 0.5 * mm) {
      EXPECT_EQ(st.cure.irradiance[st.id[i]], 0);
    }
  // Pointing away: nothing.
  CuringLight up = light_above({4 * mm, 4 * mm, 2 * mm});
  up.direction = {0, 0, 1};
  EXPECT_EQ(compute_irradiance(cm, st, up), 0u);
}

// Tooth tissue (boundary particles) shades the paste beneath it by exp(-mu_tissue thickness);
// an instrument (tool particles) blocks it.
TEST(CureLight, TissueShadesAndTheInstrumentBlocks) {
  const real s = 0.1 * mm;
  Model model = cure_model(s, {-1 * mm, -1 * mm, -1 * mm}, {5 * mm, 5 * mm, 4 * mm});
  State st;
  add_paste_layers(model, st, s, 40, 40, 0, 10);  // 4 x 4 mm, 1 mm thick
  // A ledge of tissue 0.6 mm thick over the half x < 2 mm, 0.5 mm above the paste.
  std::vector<ParticleInit> ledge;
  const real m = lattice_particle_mass(kWall.rho0, s, model.kernel);
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 20; ++i)
        ledge.push_back(make_particle(Role::boundary, {(i + 0.5) * s, (j + 0.5) * s, 1.5 * mm + (k + 0.5) * s}, m, kWall));
  st.add_particles(model, ledge);
  const CureModel cm = make_cure_model(model, constant_attenuation(1.15), s, kPaste);
  compute_irradiance(cm, st, light_above({2 * mm, 2 * mm, 3 * mm}));
  auto band = [&](real x_lo, real x_hi) {
    return mean_irradiance(st, [&](const Vec3& p) {
      return p.x > x_lo && p.x < x_hi && p.y > 1 * mm && p.y < 3 * mm && p.z > 0.9 * mm;  // the top layer
    });
  };
  const real shaded = band(0.3 * mm, 1.7 * mm), lit = band(2.3 * mm, 3.7 * mm);
  EXPECT_NEAR(shaded / lit, std::exp(-cm.tissue_attenuation * 0.6 * mm), 0.01);
  // The instrument: tool particles over the other half.
  std::vector<ParticleInit> tool;
  for (int j = 0; j < 40; ++j)
    for (int i = 20; i < 40; ++i) tool.push_back(make_particle(Role::tool, {(i + 0.5) * s, (j + 0.5) * s, 2 * mm}, m, kWall));
  st.add_particles(model, tool);
  compute_irradiance(cm, st, light_above({2 * mm, 2 * mm, 3 * mm}));
  EXPECT_LT(band(2.3 * mm, 3.7 * mm) / light_above({}).irradiance, 1e-3);
}

// Dose integrates the irradiance over time; the result does not depend on the update's dt.
TEST(CureLight, DoseIsIrradianceTimesTimeWhateverTheUpdates) {
  const real s = 0.2 * mm;
  Model model = cure_model(s, {-1 * mm, -1 * mm, -1 * mm}, {5 * mm, 5 * mm, 5 * mm});
  auto cured = [&](real dt) {
    State st;
    add_paste_layers(model, st, s, 10, 10, 0, 15);  // 3 mm thick
    const CureModel cm = make_cure_model(model, cure_material_preset("composite"), s, kPaste);
    cure_at_rest(cm, st, light_above({1 * mm, 1 * mm, 3 * mm}), 20, dt);
    return st;
  };
  const State a = cured(0.01), b = cured(0.1);
  // The top layer's first update: irradiance at 0.1 mm of uncured paste; 20 s of it, less the
  // bleaching's gain, bounds its dose.
  const real top_uncured = 1e4 * std::exp(-1150 * 0.1 * mm);
  for (std::uint32_t id = 0; id < a.size(); ++id) {
    EXPECT_NEAR(b.cure.dose[id] / a.cure.dose[id], 1.0, 0.01) << id;
    EXPECT_NEAR(b.cure.alpha[id] / a.cure.alpha[id], 1.0, 0.01) << id;
    if (a.pos[a.index_of_id[id]].z > 2.8 * mm) {
      EXPECT_GE(a.cure.dose[id], 20 * top_uncured * (1 - 1e-9));
      EXPECT_LE(a.cure.dose[id], 20 * 1e4 * std::exp(-1000 * 0.1 * mm));
    }
  }
}

// A light that comes on or goes off is taken at once; one that moves, at the next pass (within
// transition_interval), and every call adds the dose of its dt.
TEST(CureLight, APassTakesTheLightOnOffAtOnceAndAMoveWithinAnInterval) {
  const real s = 0.2 * mm, dt = 5e-5;
  Model model = cure_model(s, {-1 * mm, -1 * mm, -1 * mm}, {9 * mm, 9 * mm, 3 * mm}, dt);
  State st;
  add_paste_layers(model, st, s, 40, 10, 0, 2);  // 8 x 2 mm
  const CureModel cm = make_cure_model(model, cure_material_preset("composite"), s, kPaste);
  auto lit_x = [&] {  // mean x of the lit paste
    real x = 0;
    int n = 0;
    for (std::uint32_t i = 0; i < st.size(); ++i)
      if (st.cure.irradiance[st.id[i]] > 0) x += st.pos[i].x, ++n;
    return n ? x / n : -1;
  };
  auto call = [&](const std::optional<CuringLight>& l) {
    st.time += dt;
    return cure_between_steps(cm, st, l, dt);
  };
  const CuringLight left = light_above({2 * mm, 1 * mm, 1 * mm}, 1000, 2 * mm);
  CuringLight right = left;
  right.tip.x = 6 * mm;
  EXPECT_GT(call(left).lit, 0u);
  EXPECT_NEAR(lit_x(), 2 * mm, 0.1 * mm);
  const real dose = st.cure.dose[st.cure.lit_ids[0]];
  call(left);
  EXPECT_NEAR(st.cure.dose[st.cure.lit_ids[0]] - dose, st.cure.lit_irradiance[0] * dt, 1e-12);
  call(right);
  EXPECT_NEAR(lit_x(), 2 * mm, 0.1 * mm) << "a move is taken at the next pass";
  for (real t = 0; t < cm.transition_interval; t += dt) call(right);
  EXPECT_NEAR(lit_x(), 6 * mm, 0.1 * mm) << "within an interval";
  EXPECT_EQ(call(std::nullopt).lit, 0u);
  EXPECT_EQ(lit_x(), -1) << "off at once";
}

}  // namespace
}  // namespace dentsph::testing
