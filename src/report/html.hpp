// Small helpers for writing HTML by hand: text escaped for an element or an attribute, JSON made
// safe inside a <script> element, bytes as base64 for data: URIs.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace dentsph::report {

std::string escape_html(std::string_view text);
// JSON text that may sit inside <script type="application/json">: "</" written as "<\/".
std::string script_safe(std::string_view json);
std::string base64(const std::vector<std::uint8_t>& bytes);
// A data: URI of a PNG, for an <img src>.
std::string png_data_uri(const std::vector<std::uint8_t>& png);

}  // namespace dentsph::report
