// The tutor's criteria and their verdicts (criteria.hpp).
#include "report/criteria.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace dentsph::report {

namespace {

Verdict judge(bool good) { return good ? Verdict::good : Verdict::needs_work; }

Criterion make(std::string id, std::string label, std::string key, std::optional<double> value, std::string shown,
               std::string rule, std::string advice) {
  Criterion c;
  c.id = std::move(id);
  c.label = std::move(label);
  c.key = std::move(key);
  c.value = value;
  c.shown = value ? std::move(shown) : std::string("not measured");
  c.rule = std::move(rule);
  c.advice = std::move(advice);
  return c;
}

std::string describe_void(const nlohmann::json& v) {
  const auto c = v.value("centre_mm", nlohmann::json::array());
  const double x = c.size() == 3 && c[0].is_number() ? c[0].get<double>() : 0;
  const double z = c.size() == 3 && c[2].is_number() ? c[2].get<double>() : 0;
  const std::string against = v.value("against", "");
  const std::string where = against == "floor" ? "against the floor"
                            : against == "wall" ? "against a wall"
                                                : "inside the filling";
  return fmt::format("{:.3f} mm^3 {}, {:.1f} mm {} the occlusal reference, {:.1f} mm {} of the cavity's middle "
                     "({:.2f} mm from the nearest wall or floor)",
                     v.value("volume_mm3", 0.0), where, std::abs(z), z <= 0 ? "below" : "above", std::abs(x),
                     x >= 0 ? "mesial" : "distal", v.value("wall_distance_mm", 0.0));
}

// A section of summary.json's "grading" (an empty object where it is absent), its figure `key`
// where the section was measured, and the reason it was not.
nlohmann::json grading_section(const nlohmann::json& s, const char* name) {
  return s["grading"].value(name, nlohmann::json::object());
}
std::optional<double> measured(const nlohmann::json& section, const char* key) {
  return section.value("measured", false) ? number_at(section, key) : std::nullopt;
}
void say_if_not_measured(Criterion& c, const nlohmann::json& section) {
  if (!section.value("measured", false))
    c.details.push_back("not measured: " + section.value("why_not", std::string("no surface")));
}

// The restoration's surface against the intact tooth (summary.json's "grading.anatomic_form",
// surface_grade.hpp): good in the alpha band.
Criterion anatomic_form_criterion(const nlohmann::json& s) {
  const nlohmann::json a = grading_section(s, "anatomic_form");
  const auto p95 = measured(a, "p95_abs_mm");
  const std::string band = a.value("band", "");
  const double alpha = number_at(a, "alpha_max_mm").value_or(0.25), charlie = number_at(a, "charlie_under_mm").value_or(1.0);
  Criterion c = make("anatomic_form", "Anatomic form", "grading.anatomic_form.p95_abs_mm", p95,
                     p95 ? fmt::format("{}: 95 % within {:.2f} mm", band, *p95) : "",
                     fmt::format("alpha: 95 % of the opening within {:.2f} mm of the intact tooth", alpha),
                     "Build the last increment up to the cusps' slopes and carve it to the tooth's anatomy: neither flat "
                     "below the margin nor heaped above it.");
  if (p95)
    c.details.push_back(fmt::format("against the intact tooth: RMS {:.2f} mm, deepest under-contour {:.2f} mm, highest "
                                    "over-contour {:.2f} mm (bravo beyond alpha, charlie under-contoured by more than "
                                    "{:.1f} mm)",
                                    number_at(a, "rms_mm").value_or(0), number_at(a, "max_under_mm").value_or(0),
                                    number_at(a, "max_over_mm").value_or(0), charlie));
  if (p95) c.verdict = judge(band == "alpha");
  say_if_not_measured(c, a);
  const auto under = number_at(a, "under_area_mm2"), over = number_at(a, "over_area_mm2");
  if (p95 && under && over)
    c.details.push_back(fmt::format("{:.2f} mm^2 of the opening under-contoured and {:.2f} mm^2 over-contoured by more "
                                    "than {:.2f} mm",
                                    *under, *over, alpha));
  return c;
}

// The occlusal margin (summary.json's "grading.marginal_adaptation"): the preclinical rubric, good
// with at most max_sites defect sites and none longer than max_site_mm.
Criterion margin_criterion(const nlohmann::json& s) {
  const nlohmann::json m = grading_section(s, "marginal_adaptation");
  const auto sites = measured(m, "sites");
  const double max_sites = number_at(m, "max_sites").value_or(3), max_site = number_at(m, "max_site_mm").value_or(1.0);
  const double largest = number_at(m, "largest_site_mm").value_or(0);
  Criterion c = make("margin", "Marginal adaptation", "grading.marginal_adaptation.sites", sites,
                     sites ? fmt::format("{:.0f} defect site{}, the longest {:.2f} mm", *sites, *sites == 1 ? "" : "s", largest)
                           : "",
                     fmt::format("at most {:.0f} sites, none over {:.1f} mm", max_sites, max_site),
                     "Condense the paste into the margin all round, and carve away what laps over the enamel before "
                     "curing.");
  if (sites)
    c.details.push_back(fmt::format("{:.1f} mm of gap and {:.1f} mm of excess along {:.1f} mm of margin (a step of "
                                    "{:.2f} mm or more between paste and tooth)",
                                    number_at(m, "gap_length_mm").value_or(0), number_at(m, "excess_length_mm").value_or(0),
                                    number_at(m, "length_mm").value_or(0), number_at(m, "step_threshold_mm").value_or(0.15)));
  if (sites) c.verdict = judge(*sites <= max_sites && largest <= max_site);
  say_if_not_measured(c, m);
  if (m.contains("defects") && m["defects"].is_array())
    for (const nlohmann::json& d : m["defects"]) {
      const auto ce = d.value("centre_mm", nlohmann::json::array());
      const double x = ce.size() == 3 && ce[0].is_number() ? ce[0].get<double>() : 0;
      const double y = ce.size() == 3 && ce[1].is_number() ? ce[1].get<double>() : 0;
      // Where along the outline: its mesial or distal end, or one of its bucco-lingual sides (the
      // frame's y; which is buccal one tooth does not tell).
      const std::string where = std::abs(x) >= std::abs(y)
                                    ? fmt::format("{:.1f} mm {} of the cavity's middle", std::abs(x), x >= 0 ? "mesial" : "distal")
                                    : fmt::format("on a bucco-lingual side (y {:+.1f} mm)", y);
      c.details.push_back(fmt::format("{} of {:.2f} mm along the margin, a step of up to {:.2f} mm, {}",
                                      d.value("kind", "") == "gap" ? "a gap (the paste short of the tooth)"
                                                                   : "an excess (paste lapping over the tooth)",
                                      d.value("length_mm", 0.0), d.value("largest_step_mm", 0.0), where));
    }
  if (const auto below = number_at(m, "below_resolution_mm"); below && *below > 0)
    c.details.push_back(fmt::format("{:.2f} mm of shorter steps, each under a particle's spacing: below what the "
                                    "simulation resolves, not counted",
                                    *below));
  return c;
}

// Voids open to the surface (summary.json's "grading.surface_voids"): good when there is none of a
// particle's volume or more.
Criterion surface_voids_criterion(const nlohmann::json& s) {
  const nlohmann::json v = grading_section(s, "surface_voids");
  const auto count = measured(v, "count");
  const double least = number_at(v, "min_void_mm3").value_or(0.027);
  Criterion c = make("surface_voids", "Surface voids (pits open to the surface)", "grading.surface_voids.count", count,
                     count ? fmt::format("{:.0f} ({:.3f} mm^3)", *count, number_at(v, "volume_mm3").value_or(0)) : "",
                     fmt::format("none of {:.3f} mm^3 (a particle's volume) or more", least),
                     "Condense each increment from its middle outwards and smooth its surface with the burnisher "
                     "before curing: a pit left in the surface stains and traps plaque.");
  if (count) c.verdict = judge(*count == 0);
  say_if_not_measured(c, v);
  if (v.contains("pits") && v["pits"].is_array())
    for (const nlohmann::json& q : v["pits"]) {
      const auto ce = q.value("centre_mm", nlohmann::json::array());
      const double x = ce.size() == 3 && ce[0].is_number() ? ce[0].get<double>() : 0;
      c.details.push_back(fmt::format("a pit of {:.3f} mm^3, {:.2f} mm deep, {:.1f} mm {} of the cavity's middle",
                                      q.value("volume_mm3", 0.0), q.value("depth_mm", 0.0), std::abs(x),
                                      x >= 0 ? "mesial" : "distal"));
    }
  if (const auto pores = number_at(v, "pore_count"); pores && *pores > 0)
    c.details.push_back(fmt::format("{:.0f} smaller pit{} ({:.3f} mm^3 in all): porosity below what the simulation "
                                    "resolves, not judged",
                                    *pores, *pores == 1 ? "" : "s", number_at(v, "pore_volume_mm3").value_or(0)));
  return c;
}

// A Class II's proximal contact and overhang (summary.json's "grading.proximal"): the contact good
// when tight, the overhang good within its threshold.
std::vector<Criterion> proximal_criteria(const nlohmann::json& s) {
  std::vector<Criterion> out;
  const nlohmann::json q = grading_section(s, "proximal");
  if (!q.value("measured", false)) return out;
  const std::string contact = q.value("contact", "");
  const auto gap = number_at(q, "gap_mm");
  const double tight = number_at(q, "tight_mm").value_or(0.15), open = number_at(q, "open_mm").value_or(0.25);
  Criterion c = make("contact", "Proximal contact", "grading.proximal.gap_mm", gap,
                     gap ? fmt::format("{}: {:.2f} mm {} the intact contour", contact, std::abs(*gap),
                                       *gap >= 0 ? "short of" : "beyond")
                         : "",
                     fmt::format("tight: within {:.2f} mm of the intact contour (light within {:.2f} mm, open beyond)",
                                 tight, open),
                     "Wedge the matrix band against the neighbour and condense the paste against it, so that the "
                     "restoration reaches the contour where the neighbour touches.");
  if (gap) c.verdict = judge(contact == "tight");
  c.details.push_back(fmt::format("the {} surface; the neighbouring tooth taken where the intact tooth's contour "
                                  "stood, at its height of contour",
                                  q.value("side", std::string("proximal"))));
  out.push_back(c);
  const auto area = number_at(q, "overhang_area_mm2");
  const double thr = number_at(q, "overhang_threshold_mm").value_or(0.15);
  const double least = number_at(q, "overhang_min_area_mm2").value_or(0.09);
  c = make("overhang", "Proximal overhang", "grading.proximal.overhang_area_mm2", area,
           area ? fmt::format("{:.2f} mm^2, up to {:.2f} mm beyond the contour", *area,
                              std::max(0.0, number_at(q, "overhang_mm").value_or(0)))
                : "",
           fmt::format("under {:.2f} mm^2 (a particle's cross-section) standing {:.2f} mm or more beyond the contour "
                       "below the contact",
                       least, thr),
           "Seat the matrix band and its wedge at the gingival margin before placing the first increment, so that "
           "no paste is pressed out over the margin.");
  if (area) c.verdict = judge(*area < least);
  out.push_back(c);
  return out;
}

}  // namespace

