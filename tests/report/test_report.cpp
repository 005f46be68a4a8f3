// The report without a browser: a run folder read back (and refused, naming the file, when
// broken), the criteria's verdicts at their thresholds, the page's numbers as the files hold
// them, the bundled plotting library, the class comparison's table and CSV, the procedure's log
// and increments, and the session store (migrations, queries, two writers at once).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>
#include <thread>

#include <sqlite3.h>

#include "dentsph/dental.hpp"
#include "dentsph/dispense.hpp"
#include "dentsph/report/class_report.hpp"
#include "dentsph/report/session_folder.hpp"
#include "dentsph/report/session_report.hpp"
#include "dentsph/report/session_store.hpp"
#include "dentsph/scene.hpp"
#include "report/chartjs.hpp"
#include "report/criteria.hpp"
#include "report/grading_picture.hpp"
#include "report/html.hpp"
#include "report/procedure_log.hpp"
#include "report/store_schema.hpp"
#include "report_support.hpp"

namespace dentsph::report {
namespace {

namespace fs = std::filesystem;
using testing::summary;
using testing::write_folder;

const Criterion& by_id(const std::vector<Criterion>& cs, const std::string& id) {
  for (const Criterion& c : cs)
    if (c.id == id) return c;
  throw std::runtime_error("no criterion " + id);
}

TEST(Report, CriteriaJudgeAtTheirThresholds) {
  const nlohmann::json proc = {{"increments", {{{"index", 1}, {"thickness_p90_mm", 2.0}}}}};
  auto good = filling_criteria(summary(0.95, 0, 0.25 * 32.5, 9.0, 4.5), proc);
  for (const Criterion& c : good) EXPECT_EQ(c.verdict, Verdict::good) << c.id << " " << c.shown;
  const nlohmann::json thick = {{"increments", {{{"index", 1}, {"thickness_p90_mm", 2.01}}}}};
  auto bad = filling_criteria(summary(0.949, 1, 0.26 * 32.5, 9.01, 4.51), thick);
  for (const Criterion& c : bad)
    if (c.id != "leaked") {
      EXPECT_EQ(c.verdict, Verdict::needs_work) << c.id << " " << c.shown;
    }
  EXPECT_EQ(by_id(bad, "fill").shown, "94.9 %");
  EXPECT_EQ(by_id(bad, "voids").details.size(), 1u);
  EXPECT_NE(by_id(bad, "voids").details[0].find("against the floor, 1.8 mm below"), std::string::npos)
      << by_id(bad, "voids").details[0];
  // Gaps under a particle's volume are named as porosity in the details and do not fail the voids.
  nlohmann::json porous = summary(0.95, 0, 0.25 * 32.5, 9.0, 4.5);
  porous["assessment"]["pore_count"] = 3;
  porous["assessment"]["pore_volume_mm3"] = 0.01;
  porous["assessment"]["min_void_mm3"] = 0.027;
  const auto porous_criteria = filling_criteria(porous, proc);
  const Criterion& pores = by_id(porous_criteria, "voids");
  EXPECT_EQ(pores.verdict, Verdict::good);
  EXPECT_EQ(pores.rule, "none of 0.027 mm^3 (a particle's volume) or more");
  ASSERT_EQ(pores.details.size(), 1u);
  EXPECT_NE(pores.details[0].find("3 smaller gaps (0.010 mm^3 in all), each under 0.027 mm^3: porosity"),
            std::string::npos)
      << pores.details[0];
  // Without an assessment or increments: not measured, never good.
  const auto none = filling_criteria(nlohmann::json{{"steps", 1}}, nullptr);
  EXPECT_EQ(by_id(none, "fill").verdict, Verdict::not_measured);
  EXPECT_EQ(by_id(none, "increments").verdict, Verdict::not_measured);
  // A realtime session is judged against its device's profile.
  nlohmann::json rt = summary(1, 0, 0, 3.0, 1.0);
  rt["haptic"] = {{"profile", {{"name", "touch"}, {"max_force_N", 3.3}}}, {"target_rate_hz", 1000.0}, {"rate_hz", 995.0},
                  {"ticks", 10000}, {"deadline_misses", 11}, {"period_p99_us", 1400.0}, {"force_age_p99_us", 2000.0},
                  {"watchdog", {{"trips", 0}}}, {"recording_dropped_ticks", 0}};
  EXPECT_EQ(device_limit_N(rt), 3.3);
  EXPECT_EQ(by_id(filling_criteria(rt, nullptr), "mean_force").verdict, Verdict::good);  // 1.0 <= 1.65
  const auto h = haptic_criteria(rt);
  EXPECT_EQ(by_id(h, "haptic_rate").verdict, Verdict::good);
  EXPECT_EQ(by_id(h, "haptic_misses").verdict, Verdict::needs_work);  // 11 > 10 of 10000
  EXPECT_EQ(by_id(h, "haptic_period_p99").verdict, Verdict::good);
  EXPECT_TRUE(haptic_criteria(summary(1, 0, 0, 1, 1)).empty());
}

TEST(Report, PageCarriesTheSummarysNumbersExactly) {
  const nlohmann::json s = summary(0.9812345678901234, 1, 3.3333333333333335, 4.209053706180593, 1.1593196175395701);
  const fs::path d = write_folder("page", s);
  const fs::path file = write_session_report(d);
  std::ifstream in(file);
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Every criterion with a number: data-value is the file's number, to the last bit.
  const std::regex cell("data-key=\"([A-Za-z0-9_.:]+)\" data-value=\"([^\"]+)\">([^<]*)<");
  int checked = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), cell); it != std::sregex_iterator(); ++it) {
    const std::string key = (*it)[1], value = (*it)[2];
    if (key.rfind("procedure:", 0) == 0) continue;
    ASSERT_TRUE(number_at(s, key)) << key;
    EXPECT_EQ(std::stod(value), *number_at(s, key)) << key;
    ++checked;
  }
  EXPECT_EQ(checked, 6);  // fill, voids, overfill, leaked, peak, mean
  for (const char* shown : {">98.1 %<", ">1 (0.125 mm^3)<", ">3.33 mm^3<", ">4.21 N<", ">1.16 N<", ">0.88 mm<"})
    EXPECT_NE(html.find(shown), std::string::npos) << shown;
  // Self-contained: the library inline, no address to fetch anything from.
  EXPECT_NE(html.find(chartjs_source()), std::string::npos);
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);
  EXPECT_EQ(html.find("<link"), std::string::npos);
  // The plot's markers: the increment and the instrument switch.
  EXPECT_NE(html.find("\"label\":\"increment 1\""), std::string::npos);
  EXPECT_NE(html.find("\"label\":\"instrument: flat_plugger\""), std::string::npos);
  EXPECT_NE(html.find("A. Student, class I"), std::string::npos);
}

