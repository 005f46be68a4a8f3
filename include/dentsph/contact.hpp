// Hard contact (docs/haptics.md, "Hard contact"): the instrument against what does not flow (the
// prepared tooth, a Class II cavity's matrix band, paste that has set), rendered at the haptic
// rate by a constraint-based proxy (a god-object; Zilles & Salisbury 1995) instead of waiting for
// the simulation. The proxy is where the instrument is allowed to be: as close to the device as
// the rigid surfaces let it, sliding along them beyond the friction cone; the hand feels a spring
// and damper from the device to it. The simulated instrument is the proxy, so it never enters the
// tooth or set paste.
//
// Everything rigid is one distance: ContactField, the signed distance to the prepared tooth (its
// WallField) and to the surface of a set of rigid particles (band and set paste, on a grid of its
// own, rebuilt when paste sets). The instrument is ContactShape, spheres in the tool frame: its
// particles and its shank. HardContact is the proxy; it allocates nothing after construction and
// takes no lock, so the haptic loop runs it every tick.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "dentsph/pose.hpp"
#include "dentsph/vec3.hpp"
#include "dentsph/wall_field.hpp"

namespace dentsph {

struct Scene;
class State;

// The contact's spring, damper and friction (device frame: device N per device m). The device
// profile gives the first two (DeviceProfile::contact).
struct ContactParams {
  double stiffness_N_per_m = 3000;  // CHAI3D's Falcon
  double damping_N_s_per_m = 20;    // along the normal, in contact only
  // Coulomb friction of steel on enamel (static and kinetic alike; docs/haptics.md says where the
  // value comes from).
  double friction = 0.3;
  // The damping grows from 0 at first contact to full at this depth (device m), so that touching
  // a surface at speed is not a step of damping x speed.
  double damping_depth_m = 2e-4;
};

// The instrument as spheres in the tool frame (tip at the origin, handle along +z).
struct ContactSphere {
  Vec3 centre;  // m, tool frame
  real radius;  // m
};
struct ContactShape {
  std::vector<ContactSphere> spheres;
  Vec3 centre;         // m, tool frame: centre of a sphere bounding them all
  real bound = 0;      // m, its radius
  void finish_bound();  // sets centre and bound from the spheres
};
// An instrument's particles (tool frame) as spheres of half its spacing, and its shank: a row of
// spheres along +z from the top of the particles to `shank_length` (m) above the tip, of radius
// `shank_radius` (m; 0: no shank), a quarter of their radius apart.
ContactShape instrument_contact_shape(std::span<const Vec3> points, real spacing, real shank_length = 12e-3,
                                      real shank_radius = 0.35e-3);
// The spacing of `scene`'s instrument particles: its instrument spacing, else its material
// spacing, else half the kernel's support.
real instrument_contact_spacing(const Scene& scene);
// The tool frame places of the instrument `state` holds now (its tool particles' anchors), into
// `out` (cleared first).
void tool_anchors(const State& state, std::vector<Vec3>& out);
// The shape of the instrument `state` holds now, at instrument_contact_spacing.
ContactShape instrument_contact_shape(const Scene& scene, const State& state);

// The signed distance to everything rigid, in the scene frame (m; negative inside). The tooth's
// field must hold the whole tooth (tooth_wall_field(scene, true)). Copies share
// the tooth's field and copy the particles' grid (no allocation when copied onto a field of the
// same grid: what the runtime's exchange relies on).
class ContactField {
 public:
  ContactField() = default;  // nothing rigid
  // `tooth`: the prepared tooth's field (may be null); the rigid particles' grid over [lo, hi] in
  // cells of `cell` (m), particles of radius `particle_radius` (m: the surface of a set of them is
  // this far out from their centres). Throws std::invalid_argument for an empty box or a grid of
  // more than 16 million corners.
  ContactField(std::shared_ptr<const WallField> tooth, Vec3 lo, Vec3 hi, real cell, real particle_radius);

  // Replaces the rigid particles (m, scene frame; those outside the grid's box are left out) and
  // recomputes their grid: the distance to the smooth surface of Zhu & Bridson (2005) around them,
  // radius particle_radius, kernel support 4 particle radii. Allocates; not for the haptic thread.
  void set_particles(std::span<const Vec3> points);
  std::size_t particles() const { return particles_; }

  struct Sample {
    real distance = kFar;  // m to the nearest rigid surface, negative inside
    Vec3 normal;           // unit, out of that surface (zero where it has no direction)
    bool tooth = false;    // the nearest surface is the tooth's (else particles')
  };
  // The distance at p; `tooth` and `particles` choose which surfaces count. Outside a grid's box
  // that part's distance is the distance to its box (every surface it holds lies inside it), so
  // the result is never more than the true distance: what the hard contact's broad phase needs.
  Sample sample(const Vec3& p, bool tooth = true, bool particles = true) const;
  bool has_tooth() const { return bool(tooth_); }
  bool has_grid() const { return !phi_.empty(); }
  static constexpr real kFar = 1;  // m: no surface near

