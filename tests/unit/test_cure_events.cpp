// The cure event of procedure and scene files (src/scene/tool_json.cpp), ActiveLights, and the
// increments numbered by the dispense (src/scene/procedure.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "dentsph/active_lights.hpp"
#include "dentsph/dental.hpp"
#include "dentsph/scene.hpp"

namespace dentsph {
namespace {

constexpr real mm = 1e-3;

const ToothScene& crown() {
  static const ToothScene ts = default_tooth_scene();
  return ts;
}

std::string procedure(const std::string& events) {
  return R"({"name": "cure", "keyframes": [{"t": 0, "position": [0, 0, 8]}], "events": )" + events + "}";
}

TEST(CureEvent, AProcedureLightIsPlacedInTheToothFrame) {
  const Scene sc = dental_procedure(crown(), procedure(R"([
      {"t": 0.0, "dispense": {"cavity_fraction": 0.3, "at": [0, 0, -2]}},
      {"t": 0.5, "cure": {"position": [0, 0, 1], "duration": 20}},
      {"t": 21, "cure": {"position": [1, 0, 2], "direction": [0, 1, -1], "duration": 10, "irradiance": 1400,
                         "diameter": 8}}])"),
                                    "p.json");
  ASSERT_EQ(sc.events.size(), 3u);
  const ProcedureEvent& a = sc.events[1];
  EXPECT_EQ(a.kind, ProcedureEvent::Kind::cure);
  EXPECT_EQ(a.duration, 20);
  const ToothFrame& f = crown().tooth.frame();
  EXPECT_LT(norm(a.light.tip - f.to_world({0, 0, 1 * mm})), 1e-12);
  EXPECT_LT(norm(a.light.direction + f.z), 1e-12) << "down the long axis by default";
  EXPECT_DOUBLE_EQ(a.light.irradiance, 1e4) << "1000 mW/cm2 by default";
  EXPECT_DOUBLE_EQ(a.light.diameter, 10 * mm);
  const ProcedureEvent& b = sc.events[2];
  EXPECT_DOUBLE_EQ(b.light.irradiance, 1.4e4);
  EXPECT_NEAR(b.light.diameter, 8 * mm, 1e-15);
  EXPECT_LT(norm(b.light.direction - (f.y - f.z) / std::sqrt(2.0)), 1e-12);

  const ActiveLights lights(sc.events);
  EXPECT_FALSE(lights.empty());
  EXPECT_FALSE(lights.at(0.4));
  ASSERT_TRUE(lights.at(0.5));
  EXPECT_LT(norm(lights.at(10)->tip - a.light.tip), 1e-15);
  EXPECT_FALSE(lights.at(20.5)) << "off at t0 + duration";
  ASSERT_TRUE(lights.at(25));
  EXPECT_DOUBLE_EQ(lights.at(25)->irradiance, 1.4e4);
  EXPECT_FALSE(lights.at(31));
  EXPECT_DOUBLE_EQ(lights.end(), 31);
  EXPECT_TRUE(ActiveLights(std::vector<ProcedureEvent>{}).empty());
}

TEST(CureEvent, OverlappingLightsTheLatestWins) {
  ProcedureEvent a, b;
  a.kind = b.kind = ProcedureEvent::Kind::cure;
  a.t = 0, a.duration = 10, a.light.irradiance = 1;
  b.t = 5, b.duration = 2, b.light.irradiance = 2;
  const ActiveLights lights(std::vector<ProcedureEvent>{a, b});
  EXPECT_DOUBLE_EQ(lights.at(4)->irradiance, 1);
  EXPECT_DOUBLE_EQ(lights.at(6)->irradiance, 2);
  EXPECT_DOUBLE_EQ(lights.at(8)->irradiance, 1);
}

void expect_refused(const std::string& events, const std::string& field, const std::string& phrase) {
  try {
    dental_procedure(crown(), procedure(events), "p.json");
    FAIL() << "accepted: " << events;
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("p.json: " + field), std::string::npos) << msg;
    EXPECT_NE(msg.find(phrase), std::string::npos) << msg;
  }
}

