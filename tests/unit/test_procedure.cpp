// Procedure events in scene files (dispense, switch_tool), their checks, and a run applying them.
#include <gtest/gtest.h>

#include <filesystem>

#include "dentsph/run.hpp"
#include "dentsph/tools.hpp"

namespace dentsph {
namespace {

const char* kBase = R"({
  "name": "p",
  "simulation": {"dt": 5e-4, "h": 0.02},
  "adhesion": {"A": 0.012, "B": 0.03},
  "materials": {"paste": {"viscosity": 0.5, "stiffness": 60, "rest_density": 1000, "adhesion": 200},
                "wall": {"viscosity": 0.5, "stiffness": 200, "rest_density": 1000, "adhesion": 0}},
  "roles": {"material": "paste", "boundary": "wall", "tool": "wall"},
  "blocks": [{"role": "boundary", "shape": "box", "min": [-0.05, -0.05, -0.01], "max": [0.05, 0.05, 0], "spacing": 0.01}],
  "tool": {"blocks": [{"shape": "sphere", "center": [0, 0, 0], "radius": 0.01, "spacing": 0.01}],
           "keyframes": [{"t": 0, "position": [0, 0, 0.2]}],
           "events": EVENTS}
})";

std::string with_events(const std::string& events) {
  std::string s = kBase;
  s.replace(s.find("EVENTS"), 6, events);
  return s;
}

TEST(Procedure, EventsAreReadAndResolved) {
  const Scene sc = parse_scene(with_events(R"([
      {"t": 0.0, "dispense": {"volume": 2.7e-5, "at": [0, 0, 0.05]}},
      {"t": 0.1, "switch_tool": {"name": "condenser"}},
      {"t": 0.1, "dispense": {"volume": 1e-6, "at": [0, 0, 0.08], "spacing": 0.005}}])"),
                               "p.json");
  ASSERT_EQ(sc.events.size(), 3u);
  EXPECT_EQ(sc.events[0].kind, ProcedureEvent::Kind::dispense);
  EXPECT_NEAR(real(sc.events[0].particles.size()) * 1e-6, 2.7e-5, 0.15 * 2.7e-5) << "spacing h/2 = 0.01";
  EXPECT_EQ(sc.events[1].kind, ProcedureEvent::Kind::switch_tool);
  // A ball burnisher taken up on the iisph solver is made as it runs it: two layers (tools.hpp).
  std::string iisph = with_events(R"([{"t": 0.1, "switch_tool": {"name": "ball_burnisher"}}])");
  const std::string h = R"("h": 0.02})";
  iisph.replace(iisph.find(h), h.size(), R"("h": 0.02, "solver": "iisph"})");
  const Scene ball = parse_scene(iisph, "p.json");
  ASSERT_EQ(ball.model.solver, Solver::iisph);
  EXPECT_EQ(ball.events[0].particles.size(), tool_by_name("ball_burnisher", 0.01, Solver::iisph).points.size());
  EXPECT_GT(ball.events[0].particles.size(), tool_by_name("ball_burnisher", 0.01, Solver::paper).points.size());
  EXPECT_EQ(sc.events[1].tool, "condenser");
  EXPECT_EQ(sc.events[1].particles.size(), tool_by_name("condenser", 0.01, Solver::paper).points.size());
  EXPECT_NEAR(real(sc.events[2].particles.size()) * 1.25e-7, 1e-6, 0.2e-6);
}

void expect_error(const std::string& events, const std::string& field, const std::string& phrase) {
  try {
    parse_scene(with_events(events), "p.json");
    FAIL() << "accepted: " << events;
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("p.json"), std::string::npos) << msg;
    EXPECT_NE(msg.find(field), std::string::npos) << msg;
    EXPECT_NE(msg.find(phrase), std::string::npos) << msg;
  }
}

TEST(Procedure, BrokenEventsAreRefusedWithTheField) {
  expect_error(R"([{"t": 0, "dispense": {"volume": 1e-6, "at": [0, 0, 0]}, "switch_tool": {"name": "condenser"}}])",
               "tool.events[0]", "exactly one");
  expect_error(R"([{"t": 0, "switch_tool": {"name": "spatula"}}])", "tool.events[0].switch_tool.name", "known");
  expect_error(R"([{"t": 1, "dispense": {"volume": 1e-6, "at": [0, 0, 0]}}, {"t": 0.5, "dispense": {"volume": 1e-6, "at": [0, 0, 0]}}])",
               "tool.events[1].t", "time order");
  expect_error(R"([{"t": 0, "dispense": {"volume": -1, "at": [0, 0, 0]}}])", "tool.events[0].dispense.volume", "");
  expect_error(R"([{"t": 0, "dispense": {"volum": 1e-6, "at": [0, 0, 0]}}])", "tool.events[0].dispense.volum", "");
}

TEST(Procedure, ARunAppliesEachEventOnceAtItsTime) {
  const Scene sc = parse_scene(with_events(R"([
      {"t": 0.0, "dispense": {"volume": 2.7e-5, "at": [0, 0, 0.05]}},
      {"t": 0.05, "switch_tool": {"name": "flat_plugger"}},
      {"t": 0.05, "dispense": {"volume": 2.7e-5, "at": [0, 0, 0.1]}}])"),
                               "p.json");
  RunOptions opt;
  opt.steps = 60;  // 0.03 s: the first event only
  RunSummary s = run_offline(sc, opt);
  EXPECT_EQ(s.events_applied, 1u);
  EXPECT_EQ(s.material, sc.events[0].particles.size());
  opt.steps = 200;  // 0.1 s: all three
  s = run_offline(sc, opt);
  EXPECT_EQ(s.events_applied, 3u);
  EXPECT_EQ(s.material, sc.events[0].particles.size() + sc.events[2].particles.size());
  EXPECT_EQ(s.tool, sc.events[1].particles.size());
  EXPECT_EQ(s.status, "completed");
}

TEST(SimulationSettings, SkinAndReachAreReadAndChecked) {
  const std::string h = R"("h": 0.02})";
  const std::string one = R"([{"t": 0, "dispense": {"volume": 1e-6, "at": [0, 0, 0.05]}}])";
  std::string text = with_events(one);
  text.replace(text.find(h), h.size(), R"("h": 0.02, "neighbour_skin": 0.002, "grid_reach": 2})");
  const Scene sc = parse_scene(text, "p.json");
  EXPECT_DOUBLE_EQ(sc.model.neighbour_skin, 0.002);
  EXPECT_EQ(sc.model.grid.reach, 2);
  EXPECT_NEAR(sc.model.grid.cell_size, 0.011, 1e-12) << "(h + skin) / reach";
  std::string bad = with_events(one);
  bad.replace(bad.find(h), h.size(), R"("h": 0.02, "neighbour_skin": 0.05})");
  try {
    parse_scene(bad, "p.json");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("neighbour_skin"), std::string::npos) << e.what();
  }
}

TEST(Procedure, ExampleSceneLoads) {
  const Scene sc = load_scene("scenes/incremental_fill.json");
  EXPECT_EQ(sc.events.size(), 4u);
}

}  // namespace
}  // namespace dentsph