// The light curing's section: the overall message, a criterion per increment (adequately cured
// throughout: good; an under-cured base: needs work, with the increment's message), the numbers as
// summary.json holds them, and the curing light's marker on the force plot.
TEST(Report, LightCuringSectionJudgesEachIncrement) {
  nlohmann::json s = summary(0.99, 0, 1.0, 2.0, 0.5);
  const std::string thick =
      "increment 2 is 3.6 mm thick: its base received 0.4 J/cm2 and 41% of it is under-cured (conversion below 80% "
      "of its top's), from 2.1 mm below its top to its base";
  s["cure"] = {{"criterion_bottom_top", 0.8},
               {"paste_volume_mm3", 30.0},
               {"under_cured_volume_mm3", 6.5},
               {"light_on_s", 40.0},
               {"message", "6.50 mm3 of paste under-cured (22% of 30.00 mm3) in 1 of 2 increments"},
               {"increments",
                {{{"increment", 1}, {"thickness_mm", 1.9}, {"top_dose_J_per_cm2", 19.5}, {"base_dose_J_per_cm2", 2.5},
                  {"top_conversion", 0.6}, {"base_conversion", 0.55}, {"bottom_top_ratio", 0.92},
                  {"adequately_cured_fraction", 1.0}, {"under_cured_volume_mm3", 0.0},
                  {"message", "increment 1 is 1.9 mm thick: its base received 2.5 J/cm2, bottom/top conversion 0.92: "
                              "adequately cured throughout"}},
                 {{"increment", 2}, {"thickness_mm", 3.6}, {"top_dose_J_per_cm2", 19.5}, {"base_dose_J_per_cm2", 0.4},
                  {"top_conversion", 0.6}, {"base_conversion", 0.2}, {"bottom_top_ratio", 0.33},
                  {"adequately_cured_fraction", 0.59},
                  {"under_cured_volume_mm3", 6.5}, {"message", thick}}}}};
  const std::vector<Criterion> cs = cure_criteria(s);
  ASSERT_EQ(cs.size(), 2u);
  EXPECT_EQ(by_id(cs, "cure_1").verdict, Verdict::good);
  EXPECT_EQ(by_id(cs, "cure_2").verdict, Verdict::needs_work);
  EXPECT_EQ(by_id(cs, "cure_2").details.at(0), thick);
  // A few particles a wall shades do not fail an increment whose base is cured (the built-in
  // procedure's: 1% under-cured at the walls, bottom/top 0.98); nor does a cured share alone pass a
  // base under the criterion.
  nlohmann::json shaded = s;
  shaded["cure"]["increments"][1].update({{"bottom_top_ratio", 0.98}, {"adequately_cured_fraction", 0.99}});
  EXPECT_EQ(by_id(cure_criteria(shaded), "cure_2").verdict, Verdict::good);
  shaded["cure"]["increments"][1].update({{"bottom_top_ratio", 0.75}, {"adequately_cured_fraction", 0.97}});
  EXPECT_EQ(by_id(cure_criteria(shaded), "cure_2").verdict, Verdict::needs_work);
  shaded["cure"]["increments"][1].update({{"bottom_top_ratio", 0.9}, {"adequately_cured_fraction", 0.9}});
  EXPECT_EQ(by_id(cure_criteria(shaded), "cure_2").verdict, Verdict::needs_work);
  EXPECT_EQ(number_at(s, "cure.increments.1.adequately_cured_fraction"), 0.59);
  EXPECT_FALSE(number_at(s, "cure.increments.2.adequately_cured_fraction"));
  EXPECT_FALSE(number_at(s, "cure.increments.x.adequately_cured_fraction"));
  EXPECT_TRUE(cure_criteria(summary(1, 0, 0, 1, 1)).empty()) << "a run that did not cure has no such rows";

  const fs::path d = write_folder("cure", s);
  nlohmann::json procedure = nlohmann::json::parse(std::ifstream(d / "procedure.json"));
  procedure["events"].push_back({{"step", 150}, {"t_s", 0.0075}, {"kind", "cure"}, {"source", "procedure"}});
  std::ofstream(d / "procedure.json") << procedure.dump(2) << "\n";
  const fs::path file = write_session_report(d);
  std::ifstream in(file);
  const std::string html((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(html.find("<h2>Light curing</h2>"), std::string::npos);
  EXPECT_NE(html.find("id=\"cure-message\">6.50 mm3 of paste under-cured"), std::string::npos);
  EXPECT_NE(html.find(thick), std::string::npos);
  EXPECT_NE(html.find("data-key=\"cure.increments.1.adequately_cured_fraction\" data-value=\"0.59\">59 % adequately "
                      "cured, 3.60 mm thick<"),
            std::string::npos);
  EXPECT_NE(html.find("\"label\":\"curing light on\""), std::string::npos);
}

TEST(Report, BundledPlottingLibraryIsDebiansFileWhole) {
  std::ifstream in("/usr/share/javascript/chart.js/chart.min.js", std::ios::binary);
  if (!in) GTEST_SKIP() << "libjs-chart.js is not installed here (the build read it where it was)";
  const std::string file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(chartjs_source(), file);
  EXPECT_NE(file.find(std::string("Chart.js v") + std::string(chartjs_version())), std::string::npos);
}

TEST(Report, BrokenFoldersAreNamedWithTheFix) {
  auto refused = [](const fs::path& d, const std::vector<std::string>& phrases) {
    try {
      read_session(d);
      ADD_FAILURE() << d << " was read";
    } catch (const SessionError& e) {
      for (const std::string& p : phrases) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
    }
  };
  refused("/nonexistent/run", {"/nonexistent/run", "no such folder", "--out"});
  const fs::path empty = testing::fresh_dir("empty");
  refused(empty, {empty.string(), "no summary.json"});
  const fs::path broken = write_folder("broken", summary(1, 0, 0, 1, 1));
  std::ofstream(broken / "summary.json") << "{\"steps\": 3, ";
  refused(broken, {"summary.json", "not valid JSON", "run it again"});
  const fs::path cut = write_folder("cut", summary(1, 0, 0, 1, 1));
  std::ofstream(cut / "tool_force.csv", std::ios::app) << "0.5,1,2\n";
  refused(cut, {"tool_force.csv", "line 202", "3 columns"});
  const fs::path garbage = write_folder("garbage", summary(1, 0, 0, 1, 1));
  std::ofstream(garbage / "tool_force.csv", std::ios::app) << "0.5,1,x,0,0,0,0\n";
  refused(garbage, {"tool_force.csv", "line 202, column 3", "not a number"});
  std::ofstream(garbage / "summary.json") << "[1, 2]";
  refused(garbage, {"summary.json", "not a dentsph run summary"});
  // Figures changed by hand: a fill of 1e308 read "inf % good", -5 "-500.0 %".
  for (const auto& [field, value] : std::vector<std::pair<std::string, nlohmann::json>>{
           {"fill_fraction", 1e308}, {"fill_fraction", -5}, {"fill_fraction", "full"}, {"leaked_particles", -1}}) {
    nlohmann::json sm = summary(1, 0, 0, 1, 1);
    sm["assessment"][field] = value;
    const fs::path tampered = write_folder("tampered", sm);
    refused(tampered, {"summary.json", "assessment." + field + " is " + value.dump(), "not a number in", "run the session again"});
  }
  // An untouched summary is read.
  EXPECT_NO_THROW(read_session(write_folder("untouched", summary(0.97, 0, 0, 1, 1))));
}

// The surface's grading (summary.json's "grading", surface_grade.hpp): anatomic form good in the
// alpha band, the margin by the preclinical rubric (at most 3 defect sites, none over 1 mm); both
// absent without a grading, named as not measured with the reason when the run could not grade.
TEST(Report, TheSurfacesGradingIsJudgedByTheTutorsCriteria) {
  auto grading = [](const std::string& band, int sites, double largest) {
    nlohmann::json defects = nlohmann::json::array();
    for (int k = 0; k < sites; ++k)
      defects.push_back({{"kind", k % 2 ? "excess" : "gap"}, {"length_mm", largest}, {"largest_step_mm", 0.3},
                         {"centre_mm", {k % 2 ? -2.0 : 2.0, 0.0, 0.0}}});
    return nlohmann::json{
        {"anatomic_form", {{"measured", true}, {"band", band}, {"p95_abs_mm", band == "alpha" ? 0.2 : 0.4},
                           {"rms_mm", 0.1}, {"max_under_mm", 0.3}, {"max_over_mm", 0.1}, {"under_area_mm2", 1.0},
                           {"over_area_mm2", 0.0}, {"alpha_max_mm", 0.25}, {"charlie_under_mm", 1.0}}},
        {"marginal_adaptation", {{"measured", true}, {"length_mm", 15.1}, {"gap_length_mm", sites * largest},
                                 {"excess_length_mm", 0.0}, {"sites", sites}, {"largest_site_mm", largest},
                                 {"max_sites", 3}, {"max_site_mm", 1.0}, {"step_threshold_mm", 0.15},
                                 {"below_resolution_mm", 0.1}, {"defects", defects}}}};
  };
  nlohmann::json s = summary(0.97, 0, 0, 1, 1);
  EXPECT_THROW(by_id(filling_criteria(s, nullptr), "margin"), std::runtime_error);  // no grading: no row
  s["grading"] = grading("alpha", 3, 1.0);
  auto cs = filling_criteria(s, nullptr);
  EXPECT_EQ(by_id(cs, "anatomic_form").verdict, Verdict::good);
  EXPECT_EQ(by_id(cs, "margin").verdict, Verdict::good);
  EXPECT_EQ(by_id(cs, "margin").shown, "3 defect sites, the longest 1.00 mm");
  // The lengths, three sites and the steps below resolution.
  ASSERT_EQ(by_id(cs, "margin").details.size(), 5u);
  EXPECT_NE(by_id(cs, "margin").details[1].find("a gap (the paste short of the tooth) of 1.00 mm"), std::string::npos)
      << by_id(cs, "margin").details[1];
  EXPECT_NE(by_id(cs, "margin").details[2].find("2.0 mm distal"), std::string::npos) << by_id(cs, "margin").details[2];
  EXPECT_EQ(by_id(cs, "anatomic_form").shown, "alpha: 95 % within 0.20 mm");
  s["grading"] = grading("bravo", 4, 0.5);
  cs = filling_criteria(s, nullptr);
  EXPECT_EQ(by_id(cs, "anatomic_form").verdict, Verdict::needs_work);
  EXPECT_EQ(by_id(cs, "margin").verdict, Verdict::needs_work);  // four sites
  s["grading"] = grading("alpha", 1, 1.2);
  EXPECT_EQ(by_id(filling_criteria(s, nullptr), "margin").verdict, Verdict::needs_work);  // a site over 1 mm
  s["grading"] = {{"anatomic_form", {{"measured", false}, {"why_not", "no opening"}}},
                  {"marginal_adaptation", {{"measured", false}, {"why_not", "no margin"}}}};
  cs = filling_criteria(s, nullptr);
  EXPECT_EQ(by_id(cs, "anatomic_form").verdict, Verdict::not_measured);
  EXPECT_EQ(by_id(cs, "margin").details.at(0), "not measured: no margin");
  // A Class II's proximal contact (tight good, light or open not) and overhang (under its threshold).
  s["grading"] = grading("alpha", 0, 0);
  EXPECT_THROW(by_id(filling_criteria(s, nullptr), "contact"), std::runtime_error);  // a Class I: no row
  auto proximal = [&](const std::string& contact, double gap, double overhang) {
    s["grading"]["proximal"] = {{"measured", true},    {"side", "mesial"},  {"contact", contact},
                                {"gap_mm", gap},        {"tight_mm", 0.15},  {"open_mm", 0.25},
                                {"overhang_mm", overhang}, {"overhang_area_mm2", overhang > 0.15 ? 1.0 : 0.0},
                                {"overhang_threshold_mm", 0.15}, {"overhang_min_area_mm2", 0.09}};
    return filling_criteria(s, nullptr);
  };
  cs = proximal("tight", 0.02, 0.05);
  EXPECT_EQ(by_id(cs, "contact").verdict, Verdict::good);
  EXPECT_EQ(by_id(cs, "contact").shown, "tight: 0.02 mm short of the intact contour");
  EXPECT_EQ(by_id(cs, "overhang").verdict, Verdict::good);
  cs = proximal("open", 0.4, 0.3);
  EXPECT_EQ(by_id(cs, "contact").verdict, Verdict::needs_work);
  EXPECT_EQ(by_id(cs, "overhang").verdict, Verdict::needs_work);
  EXPECT_EQ(by_id(proximal("light", 0.2, 0.0), "contact").verdict, Verdict::needs_work);
  s["grading"].erase("proximal");

  // Surface voids: good with none; each pit in the details.
  s["grading"]["surface_voids"] = {{"measured", true}, {"count", 0}, {"volume_mm3", 0.0}, {"min_void_mm3", 0.027},
                                   {"pore_count", 2}, {"pore_volume_mm3", 0.01}, {"pits", nlohmann::json::array()}};
  cs = filling_criteria(s, nullptr);
  EXPECT_EQ(by_id(cs, "surface_voids").verdict, Verdict::good);
  EXPECT_EQ(by_id(cs, "surface_voids").details.size(), 1u);  // the porosity
  s["grading"]["surface_voids"]["count"] = 1;
  s["grading"]["surface_voids"]["volume_mm3"] = 0.06;
  s["grading"]["surface_voids"]["pits"] = {{{"volume_mm3", 0.06}, {"depth_mm", 0.4}, {"centre_mm", {0.0, 0.0, 0.0}}}};
  cs = filling_criteria(s, nullptr);
  EXPECT_EQ(by_id(cs, "surface_voids").verdict, Verdict::needs_work);
  EXPECT_EQ(by_id(cs, "surface_voids").shown, "1 (0.060 mm^3)");
  EXPECT_NE(by_id(cs, "surface_voids").details[0].find("a pit of 0.060 mm^3, 0.40 mm deep"), std::string::npos);
  s["grading"].erase("surface_voids");

  // The page shows them, and a tampered grading is refused naming the field.
  s["grading"] = grading("bravo", 1, 0.5);
  const std::string html = session_report_html(read_session(write_folder("graded", s)));
  EXPECT_NE(html.find("data-criterion=\"anatomic_form\""), std::string::npos);
  EXPECT_NE(html.find("Marginal adaptation"), std::string::npos);
  s["grading"]["marginal_adaptation"]["measured"] = "yes";
  EXPECT_THROW(read_session(write_folder("graded_tampered", s)), SessionError);
}

// The grading's picture (grading.svg): a square per column of the opening in its band's colour, a
// dot per margin point in its reading's, nothing when neither criterion was measured; the page
// shows it from the run's folder.
TEST(Report, TheGradingsPictureColoursEachColumnByItsBand) {
  EXPECT_STREQ(deviation_colour(0.1, 0.25, 1.0), deviation_colour(-0.25, 0.25, 1.0));  // alpha either way
  EXPECT_STRNE(deviation_colour(-0.3, 0.25, 1.0), deviation_colour(0.3, 0.25, 1.0));
  EXPECT_STRNE(deviation_colour(-0.3, 0.25, 1.0), deviation_colour(-0.6, 0.25, 1.0));
  EXPECT_STRNE(deviation_colour(-0.6, 0.25, 1.0), deviation_colour(-1.1, 0.25, 1.0));
  EXPECT_EQ(grading_svg(SurfaceGrade{}), "");
  SurfaceGrade g;
  g.anatomic.measured = true;
  g.anatomic.band = 'B';
  g.anatomic.column_mm = 0.1;
  g.anatomic.alpha_max_mm = 0.25;
  g.anatomic.charlie_under_mm = 1.0;
  g.anatomic.column_centre_mm = {{0, 0, 0}, {0.1, 0, 0}, {0.2, 0, 0}};
  g.anatomic.deviation_mm = {0.0, -0.4, 0.7};
  g.margin.measured = true;
  g.margin.point_mm = {{-0.5, 0, 0}, {0.5, 0, 0}};
  g.margin.reading = {0, 1};
  const std::string svg = grading_svg(g);
  auto count = [&](const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = svg.find(what); at != std::string::npos; at = svg.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("<rect class=\"column\""), 3u);
  EXPECT_EQ(count("<circle class=\"margin"), 2u);
  for (const double d : g.anatomic.deviation_mm)
    EXPECT_NE(svg.find(std::string("fill=\"") + deviation_colour(d, 0.25, 1.0) + "\"/>"), std::string::npos) << d;
  EXPECT_NE(svg.find("anatomic form bravo; margin 0 sites"), std::string::npos);
  const fs::path d = write_folder("grading_picture", summary(0.97, 0, 0, 1, 1));
  write_grading_picture(d, g);
  EXPECT_NE(session_report_html(read_session(d)).find("id=\"picture-grading\""), std::string::npos);
}

// Every field the report reads has the type a run writes: a void's "against" of 99999999999 threw
// a library's type error out of the report (found by fuzz_report_folder), a step count of 1e300 was
// cast to an int out of its range, an event that is not an object threw from the markers.
TEST(Report, FieldsOfAnotherTypeAreNamedWithTheFix) {
  auto refused = [](const fs::path& d, const std::vector<std::string>& phrases) {
    try {
      const SessionFolder s = read_session(d);
      (void)session_report_html(s);
      ADD_FAILURE() << d << " was read";
    } catch (const SessionError& e) {
      for (const std::string& p : phrases) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
    }
  };
  struct Case {
    std::string path;  // in the summary, by keys, with a list's index
    nlohmann::json value;
    std::string named, want;
  };
  const std::vector<Case> cases = {
      {"/assessment/voids", nlohmann::json::array({{{"against", 99999999999LL}}}), "assessment.voids[0].against is 99999999999", "not a text"},
      {"/assessment/voids", nlohmann::json::array({3}), "assessment.voids[0] is 3", "not an object"},
      {"/assessment/voids", "none", "assessment.voids is \"none\"", "not a list"},
      {"/steps", 1e300, "steps is 1e+300", "not a whole number"},
      {"/threads", -2, "threads is -2", "not a whole number"},
      {"/scene", nlohmann::json::array(), "scene is []", "not a text"},
      {"/particles", 7, "particles is 7", "not an object"},
      {"/session", nlohmann::json{{"student", 5}}, "session.student is 5", "not a text"},
      {"/cure", nlohmann::json{{"increments", {{"a", 1}}}}, "cure.increments is", "not a list"},
      {"/cure", nlohmann::json{{"increments", {{{"increment", 1.5}}}}}, "cure.increments[0].increment is 1.5", "not a whole number"},
      {"/tool/force_scale", "x", "tool.force_scale is \"x\"", "not a number"},
  };
  for (const Case& c : cases) {
    nlohmann::json sm = summary(1, 0, 0, 1, 1);
    sm[nlohmann::json::json_pointer(c.path)] = c.value;
    refused(write_folder("typed", sm), {"summary.json", c.named, c.want, "run the session again"});
  }
  // A folder with its force log but no procedure.json has no markers (its markers were read from a
  // null procedure: found by fuzz_report_folder).
  const fs::path no_log = write_folder("no_procedure", summary(1, 0, 0, 1, 1));
  fs::remove(no_log / "procedure.json");
  const SessionFolder bare = read_session(no_log);
  EXPECT_TRUE(bare.markers.empty());
  EXPECT_EQ(bare.forces.size(), 1u);
  EXPECT_NE(session_report_html(bare).find("force-plot"), std::string::npos);
  // procedure.json's events and increments.
  for (const auto& [procedure, named] : std::vector<std::pair<nlohmann::json, std::string>>{
           {nlohmann::json::array(), "the file is []"},
           {{{"events", {1}}}, "events[0] is 1"},
           {{{"events", {{{"kind", "dispense"}, {"step", -1}}}}}, "events[0].step is -1"},
           {{{"increments", {{{"thickness_p90_mm", "thick"}}}}}, "increments[0].thickness_p90_mm is \"thick\""}}) {
    const fs::path d = write_folder("typed_procedure", summary(1, 0, 0, 1, 1));
    std::ofstream(d / "procedure.json") << procedure.dump();
    refused(d, {"procedure.json", named, "run the session again"});
  }
}

TEST(Report, DecimationKeepsThePeaks) {
  Series s{"f", {}, {}};
  for (int k = 0; k < 100000; ++k) {
    s.t.push_back(k * 1e-4);
    s.f.push_back(k == 71234 ? 9.5 : (k == 4321 ? -1.0 : std::sin(k * 1e-3)));
  }
  const Series d = decimate(s, 1000);
  EXPECT_LE(d.t.size(), 2000u);
  EXPECT_EQ(*std::max_element(d.f.begin(), d.f.end()), 9.5);
  EXPECT_EQ(*std::min_element(d.f.begin(), d.f.end()), -1.0);
  EXPECT_TRUE(std::is_sorted(d.t.begin(), d.t.end()));
}

TEST(Report, ClassComparisonTableAndCsv) {
  std::vector<SessionEntry> sessions;
  const double fills[] = {0.99, 0.80, 0.97};
  for (int k = 0; k < 3; ++k) {
    nlohmann::json s = summary(fills[k], k == 1, 1.0, 2.0 + k, 1.0);
    s["session"]["student"] = "student " + std::to_string(k);
    sessions.push_back(session_entry(write_folder("class" + std::to_string(k), s)));
  }
  EXPECT_EQ(sessions[1].label, "student 1");
  const std::string csv = class_report_csv(sessions);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
  EXPECT_NE(csv.find("student 1,student 1,class I,2026-01-02T03:04:05Z,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",0.8,needs work,1.0,needs work,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",0.99,good,0.0,good,"), std::string::npos) << csv;
  // A cell a spreadsheet would take for a formula is text (OWASP's CSV injection): prefixed with '.
  std::vector<SessionEntry> hostile = {sessions[0], sessions[1], sessions[2]};
  hostile[0].label = "=HYPERLINK(\"http://x\",\"a\")";
  hostile[1].label = "@SUM(A1)";
  hostile[2].label = "-2+3";
  hostile[2].student = "+1";
  const std::string safe = class_report_csv(hostile);
  EXPECT_NE(safe.find("\n\"'=HYPERLINK(\"\"http://x\"\",\"\"a\"\")\","), std::string::npos) << safe;
  EXPECT_NE(safe.find("\n\"'@SUM(A1)\","), std::string::npos) << safe;
  EXPECT_NE(safe.find("\n\"'-2+3\",\"'+1\","), std::string::npos) << safe;
  for (const char* formula : {"\n=", "\n@", "\n-", ",+", ",="}) EXPECT_EQ(safe.find(formula), std::string::npos) << formula;
  const std::string html = class_report_html(sessions, "Class of 2026 & friends");
  EXPECT_NE(html.find("Class of 2026 &amp; friends"), std::string::npos);
  EXPECT_EQ(std::count(html.begin(), html.end(), '\n') > 10, true);
  for (const char* id : {"chart-fill", "chart-voids", "chart-overfill", "chart-increments", "chart-peak_force"})
    EXPECT_NE(html.find(id), std::string::npos) << id;
  EXPECT_NE(html.find("data-value=\"0.8\">80.0 %"), std::string::npos);
}

TEST(Report, IncrementThicknessFromTheFinalState) {
  // The built-in scene's paste, 1600 particles filling the 2 mm deep cavity and heaped above it,
  // as one increment: at least the cavity's depth thick, at most the paste's whole height.
  const Scene scene = default_dental_scene();
  const State state = make_state(scene);
  double lo = 1e9, hi = -1e9;
  for (std::uint32_t i = 0; i < state.size(); ++i)
    if (state.role[i] == Role::material) {
      const double z = scene.tooth->frame().to_local(state.pos[i]).z;
      lo = std::min(lo, z), hi = std::max(hi, z);
    }
  const double height_mm = (hi - lo + scene.material_spacing) * 1e3;
  ProcedureLog log(0u);
  log.add({0, 0.0, "dispense", "procedure", "", state.count(Role::material)});
  const auto t = log.thickness(scene, state);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].particles, state.count(Role::material));
  EXPECT_GT(t[0].median_mm, 2.0);
  EXPECT_LE(t[0].p90_mm, height_mm + 1e-9);
  EXPECT_GE(t[0].p90_mm, t[0].median_mm);
  // Split in two by id: two thinner layers, each about half.
  ProcedureLog two(0u);
  const std::uint32_t half = state.count(Role::material) / 2;
  two.add({0, 0.0, "dispense", "procedure", "", half});
  two.add({10, 0.1, "dispense", "procedure", "", state.count(Role::material) - half});
  const auto t2 = two.thickness(scene, state);
  ASSERT_EQ(t2.size(), 2u);
  EXPECT_LT(t2[0].median_mm, 0.75 * t[0].median_mm);
  // Counts not known (a recording's button increments), or not adding up: not measured.
  ProcedureLog unknown(0u);
  unknown.add({0, 0.0, "dispense", "button", "", -1});
  EXPECT_TRUE(unknown.thickness(scene, state).empty());
  ProcedureLog wrong(0u);
  wrong.add({0, 0.0, "dispense", "procedure", "", 5});
  EXPECT_TRUE(wrong.thickness(scene, state).empty());
}