 private:
  std::shared_ptr<const WallField> tooth_;
  Vec3 origin_, hi_;  // the particles' grid's box
  real cell_ = 0, inv_cell_ = 0, radius_ = 0, far_ = 0;
  int n_[3] = {0, 0, 0};
  std::size_t particles_ = 0;
  std::vector<float> phi_;  // m, x fastest; far_ where no particle is within reach
};

// The contact field of a scene: its prepared tooth's wall field (the iisph solver's, or one made
// alike), and a particles' grid over its lining's box grown by 2 mm (within the domain) at half
// the material spacing, holding the matrix band (boundary particles off the prepared tooth). A
// scene without a tooth: an empty field.
ContactField scene_contact_field(const Scene& scene);
// The rigid particles of `state` for ContactField::set_particles: the matrix band (boundary
// particles the scene did not place on the prepared tooth: `band` of scene_rigid_band) and set
// paste (CureState::rigid), appended to `out` (cleared first).
void rigid_particles(const State& state, std::span<const Vec3> band, std::vector<Vec3>& out);
// The scene's matrix band: boundary particles farther than a quarter spacing outside its tooth.
std::vector<Vec3> scene_rigid_band(const Scene& scene);

// What the contact's field and shape are built from, watched: a state's rigid particles (the
// band and set paste) and its instrument's anchors, as last built. changed() says whether paste
// set or came loose, set paste moved more than `tolerance` (m) from where the field has it (its
// shrinkage), or the instrument was switched; then it keeps the new ones. The first call says
// true. Its buffers are reused: no allocation once they have grown.
class RigidWatch {
 public:
  // `band`: scene_rigid_band's particles.
  explicit RigidWatch(std::vector<Vec3> band = {}, real tolerance = kDefaultTolerance);
  bool changed(const State& state);
  const std::vector<Vec3>& particles() const { return particles_; }  // rigid_particles' order
  const std::vector<Vec3>& tool() const { return tool_; }            // tool_anchors'
  void forget() { first_ = true; }  // the next changed() says true (a state reset)

  static constexpr real kDefaultTolerance = 0.02e-3;  // m: a tenth of the contact's projection step

 private:
  std::vector<Vec3> band_, particles_, tool_;
  std::vector<Vec3> built_;  // by paste id: where the field has each set particle (NaN: not set)
  std::size_t set_count_ = 0;
  double tool_signature_ = 0;
  real tolerance2_;
  bool first_ = true;
};

// The proxy's state after a tick.
struct ContactResult {
  Vec3 proxy;          // m, scene frame: where the instrument's origin may be
  Vec3 force_N;        // device frame: spring and damper from the device to the proxy
  Vec3 torque_N_m;     // about the instrument's origin (device frame lever)
  Vec3 normal;         // unit, of the surface touched (zero in air)
  double depth_m = 0;  // device m: how far the device is behind the surface along the normal
  bool touching = false;
  bool sliding = false;  // the friction cone was left: the proxy slid
};

class HardContact {
 public:
  // `scale`: scene m per device m (WorkspaceMap::scale); `max_spheres`: the room reserved for a
  // shape's spheres (update() allocates nothing; spheres beyond it are left out).
  explicit HardContact(const ContactParams& params = {}, double scale = 1, std::size_t max_spheres = 4096);
  // Puts the proxy at `position` (scene m) with nothing touched.
  void reset(const Vec3& position);
  // One tick: the device's tool origin at `target` (scene m) with orientation `q`, moving at
  // `device_velocity` (device m/s). Moves the proxy from where it was towards the target, in steps
  // of at most a third of the smallest sphere's radius, never into `field`'s surfaces (an
  // instrument already inside a surface when it appeared, e.g. paste that set around it, is not
  // held by that surface until it is out), with Coulomb friction, and returns the force on the hand.
  const ContactResult& update(const ContactField& field, const ContactShape& shape, const Vec3& target, const Quat& q,
                              const Vec3& device_velocity);
  const ContactResult& result() const { return res_; }
  bool started() const { return started_; }

 private:
  // Pushes `g` out of the surfaces along their normals (a few passes over the spheres in
  // `active_`); returns the deepest penetration left (m, >= 0) and the mean normal of the pushes.
  real project(const ContactField& field, Vec3& g, Vec3& normal, Vec3& contact_point);
  // The proxy at `g` touching at `contact` (res_.touching and res_.normal set by the caller):
  // the force and torque on the hand at `target`.
  const ContactResult& finish(const Vec3& g, const Vec3& contact, const Vec3& target, const Vec3& device_velocity);

  ContactParams p_;
  double scale_;
  std::vector<Vec3> offset_;        // sphere centres rotated to the scene (capacity fixed)
  std::vector<real> radius_;
  std::vector<std::uint32_t> active_;  // spheres that may touch this tick
  real min_radius_ = 0;
  Vec3 proxy_;
  bool started_ = false;
  bool ignore_tooth_ = false, ignore_particles_ = false;  // inside a surface when it appeared
  ContactResult res_;
};

}  // namespace dentsph
