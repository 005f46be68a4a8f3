// One session's report.html (session_report.hpp).
#include "dentsph/report/session_report.hpp"

#include <algorithm>
#include <fstream>

#include <fmt/format.h>

#include "report/criteria.hpp"
#include "report/html.hpp"
#include "report/page.hpp"

namespace dentsph::report {

namespace {

constexpr std::size_t kPlotBuckets = 1500;  // at most 3000 points per curve

std::string criteria_table(const std::vector<Criterion>& cs, const char* id) {
  std::string h = fmt::format("<table id=\"{}\">\n<tr><th>criterion</th><th>measured</th><th>verdict</th><th>good when</th></tr>\n", id);
  for (const Criterion& c : cs) {
    h += fmt::format("<tr data-criterion=\"{}\"><td>{}", escape_html(c.id), escape_html(c.label));
    if (!c.details.empty()) {
      h += "<ul class=\"details\">";
      for (const std::string& d : c.details) h += "<li>" + escape_html(d) + "</li>";
      h += "</ul>";
    }
    if (c.verdict == Verdict::needs_work) h += "<div class=\"advice\">" + escape_html(c.advice) + "</div>";
    h += fmt::format("</td>{}<td>{}</td><td>{}</td></tr>\n", value_cell(c), verdict_badge(c.verdict), escape_html(c.rule));
  }
  return h + "</table>\n";
}

// The plot's data as compact JSON (6 significant digits: a plot needs no more).
std::string plot_json(const SessionFolder& s, double limit, const std::string& limit_label) {
  std::string j = fmt::format("{{\"axis\":{},\"limit\":{:.6g},\"limit_label\":{},\"series\":[",
                              nlohmann::json(s.time_axis).dump(), limit, nlohmann::json(limit_label).dump());
  for (std::size_t k = 0; k < s.forces.size(); ++k) {
    const Series d = decimate(s.forces[k], kPlotBuckets);
    j += fmt::format("{}{{\"label\":{},\"t\":[", k ? "," : "", nlohmann::json(d.label).dump());
    for (std::size_t i = 0; i < d.t.size(); ++i) j += fmt::format("{}{:.6g}", i ? "," : "", d.t[i]);
    j += "],\"f\":[";
    for (std::size_t i = 0; i < d.f.size(); ++i) j += fmt::format("{}{:.6g}", i ? "," : "", d.f[i]);
    j += "]}";
  }
  j += "],\"markers\":[";
  for (std::size_t k = 0; k < s.markers.size(); ++k)
    j += fmt::format("{}{{\"t\":{:.6g},\"kind\":{},\"label\":{}}}", k ? "," : "", s.markers[k].t,
                     nlohmann::json(s.markers[k].kind).dump(), nlohmann::json(s.markers[k].label).dump());
  return j + "]}";
}

constexpr const char* kForcePlotScript = R"js(
(function () {
  const data = JSON.parse(document.getElementById('force-data').textContent);
  const canvas = document.getElementById('force-plot');
  const colours = ['#2a6edb', '#8e44ad', '#16a085'];
  const datasets = data.series.map((s, i) => ({
    label: s.label, data: s.t.map((t, k) => ({x: t, y: s.f[k]})), borderColor: colours[i % colours.length],
    backgroundColor: colours[i % colours.length], borderWidth: 1.2, pointRadius: 0, tension: 0}));
  let tmax = 0, fmax = data.limit;
  for (const s of data.series) { for (const t of s.t) tmax = Math.max(tmax, t); for (const f of s.f) fmax = Math.max(fmax, f); }
  for (const m of data.markers) tmax = Math.max(tmax, m.t);
  const top = fmax * 1.05;
  datasets.push({label: 'device limit: ' + data.limit_label, data: [{x: 0, y: data.limit}, {x: tmax, y: data.limit}],
                 borderColor: '#c0392b', backgroundColor: '#c0392b', borderDash: [6, 4], borderWidth: 1.5, pointRadius: 0});
  const kinds = {dispense: ['increments', '#27ae60'], switch_tool: ['instrument switches', '#e67e22'], cure: ['curing light on', '#d4ac0d'], light: ['curing light switched', '#d4ac0d'], event: ['events', '#7f8c8d']};
  for (const kind of Object.keys(kinds)) {
    const ms = data.markers.filter(m => m.kind === kind);
    if (!ms.length) continue;
    const pts = [];
    for (const m of ms) pts.push({x: m.t, y: 0, label: m.label}, {x: m.t, y: top, label: m.label}, {x: m.t, y: null});
    datasets.push({label: kinds[kind][0], data: pts, borderColor: kinds[kind][1], backgroundColor: kinds[kind][1],
                   borderDash: [3, 3], borderWidth: 1.5, pointRadius: 0, spanGaps: false});
  }
  const chart = new Chart(canvas, {
    type: 'line', data: {datasets: datasets},
    options: {animation: false, responsive: false, parsing: true, normalized: true,
      interaction: {mode: 'nearest', intersect: false},
      scales: {x: {type: 'linear', min: 0, max: tmax, title: {display: true, text: data.axis}},
               y: {min: 0, max: top, title: {display: true, text: 'force (device N)'}}},
      plugins: {legend: {position: 'bottom'},
        tooltip: {callbacks: {label: (c) => (c.raw && c.raw.label ? c.raw.label + ': ' : c.dataset.label + ': ') +
                                            (c.parsed.y === null ? '' : c.parsed.y.toPrecision(3) + ' N')}}}}});
  canvas.setAttribute('data-plotted', String(chart.data.datasets.length));
})();
)js";

std::string particulars(const SessionFolder& s) {
  const nlohmann::json& j = s.summary;
  std::string h = "<table id=\"run\">\n";
  auto row = [&](const std::string& k, const std::string& v, const std::string& key = "") {
    h += fmt::format("<tr><th>{}</th><td{}>{}</td></tr>\n", escape_html(k),
                     key.empty() ? "" : fmt::format(" data-key=\"{}\"", key), escape_html(v));
  };
  row("scene", j.value("scene", "?"));
  if (j.contains("cavity") && j["cavity"].is_object()) {
    const nlohmann::json& c = j["cavity"];
    row("cavity", fmt::format("{}, {:.1f} x {:.1f} mm, {:.1f} mm deep ({:.2f} mm^3)",
                              c.value("class", "?") == "class2" ? "Class II (" + c.value("side", "") + ")" : "Class I",
                              c.value("width_mm", 0.0), c.value("length_mm", 0.0), c.value("depth_mm", 0.0),
                              c.value("volume_mm3", 0.0)));
  }
  row("status", j.value("status", "?") + (j.contains("message") ? ": " + j.value("message", "") : ""));
  row("simulated time", fmt::format("{:.4g} s in {} steps", j.value("sim_time_s", 0.0), j.value("steps", 0)));
  row("wall time", fmt::format("{:.3g} s ({:.0f} steps/s on {} threads)", j.value("wall_time_s", 0.0),
                               j.value("steps_per_second", 0.0), j.value("threads", 1)));
  if (j.contains("particles"))
    row("particles", fmt::format("{} paste, {} lining the cavity, {} instrument", j["particles"].value("material", 0),
                                 j["particles"].value("boundary", 0), j["particles"].value("tool", 0)));
  if (j.contains("tool"))
    row("force scale", fmt::format("{:.4g} device N per simulated N", j["tool"].value("force_scale", 1.0)));
  if (s.realtime && j.contains("device")) row("device", j["device"].value("name", "?"));
  return h + "</table>\n";
}

}  // namespace

