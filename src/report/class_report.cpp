// The class comparison (class_report.hpp).
#include "dentsph/report/class_report.hpp"

#include <algorithm>
#include <fstream>
#include <string_view>

#include <fmt/format.h>

#include "dentsph/report/session_folder.hpp"
#include "report/criteria.hpp"
#include "report/html.hpp"
#include "report/page.hpp"

namespace dentsph::report {

namespace {

// The number a chart shows for a criterion: percentages for the fill.
double chart_value(const Criterion& c) { return c.id == "fill" ? 100 * *c.value : *c.value; }

const Criterion* find(const std::vector<Criterion>& cs, const std::string& id) {
  for (const Criterion& c : cs)
    if (c.id == id) return &c;
  return nullptr;
}

// A text cell of the CSV: quoted where it holds a comma, a quote or a line break; one that begins
// with = + - @, a tab or a carriage return (a spreadsheet would take it for a formula: OWASP's CSV
// injection) is prefixed with ' and quoted, so that it is shown as the text it is.
std::string csv_field(const std::string& text) {
  const bool formula = !text.empty() && std::string_view("=+-@\t\r").find(text.front()) != std::string_view::npos;
  const std::string s = formula ? "'" + text : text;
  if (!formula && s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

constexpr const char* kChartsScript = R"js(
(function () {
  const data = JSON.parse(document.getElementById('class-data').textContent);
  // The threshold across the whole plot (a line dataset on a bar chart's categories would stop at
  // the first and last bars' middles); its dataset, empty, stands for it in the legend.
  const threshold = {id: 'threshold', afterDatasetsDraw(chart, args, opts) {
    if (opts.value === null || opts.value === undefined) return;
    const y = chart.scales.y.getPixelForValue(opts.value), area = chart.chartArea, ctx = chart.ctx;
    ctx.save(); ctx.strokeStyle = '#c0392b'; ctx.lineWidth = 1.5; ctx.setLineDash([6, 4]);
    ctx.beginPath(); ctx.moveTo(area.left, y); ctx.lineTo(area.right, y); ctx.stroke(); ctx.restore();
  }};
  let drawn = 0;
  for (const c of data.charts) {
    const canvas = document.getElementById('chart-' + c.id);
    const colours = c.verdicts.map(v => v === 'good' ? '#4caf50' : v === 'needs work' ? '#ef8a2b' : '#bbbbbb');
    const sets = [{type: 'bar', label: c.label + ' (' + c.unit + ')', data: c.values, backgroundColor: colours}];
    if (c.threshold !== null)
      sets.push({type: 'line', label: c.rule, data: c.values.map(() => null), borderColor: '#c0392b',
                 backgroundColor: '#c0392b', borderDash: [6, 4], borderWidth: 1.5, pointRadius: 0});
    new Chart(canvas, {data: {labels: data.labels, datasets: sets}, plugins: [threshold],
      options: {animation: false, responsive: false,
        scales: {y: {beginAtZero: true, max: c.unit === '%' ? 100 : undefined,
                     suggestedMax: c.threshold === null ? undefined : 1.1 * c.threshold,
                     title: {display: true, text: c.unit}}},
        plugins: {legend: {position: 'bottom'}, title: {display: true, text: c.label}, threshold: {value: c.threshold}}}});
    canvas.setAttribute('data-plotted', String(sets.length));
    ++drawn;
  }
  document.getElementById('charts').setAttribute('data-charts', String(drawn));
})();
)js";

}  // namespace

SessionEntry session_entry(const std::filesystem::path& dir) {
  const SessionFolder s = read_session(dir);
  SessionEntry e;
  e.folder = dir.string();
  e.summary = s.summary;
  e.procedure = s.procedure;
  const nlohmann::json session = s.summary.value("session", nlohmann::json::object());
  e.student = session.value("student", "");
  e.exercise = session.value("exercise", "");
  e.finished_at = session.value("finished_at", "");
  if (std::filesystem::exists(dir / "report.html")) e.report = (dir / "report.html").string();
  std::filesystem::path name = dir.filename().empty() ? dir.parent_path().filename() : dir.filename();
  e.label = !e.student.empty() ? e.student : name.string();
  return e;
}

const std::vector<std::string>& compared_criteria() {
  static const std::vector<std::string> ids = {"fill", "voids", "overfill", "leaked", "increments", "peak_force",
                                               "mean_force"};
  return ids;
}

std::string class_report_html(const std::vector<SessionEntry>& sessions, const std::string& title) {
  std::vector<std::vector<Criterion>> all;
  for (const SessionEntry& e : sessions) all.push_back(filling_criteria(e.summary, e.procedure));
  std::string h = page_begin(title);
  h += fmt::format("<h1>{}</h1>\n<div class=\"sub\">{} session{}</div>\n", escape_html(title), sessions.size(),
                   sessions.size() == 1 ? "" : "s");
  h += "<h2>Scores</h2>\n<table id=\"sessions\">\n<tr><th>session</th><th>exercise</th><th>finished</th>";
  const std::vector<Criterion> names = filling_criteria(nlohmann::json::object(), nullptr);
  for (const std::string& id : compared_criteria()) h += "<th>" + escape_html(find(names, id)->label) + "</th>";
  h += "</tr>\n";
  for (std::size_t k = 0; k < sessions.size(); ++k) {
    const SessionEntry& e = sessions[k];
    const std::string name = e.report.empty() ? escape_html(e.label)
                                              : fmt::format("<a href=\"file://{}\">{}</a>", escape_html(e.report),
                                                            escape_html(e.label));
    h += fmt::format("<tr data-session=\"{}\"><td>{}</td><td>{}</td><td>{}</td>", k, name, escape_html(e.exercise),
                     escape_html(e.finished_at));
    for (const std::string& id : compared_criteria()) {
      const Criterion& c = *find(all[k], id);
      std::string cell = value_cell(c);
      cell.insert(cell.size() - 5, "<br>" + verdict_badge(c.verdict));  // before </td>
      h += cell;
    }
    h += "</tr>\n";
  }
  h += "</table>\n";

  // One bar chart per criterion that some session measured.
  nlohmann::json data = {{"labels", nlohmann::json::array()}, {"charts", nlohmann::json::array()}};
  for (const SessionEntry& e : sessions) data["labels"].push_back(e.label);
  h += "<h2>Side by side</h2>\n<div id=\"charts\" class=\"pictures\">\n";
  const Thresholds t;
  for (const std::string& id : compared_criteria()) {
    if (id == "leaked") continue;  // counts of particles: the table says it
    nlohmann::json chart = {{"id", id}, {"values", nlohmann::json::array()}, {"verdicts", nlohmann::json::array()}};
    bool any = false;
    for (const auto& cs : all) {
      const Criterion& c = *find(cs, id);
      chart["values"].push_back(c.value ? nlohmann::json(chart_value(c)) : nlohmann::json(nullptr));
      chart["verdicts"].push_back(verdict_name(c.verdict));
      any |= c.value.has_value();
    }
    if (!any) continue;
    const Criterion& c = *find(all.front(), id);
    chart["label"] = c.label;
    chart["rule"] = "good when " + c.rule;
    chart["unit"] = id == "fill" ? "%" : id == "voids" ? "count" : id == "overfill" ? "mm^3" : id == "increments" ? "mm" : "N";
    chart["threshold"] = id == "fill"         ? nlohmann::json(100 * t.fill_min)
                         : id == "increments" ? nlohmann::json(t.increment_max_mm)
                         : id == "peak_force" ? nlohmann::json(device_limit_N(sessions.front().summary, t))
                         : id == "mean_force" ? nlohmann::json(t.mean_force_max_share * device_limit_N(sessions.front().summary, t))
                                              : nlohmann::json(nullptr);
    data["charts"].push_back(chart);
    h += fmt::format("<figure class=\"plot\"><canvas id=\"chart-{}\" width=\"460\" height=\"260\"></canvas></figure>\n", id);
  }
  h += "</div>\n<script type=\"application/json\" id=\"class-data\">" + script_safe(data.dump()) + "</script>\n<script>" +
       kChartsScript + "</script>\n";
  h += "<p class=\"sub\">Bars are green where the session's verdict is good, orange where it needs work; the dashed line "
       "is the threshold (docs/report.md).</p>\n";
  return h + page_end();
}

std::string class_report_csv(const std::vector<SessionEntry>& sessions) {
  std::string out = "session,student,exercise,finished_at,folder";
  for (const std::string& id : compared_criteria()) out += fmt::format(",{0},{0}_verdict", id);
  out += "\n";
  for (const SessionEntry& e : sessions) {
    out += fmt::format("{},{},{},{},{}", csv_field(e.label), csv_field(e.student), csv_field(e.exercise),
                       csv_field(e.finished_at), csv_field(e.folder));
    const std::vector<Criterion> cs = filling_criteria(e.summary, e.procedure);
    for (const std::string& id : compared_criteria()) {
      const Criterion& c = *find(cs, id);
      out += ',';
      if (c.value) out += nlohmann::json(*c.value).dump();
      out += ',';
      out += verdict_name(c.verdict);
    }
    out += "\n";
  }
  return out;
}

}  // namespace dentsph::report
