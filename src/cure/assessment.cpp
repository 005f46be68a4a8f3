// The assessment of cure (include/dentsph/cure_assessment.hpp).
#include "dentsph/cure_assessment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "dentsph/layer_thickness.hpp"

namespace dentsph {

namespace {

constexpr real mm = 1e-3;

std::string increment_name(int index) {
  return index == 0 ? std::string("the initial paste") : fmt::format("increment {}", index);
}

std::string increment_message(const IncrementCure& c, real criterion) {
  const std::string name = increment_name(c.index);
  if (c.top_alpha <= 0) return fmt::format("{} is {:.2f} mm thick and was not cured: no light reached it", name, c.thickness / mm);
  const real under = 1 - c.adequate_fraction;
  const std::string head =
      fmt::format("{} is {:.2f} mm thick: its base received {:.2g} J/cm2", name, c.thickness / mm, c.base_dose / 1e4);
  if (under <= 0)
    return fmt::format("{}, bottom/top conversion {:.2f}: adequately cured throughout", head, c.base_alpha / c.top_alpha);
  const int digits = 100 * under < 1 ? 1 : 0;  // "0.4%", never "0%" of paste that is under-cured
  // Under-cured paste below the median's depth lies where the increment is thicker: say how thick.
  const std::string where = c.under_cured_to > c.thickness + 0.05 * mm
                                ? fmt::format(", where it is up to {:.2f} mm thick", c.under_cured_column_thickness / mm)
                                : std::string();
  return fmt::format("{} and {:.{}f}% of it is under-cured (conversion below {:.0f}% of its top's), from {:.2f} mm below its "
                     "top down to {:.2f} mm{}",
                     head, 100 * under, digits, 100 * criterion, c.under_cured_from / mm, c.under_cured_to / mm, where);
}

}  // namespace

CureAssessment assess_cure(const CureModel& cm, const State& s, const Vec3& up_in, real criterion, real ceiling,
                           real floor) {
  CureAssessment a;
  a.criterion = criterion;
  const Vec3 up = up_in / norm(up_in);
  const CureState& c = s.cure;
  const real sp = cm.spacing;
  constexpr real inf = std::numeric_limits<real>::infinity();
  // The paste assessed: curable, finite, not above the ceiling (drawn up on the instrument) nor
  // below the floor (fallen out of the cavity).
  auto assessed = [&](std::uint32_t i) {
    const real h = dot(s.pos[i], up);
    return c.curable[s.id[i]] && is_finite(s.pos[i]) && !(h > ceiling) && !(h < floor);
  };
  // Each increment is measured in columns along `up`, two spacings square (layer_thickness: its
  // thickness and each particle's depth as the paste's volume over the area it covers).
  std::map<int, std::vector<std::uint32_t>> members;  // increment -> its assessed particles
  for (std::uint32_t i = 0; i < s.size(); ++i) {
    const std::uint32_t id = s.id[i];
    if (c.curable[id] && is_finite(s.pos[i]) && !assessed(i)) ++a.left_out;
    if (assessed(i)) members[c.increment[id]].push_back(i);
  }
  for (const auto& [index, particles] : members) {
    IncrementCure r;
    r.index = index;
    r.particles = std::uint32_t(particles.size());
    std::vector<Vec3> points;
    points.reserve(particles.size());
    for (const std::uint32_t i : particles) points.push_back(s.pos[i]);
    const LayerThickness layer = layer_thickness(points, up, sp);
    r.thickness = layer.median;
    r.thickness_p90 = layer.p90;
    // Top and base layers: within half a spacing of each column's highest and lowest particle.
    struct Extent {
      real lo = inf, hi = -inf;
    };
    std::vector<Extent> extent(layer.column_particles.size());
    for (std::size_t k = 0; k < particles.size(); ++k) {
      Extent& e = extent[layer.column[k]];
      const real h = dot(points[k], up);
      e.lo = std::min(e.lo, h), e.hi = std::max(e.hi, h);
    }
    std::uint32_t n_top = 0, n_base = 0;
    for (std::size_t k = 0; k < particles.size(); ++k) {
      const std::uint32_t id = s.id[particles[k]];
      const Extent& e = extent[layer.column[k]];
      const real h = dot(points[k], up);
      if (h > e.hi - 0.5 * sp) r.top_dose += c.dose[id], r.top_alpha += c.alpha[id], ++n_top;
      if (h < e.lo + 0.5 * sp) r.base_dose += c.dose[id], r.base_alpha += c.alpha[id], ++n_base;
    }
    r.top_dose /= n_top, r.top_alpha /= n_top, r.base_dose /= n_base, r.base_alpha /= n_base;
    std::uint32_t adequate = 0;
    real from = inf, to = -inf;
    for (std::size_t k = 0; k < particles.size(); ++k) {
      const std::uint32_t i = particles[k], id = s.id[i];
      const bool ok = r.top_alpha > 0 && c.alpha[id] >= criterion * r.top_alpha;
      const real volume = s.mass[i] / s.rho0[i];
      a.paste_volume += volume;
      if (ok) {
        ++adequate;
        continue;
      }
      r.under_cured_volume += volume;
      // Its depth in its column, and the paste it stands for below that (layer_thickness.hpp).
      const real share = sp / real(layer.column_cells[layer.column[k]]);
      from = std::min(from, layer.depth[k]), to = std::max(to, layer.depth[k] + share);
      r.under_cured_column_thickness =
          std::max(r.under_cured_column_thickness, layer.column_thickness(layer.column[k]));
    }
    r.adequate_fraction = real(adequate) / real(r.particles);
    if (to > from) r.under_cured_from = std::max<real>(0, from), r.under_cured_to = to;
    a.under_cured_volume += r.under_cured_volume;
    r.message = increment_message(r, criterion);
    a.increments.push_back(r);
  }
  std::uint32_t bad = 0;
  for (const IncrementCure& r : a.increments) bad += r.adequate_fraction < 1;
  if (cm.paste.self_setting && !a.increments.empty()) {
    // A paste that sets by itself (an amalgam): the light is not what sets it, so no increment is
    // under-cured by it; say how much has set and when the rest will.
    real set = 0;
    for (const auto& [index, particles] : members)
      for (const std::uint32_t i : particles)
        if (c.rigid[s.id[i]]) set += s.mass[i] / s.rho0[i];
    const real gel = gel_age(cm.paste);
    for (IncrementCure& r : a.increments) {
      r.under_cured_volume = 0;
      r.message = fmt::format("{} is {:.2f} mm thick and sets by itself, light or none", increment_name(r.index),
                              r.thickness / mm);
    }
    a.under_cured_volume = 0;
    a.message = fmt::format("the paste sets by itself ({}), not by light: {:.2f} of {:.2f} mm3 set; it works for {:.0f} s "
                            "after it is mixed and is rigid {:.0f} s after",
                            cm.paste.name, set / (mm * mm * mm), a.paste_volume / (mm * mm * mm),
                            cm.paste.working_time, gel);
  } else if (a.increments.empty())
    a.message = "no paste to assess";
  else if (bad == 0)
    a.message = fmt::format("all paste adequately cured (bottom/top conversion at least {:.1f} in every increment)", criterion);
  else
    a.message = fmt::format("{:.2f} mm3 of paste under-cured ({:.{}f}% of {:.2f} mm3) in {} of {} increments",
                            a.under_cured_volume / (mm * mm * mm), 100 * a.under_cured_volume / a.paste_volume,
                            a.under_cured_volume < 0.01 * a.paste_volume ? 1 : 0, a.paste_volume / (mm * mm * mm), bad,
                            a.increments.size());
  return a;
}

std::string cure_assessment_json(const CureAssessment& a) {
  using nlohmann::json;
  json j;
  j["criterion_bottom_top"] = a.criterion;
  j["paste_volume_mm3"] = a.paste_volume / (mm * mm * mm);
  j["under_cured_volume_mm3"] = a.under_cured_volume / (mm * mm * mm);
  j["message"] = a.message;
  j["left_out_particles"] = a.left_out;
  json incs = json::array();
  for (const IncrementCure& r : a.increments) {
    json x;
    x["increment"] = r.index;
    x["particles"] = r.particles;
    x["thickness_mm"] = r.thickness / mm;
    x["thickness_p90_mm"] = r.thickness_p90 / mm;
    x["top_dose_J_per_cm2"] = r.top_dose / 1e4;
    x["base_dose_J_per_cm2"] = r.base_dose / 1e4;
    x["top_conversion"] = r.top_alpha;
    x["base_conversion"] = r.base_alpha;
    x["bottom_top_ratio"] = r.top_alpha > 0 ? r.base_alpha / r.top_alpha : 0;
    x["adequately_cured_fraction"] = r.adequate_fraction;
    x["under_cured_volume_mm3"] = r.under_cured_volume / (mm * mm * mm);
    x["under_cured_depth_mm"] = json::array({r.under_cured_from / mm, r.under_cured_to / mm});
    x["under_cured_column_thickness_mm"] = r.under_cured_column_thickness / mm;
    x["message"] = r.message;
    incs.push_back(x);
  }
  j["increments"] = incs;
  return j.dump();
}

std::string cure_assessment_report(const CureAssessment& a) {
  std::string out = fmt::format("cure: {}\n", a.message);
  for (const IncrementCure& r : a.increments) out += fmt::format("  {}\n", r.message);
  return out;
}

}  // namespace dentsph
