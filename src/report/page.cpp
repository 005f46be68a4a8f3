// The shared page frame (page.hpp).
#include "report/page.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "report/chartjs.hpp"
#include "report/html.hpp"

namespace dentsph::report {

namespace {

constexpr const char* kStyle = R"css(
body { font-family: "DejaVu Sans", Helvetica, Arial, sans-serif; margin: 24px auto; max-width: 1000px; color: #222; background: #fafafa; }
h1 { font-size: 22px; margin-bottom: 4px; }
h2 { font-size: 17px; margin-top: 28px; border-bottom: 1px solid #ddd; padding-bottom: 4px; }
.sub { color: #555; font-size: 13px; }
table { border-collapse: collapse; width: 100%; font-size: 14px; background: #fff; }
#sessions { font-size: 12px; }
#sessions td, #sessions th { padding: 4px 5px; }
th, td { text-align: left; padding: 6px 8px; border-bottom: 1px solid #e4e4e4; vertical-align: top; }
th { background: #f0f0f0; }
td.num { white-space: nowrap; }
.verdict { display: inline-block; padding: 1px 8px; border-radius: 10px; font-size: 12px; font-weight: bold; white-space: nowrap; }
.verdict.good { background: #d8f0da; color: #1d6b2a; }
.verdict.needs-work { background: #fde2c8; color: #9a4a00; }
.verdict.not-measured { background: #e8e8e8; color: #666; }
.details { color: #444; font-size: 13px; margin: 2px 0 0 0; padding-left: 18px; }
.advice { color: #7a4a10; font-size: 13px; }
.pictures { display: flex; gap: 12px; flex-wrap: wrap; }
.pictures figure { margin: 0; flex: 1 1 440px; }
.pictures img { width: 100%; border: 1px solid #ddd; background: #fff; }
figcaption { font-size: 13px; color: #555; }
.plot { background: #fff; border: 1px solid #ddd; padding: 8px; }
.status-bad { color: #a00; font-weight: bold; }
)css";

}  // namespace

std::string page_begin(std::string_view title) {
  return fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{}</title>\n<style>{}</style>\n"
      "<!-- Chart.js {} (MIT License, https://www.chartjs.org), bundled so that the page needs no network -->\n"
      "<script>{}</script>\n</head>\n<body>\n",
      escape_html(title), kStyle, chartjs_version(), chartjs_source());
}

std::string page_end() { return "</body>\n</html>\n"; }

std::string verdict_badge(Verdict v) {
  const char* cls = v == Verdict::good ? "good" : v == Verdict::needs_work ? "needs-work" : "not-measured";
  return fmt::format("<span class=\"verdict {}\">{}</span>", cls, verdict_name(v));
}

std::string value_cell(const Criterion& c) {
  if (!c.value) return fmt::format("<td class=\"num\" data-key=\"{}\">{}</td>", escape_html(c.key), escape_html(c.shown));
  return fmt::format("<td class=\"num\" data-key=\"{}\" data-value=\"{}\">{}</td>", escape_html(c.key),
                     nlohmann::json(*c.value).dump(), escape_html(c.shown));
}

}  // namespace dentsph::report
