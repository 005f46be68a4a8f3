// The render loop (viewer_app.hpp).
#include "viewer_app.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <span>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <fmt/format.h>
#include <imgui.h>

#include "camera.hpp"
#include "colour_map.hpp"
#include "dentsph/dispense.hpp"
#include "frame_timer.hpp"
#include "panels.hpp"
#include "paste_surface_view.hpp"
#include "renderers.hpp"
#include "screenshot.hpp"

namespace dentsph::viewer {

namespace {

std::atomic<bool> g_close_requested{false};

using clock_type = std::chrono::steady_clock;

glm::vec3 g(const Vec3& v) { return {float(v.x), float(v.y), float(v.z)}; }

struct Window {
  GLFWwindow* handle = nullptr;
  Window(int w, int h) {
    glfwSetErrorCallback([](int, const char*) {});
    if (!glfwInit())
      throw std::runtime_error("cannot open a window: no display (set DISPLAY, or run headless under "
                               "xvfb-run -a -s '-screen 0 1280x800x24' dentsph-viewer ...)");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    handle = glfwCreateWindow(w, h, "dentsph viewer", nullptr, nullptr);
    if (!handle) {
      glfwTerminate();
      throw std::runtime_error("cannot open a window with OpenGL 3.3 core: update the graphics driver (Mesa's "
                               "llvmpipe works without a GPU)");
    }
    glfwMakeContextCurrent(handle);
  }
  ~Window() {
    glfwDestroyWindow(handle);
    glfwTerminate();
  }
};

// The camera's starting view: the cavity from above and aside, or the whole domain.
Camera initial_camera(const Scene& sc) {
  Camera c;
  if (sc.tooth) {
    const ToothFrame& f = sc.tooth->frame();
    c.up = f.z;
    c.side = f.x;
    c.target = f.origin - f.z * 1e-3;
    c.distance = 0.021f;
    c.pitch = 1.0f;
  } else {
    const Vec3 up = norm(sc.model.gravity) > 0 ? -sc.model.gravity / norm(sc.model.gravity) : Vec3{0, 0, 1};
    c.up = up;
    const Vec3 helper = std::abs(up.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    const Vec3 side = helper - up * dot(helper, up);
    c.side = side / norm(side);
    c.target = 0.5 * (sc.model.domain_min + sc.model.domain_max);
    c.distance = float(1.3 * norm(sc.model.domain_max - sc.model.domain_min));
  }
  return c;
}

// Mouse and keys: the tool (a stand-in haptic device), the camera, shortcuts.
struct Input {
  bool dragging_tool = false, orbiting = false, panning = false;
  double last_x = 0, last_y = 0;
  float wheel = 0;
  bool space_was = false;
  bool key_down[GLFW_KEY_LAST + 1] = {};
};

Input* g_input = nullptr;

// The script: its simulation actions posted to the session at their steps; its view actions
// (colour_by, end) returned, applied as the snapshots reach their steps.
std::vector<ScriptAction> schedule_script(SimSession& session, const InputScript& script, const Scene& sc) {
  std::vector<ScriptAction> view_actions;
  auto to_world = [&](const Vec3& mm) { return sc.tooth ? sc.tooth->frame().to_world(mm * 1e-3) : mm * 1e-3; };
  for (const ScriptAction& a : script.actions) {
    Command c;
    switch (a.kind) {
      case ScriptAction::Kind::move: c = {Command::Kind::tool_target}; c.target = to_world(a.position_mm); break;
      case ScriptAction::Kind::press: c = {Command::Kind::press}; c.pressed = true; break;
      case ScriptAction::Kind::release: c = {Command::Kind::press}; c.pressed = false; break;
      case ScriptAction::Kind::dispense: c = {Command::Kind::dispense}; break;
      case ScriptAction::Kind::switch_tool: c = {Command::Kind::switch_tool}; c.tool = a.name; break;
      case ScriptAction::Kind::pause: c = {Command::Kind::pause}; break;
      case ScriptAction::Kind::resume: c = {Command::Kind::resume}; break;
      case ScriptAction::Kind::reset: c = {Command::Kind::reset}; break;
      case ScriptAction::Kind::light_on: c = {Command::Kind::light}; c.pressed = true; break;
      case ScriptAction::Kind::light_off: c = {Command::Kind::light}; c.pressed = false; break;
      case ScriptAction::Kind::load_preset:
        c = {Command::Kind::load_preset};
        c.preset = a.name;
        c.temperature_c = a.temperature_c;
        break;
      case ScriptAction::Kind::colour_by:
      case ScriptAction::Kind::end: view_actions.push_back(a); continue;
    }
    session.post_at(a.step, c);
  }
  return view_actions;
}

// What the hand and the view do with the mouse and keys this frame.
struct FrameInput {
  Camera& cam;
  Vec3& tool_target;  // where the mouse drives the tool (world, m)
  UiState& ui;
  const Snapshot& snap;
  const std::vector<std::string>& tools;
  real spacing;
};

// Reads the mouse and keys of one frame: the tool's target and the buttons as commands, the camera
// moved, the view's toggles flipped (docs/viewer.md, "Keys and mouse").
void read_input(GLFWwindow* win, Input& input, int fb_h, FrameInput f, std::vector<Command>& commands) {
  const ImGuiIO& io = ImGui::GetIO();
  double mx, my;
  glfwGetCursorPos(win, &mx, &my);
  const float dx = float(mx - input.last_x), dy = float(my - input.last_y);
  input.last_x = mx;
  input.last_y = my;
  auto move_tool = [&](const Vec3& by) {
    f.tool_target += by;
    Command c{Command::Kind::tool_target};
    c.target = f.tool_target;
    commands.push_back(c);
  };
  if (!io.WantCaptureMouse) {
    const bool left = glfwGetMouseButton(win, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool right = glfwGetMouseButton(win, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    const bool shift = glfwGetKey(win, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
    const bool ctrl = glfwGetKey(win, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS;
    if (left && (dx != 0 || dy != 0)) move_tool(f.cam.view_plane_offset(dx, dy, fb_h));
    if (right && shift) f.cam.pan(dx, dy, fb_h);
    else if (right) f.cam.orbit(dx, dy);
    if (input.wheel != 0) {
      if (ctrl) f.cam.zoom(input.wheel);
      else move_tool(f.cam.forward() * (input.wheel * 0.5 * f.spacing));
      input.wheel = 0;
    }
  }
  if (io.WantCaptureKeyboard) return;
  const bool space = glfwGetKey(win, GLFW_KEY_SPACE) == GLFW_PRESS;
  if (space != input.space_was) {
    Command c{Command::Kind::press};
    c.pressed = space;
    commands.push_back(c);
    input.space_was = space;
  }
  auto pressed_once = [&](int key) {
    const bool now = glfwGetKey(win, key) == GLFW_PRESS;
    const bool edge = now && !input.key_down[key];
    input.key_down[key] = now;
    return edge;
  };
  UiState& ui = f.ui;
  if (pressed_once(GLFW_KEY_P)) commands.push_back({f.snap.paused ? Command::Kind::resume : Command::Kind::pause});
  if (pressed_once(GLFW_KEY_N)) commands.push_back({Command::Kind::single_step});
  if (pressed_once(GLFW_KEY_R)) commands.push_back({Command::Kind::reset});
  if (pressed_once(GLFW_KEY_D)) commands.push_back({Command::Kind::dispense});
  if (pressed_once(GLFW_KEY_L)) {  // the curing light over the cavity, on or off
    Command c{Command::Kind::light};
    c.pressed = !f.snap.light.has_value();
    commands.push_back(c);
  }
  if (pressed_once(GLFW_KEY_T)) {
    ui.tool_index = (ui.tool_index + 1) % int(f.tools.size());
    Command c{Command::Kind::switch_tool};
    c.tool = f.tools[std::size_t(ui.tool_index)];
    commands.push_back(c);
  }
  if (pressed_once(GLFW_KEY_C)) {
    std::size_t k = 0;
    while (kColourModes[k] != ui.colour_by) ++k;
    ui.colour_by = kColourModes[(k + 1) % kColourModes.size()];
  }
  if (pressed_once(GLFW_KEY_B)) ui.show_boundary = !ui.show_boundary;
  if (pressed_once(GLFW_KEY_X)) ui.cut = !ui.cut;
  if (pressed_once(GLFW_KEY_S)) ui.surface = !ui.surface;
  if (pressed_once(GLFW_KEY_ESCAPE)) glfwSetWindowShouldClose(win, GLFW_TRUE);
}

// The particles' colours by the chosen field (its range set automatically unless fixed in the
// panel), and those drawn: all but the hidden walls and, with the surface on, the paste.
class ParticleView {
 public:
  void draw(const Snapshot& snap, UiState& ui, const ViewUniforms& u, real spacing) {
    const std::span<const float> field =
        ui.colour_by == ColourBy::pressure     ? std::span<const float>(snap.pressure)
        : ui.colour_by == ColourBy::density    ? std::span<const float>(snap.density)
        : ui.colour_by == ColourBy::speed      ? std::span<const float>(snap.speed)
        : ui.colour_by == ColourBy::conversion ? std::span<const float>(snap.conversion)
                                               : std::span<const float>(snap.bonds);
    // Conversion on its own scale, from uncured to fully cured paste.
    if (ui.colour_by == ColourBy::conversion && ui.auto_range) ui.range = {0.f, float(snap.conversion_max)};
    else if (ui.colour_by != ColourBy::role && ui.auto_range) ui.range = auto_range(field, snap.role);
    particle_colours(ui.colour_by, field, snap.role, ui.range, rgb_);
    xyz_.clear();
    vis_rgb_.clear();
    for (std::size_t i = 0; i < snap.role.size(); ++i) {
      if (!ui.show_boundary && snap.role[i] == Role::boundary) continue;
      if (ui.surface && snap.role[i] == Role::material) continue;
      xyz_.insert(xyz_.end(), {snap.xyz[3 * i], snap.xyz[3 * i + 1], snap.xyz[3 * i + 2]});
      vis_rgb_.insert(vis_rgb_.end(), {rgb_[3 * i], rgb_[3 * i + 1], rgb_[3 * i + 2]});
    }
    renderer_.draw(u, xyz_, vis_rgb_, float(0.5 * spacing));
  }

 private:
  ParticleRenderer renderer_;
  std::vector<float> rgb_, xyz_, vis_rgb_;  // reused between frames
};

}  // namespace

void request_close() { g_close_requested.store(true); }

ViewerResult run_viewer(SimSession& session, const ViewerOptions& opt) {
  const Scene& sc = session.scene();
  Window win(opt.width, opt.height);
  glfwSwapInterval(opt.vsync ? 1 : 0);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the user's folder
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(win.handle, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
  struct ImGuiGuard {
    ~ImGuiGuard() {
      ImGui_ImplOpenGL3_Shutdown();
      ImGui_ImplGlfw_Shutdown();
      ImGui::DestroyContext();
    }
  } imgui_guard;

  const real spacing = increment_spacing(sc);
  ParticleView particles;
  std::unique_ptr<ToothRenderer> tooth;
  if (sc.tooth) tooth = std::make_unique<ToothRenderer>(*sc.tooth);
  ArrowRenderer arrows;
  PasteSurfaceView paste_surface(sc, spacing, !opt.screenshot.empty());
  Camera cam = initial_camera(sc);
  UiState ui;
  ui.colour_by = colour_by_from_name(opt.colour_by);
  ui.cut = opt.cut;
  ui.surface = opt.surface;
  const std::vector<std::string> tools = session.tools();

  Input input;
  g_input = &input;
  glfwSetScrollCallback(win.handle, [](GLFWwindow* w, double dx, double dy) {
    ImGui_ImplGlfw_ScrollCallback(w, dx, dy);
    if (g_input && !ImGui::GetIO().WantCaptureMouse) g_input->wheel += float(dy);
  });

  const std::vector<ScriptAction> view_actions = opt.script ? schedule_script(session, *opt.script, sc)
                                                            : std::vector<ScriptAction>{};
  std::size_t next_view_action = 0;
  const std::uint64_t script_end = opt.script ? opt.script->end_step() : 0;

  session.start();
  Snapshot snap;
  session.latest(snap);
  Vec3 tool_target = snap.tool_pose.position;
  std::uint64_t last_version = 0;
  FrameTimer timer;
  FrameStats stats;
  ViewerResult result;
  float force_peak = 0;
  auto next_frame = clock_type::now();  // the frame cap's schedule

  for (;;) {
    if (glfwWindowShouldClose(win.handle) || g_close_requested.load()) {
      result.closed_by_user = true;
      break;
    }
    glfwPollEvents();
    std::vector<Command> commands;
    int fb_w = 1, fb_h = 1;
    glfwGetFramebufferSize(win.handle, &fb_w, &fb_h);
    read_input(win.handle, input, fb_h, {cam, tool_target, ui, snap, tools, spacing}, commands);

    // ---- the newest snapshot -------------------------------------------------------------------
    if (session.latest(snap) && snap.version != last_version) {
      last_version = snap.version;
      const float f = float(norm(snap.device_force_N));
      ui.force_history.push_back(std::isfinite(f) ? f : 0.f);
      while (ui.force_history.size() > 600) ui.force_history.pop_front();
      force_peak = *std::max_element(ui.force_history.begin(), ui.force_history.end());
    }
    while (next_view_action < view_actions.size() && view_actions[next_view_action].step <= snap.steps) {
      const ScriptAction& a = view_actions[next_view_action++];
      if (a.kind == ScriptAction::Kind::colour_by) ui.colour_by = colour_by_from_name(a.name);
    }

    // ---- draw ------------------------------------------------------------------------------------
    glViewport(0, 0, fb_w, fb_h);
    glClearColor(0.11f, 0.12f, 0.14f, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    ViewUniforms u;
    u.view = cam.view();
    u.proj = cam.projection(float(fb_w) / float(std::max(fb_h, 1)));
    u.viewport_h = float(fb_h);
    if (ui.cut) {
      const Vec3 n = sc.tooth ? sc.tooth->frame().y : cam.right();
      u.clip_plane = glm::vec4(g(n), float(-dot(n, cam.target)));
    }
    if (tooth) tooth->draw(u);
    paste_surface.update(snap, ui.surface);
    if (ui.surface) paste_surface.draw(u);
    particles.draw(snap, ui, u, spacing);
    // The force on the tool, from its tip: 1.5 mm (out of the instrument) plus 4 mm at the largest
    // force of the last 10 s.
    const float f = float(norm(snap.device_force_N));
    if (f > 0 && force_peak > 0 && std::isfinite(f)) {
      const glm::vec3 dir = g(snap.device_force_N) / f;
      arrows.add(g(snap.tool_pose.position), dir * (1.5e-3f + 4e-3f * f / force_peak), float(0.12 * spacing),
                 glm::vec3(0.9f, 0.15f, 0.2f));
    }
    if (snap.light) add_curing_light(arrows, *snap.light);
    arrows.draw(u);

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    draw_panels(snap, ui, stats, tools, commands);
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    for (const Command& c : commands) session.post(c);

    // ---- frame statistics and the end of a counted run -------------------------------------------
    const auto now = clock_type::now();
    stats = timer.frame_done(now);
    const bool frames_done = opt.frames > 0 && stats.frames >= opt.frames;
    const bool script_done = !opt.script || (session.schedule_done() && snap.steps >= script_end &&
                                             next_view_action == view_actions.size());
    if (frames_done && script_done) {
      if (!opt.screenshot.empty()) write_screenshot(opt.screenshot, fb_w, fb_h);
      glfwSwapBuffers(win.handle);
      break;
    }
    glfwSwapBuffers(win.handle);
    if (opt.max_fps > 0) {
      // Sleep out the rest of the frame's time share.
      next_frame = std::max(next_frame + std::chrono::duration_cast<clock_type::duration>(
                                             std::chrono::duration<double>(1.0 / opt.max_fps)),
                            clock_type::now() - std::chrono::milliseconds(100));
      std::this_thread::sleep_until(next_frame);
    }
    if (opt.timeout_s > 0 && timer.seconds_since_start(now) > opt.timeout_s) {
      result.timed_out = true;
      break;
    }
  }
  session.stop();
  g_input = nullptr;
  session.latest(result.last);
  result.sim_steps = result.last.steps;
  result.sim_steps_per_second = result.last.steps_per_second;
  result.surfaces_built = paste_surface.built();
  result.surface_frames_due = paste_surface.frames_due();
  result.surface_frames_late = paste_surface.frames_late();
  timer.finish(result);
  return result;
}

}  // namespace dentsph::viewer