TEST(CureEvent, BrokenCureEventsNameTheField) {
  expect_refused(R"([{"t": 0, "cure": {"position": [0, 0, 1]}}])", "events[0].cure.duration", "missing");
  expect_refused(R"([{"t": 0, "cure": {"duration": 20}}])", "events[0].cure.position", "missing");
  expect_refused(R"([{"t": 0, "cure": {"position": [0, 0, 1], "duration": -1}}])", "events[0].cure.duration", "");
  expect_refused(R"([{"t": 0, "cure": {"position": [0, 0, 1], "duration": 20, "irradiance": 1e6}}])",
                 "events[0].cure.irradiance", "mW/cm^2");
  expect_refused(R"([{"t": 0, "cure": {"position": [0, 0, 1], "duration": 20, "direction": [0, 0, 0]}}])",
                 "events[0].cure.direction", "non-zero");
  expect_refused(R"([{"t": 0, "cure": {"position": [0, 0, 1], "duration": 20, "colour": "blue"}}])",
                 "events[0].cure.colour", "unknown");
  expect_refused(R"([{"t": 0, "cure": {"position": [0, 0, 1], "duration": 20}, "switch_tool": {"name": "condenser"}}])",
                 "events[0]", "exactly one");
}

// A scene file's cure event is in metres in the world.
TEST(CureEvent, ASceneFileLightIsInMetres) {
  const Scene sc = parse_scene(R"({
    "name": "c", "simulation": {"dt": 5e-4, "h": 0.02}, "adhesion": {"A": 0.012, "B": 0.03},
    "materials": {"paste": {"viscosity": 0.5, "stiffness": 60, "rest_density": 1000, "adhesion": 200},
                  "wall": {"viscosity": 0.5, "stiffness": 200, "rest_density": 1000, "adhesion": 0}},
    "roles": {"material": "paste", "boundary": "wall", "tool": "wall"},
    "blocks": [{"role": "boundary", "shape": "box", "min": [-0.05, -0.05, -0.01], "max": [0.05, 0.05, 0], "spacing": 0.01}],
    "tool": {"blocks": [{"shape": "sphere", "center": [0, 0, 0], "radius": 0.01, "spacing": 0.01}],
             "keyframes": [{"t": 0, "position": [0, 0, 0.2]}],
             "events": [{"t": 1, "cure": {"position": [0, 0, 0.1], "duration": 5, "diameter": 0.008}}]}})",
                               "c.json");
  ASSERT_EQ(sc.events.size(), 1u);
  EXPECT_LT(norm(sc.events[0].light.tip - Vec3{0, 0, 0.1}), 1e-15);
  EXPECT_DOUBLE_EQ(sc.events[0].light.diameter, 0.008);
  // Applying it changes no particle.
  State st = make_state(sc);
  const std::uint32_t n = st.size();
  apply_event(sc, st, sc.events[0]);
  EXPECT_EQ(st.size(), n);
}

// Each dispense is an increment of its own, numbered in order; the scene's own paste is increment 0.
TEST(CureEvent, DispensesNumberTheIncrements) {
  const Scene sc = dental_procedure(crown(), procedure(R"([
      {"t": 0.0, "dispense": {"cavity_fraction": 0.3, "at": [0, 0, -2]}},
      {"t": 0.1, "dispense": {"cavity_fraction": 0.3, "at": [0, 0, -1.4]}}])"),
                                    "p.json");
  State st = make_state(sc);
  apply_event(sc, st, sc.events[0]);
  const std::uint32_t first = st.size();
  apply_event(sc, st, sc.events[1]);
  EXPECT_EQ(st.cure.increments, 2);
  for (std::uint32_t i = 0; i < st.size(); ++i) {
    const std::uint32_t id = st.id[i];
    if (st.role[i] != Role::material)
      EXPECT_EQ(st.cure.increment[id], 0);
    else
      EXPECT_EQ(st.cure.increment[id], id < first ? 1 : 2);
    EXPECT_EQ(st.cure.curable[id], st.role[i] == Role::material);
  }
}

}  // namespace
}  // namespace dentsph
