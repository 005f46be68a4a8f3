// The cavity as a user chooses it (include/dentsph/dental.hpp): the table of cavity parameters
// that the command line and dental scene files share, the names of classes and sides, the
// cavity's description for people and for the run summary. The tooth itself is prepared by
// prepare_tooth() (src/tooth/default_scene.cpp).
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "dentsph/dental.hpp"

namespace dentsph {

namespace {

constexpr real mm = 1e-3;
constexpr real no_max = max_cavity_length / mm;  // mm: no tooth is that large

}  // namespace

const std::vector<CavityField>& cavity_fields() {
  static const std::vector<CavityField> fields = {
      {"width", "--cavity-width", "mm", &CavityParams::width, mm, 0, false, no_max, false,
       "the occlusal outline's bucco-lingual width in mm, e.g. 3"},
      {"length", "--cavity-length", "mm", &CavityParams::length, mm, 0, false, no_max, false,
       "the occlusal outline's mesio-distal length in mm, e.g. 5"},
      {"depth", "--cavity-depth", "mm", &CavityParams::depth, mm, 0, false, no_max, false,
       "the pulpal floor's depth below the occlusal surface in mm, e.g. 2"},
      {"taper_deg", "--cavity-taper", "degrees", &CavityParams::taper_deg, 1, 0, true, 30, false,
       "each wall's occlusal divergence in degrees, 2 to 8 is usual"},
      {"rounding", "--cavity-rounding", "mm", &CavityParams::rounding, mm, 0, true, no_max, false,
       "the radius of the internal line and point angles in mm, e.g. 0.5"},
      {"box_width", "--cavity-box-width", "mm", &CavityParams::box_width, mm, 0, false, no_max, true,
       "the proximal box's bucco-lingual width in mm, e.g. 3"},
      {"box_depth", "--cavity-box-depth", "mm", &CavityParams::box_depth, mm, 0, false, no_max, true,
       "the proximal box's gingival floor below the occlusal surface in mm, at least the depth, e.g. 3.5"},
      {"box_axial_depth", "--cavity-box-axial-depth", "mm", &CavityParams::box_axial_depth, mm, 0, false, no_max,
       true, "how far the proximal box's axial wall lies inside the proximal surface in mm, e.g. 1.5"},
  };
  return fields;
}

namespace {

// Empty when `v` (in the field's unit) is within the field's range, else what is wrong.
std::string out_of_range(const CavityField& f, real v) {
  if (!std::isfinite(v)) return fmt::format("must be a finite number of {}", f.unit);
  const bool low = f.min_inclusive ? v < f.min : v <= f.min;
  if (low || v >= f.max) {
    const std::string lower = fmt::format("{} {} {}", f.min_inclusive ? ">=" : ">", f.min, f.unit);
    return fmt::format("must be {} and < {} {}, got {:.4g}", lower, f.max, f.unit, v);
  }
  return {};
}

}  // namespace

CavityValueCheck set_cavity_value(CavityParams& params, const CavityField& f, real v) {
  if (f.class_2_only && params.kind != CavityClass::class_2) return {CavityValueCheck::Outcome::needs_class_2, {}, {}};
  if (std::string problem = out_of_range(f, v); !problem.empty())
    return {CavityValueCheck::Outcome::refused, std::move(problem), fmt::format("give {}", f.hint)};
  params.*f.member = v * f.scale;
  return {};
}

const char* cavity_class_name(CavityClass kind) { return kind == CavityClass::class_1 ? "class1" : "class2"; }

std::optional<CavityClass> cavity_class_from_name(std::string_view name) {
  if (name == "class1") return CavityClass::class_1;
  if (name == "class2") return CavityClass::class_2;
  return std::nullopt;
}

const char* proximal_side_name(ProximalSide side) { return side == ProximalSide::mesial ? "mesial" : "distal"; }

std::optional<ProximalSide> proximal_side_from_name(std::string_view name) {
  if (name == "mesial") return ProximalSide::mesial;
  if (name == "distal") return ProximalSide::distal;
  return std::nullopt;
}

std::string cavity_description(const CavityParams& p) {
  std::string s = fmt::format("Class {}, outline {:.3g} x {:.3g} mm, {:.3g} mm deep, taper {:.3g} deg, rounding {:.3g} mm",
                              p.kind == CavityClass::class_1 ? "I" : "II", p.width / mm, p.length / mm, p.depth / mm,
                              p.taper_deg, p.rounding / mm);
  if (p.kind == CavityClass::class_2)
    s += fmt::format("; {} box {:.3g} mm wide, {:.3g} mm deep, axial wall {:.3g} mm in", proximal_side_name(p.side),
                     p.box_width / mm, p.box_depth / mm, p.box_axial_depth / mm);
  return s;
}

std::string cavity_json(const PreparedTooth& tooth) {
  const CavityParams& p = tooth.params();
  const CavityReport& r = tooth.report();
  nlohmann::json j;
  j["class"] = cavity_class_name(p.kind);
  for (const CavityField& f : cavity_fields())
    if (!f.class_2_only || p.kind == CavityClass::class_2)
      j[std::string(f.key) + (f.unit == std::string_view("mm") ? "_mm" : "")] = p.*f.member / f.scale;
  if (p.kind == CavityClass::class_2) j["side"] = proximal_side_name(p.side);
  j["volume_mm3"] = r.cavity_volume / (mm * mm * mm);
  j["thinnest_wall_mm"] = r.min_wall / mm;
  j["thinnest_floor_mm"] = r.min_floor / mm;
  return j.dump(2);
}

}  // namespace dentsph