// Increments of the device's button (their particle counts not in the log) are counted from the
// increment numbers every dispense gives its particles.
TEST(Report, ButtonIncrementsThicknessFromTheirNumbers) {
  const Scene scene = default_dental_scene();
  State state = make_state(scene);
  const std::uint32_t initial = state.count(Role::material);
  const real volume = 40 * std::pow(scene.material_spacing, 3);
  const std::size_t a = dispense_increment(scene, state, volume, increment_axis(scene), scene_paste(scene));
  const std::size_t b = dispense_increment(scene, state, volume, increment_axis(scene), scene_paste(scene));
  ASSERT_GT(a, 0u);
  ASSERT_GT(b, 0u);
  ProcedureLog log(initial);
  log.add({0, 0.0, "dispense", "button", "", -1});
  log.add({5, 0.1, "dispense", "button", "", -1});
  const auto t = log.thickness(scene, state);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].particles, a);
  EXPECT_EQ(t[1].particles, b);
  EXPECT_GT(t[0].median_mm, 0);
  // A third button increment the state never saw: not measured.
  log.add({9, 0.2, "dispense", "button", "", -1});
  EXPECT_TRUE(log.thickness(scene, state).empty());
}

TEST(Report, StoreMigratesFindsAndKeepsSessions) {
  const fs::path d = testing::fresh_dir("store");
  const std::string db = (d / "sessions.sqlite").string();
  std::vector<fs::path> folders;
  for (int k = 0; k < 3; ++k) {
    nlohmann::json s = summary(0.9 + 0.03 * k, 0, 1.0, 2.0, 1.0);
    s["session"] = {{"student", k == 2 ? "B" : "A"}, {"exercise", k == 0 ? "class II" : "class I"},
                    {"finished_at", "2026-01-0" + std::to_string(3 - k) + "T10:00:00Z"}};
    folders.push_back(write_folder("store" + std::to_string(k), s));
  }
  {
    SessionStore store(db);
    EXPECT_EQ(store.schema_version(), current_store_version());
    for (const fs::path& f : folders) store.add_folder(f);
  }
  const SessionStore again(db);  // reopened: nothing migrated twice, everything kept
  EXPECT_EQ(again.schema_version(), current_store_version());
  const auto a = again.find("A", "");
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a[0].finished_at, "2026-01-02T10:00:00Z");  // oldest first
  EXPECT_EQ(a[0].exercise, "class I");
  EXPECT_EQ(a[0].summary, nlohmann::json::parse(std::ifstream(folders[1] / "summary.json")));
  EXPECT_EQ(a[0].procedure["increments"][0]["thickness_p90_mm"], 0.875);
  EXPECT_EQ(a[0].folder, fs::absolute(folders[1]).lexically_normal().string());
  EXPECT_EQ(again.find("", "class I").size(), 2u);
  EXPECT_EQ(again.find("A", "class II").size(), 1u);
  EXPECT_TRUE(again.find("C", "").empty());
}