std::string session_report_html(const SessionFolder& s) {
  const nlohmann::json& j = s.summary;
  const nlohmann::json session = j.value("session", nlohmann::json::object());
  const std::string who = session.value("student", "");
  const std::string exercise = session.value("exercise", "");
  std::string title = "Filling report: " + (who.empty() ? j.value("scene", std::string("session")) : who);
  if (!exercise.empty()) title += ", " + exercise;
  std::string h = page_begin(title);
  h += fmt::format("<h1>{}</h1>\n<div class=\"sub\">{}{}{}</div>\n", escape_html(title),
                   s.realtime ? "realtime session with a haptic device" : "simulated procedure",
                   session.contains("finished_at") ? ", finished " + escape_html(session.value("finished_at", "")) : "",
                   fmt::format(", scene {}", escape_html(j.value("scene", "?"))));
  if (j.value("status", "completed") != "completed")
    h += fmt::format("<p class=\"status-bad\">The simulation {}: {}</p>\n", escape_html(j.value("status", "")),
                     escape_html(j.value("message", "")));

  h += "<h2>The filling</h2>\n<div class=\"pictures\">\n";
  if (!s.cut_png.empty())
    h += "<figure><img id=\"picture-cut\" alt=\"section through the cavity\" src=\"" + png_data_uri(s.cut_png) +
         "\"><figcaption>Section through the middle of the cavity (mesio-distal), the near half removed: tooth in "
         "ivory, its cut face in tan, the paste's surface in blue and its cut face in dark blue, the instrument in "
         "orange; voids ringed in red; bar: 1 mm.</figcaption></figure>\n";
  if (!s.top_png.empty())
    h += "<figure><img id=\"picture-top\" alt=\"the tooth from above\" src=\"" + png_data_uri(s.top_png) +
         "\"><figcaption>From above, along the tooth's long axis. Bar: 1 mm.</figcaption></figure>\n";
  if (s.cut_png.empty() && s.top_png.empty() && !s.preview_png.empty())
    h += "<figure><img id=\"picture-preview\" alt=\"the particles\" src=\"" + png_data_uri(s.preview_png) +
         "\"><figcaption>The particles at the end (no tooth in this scene).</figcaption></figure>\n";
  if (s.cut_png.empty() && s.top_png.empty() && s.preview_png.empty()) h += "<p>No pictures in this folder.</p>\n";
  if (!s.grading_svg.empty())
    h += "<figure><img id=\"picture-grading\" alt=\"the restoration against the intact tooth, from above\" "
         "src=\"data:image/svg+xml;base64," +
         base64(s.grading_svg) +
         "\"><figcaption>The restoration's surface against the intact tooth's, from above: each 0.1 mm column of "
         "the cavity's opening coloured by how far it lies under (blue) or over (orange) the intact surface, the "
         "margin's points by their reading (green sound, red a gap, purple an excess); the criteria Anatomic form "
         "and Marginal adaptation below.</figcaption></figure>\n";
  h += "</div>\n";
  if (!s.cut_particles_png.empty() || !s.top_particles_png.empty()) {
    h += "<details id=\"particles-view\"><summary>The same as particles</summary>\n<div class=\"pictures\">\n";
    if (!s.cut_particles_png.empty())
      h += "<figure><img id=\"picture-cut-particles\" alt=\"section through the cavity, the paste's particles\" src=\"" +
           png_data_uri(s.cut_particles_png) +
           "\"><figcaption>The section with the paste's particles (spheres half a spacing across), from which its "
           "surface is made.</figcaption></figure>\n";
    if (!s.top_particles_png.empty())
      h += "<figure><img id=\"picture-top-particles\" alt=\"the tooth from above, the paste's particles\" src=\"" +
           png_data_uri(s.top_particles_png) + "\"><figcaption>From above, the paste's particles.</figcaption></figure>\n";
    h += "</div></details>\n";
  }

  h += "<h2>Assessment</h2>\n";
  if (!j.contains("assessment"))
    h += "<p>No assessment: this scene has no prepared tooth.</p>\n";
  h += criteria_table(filling_criteria(j, s.procedure), "criteria");

  if (j.contains("cure") && j["cure"].is_object()) {
    const nlohmann::json& c = j["cure"];
    h += "<h2>Light curing</h2>\n";
    h += fmt::format("<p id=\"cure-message\">{}</p>\n", escape_html(c.value("message", "the paste was not assessed")));
    h += criteria_table(cure_criteria(j), "cure");
    h += fmt::format("<p class=\"sub\">The light was on for {:.3g} s. An increment is adequately cured where its "
                     "paste reached at least {:.1f} of the conversion at its top (the usual bottom/top criterion); "
                     "under-cured paste at the base of a thick increment fails later.</p>\n",
                     c.value("light_on_s", 0.0), c.value("criterion_bottom_top", 0.8));
  }

  h += "<h2>Force on the instrument</h2>\n";
  if (s.forces.empty()) {
    h += "<p>No force record in this folder.</p>\n";
  } else {
    const double limit = device_limit_N(j);
    h += "<div class=\"plot\"><canvas id=\"force-plot\" width=\"960\" height=\"340\"></canvas></div>\n";
    h += "<script type=\"application/json\" id=\"force-data\">" + script_safe(plot_json(s, limit, device_limit_name(j))) +
         "</script>\n<script>" + kForcePlotScript + "</script>\n";
    h += "<p class=\"sub\">The force the instrument meets, as a haptic device renders it (simulated force times the "
         "force scale); the dashed red line is the device's limit, dashed green lines the increments, orange the "
         "instrument switches, yellow the curing light turned on.</p>\n";
  }

  if (s.realtime) {
    h += "<h2>Haptic loop</h2>\n" + criteria_table(haptic_criteria(j), "haptic");
  }
  h += "<h2>The run</h2>\n" + particulars(s);
  h += "<script type=\"application/json\" id=\"summary\">" + script_safe(j.dump()) + "</script>\n";
  return h + page_end();
}

std::filesystem::path write_session_report(const std::filesystem::path& dir) {
  const SessionFolder s = read_session(dir);
  const std::filesystem::path file = dir / "report.html";
  std::ofstream out(file, std::ios::binary);
  out << session_report_html(s);
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write the report", file.string()));
  return file;
}

}  // namespace dentsph::report
