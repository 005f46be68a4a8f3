// Panels (panels.hpp).
#include "panels.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <imgui.h>

#include "dentsph/paste_presets.hpp"

namespace dentsph::viewer {

namespace {

void simulation_panel(const Snapshot& s, UiState& ui, const std::vector<std::string>& tools,
                      std::vector<Command>& out) {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(290, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("Simulation", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::Text("t = %.4f s   step %llu", double(s.time), static_cast<unsigned long long>(s.steps));
  ImGui::Text("%.0f steps/s%s%s", s.steps_per_second, s.paused ? "   paused" : "", s.diverged ? "   DIVERGED" : "");
  if (ImGui::Button(s.paused ? "Run (P)" : "Pause (P)")) out.push_back({s.paused ? Command::Kind::resume : Command::Kind::pause});
  ImGui::SameLine();
  if (ImGui::Button("Step (N)")) out.push_back({Command::Kind::single_step});
  ImGui::SameLine();
  if (ImGui::Button("Reset (R)")) out.push_back({Command::Kind::reset});
  ImGui::SameLine();
  if (ImGui::Button("Dispense (D)")) out.push_back({Command::Kind::dispense});
  std::vector<const char*> names;
  for (const std::string& t : tools) names.push_back(t.c_str());
  if (ImGui::Combo("tool (T)", &ui.tool_index, names.data(), int(names.size()))) {
    Command c{Command::Kind::switch_tool};
    c.tool = tools[std::size_t(ui.tool_index)];
    out.push_back(c);
  }
  ImGui::TextDisabled("in use: %s", s.tool_name.c_str());
  if (!s.message.empty()) ui.last_message = s.message;
  if (!ui.last_message.empty()) ImGui::TextWrapped("%s", ui.last_message.c_str());
  ImGui::Separator();
  ImGui::TextDisabled("left drag: move the tool   wheel: depth\nspace: press   right drag: orbit\nshift+right drag: pan   ctrl+wheel: zoom");
  ImGui::End();
}

void display_panel(const Snapshot& s, UiState& ui) {
  ImGui::SetNextWindowPos(ImVec2(10, 260), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(290, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("Display", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  int mode = 0;
  for (std::size_t k = 0; k < kColourModes.size(); ++k)
    if (kColourModes[k] == ui.colour_by) mode = int(k);
  const char* modes[] = {"role", "pressure", "density", "speed", "bonds", "conversion"};
  if (ImGui::Combo("colour by (C)", &mode, modes, int(kColourModes.size()))) ui.colour_by = kColourModes[std::size_t(mode)];
  ImGui::Checkbox("boundary particles (B)", &ui.show_boundary);
  ImGui::Checkbox("section (X)", &ui.cut);
  if (ui.colour_by != ColourBy::role) {
    ImGui::Checkbox("automatic range", &ui.auto_range);
    if (!ui.auto_range) ImGui::DragFloatRange2("range", &ui.range.lo, &ui.range.hi, std::max(1e-3f, 0.01f * (ui.range.hi - ui.range.lo)));
    // The colour bar.
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float w = ImGui::GetContentRegionAvail().x, h = 14;
    constexpr int kSteps = 32;
    for (int k = 0; k < kSteps; ++k) {
      const Rgb a = colour_map(float(k) / kSteps), b = colour_map(float(k + 1) / kSteps);
      const ImU32 ca = ImGui::ColorConvertFloat4ToU32(ImVec4(a[0], a[1], a[2], 1));
      const ImU32 cb = ImGui::ColorConvertFloat4ToU32(ImVec4(b[0], b[1], b[2], 1));
      dl->AddRectFilledMultiColor(ImVec2(p.x + w * k / kSteps, p.y), ImVec2(p.x + w * (k + 1) / kSteps, p.y + h), ca, cb, cb, ca);
    }
    ImGui::Dummy(ImVec2(w, h));
    ImGui::Text("%.4g", double(ui.range.lo));
    ImGui::SameLine(w - 60);
    ImGui::Text("%.4g %s", double(ui.range.hi), colour_by_unit(ui.colour_by));
  }
  (void)s;
  ImGui::End();
}

void material_panel(const Snapshot& s, UiState& ui, std::vector<Command>& out) {
  const std::vector<std::string>& presets = paste_preset_names();
  if (!ui.material_loaded || s.preset != ui.loaded_preset || s.preset_temperature_c != ui.loaded_temperature_c) {
    // The chooser and the edit fields follow the paste in use (at the start, and once a preset is
    // loaded, by the button or a script).
    const auto at = std::find(presets.begin(), presets.end(), s.preset);
    ui.preset_index = at == presets.end() ? 0 : int(at - presets.begin()) + 1;
    ui.preset_temperature_c = float(s.preset_temperature_c);
    ui.material = s.material;
    ui.material_loaded = true;
    ui.loaded_preset = s.preset;
    ui.loaded_temperature_c = s.preset_temperature_c;
  }
  ImGui::SetNextWindowPos(ImVec2(10, 430), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(290, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("Material", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  // The paste preset (docs/model.md, "Presets"): the scene filled with it again, its force at
  // scale 1; the scene's own paste at the paper's scale.
  std::vector<const char*> names{"the scene's own"};
  for (const std::string& p : presets) names.push_back(p.c_str());
  ImGui::Combo("preset", &ui.preset_index, names.data(), int(names.size()));
  if (ui.preset_index > 0) ImGui::DragFloat("temperature (C)", &ui.preset_temperature_c, 0.5f, 10.f, 70.f, "%.1f");
  if (ImGui::Button("Load preset (resets)")) {
    Command c{Command::Kind::load_preset};
    c.preset = ui.preset_index > 0 ? presets[std::size_t(ui.preset_index - 1)] : std::string();
    c.temperature_c = ui.preset_temperature_c;
    out.push_back(c);
  }
  if (s.preset.empty())
    ImGui::TextDisabled("in use: the scene's own paste");
  else
    ImGui::TextDisabled("in use: %s at %g C", s.preset.c_str(), s.preset_temperature_c);
  ImGui::Separator();
  MaterialEdit& m = ui.material;
  auto field = [](const char* label, real& v, float lo, float hi, const char* fmt_str) {
    float f = float(v);
    if (ImGui::DragFloat(label, &f, std::max(1e-6f, 0.005f * std::abs(f)), lo, hi, fmt_str)) v = f;
  };
  field("Kp (m^2/s^2)", m.Kp, 0.1f, 1e6f, "%.3g");
  field("Ka (Pa)", m.Ka, 0.f, 1e5f, "%.3g");
  const bool newtonian = m.flow_index == 1 && m.yield_stress == 0;
  field(newtonian ? "mu (Pa s)" : "K (Pa s^n)", m.mu, 0.f, 1e6f, "%.3g");
  if (!newtonian)  // a preset's rheology (docs/model.md, "Rheology"): kept by an edit
    ImGui::TextDisabled("n %.2f, yield stress %.3g Pa", double(m.flow_index), double(m.yield_stress));
  float a_mm = float(m.A * 1e3), b_mm = float(m.B * 1e3);
  if (ImGui::DragFloat("A (mm)", &a_mm, 0.002f, 0.f, 5.f, "%.3f")) m.A = a_mm * 1e-3;
  if (ImGui::DragFloat("B (mm)", &b_mm, 0.002f, 0.f, 5.f, "%.3f")) m.B = b_mm * 1e-3;
  field("eps", m.eps, 0.5f, 10.f, "%.2f");
  field("zeta", m.zeta, 0.1f, 10.f, "%.2f");
  if (ImGui::Button("Apply")) {
    Command c{Command::Kind::set_material};
    c.material = m;
    out.push_back(c);
  }
  ImGui::SameLine();
  if (ImGui::Button("Revert")) m = s.material;
  const StabilityLimits& l = s.limits;
  auto limit = [&](const char* name, real v) {
    const bool bad = s.dt > v;
    ImGui::TextColored(bad ? ImVec4(1, 0.3f, 0.3f, 1) : ImVec4(0.6f, 0.9f, 0.6f, 1), "%-9s limit %.3g s %s", name,
                       double(v), bad ? "(dt over it)" : "");
  };
  ImGui::Text("dt = %.3g s", double(s.dt));
  limit("acoustic", l.acoustic);
  limit("viscous", l.viscous);
  limit("force", l.force);
  ImGui::End();
}

void force_panel(const Snapshot& s, UiState& ui) {
  ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 360, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(340, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("Tool force (device N)", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  const float f = float(norm(s.device_force_N));
  std::vector<float> h(ui.force_history.begin(), ui.force_history.end());
  const float peak = h.empty() ? 0.f : *std::max_element(h.begin(), h.end());
  const std::string label = fmt::format("{:.3g} N", f);
  ImGui::PlotLines("##force", h.data(), int(h.size()), 0, label.c_str(), 0.f, std::max(peak * 1.1f, 1e-12f),
                   ImVec2(320, 90));
  ImGui::Text("|F| = %.4g N on the device (%.4g N simulated x %.3g)", double(f), double(f) / s.force_scale,
              s.force_scale);
  ImGui::Text("F = (%.3g, %.3g, %.3g) N", double(s.device_force_N.x), double(s.device_force_N.y), double(s.device_force_N.z));
  ImGui::End();
}

void assessment_panel(const Snapshot& s) {
  if (!s.assessment) return;
  const Assessment& a = *s.assessment;
  ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 360, 190), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(340, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("Assessment", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::Text("filled     %.1f %% of %.2f mm^3", 100 * double(a.fill_fraction), double(a.cavity_volume_mm3));
  // Pores (gaps under a particle's volume) on the voids' line: the panel keeps its height.
  ImGui::Text("voids      %d (%.3f mm^3); pores %d (%.3f mm^3)", a.void_count, double(a.void_volume_mm3), a.pore_count,
              double(a.pore_volume_mm3));
  ImGui::Text("overfill   %.3f mm^3", double(a.overfill_mm3));
  ImGui::Text("leaked     %u   lost %u   of %u", a.leaked_particles, a.lost_particles, a.material_particles);
  ImGui::Text("tool force peak %.3g N, mean %.3g N on the device", double(a.peak_device_force_N),
              double(a.mean_device_force_N));
  ImGui::Text("           (simulated: peak %.3g N, mean %.3g N)", double(a.peak_tool_force_N), double(a.mean_tool_force_N));
  ImGui::End();
}

void loops_panel(const Snapshot& s, const FrameStats& st) {
  ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 360, 330), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(340, 0), ImGuiCond_FirstUseEver);
  ImGui::Begin("Loops", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::Text("render      %.1f fps", st.fps);
  ImGui::Text("            frame p50 %.1f ms, p99 %.1f ms", st.frame_p50_ms, st.frame_p99_ms);
  ImGui::Text("simulation  %.0f steps/s  (%.3g x real time)", s.steps_per_second, s.steps_per_second * double(s.dt));
  ImGui::Text("            on %s", s.backend.c_str());
  if (s.haptic) {
    const Snapshot::Haptic& h = *s.haptic;
    ImGui::Separator();
    ImGui::Text("haptic      %.0f Hz  (%s)", h.rate_hz, h.device.c_str());
    ImGui::Text("            period %.0f us, max %.0f us (0.5 s)", h.period_last_us, h.period_max_recent_us);
    ImGui::Text("            %llu deadline misses", static_cast<unsigned long long>(h.deadline_misses));
    ImGui::Text("device      |F| = %.3g N, gain %.2f", double(norm(h.force_N)), h.gain);
    if (h.pose_age_ms < 0)
      ImGui::TextColored(ImVec4(1, 0.6f, 0.2f, 1), "no pose from the device yet: zero force");
    else if (h.status & 2u)
      ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "device quiet for %.0f ms: force ramped to zero", h.pose_age_ms);
    if (h.status & 1u)
      ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "simulation output %.0f ms old: force ramped down", h.sim_age_ms);
  }
  ImGui::End();
}

}  // namespace

void draw_panels(const Snapshot& snap, UiState& ui, const FrameStats& stats, const std::vector<std::string>& tools,
                 std::vector<Command>& commands) {
  simulation_panel(snap, ui, tools, commands);
  display_panel(snap, ui);
  material_panel(snap, ui, commands);
  force_panel(snap, ui);
  assessment_panel(snap);
  loops_panel(snap, stats);
}

}  // namespace dentsph::viewer