TEST(Report, StoreRefusesWhatItCannotUse) {
  const fs::path d = testing::fresh_dir("store_refusals");
  auto refused = [](const std::string& location, const std::string& phrase) {
    try {
      SessionStore s(location);
      ADD_FAILURE() << location << " opened";
    } catch (const StoreError& e) {
      EXPECT_NE(std::string(e.what()).find(phrase), std::string::npos) << e.what();
    }
  };
  refused((d / "no" / "such" / "dir.sqlite").string(), "cannot open the session store");
  // A store written by a newer version.
  const std::string newer = (d / "newer.sqlite").string();
  { SessionStore s(newer); }
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(newer.c_str(), &db), SQLITE_OK);
  sqlite3_exec(db, "UPDATE schema_version SET version = 99", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  refused(newer, "newer than this program's");
  // A store another program holds locked: said after the busy timeout, not "not a session store".
  const std::string locked = (d / "locked.sqlite").string();
  { SessionStore s(locked); }
  ASSERT_EQ(sqlite3_open(locked.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "BEGIN EXCLUSIVE", nullptr, nullptr, nullptr), SQLITE_OK);
  refused(locked, "locked by another program");
  sqlite3_exec(db, "ROLLBACK", nullptr, nullptr, nullptr);
  sqlite3_close(db);
}

