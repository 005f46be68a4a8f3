// The viewer's simulation loop (sim_session.hpp).
#include "sim_session.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "dentsph/run.hpp"
#include "dentsph/tools.hpp"

namespace dentsph::viewer {

namespace {

using clock_type = std::chrono::steady_clock;

const ParticleInit* first_of(const Scene& sc, Role r) {
  for (const ParticleInit& p : sc.particles)
    if (p.role == r) return &p;
  for (const ProcedureEvent& e : sc.events)
    for (const ParticleInit& p : e.particles)
      if (p.role == r) return &p;
  return nullptr;
}

// Material runs faster than ten times its sound speed only when the simulation has exploded
// (the offline runner uses the same test).
constexpr real kExplosionSpeedFactor = 10;

}  // namespace

SimSession::SimSession(Scene scene, SessionOptions options) : scene_(std::move(scene)), opt_(options) {
  const ParticleInit* paste = first_of(scene_, Role::material);
  const ParticleInit* tool = first_of(scene_, Role::tool);
  const real s = scene_.material_spacing > 0 ? scene_.material_spacing : 0.5 * scene_.model.kernel.h;
  paste_ = paste ? paste->material : Material{1.0, 10, 2000, 50};
  paste_mass_ = paste ? paste->mass : lattice_particle_mass(paste_.rho0, s, scene_.model.kernel);
  tool_material_ = tool ? tool->material : Material{1.0, 15, 2000, 0};
  press_axis_ = scene_.tooth ? scene_.tooth->frame().z : Vec3{0, 0, 1};
  if (scene_.tooth) {
    AssessParams ap;
    ap.spacing = s;
    assessor_.emplace(*scene_.tooth, ap);
  }
  if (opt_.dispense_volume <= 0)
    opt_.dispense_volume = scene_.tooth ? scene_.tooth->cavity_volume() / 6 : 200 * s * s * s;
  paused_ = opt_.start_paused;
  reset_state();
  publish(true, 0);
}

SimSession::~SimSession() { stop(); }

void SimSession::reset_state() {
  state_ = make_state(scene_);
  apply_paste();  // the paste as edited, not as the scene first gave it
  tool_name_ = scene_.tooth ? "ball_burnisher" : "scene tool";
  target_ = scene_.tool.keyframes.empty() ? Vec3{} : scene_.tool.at(0).position;
  state_.tool_pose = state_.tool_pose_applied;
  forces_ = {};
  diverged_ = false;
  steps_.store(0, std::memory_order_release);
}

void SimSession::apply_paste() {
  for (std::uint32_t i = 0; i < state_.size(); ++i)
    if (state_.role[i] == Role::material) {
      state_.Kp[i] = paste_.Kp;
      state_.Ka[i] = paste_.Ka;
      state_.mu[i] = paste_.mu;
    }
  sound_speed_ = stability_limits(scene_.model, state_).sound_speed;
}

std::vector<std::string> SimSession::tools() const { return {"ball_burnisher", "flat_plugger", "condenser"}; }

void SimSession::start() {
  if (running_.exchange(true)) return;
  thread_ = std::thread([this] { run(); });
}

void SimSession::stop() {
  if (!running_.exchange(false)) {
    if (thread_.joinable()) thread_.join();
    return;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void SimSession::post(const Command& c) {
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(c);
  }
  wake_.notify_all();
}

void SimSession::post_at(std::uint64_t step, const Command& c) {
  {
    std::lock_guard lock(mutex_);
    scheduled_.emplace(step, c);
  }
  wake_.notify_all();
}

bool SimSession::schedule_done() const {
  std::lock_guard lock(mutex_);
  return scheduled_.empty() && queue_.empty();
}

bool SimSession::latest(Snapshot& out) const {
  std::lock_guard lock(mutex_);
  if (published_.version <= out.version && out.version != 0) return false;
  out = published_;
  return true;
}

Vec3 SimSession::tool_tip_goal() const {
  const real s = scene_.material_spacing > 0 ? scene_.material_spacing : 0.5 * scene_.model.kernel.h;
  return pressed_ ? target_ - press_axis_ * (opt_.press_depth_spacings * s) : target_;
}

void SimSession::apply(const Command& c) {
  message_.clear();
  switch (c.kind) {
    case Command::Kind::pause: paused_ = true; return;
    case Command::Kind::resume: paused_ = false; return;
    case Command::Kind::single_step: paused_ = true; single_ = true; return;
    case Command::Kind::reset: reset_state(); return;
    case Command::Kind::tool_target: target_ = c.target; return;
    case Command::Kind::press: pressed_ = c.pressed; return;
    case Command::Kind::dispense: {
      const real s = scene_.material_spacing > 0 ? scene_.material_spacing : 0.5 * scene_.model.kernel.h;
      const real r = std::cbrt(3 * opt_.dispense_volume / (4 * M_PI));
      // Above the highest material on the tooth's axis (or the domain's middle), clear of it.
      const Vec3 up = press_axis_;
      const Vec3 axis_origin = scene_.tooth ? scene_.tooth->frame().origin
                                            : 0.5 * (scene_.model.domain_min + scene_.model.domain_max);
      real top = 0;
      for (std::uint32_t i = 0; i < state_.size(); ++i)
        if (state_.role[i] == Role::material) top = std::max(top, dot(state_.pos[i] - axis_origin, up));
      const Vec3 centre = axis_origin + up * (top + r + 2 * s);
      state_.add_particles(scene_.model, material_increment(centre, opt_.dispense_volume, s, paste_mass_, paste_));
      return;
    }
    case Command::Kind::switch_tool: {
      const real s = scene_.material_spacing > 0 ? scene_.material_spacing : 0.5 * scene_.model.kernel.h;
      try {
        switch_tool(state_, scene_.model, tool_by_name(c.tool, s), paste_mass_, tool_material_);
        tool_name_ = c.tool;
      } catch (const std::exception& e) {
        message_ = e.what();
      }
      return;
    }
    case Command::Kind::set_material: {
      const MaterialEdit& m = c.material;
      if (!(m.Kp > 0) || !(m.mu >= 0) || !(m.Ka >= 0)) {
        message_ = "material: Kp must be positive, mu and Ka non-negative";
        return;
      }
      ModelParams p = scene_.params;
      p.adhesion.A = m.A;
      p.adhesion.B = m.B;
      p.adhesion.eps = m.eps;
      p.adhesion.zeta = m.zeta;
      Model model;
      try {
        model = make_model(p);
      } catch (const std::exception& e) {
        message_ = e.what();
        return;
      }
      // Refuse an edit that would put dt over a stability limit: the paste would explode.
      const real acoustic = model.cfl_lambda * model.kernel.h / std::sqrt(std::max(m.Kp, tool_material_.Kp));
      const real viscous = m.mu > 0 ? 0.125 * model.kernel.h2 * paste_.rho0 / m.mu : INFINITY;
      if (model.dt > acoustic || model.dt > viscous) {
        message_ = fmt::format(
            "refused: dt = {:.3g} s would exceed the {} limit ({:.3g} s); lower {}", model.dt,
            model.dt > acoustic ? "acoustic" : "viscous", std::min(acoustic, viscous),
            model.dt > acoustic ? "Kp" : "mu");
        return;
      }
      scene_.params = p;
      scene_.model = model;
      paste_.Kp = m.Kp;
      paste_.Ka = m.Ka;
      paste_.mu = m.mu;
      apply_paste();
      return;
    }
  }
}

void SimSession::publish(bool with_assessment, double steps_per_second) {
  Snapshot s;
  const std::uint32_t n = state_.size();
  s.time = state_.time;
  s.steps = state_.steps;
  s.xyz.resize(3 * std::size_t(n));
  s.role.assign(state_.role.begin(), state_.role.end());
  s.pressure.resize(n);
  s.density.resize(n);
  s.speed.resize(n);
  s.bonds.resize(n);
  const bool have_fields = state_.rho.size() == n && state_.pressure.size() == n;
  for (std::uint32_t i = 0; i < n; ++i) {
    s.xyz[3 * i] = float(state_.pos[i].x);
    s.xyz[3 * i + 1] = float(state_.pos[i].y);
    s.xyz[3 * i + 2] = float(state_.pos[i].z);
    s.pressure[i] = have_fields ? float(state_.pressure[i]) : 0.f;
    s.density[i] = have_fields ? float(state_.rho[i]) : 0.f;
    s.speed[i] = float(norm(state_.vel[i]));
    s.bonds[i] = float(state_.bonds.count(state_.id[i]));
  }
  s.tool_pose = state_.tool_pose_applied;
  s.tool_force_N = state_.tool_wrench.force * scene_.force_scale;
  if (with_assessment && assessor_) s.assessment = assessor_->assess(state_, scene_.model, forces_);
  s.limits = stability_limits(scene_.model, state_);
  s.dt = scene_.model.dt;
  s.material = {paste_.Kp, paste_.Ka, paste_.mu, scene_.model.adhesion.A, scene_.model.adhesion.B,
                scene_.model.adhesion.eps, scene_.model.adhesion.zeta};
  s.tool_name = tool_name_;
  s.message = message_;
  s.paused = paused_;
  s.diverged = diverged_;
  s.steps_per_second = steps_per_second;
  std::lock_guard lock(mutex_);
  const std::uint64_t version = published_.version + 1;
  if (!with_assessment && published_.assessment) s.assessment = published_.assessment;  // keep the last one
  published_ = std::move(s);
  published_.version = version;
}

void SimSession::run() {
  auto last_publish = clock_type::now();
  auto last_assess = last_publish;
  auto rate_t0 = last_publish;
  std::uint64_t rate_steps0 = state_.steps;
  double rate = 0;
  const auto publish_every = std::chrono::duration<double>(1.0 / opt_.snapshot_hz);
  const auto assess_every = std::chrono::duration<double>(1.0 / opt_.assess_hz);
  while (running_.load(std::memory_order_acquire)) {
    bool changed = false;
    {
      std::unique_lock lock(mutex_);
      const bool idle = (paused_ || diverged_) && !single_ && queue_.empty() &&
                        (scheduled_.empty() || scheduled_.begin()->first > state_.steps || paused_);
      if (idle) wake_.wait_for(lock, std::chrono::milliseconds(20));
      std::deque<Command> now;
      now.swap(queue_);
      while (!scheduled_.empty() && scheduled_.begin()->first <= state_.steps) {
        now.push_back(scheduled_.begin()->second);
        scheduled_.erase(scheduled_.begin());
      }
      lock.unlock();
      for (const Command& c : now) apply(c);
      changed = !now.empty();
    }
    const bool stepping = (!paused_ || single_) && !diverged_;
    if (stepping) {
      single_ = false;
      // The tool follows its goal at a bounded speed: a mouse jumps, a tool must not.
      const Vec3 goal = tool_tip_goal();
      const Vec3 from = state_.tool_pose_applied.position;
      const Vec3 d = goal - from;
      const real max_move = opt_.tool_speed * scene_.model.dt;
      const real len = norm(d);
      state_.tool_pose = state_.tool_pose_applied;
      state_.tool_pose.position = len > max_move ? from + d * (max_move / len) : goal;
      step(scene_.model, state_, StepOptions{opt_.threads, nullptr});
      forces_.add(state_.tool_wrench.force * scene_.force_scale, scene_.model.dt);
      steps_.store(state_.steps, std::memory_order_release);
      if (state_.diagnostics.non_finite > 0 ||
          state_.diagnostics.max_speed > kExplosionSpeedFactor * sound_speed_) {
        diverged_ = true;
        message_ = fmt::format("the simulation diverged at t = {:.4g} s (material faster than {} times the sound "
                               "speed, or non-finite): reset it (R) and soften the paste",
                               state_.time, kExplosionSpeedFactor);
      }
    }
    const auto now = clock_type::now();
    if (now - rate_t0 >= std::chrono::milliseconds(500)) {
      rate = double(state_.steps - rate_steps0) / std::chrono::duration<double>(now - rate_t0).count();
      rate_t0 = now;
      rate_steps0 = state_.steps;
    }
    if (changed || now - last_publish >= publish_every || !stepping) {
      const bool assess = changed || now - last_assess >= assess_every;
      publish(assess, rate);
      last_publish = now;
      if (assess) last_assess = now;
    }
  }
  publish(true, rate);
}

}  // namespace dentsph::viewer
