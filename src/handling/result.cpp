// A handling test's result for people, for programs (result.json) and as plots
// (include/dentsph/handling.hpp).
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "dentsph/handling.hpp"
#include "handling/svg_plot.hpp"

namespace dentsph {

const HandlingFigure& HandlingResult::figure(const std::string& name) const {
  for (const HandlingFigure& f : figures)
    if (f.name == name) return f;
  throw std::out_of_range(fmt::format("the {} test has no figure \"{}\"", test, name));
}

const std::vector<std::string>& handling_test_names() {
  static const std::vector<std::string> names{"rheometer", "slump", "packing", "tack", "condensation"};
  return names;
}

namespace {

// A test's default options with `run`.
template <class Options>
HandlingResult with_run(HandlingResult (*test)(const PastePreset&, const Options&), const PastePreset& preset,
                        const HandlingRunOptions& run) {
  Options o;
  o.run = run;
  return test(preset, o);
}

}  // namespace

HandlingResult run_handling_test(const std::string& test, const PastePreset& preset, const HandlingRunOptions& run) {
  if (test == "rheometer") return with_run(&rheometer_test, preset, run);
  if (test == "slump") return with_run(&slump_test, preset, run);
  if (test == "packing") return with_run(&packing_test, preset, run);
  if (test == "tack") return with_run(&tack_test, preset, run);
  if (test == "condensation") return with_run(&condensation_test, preset, run);
  throw std::invalid_argument(
      fmt::format("unknown handling test \"{}\"; choose {}", test, fmt::join(handling_test_names(), ", ")));
}

std::string handling_report(const HandlingResult& r) {
  std::string out = fmt::format("{} test, material {} at {:g} C\n", r.test, r.material, r.temperature_c);
  for (const HandlingFigure& f : r.figures) {
    const std::string range =
        f.range ? fmt::format("published {:.4g} to {:.4g}{}{}: {}", (*f.range)[0], (*f.range)[1], f.unit.empty() ? "" : " ", f.unit,
                              f.in_range() ? "in range" : "OUT OF RANGE")
                : std::string("no published range");
    out += fmt::format("  {}: {:.4g} {} ({})\n    source: {}\n", f.name, f.value, f.unit, range, f.source);
  }
  for (const std::string& n : r.notes) out += fmt::format("  note: {}\n", n);
  return out;
}

std::string handling_result_json(const HandlingResult& r) {
  nlohmann::ordered_json j;
  j["test"] = r.test;
  j["material"] = r.material;
  j["temperature_c"] = r.temperature_c;
  j["figures"] = nlohmann::ordered_json::array();
  for (const HandlingFigure& f : r.figures) {
    nlohmann::ordered_json e;
    e["name"] = f.name;
    e["value"] = f.value;
    e["unit"] = f.unit;
    e["range"] = f.range ? nlohmann::ordered_json::array({(*f.range)[0], (*f.range)[1]}) : nlohmann::ordered_json();
    e["in_range"] = f.range ? nlohmann::ordered_json(f.in_range()) : nlohmann::ordered_json();
    e["source"] = f.source;
    j["figures"].push_back(e);
  }
  j["curves"] = nlohmann::ordered_json::array();
  for (const HandlingCurve& c : r.curves) {
    nlohmann::ordered_json e;
    e["file"] = c.file + ".svg";
    e["title"] = c.title;
    e["x_label"] = c.x_label;
    e["y_label"] = c.y_label;
    e["series"] = nlohmann::ordered_json::array();
    for (const HandlingSeries& s : c.series) e["series"].push_back({{"name", s.name}, {"x", s.x}, {"y", s.y}});
    j["curves"].push_back(e);
  }
  j["notes"] = r.notes;
  return j.dump(2) + "\n";
}

namespace {

void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write it; is the folder writable?", file.string()));
}

}  // namespace

void write_handling_outputs(const std::filesystem::path& dir, const HandlingResult& r) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(fmt::format("{}: cannot create the folder: {}", dir.string(), ec.message()));
  write_text(dir / "result.json", handling_result_json(r));
  for (const HandlingCurve& c : r.curves) write_text(dir / (c.file + ".svg"), handling::svg_plot(c));
}

}  // namespace dentsph