const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::good: return "good";
    case Verdict::needs_work: return "needs work";
    case Verdict::not_measured: return "not measured";
  }
  return "?";
}

std::optional<double> number_at(const nlohmann::json& j, const std::string& path) {
  const nlohmann::json* at = &j;
  std::size_t a = 0;
  while (true) {
    const std::size_t b = path.find('.', a);
    const std::string key = path.substr(a, b == std::string::npos ? std::string::npos : b - a);
    if (at->is_array()) {  // an index: "cure.increments.0.thickness_mm"
      if (key.empty() || key.size() > 9 || key.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
      const std::size_t k = std::stoul(key);
      if (k >= at->size()) return std::nullopt;
      at = &(*at)[k];
    } else {
      if (!at->is_object()) return std::nullopt;
      const auto it = at->find(key);
      if (it == at->end()) return std::nullopt;
      at = &*it;
    }
    if (b == std::string::npos) break;
    a = b + 1;
  }
  if (!at->is_number()) return std::nullopt;
  return at->get<double>();
}

// The share of an increment that must be adequately cured for a good verdict.
constexpr double kAdequateShare = 0.95;

std::vector<Criterion> cure_criteria(const nlohmann::json& s) {
  std::vector<Criterion> out;
  if (!s.contains("cure") || !s["cure"].is_object() || !s["cure"].contains("increments")) return out;
  const nlohmann::json& cure = s["cure"];
  const double criterion = cure.value("criterion_bottom_top", 0.8);
  const nlohmann::json& incs = cure["increments"];
  for (std::size_t k = 0; k < incs.size(); ++k) {
    const nlohmann::json& x = incs[k];
    const int index = x.value("increment", 0);
    const std::optional<double> adequate = number_at(x, "adequately_cured_fraction");
    Criterion c = make(fmt::format("cure_{}", index),
                       index == 0 ? std::string("The initial paste cured") : fmt::format("Increment {} cured", index),
                       fmt::format("cure.increments.{}.adequately_cured_fraction", k), adequate,
                       adequate ? fmt::format("{:.0f} % adequately cured, {:.2f} mm thick", 100 * *adequate,
                                              x.value("thickness_mm", 0.0))
                                : "",
                       fmt::format("bottom/top conversion at least {:.1f}, and in {:.0f} % of it or more", criterion,
                                   100 * kAdequateShare),
                       "Place increments of 2 mm or less and cure each for the light's full time (20 s at "
                       "1000 mW/cm2) with the light's tip close over the cavity.");
    // Good: the usual criterion on the increment (its base layer's conversion over its top's) and on
    // nearly all of it; the few particles a wall shades (the built-in procedure leaves 0.6 to 1% of
    // an increment 1 mm thick under-cured at its walls, its base at 0.98 of its top) are named in
    // the details and do not fail it.
    if (adequate)
      c.verdict = judge(x.value("bottom_top_ratio", 0.0) >= criterion && *adequate >= kAdequateShare);
    c.details.push_back(x.value("message", ""));
    c.details.push_back(fmt::format("dose at its top {:.3g} J/cm2, at its base {:.3g} J/cm2; conversion {:.2f} at its "
                                    "top, {:.2f} at its base",
                                    x.value("top_dose_J_per_cm2", 0.0), x.value("base_dose_J_per_cm2", 0.0),
                                    x.value("top_conversion", 0.0), x.value("base_conversion", 0.0)));
    out.push_back(c);
  }
  return out;
}

double device_limit_N(const nlohmann::json& summary, const Thresholds& t) {
  return number_at(summary, "haptic.profile.max_force_N").value_or(t.default_device_limit_N);
}

std::string device_limit_name(const nlohmann::json& summary) {
  if (const auto limit = number_at(summary, "haptic.profile.max_force_N")) {
    const std::string name = summary["haptic"]["profile"].value("name", "the device");
    return fmt::format("the {} profile's {:.3g} N", name, *limit);
  }
  return "9 N, the Novint Falcon's (the default device profile)";
}

std::vector<Criterion> filling_criteria(const nlohmann::json& s, const nlohmann::json& procedure, const Thresholds& t) {
  std::vector<Criterion> out;
  const auto fill = number_at(s, "assessment.fill_fraction");
  Criterion c = make("fill", "Cavity filled", "assessment.fill_fraction", fill,
                     fill ? fmt::format("{:.1f} %", 100 * *fill) : "", fmt::format("{:.0f} % or more", 100 * t.fill_min),
                     "Dispense enough paste and condense each increment into the line angles before the next.");
  if (fill) c.verdict = judge(*fill >= t.fill_min);
  out.push_back(c);

  const auto voids = number_at(s, "assessment.void_count");
  const auto void_mm3 = number_at(s, "assessment.void_volume_mm3");
  // Gaps under one particle's volume are porosity below what the model resolves: named, not judged.
  const auto min_void = number_at(s, "assessment.min_void_mm3");
  c = make("voids", "Voids (enclosed gaps)", "assessment.void_count", voids,
           voids ? fmt::format("{:.0f} ({:.3f} mm^3)", *voids, void_mm3.value_or(0)) : "",
           min_void ? fmt::format("none of {:.3f} mm^3 (a particle's volume) or more", *min_void) : "none",
           "Press each increment down and against the walls before adding the next; do not bridge over gaps.");
  if (voids) c.verdict = judge(*voids == 0);
  if (s.contains("assessment") && s["assessment"].contains("voids") && s["assessment"]["voids"].is_array())
    for (const nlohmann::json& v : s["assessment"]["voids"]) c.details.push_back(describe_void(v));
  const auto pores = number_at(s, "assessment.pore_count");
  if (pores && *pores > 0 && min_void)
    c.details.push_back(fmt::format("{:.0f} smaller gap{} ({:.3f} mm^3 in all), each under {:.3f} mm^3: porosity below "
                                    "what the simulation resolves, not judged",
                                    *pores, *pores == 1 ? "" : "s",
                                    number_at(s, "assessment.pore_volume_mm3").value_or(0), *min_void));
  out.push_back(c);

  const auto over = number_at(s, "assessment.overfill_mm3");
  const auto cavity = number_at(s, "assessment.cavity_volume_mm3");
  c = make("overfill", "Overfill above the margin", "assessment.overfill_mm3", over,
           over ? fmt::format("{:.2f} mm^3", *over) : "",
           cavity ? fmt::format("at most {:.0f} % of the cavity ({:.2f} mm^3)", 100 * t.overfill_max_share,
                                t.overfill_max_share * *cavity)
                  : fmt::format("at most {:.0f} % of the cavity", 100 * t.overfill_max_share),
           "Dispense less in the last increment, and condense it to the margin rather than heaping it.");
  if (over && cavity) c.verdict = judge(*over <= t.overfill_max_share * *cavity);
  out.push_back(c);

  if (s.contains("grading")) {
    out.push_back(anatomic_form_criterion(s));
    out.push_back(margin_criterion(s));
    if (s["grading"].contains("surface_voids")) out.push_back(surface_voids_criterion(s));
    for (Criterion& p : proximal_criteria(s)) out.push_back(std::move(p));
  }

  const auto leaked = number_at(s, "assessment.leaked_particles");
  const auto lost = number_at(s, "assessment.lost_particles");
  c = make("leaked", "Paste leaked or lost", "assessment.leaked_particles", leaked,
           leaked ? fmt::format("{:.0f} particles leaked, {:.0f} lost", *leaked, lost.value_or(0)) : "", "none",
           "Press more gently: paste forced through the lining (or flung away) is lost to the filling.");
  if (leaked) c.verdict = judge(*leaked == 0 && lost.value_or(0) == 0);
  out.push_back(c);

  // The thickest increment by the 90th percentile of its columns.
  std::optional<double> thickest;
  std::vector<std::string> layers;
  if (procedure.is_object() && procedure.contains("increments") && procedure["increments"].is_array() &&
      !procedure["increments"].empty())
    for (const nlohmann::json& inc : procedure["increments"]) {
      const double p90 = inc.value("thickness_p90_mm", 0.0);
      thickest = std::max(thickest.value_or(0.0), p90);
      layers.push_back(fmt::format("increment {}: {} particles, {:.2f} mm thick (median), {:.2f} mm (90th percentile)",
                                   inc.value("index", 0), inc.value("particles", 0), inc.value("thickness_median_mm", 0.0),
                                   p90));
    }
  c = make("increments", "Thickest increment", "procedure:increments", thickest,
           thickest ? fmt::format("{:.2f} mm", *thickest) : "", fmt::format("{:.1f} mm or less", t.increment_max_mm),
           "Place thinner increments: a layer over 2 mm does not cure through and shrinks more.");
  if (thickest) c.verdict = judge(*thickest <= t.increment_max_mm);
  c.details = layers;
  out.push_back(c);

  const double limit = device_limit_N(s, t);
  const std::optional<double> peak = number_at(s, "assessment.peak_device_force_N").has_value()
                                         ? number_at(s, "assessment.peak_device_force_N")
                                         : number_at(s, "tool.peak_device_force_N");
  c = make("peak_force", "Peak force on the instrument",
           number_at(s, "assessment.peak_device_force_N") ? "assessment.peak_device_force_N" : "tool.peak_device_force_N",
           peak, peak ? fmt::format("{:.3g} N", *peak) : "", fmt::format("at most {}", device_limit_name(s)),
           "Condense with less force: the device cannot render more than its limit, and the paste leaks under it.");
  if (peak) c.verdict = judge(*peak <= limit);
  out.push_back(c);

  const auto mean = number_at(s, "assessment.mean_device_force_N");
  c = make("mean_force", "Mean force while in contact", "assessment.mean_device_force_N", mean,
           mean ? fmt::format("{:.3g} N", *mean) : "",
           fmt::format("at most {:.0f} % of the device's limit ({:.3g} N)", 100 * t.mean_force_max_share,
                       t.mean_force_max_share * limit),
           "Ease off between strokes: a steady hard press tires the hand and pushes paste out of the cavity.");
  if (mean) c.verdict = judge(*mean <= t.mean_force_max_share * limit);
  out.push_back(c);
  return out;
}

std::vector<Criterion> haptic_criteria(const nlohmann::json& s, const Thresholds& t) {
  std::vector<Criterion> out;
  if (!s.contains("haptic")) return out;
  const double target = number_at(s, "haptic.target_rate_hz").value_or(1000);
  const auto rate = number_at(s, "haptic.rate_hz");
  Criterion c = make("haptic_rate", "Haptic loop rate", "haptic.rate_hz", rate, rate ? fmt::format("{:.1f} Hz", *rate) : "",
                     fmt::format("within {:.0f} % of {:.0f} Hz", 100 * t.rate_tolerance, target),
                     "The computer could not keep the haptic loop's rate: close other programs, or use fewer threads.");
  if (rate) c.verdict = judge(std::abs(*rate - target) <= t.rate_tolerance * target);
  out.push_back(c);

  const auto p99 = number_at(s, "haptic.period_p99_us");
  c = make("haptic_period_p99", "Period, 99th percentile", "haptic.period_p99_us", p99,
           p99 ? fmt::format("{:.0f} us", *p99) : "",
           fmt::format("at most {:.0f} us ({:.1f} periods)", t.period_p99_max_share * 1e6 / target, t.period_p99_max_share),
           "The haptic thread was delayed: run it with real-time priority (root or CAP_SYS_NICE).");
  if (p99) c.verdict = judge(*p99 <= t.period_p99_max_share * 1e6 / target);
  out.push_back(c);

  const auto misses = number_at(s, "haptic.deadline_misses");
  const double ticks = number_at(s, "haptic.ticks").value_or(0);
  c = make("haptic_misses", "Missed deadlines", "haptic.deadline_misses", misses,
           misses ? fmt::format("{:.0f} of {:.0f} ticks", *misses, ticks) : "",
           fmt::format("at most {:.1f} per 1000 ticks", 1000 * t.deadline_miss_max_share),
           "Ticks started late: the force felt rough. Close other programs or use fewer simulation threads.");
  if (misses) c.verdict = judge(*misses <= t.deadline_miss_max_share * std::max(1.0, ticks));
  out.push_back(c);

  const auto age = number_at(s, "haptic.force_age_p99_us");
  c = make("haptic_force_age", "Force age, 99th percentile", "haptic.force_age_p99_us", age,
           age ? fmt::format("{:.2f} ms", *age / 1000) : "", fmt::format("at most {:.0f} ms", t.force_age_p99_max_us / 1000),
           "The simulation lagged the hand: the force felt late. Use the coupling mode or a faster machine.");
  if (age) c.verdict = judge(*age <= t.force_age_p99_max_us);
  out.push_back(c);

  const auto trips = number_at(s, "haptic.watchdog.trips");
  c = make("haptic_watchdog", "Watchdog trips", "haptic.watchdog.trips", trips, trips ? fmt::format("{:.0f}", *trips) : "",
           "none", "The force was ramped to zero when the device or the simulation went quiet: check the connection.");
  if (trips) c.verdict = judge(*trips == 0);
  out.push_back(c);

  const auto dropped = number_at(s, "haptic.recording_dropped_ticks");
  c = make("haptic_recording", "Ticks missing from the recording", "haptic.recording_dropped_ticks", dropped,
           dropped ? fmt::format("{:.0f}", *dropped) : "", "none",
           "The session outlasted the recording's memory: its replay is incomplete.");
  if (dropped) c.verdict = judge(*dropped == 0);
  out.push_back(c);
  return out;
}

}  // namespace dentsph::report