TEST(Report, TwoWritersAtOnceLoseNothing) {
  const fs::path d = testing::fresh_dir("store_writers");
  const std::string db = (d / "s.sqlite").string();
  { SessionStore init(db); }
  const fs::path folder = write_folder("store_writer", summary(1, 0, 0, 1, 1));
  auto writer = [&](const std::string& student) {
    SessionStore s(db);
    SessionEntry e = session_entry(folder);
    e.student = student;
    for (int k = 0; k < 25; ++k) s.add(e);
  };
  std::thread a(writer, "first"), b(writer, "second");
  a.join();
  b.join();
  const SessionStore s(db);
  EXPECT_EQ(s.find("first", "").size(), 25u);
  EXPECT_EQ(s.find("second", "").size(), 25u);
}

TEST(Report, SceneFilesNameTheStudentAndTheExercise) {
  nlohmann::json j = nlohmann::json::parse(std::ifstream("scenes/tool_press.json"));
  j["student"] = "A. Student";
  j["exercise"] = "press";
  const Scene sc = parse_scene(j.dump(), "named.json");
  EXPECT_EQ(sc.student, "A. Student");
  EXPECT_EQ(sc.exercise, "press");
  EXPECT_TRUE(parse_scene(nlohmann::json::parse(std::ifstream("scenes/tool_press.json")).dump(), "x.json").student.empty());
  j["student"] = 3;
  try {
    parse_scene(j.dump(), "named.json");
    ADD_FAILURE() << "a number as the student's name was taken";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("named.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("student"), std::string::npos) << e.what();
  }
  // A dental scene file takes them too.
  const Scene dental = parse_scene(R"({"name": "d", "cavity": {"depth": 2}, "student": "B", "exercise": "class I"})",
                                   "dental.json");
  EXPECT_EQ(dental.student, "B");
  EXPECT_EQ(dental.exercise, "class I");
}

TEST(Report, HtmlHelpers) {
  EXPECT_EQ(escape_html("a<b & \"c\"'"), "a&lt;b &amp; &quot;c&quot;&#39;");
  EXPECT_EQ(script_safe("{\"x\":\"</script>\"}"), "{\"x\":\"<\\/script>\"}");
  EXPECT_EQ(base64({}), "");
  EXPECT_EQ(base64({'f'}), "Zg==");
  EXPECT_EQ(base64({'f', 'o'}), "Zm8=");
  EXPECT_EQ(base64({'f', 'o', 'o', 'b', 'a', 'r'}), "Zm9vYmFy");
}

}  // namespace
}  // namespace dentsph::report
