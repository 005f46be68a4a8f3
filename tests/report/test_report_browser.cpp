// The report as a person sees it: report.html rendered by headless Chromium (Debian's chromium,
// installed by scripts/install-deps.sh). Its scripts run (the plot's canvas is drawn), the page's
// numbers equal summary.json's, the screenshot is not blank and shows the tooth and the paste; a
// realtime session's report shows the haptic loop; a class comparison of three sessions draws its
// charts; a missing or broken folder is named (exit 2). Each test skips, saying why, without
// chromium.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iterator>
#include <regex>
#include <string>
#include <tuple>

#include <nlohmann/json.hpp>
#include <stb/stb_image.h>

#include "dentsph/report/session_store.hpp"
#include "report/criteria.hpp"
#include "report_support.hpp"
#include "support/cli_process.hpp"

namespace dentsph::report {
namespace {

namespace fs = std::filesystem;

using Result = dentsph::testing::CliResult;

Result shell(const std::string& cmd) { return dentsph::testing::run_command(cmd); }

std::string text_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string chromium() {
  for (const char* c : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
    if (fs::exists(c)) return c;
  return "";
}

#define NEED_CHROMIUM()                                                                               \
  if (chromium().empty()) GTEST_SKIP() << "chromium is not installed (scripts/install-deps.sh installs it)"

const fs::path& work();

std::string browser(const std::string& args) {
  // --no-sandbox: the tests may run as root (CI), where Chromium's sandbox refuses to start. A
  // profile of its own for each call: two browsers sharing one (tests run in parallel) would hand
  // the page to the first and print nothing.
  static int calls = 0;
  const fs::path profile = work() / ("profile-" + std::to_string(::getpid()) + "-" + std::to_string(++calls));
  return chromium() + " --headless --no-sandbox --disable-gpu --hide-scrollbars --user-data-dir=" + profile.string() +
         " " + args;
}

// The DOM after the page's scripts ran.
std::string dump_dom(const fs::path& html) {
  const Result r = shell(browser("--dump-dom file://" + fs::absolute(html).string()) + " 2>/dev/null");
  EXPECT_EQ(r.code, 0) << r.output.substr(0, 2000);
  return r.output;
}

struct Png {
  int w = 0, h = 0;
  std::vector<unsigned char> rgb;
  std::array<int, 3> at(int x, int y) const {
    const std::size_t i = (std::size_t(y) * w + x) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

Png screenshot(const fs::path& html, const fs::path& png, int w, int h) {
  fs::remove(png);
  const Result r = shell(browser("--screenshot=" + png.string() + " --window-size=" + std::to_string(w) + "," +
                                 std::to_string(h) + " file://" + fs::absolute(html).string()));
  Png p;
  int n = 0;
  unsigned char* data = stbi_load(png.c_str(), &p.w, &p.h, &n, 3);
  EXPECT_NE(data, nullptr) << r.output;
  if (data) {
    p.rgb.assign(data, data + std::size_t(p.w) * p.h * 3);
    stbi_image_free(data);
  }
  return p;
}

Result dentsph(const std::string& args) { return shell(std::string(DENTSPH_CLI) + " " + args); }

const fs::path& work() {
  static const fs::path d = testing::fresh_dir("browser_" + std::to_string(::getpid()));
  return d;
}

// The data-value of each data-key in the DOM, checked against summary.json.
int expect_numbers_equal(const std::string& dom, const nlohmann::json& summary) {
  const std::regex cell("data-key=\"([A-Za-z0-9_.]+)\" data-value=\"([^\"]+)\"");
  int n = 0;
  for (auto it = std::sregex_iterator(dom.begin(), dom.end(), cell); it != std::sregex_iterator(); ++it) {
    const std::optional<double> want = number_at(summary, (*it)[1]);
    EXPECT_TRUE(want) << (*it)[1];
    if (want) {
      EXPECT_EQ(std::stod((*it)[2]), *want) << (*it)[1];
    }
    ++n;
  }
  return n;
}

TEST(ReportBrowser, OfflineRunsReportRendersWithItsPicturesPlotAndNumbers) {
  NEED_CHROMIUM();
  const fs::path out = work() / "offline";
  const Result run = dentsph("run --steps 1500 --threads 1 --out " + out.string() + " -q --student 'A. Student' --exercise 'class I'");
  ASSERT_EQ(run.code, 0) << run.output;
  ASSERT_TRUE(fs::exists(out / "report.html"));
  const nlohmann::json summary = nlohmann::json::parse(std::ifstream(out / "summary.json"));
  const std::string dom = dump_dom(out / "report.html");
  // The script ran and Chart.js drew: the canvas carries the number of datasets it plotted.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(dom, m, std::regex("id=\"force-plot\"[^>]*data-plotted=\"([0-9]+)\""))) << dom.substr(0, 3000);
  EXPECT_GE(std::stoi(m[1]), 3);  // the force, the device limit, the increments
  // The filling's six numbers, its surface's grading's three (anatomic form, margin, surface voids)
  // and the cure's one (the built-in procedure cures; 0.075 s is before its light: the first
  // increment's adequately cured share, 0).
  EXPECT_EQ(expect_numbers_equal(dom, summary), 10);
  EXPECT_NE(dom.find("id=\"picture-grading\""), std::string::npos);
  EXPECT_NE(dom.find("A. Student, class I"), std::string::npos);
  EXPECT_NE(dom.find("id=\"picture-cut\""), std::string::npos);
  EXPECT_NE(dom.find("id=\"picture-top\""), std::string::npos);
  // The paste as its surface in those two, and as particles in a second view.
  EXPECT_NE(dom.find("id=\"picture-cut-particles\""), std::string::npos);
  EXPECT_NE(dom.find("id=\"picture-top-particles\""), std::string::npos);

  // As a person sees it: not blank; the pictures' enamel and paste, the plot's blue curve.
  const Png p = screenshot(out / "report.html", work() / "offline.png", 1100, 2400);
  ASSERT_GT(p.w, 0);
  int enamel = 0, paste = 0, dentine = 0, other = 0;
  for (int y = 0; y < p.h; ++y)
    for (int x = 0; x < p.w; ++x) {
      const auto c = p.at(x, y);
      if (c[0] >= 245 && c[1] >= 245 && c[2] >= 245) continue;  // page background
      ++other;
      enamel += c[0] > 150 && c[0] >= c[1] && c[1] >= c[2] && c[0] - c[2] > 8 && c[0] - c[2] < 60;
      dentine += std::abs(c[0] - 214) < 4 && std::abs(c[1] - 184) < 4 && std::abs(c[2] - 140) < 4;
      paste += c[2] > c[0] + 60 && c[2] > c[1] + 20;
    }
  EXPECT_GT(other, p.w * p.h / 10) << "the page looks blank";
  EXPECT_GT(enamel, 20000);
  EXPECT_GT(dentine, 10000);
  EXPECT_GT(paste, 3000);
}

// The built-in procedure (each increment light-cured) until 0.3 s into its first
// increment's cure: the report's Light curing section gives the increment's verdict and message,
// with the numbers summary.json holds, and the curing light's marker on the force plot.
TEST(ReportBrowser, OfflineRunsReportShowsTheLightCuring) {
  NEED_CHROMIUM();
  const fs::path out = work() / "cured";
  const Result run = dentsph("run --duration 1.2 --threads 2 --out " + out.string() + " -q");
  ASSERT_EQ(run.code, 0) << run.output;
  const nlohmann::json summary = nlohmann::json::parse(std::ifstream(out / "summary.json"));
  ASSERT_TRUE(summary.contains("cure")) << summary.dump(2);
  const nlohmann::json& cure = summary["cure"];
  EXPECT_NEAR(cure["light_on_s"].get<double>(), 1.2 - 0.906, 1e-3);
  ASSERT_EQ(cure["increments"].size(), 1u);
  const nlohmann::json& one = cure["increments"][0];
  // 0.29 s at 1000 mW/cm2 is 0.29 J/cm2 at the window: the top received nearly that.
  EXPECT_GT(one["top_dose_J_per_cm2"].get<double>(), 0.2);
  EXPECT_LT(one["top_dose_J_per_cm2"].get<double>(), 0.3);
  const std::string dom = dump_dom(out / "report.html");
  EXPECT_NE(dom.find("<h2>Light curing</h2>"), std::string::npos);
  EXPECT_NE(dom.find(cure["message"].get<std::string>()), std::string::npos) << cure["message"];
  EXPECT_NE(dom.find(one["message"].get<std::string>()), std::string::npos) << one["message"];
  EXPECT_NE(dom.find("data-criterion=\"cure_1\""), std::string::npos);
  EXPECT_EQ(expect_numbers_equal(dom, summary), 10);
  // The procedure's log counts each dispense's particles (it once logged an event before applying
  // it, so every count was the interval's before and no increment's thickness was measured).
  const nlohmann::json proc = nlohmann::json::parse(std::ifstream(out / "procedure.json"));
  ASSERT_GE(proc["events"].size(), 2u);
  EXPECT_EQ(proc["events"][0]["kind"], "dispense");
  EXPECT_EQ(proc["events"][0]["particles"].get<int>(), summary["particles"]["material"].get<int>());
  ASSERT_EQ(proc["increments"].size(), 1u);
  EXPECT_GT(proc["increments"][0]["thickness_median_mm"].get<double>(), 0.3);
  EXPECT_LT(proc["increments"][0]["thickness_median_mm"].get<double>(), 1.5);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(dom, m, std::regex("id=\"force-plot\"[^>]*data-plotted=\"([0-9]+)\"")));
  EXPECT_GE(std::stoi(m[1]), 4);  // the force, the device limit, the increments, the curing light
  // As a person sees it: not blank, the section's verdict badge drawn in its colour.
  const Png p = screenshot(out / "report.html", work() / "cured.png", 1100, 2600);
  ASSERT_GT(p.w, 0);
  int badges = 0;
  for (int y = 0; y < p.h; ++y)
    for (int x = 0; x < p.w; ++x) {
      const auto c = p.at(x, y);
      badges += (std::abs(c[0] - 0xd8) < 3 && std::abs(c[1] - 0xf0) < 3 && std::abs(c[2] - 0xda) < 3) ||
                (std::abs(c[0] - 0xfd) < 3 && std::abs(c[1] - 0xe2) < 3 && std::abs(c[2] - 0xc8) < 3);
    }
  EXPECT_GT(badges, 500);
}

TEST(ReportBrowser, RealtimeSessionsReportShowsTheHapticLoop) {
  NEED_CHROMIUM();
  const fs::path out = work() / "realtime";
  const Result run = dentsph("run --realtime --duration 1 --threads 1 --out " + out.string() + " -q");
  ASSERT_EQ(run.code, 0) << run.output;
  const nlohmann::json summary = nlohmann::json::parse(std::ifstream(out / "summary.json"));
  ASSERT_TRUE(summary.contains("assessment"));
  EXPECT_EQ(summary["haptic"]["profile"]["max_force_N"], 9.0);
  const std::string dom = dump_dom(out / "report.html");
  EXPECT_NE(dom.find("id=\"haptic\""), std::string::npos);
  EXPECT_NE(dom.find("data-plotted=\""), std::string::npos);
  // The filling's six numbers, its surface's grading's three, the haptic loop's six and the cure's
  // one (the built-in procedure).
  EXPECT_EQ(expect_numbers_equal(dom, summary), 16);
  EXPECT_NE(dom.find("force sent to the device"), std::string::npos);

  // Its replay written as a run folder: the same forces (exit 0), a report of its own, and the
  // increment's particles known, so its thickness is measured.
  const fs::path replayed = work() / "replayed";
  const Result rep = dentsph("replay " + (out / "recording").string() + " --threads 1 --out " + replayed.string());
  ASSERT_EQ(rep.code, 0) << rep.output;
  EXPECT_NE(rep.output.find("0 tool forces differ"), std::string::npos) << rep.output;
  const nlohmann::json rs = nlohmann::json::parse(std::ifstream(replayed / "summary.json"));
  EXPECT_EQ(rs["steps"], summary["sim"]["steps"]);
  EXPECT_EQ(rs["tool"]["peak_force_N"], summary["tool"]["peak_force_N"]);
  const nlohmann::json proc = nlohmann::json::parse(std::ifstream(replayed / "procedure.json"));
  ASSERT_FALSE(proc["increments"].empty());
  EXPECT_GT(proc["increments"][0]["particles"].get<int>(), 100);
  // The filling's six numbers, the grading's three and the cure's one, as an offline run's report.
  EXPECT_EQ(expect_numbers_equal(dump_dom(replayed / "report.html"), rs), 10);

  // One end of run: the replay's summary holds every field an offline run's does (the solver's
  // statistics and the cure among them), but the snapshots' surfaces, which a replay does not write.
  const fs::path offline = work() / "offline";
  const Result off = dentsph("run --duration 0.2 --threads 1 --out " + offline.string() + " -q");
  ASSERT_EQ(off.code, 0) << off.output;
  const nlohmann::json os = nlohmann::json::parse(std::ifstream(offline / "summary.json"));
  std::vector<std::string> missing;
  std::function<void(const nlohmann::json&, const nlohmann::json&, const std::string&)> compare =
      [&](const nlohmann::json& want, const nlohmann::json& have, const std::string& path) {
        for (const auto& [key, value] : want.items()) {
          const std::string at = path + "/" + key;
          if (at == "/paste_surface") continue;
          if (!have.contains(key)) {
            missing.push_back(at);
            continue;
          }
          if (value.is_object()) compare(value, have[key], at);
        }
      };
  compare(os, rs, "");
  EXPECT_TRUE(missing.empty()) << "the replay's summary lacks " << ::testing::PrintToString(missing);
  EXPECT_TRUE(rs.contains("cure")) << rs.dump();
  EXPECT_EQ(rs["solver"]["name"], summary["solver"]["name"]);
}

TEST(ReportBrowser, ClassComparisonOfThreeSessionsDrawsItsCharts) {
  NEED_CHROMIUM();
  std::string dirs;
  const double fills[] = {0.99, 0.82, 0.96};
  for (int k = 0; k < 3; ++k) {
    nlohmann::json s = testing::summary(fills[k], k == 1, 2.0 + k, 3.0 + k, 1.0 + 0.2 * k);
    s["session"]["student"] = "student " + std::to_string(k + 1);
    dirs += ' ';
    dirs += testing::write_folder("browser_class" + std::to_string(k), s).string();
  }
  const fs::path html = work() / "class.html";
  const Result r = dentsph("report" + dirs + " --out " + html.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string dom = dump_dom(html);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(dom, m, std::regex("id=\"charts\"[^>]*data-charts=\"([0-9]+)\""))) << dom.substr(0, 2000);
  EXPECT_EQ(std::stoi(m[1]), 6);  // fill, voids, overfill, increments, peak and mean force
  EXPECT_EQ(std::regex_search(dom, std::regex("data-value=\"0.82\">82.0 %")), true);
  std::ifstream csv(work() / "class.csv");
  const std::string text((std::istreambuf_iterator<char>(csv)), std::istreambuf_iterator<char>());
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 4);
  const Png p = screenshot(html, work() / "class.png", 1100, 1400);
  int green = 0, orange = 0;
  for (int y = 0; y < p.h; ++y)
    for (int x = 0; x < p.w; ++x) {
      const auto c = p.at(x, y);
      green += c == std::array<int, 3>{0x4c, 0xaf, 0x50};
      orange += c == std::array<int, 3>{0xef, 0x8a, 0x2b};
    }
  EXPECT_GT(green, 5000);   // good bars
  EXPECT_GT(orange, 1000);  // the 82 % fill and its void
}

TEST(ReportBrowser, MissingOrBrokenFoldersAreNamed) {
  // No browser needed: the command refuses before writing anything.
  const Result missing = dentsph("report " + (work() / "no_such_run").string());
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.output.find("no_such_run: no such folder"), std::string::npos) << missing.output;
  const fs::path broken = testing::write_folder("browser_broken", testing::summary(1, 0, 0, 1, 1));
  std::ofstream(broken / "summary.json") << "{\"steps\": ";
  const Result bad = dentsph("report " + broken.string() + " --out " + (work() / "x.html").string());
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.output.find("summary.json: not valid JSON"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(work() / "x.html"));
  // A store with no session of the student (made as a run's --db makes one): named.
  const fs::path empty = work() / "empty.sqlite";
  {
    report::SessionStore made(empty.string());
  }
  const Result none = dentsph("report --db " + empty.string() + " --student nobody --out " + (work() / "y.html").string());
  EXPECT_EQ(none.code, 2);
  EXPECT_NE(none.output.find("no session of student 'nobody'"), std::string::npos) << none.output;
  // The comparison never overwrites a run folder's own files: its summary.json became HTML.
  const fs::path run = testing::write_folder("browser_own_files", testing::summary(1, 0, 0, 1, 1));
  const std::string before = text_of(run / "summary.json");
  for (const char* target : {"summary.json", "report.html", "tool_force.csv"}) {
    std::ofstream(run / target, std::ios::app).flush();  // each exists, as a run leaves it
    const Result own = dentsph("report " + run.string() + " --out " + (run / target).string());
    EXPECT_EQ(own.code, 2) << target;
    EXPECT_NE(own.output.find("which the report reads"), std::string::npos) << own.output;
  }
  EXPECT_EQ(text_of(run / "summary.json"), before);
  const Result beside = dentsph("report " + run.string() + " --out " + (run / "compare.html").string());
  EXPECT_EQ(beside.code, 0) << "a new page beside the run's files: " << beside.output;
  // A pipe in summary.json's place is named, not read for ever.
  const fs::path piped = testing::write_folder("browser_fifo", testing::summary(1, 0, 0, 1, 1));
  fs::remove(piped / "summary.json");
  ASSERT_EQ(mkfifo((piped / "summary.json").c_str(), 0600), 0);
  const Result fifo = dentsph::testing::run_command(std::string(DENTSPH_CLI) + " report " + piped.string() + " --out " +
                                           (work() / "fifo.html").string(), 30);
  EXPECT_EQ(fifo.code, 2) << fifo.output;
  EXPECT_NE(fifo.output.find("not a regular file"), std::string::npos) << fifo.output;
  // Files larger than a run writes are refused before they are read (a 300 MB summary.json made a
  // 944 MB report using 2.2 GB): sparse files here, taking no disk.
  for (const auto& [file, size, what] : {std::tuple{"summary.json", 300u << 20, "16 MB the run's summary can be"},
                                         std::tuple{"tooth_cut.png", 100u << 20, "64 MB a run's picture can be"},
                                         std::tuple{"tool_force.csv", 1500u << 20, "1024 MB a run's log can be"}}) {
    const fs::path huge = testing::write_folder(std::string("browser_huge_") + file, testing::summary(1, 0, 0, 1, 1));
    std::ofstream(huge / file, std::ios::app).flush();
    fs::resize_file(huge / file, size);
    const Result r = dentsph("report " + huge.string() + " --out " + (work() / "huge.html").string());
    EXPECT_EQ(r.code, 2) << file << ": " << r.output;
    EXPECT_NE(r.output.find(std::string(file) + ": " + std::to_string(size >> 20) + " MB, more than the " + what),
              std::string::npos) << r.output;
    fs::remove_all(huge);
  }
  EXPECT_FALSE(fs::exists(work() / "huge.html"));
}

TEST(ReportBrowser, ManySessionsShowTheirProgress) {
  // No browser needed. Six folders: the comparison says how far it is (a plain line off a
  // terminal, the last one at 100%).
  std::string dirs;
  for (int k = 0; k < 6; ++k) {
    dirs += ' ';
    dirs += testing::write_folder("browser_many" + std::to_string(k), testing::summary(0.9, 0, 1, 1, 1)).string();
  }
  const Result r = dentsph("report" + dirs + " --out " + (work() / "many.html").string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("progress 100.0%  step 6/6"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(6 sessions)"), std::string::npos) << r.output;
}

TEST(ReportBrowser, StoreFindsAStudentsSessionsWithoutFolders) {
  NEED_CHROMIUM();
  const std::string db = (work() / "store.sqlite").string();
  fs::remove(db);
  for (int k = 0; k < 3; ++k) {
    const fs::path out = work() / ("store_run" + std::to_string(k));
    const Result r = dentsph("run --steps " + std::to_string(300 + 200 * k) + " --threads 1 --out " + out.string() +
                             " -q --student 'B. Student' --exercise 'class I' --db " + db);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("added to the session store"), std::string::npos);
    fs::remove_all(out);  // the store holds what the comparison needs
  }
  const fs::path html = work() / "student.html";
  const Result r = dentsph("report --db " + db + " --student 'B. Student' --out " + html.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("(3 sessions)"), std::string::npos) << r.output;
  const std::string dom = dump_dom(html);
  EXPECT_NE(dom.find("Sessions of B. Student"), std::string::npos);
  EXPECT_NE(dom.find("data-charts=\""), std::string::npos);
}

// A handling test's plot as a person sees it (`material-test rheometer --out`): flow_curve.svg in
// Chromium shows the measured curve (blue), the preset's law (red, dashed) and the published range
// (an orange bar), on white with dark axes and labels.
TEST(ReportBrowser, AHandlingTestsPlotShowsItsCurveLawAndPublishedRange) {
  NEED_CHROMIUM();
  const fs::path out = work() / "rheometer";
  const Result r = dentsph("material-test rheometer --material universal --shear-rates 5,10,20,50 --threads 2 --out " +
                           out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  const Png png = screenshot(out / "flow_curve.svg", work() / "flow_curve.png", 640, 420);
  ASSERT_EQ(png.w, 640);
  auto near = [](const std::array<int, 3>& c, int r, int g, int b) {
    return std::abs(c[0] - r) < 30 && std::abs(c[1] - g) < 30 && std::abs(c[2] - b) < 30;
  };
  int white = 0, dark = 0, blue = 0, red = 0, orange = 0;
  for (int y = 0; y < png.h; ++y)
    for (int x = 0; x < png.w; ++x) {
      const auto c = png.at(x, y);
      white += c[0] > 245 && c[1] > 245 && c[2] > 245;
      dark += c[0] < 80 && c[1] < 80 && c[2] < 80;
      blue += near(c, 31, 95, 168);
      red += near(c, 192, 57, 43);
      orange += near(c, 249, 211, 150);
    }
  const int all = png.w * png.h;
  EXPECT_GT(white, all / 2) << "a white page";
  EXPECT_GT(dark, 500) << "axes, ticks and labels";
  EXPECT_GT(blue, 400) << "the measured curve";
  EXPECT_GT(red, 200) << "the preset's law";
  EXPECT_GT(orange, 200) << "the published range";
}

}  // namespace
}  // namespace dentsph::report
