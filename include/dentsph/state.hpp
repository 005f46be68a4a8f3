// State: everything a step changes (docs/model.md; cf. MuJoCo's mjData). Particles are stored as
// structure of arrays, one array per quantity, all of length size(), in the current order
// (sorted by grid cell after every step). A particle's stable id never changes; index_of_id
// maps it to its current index.
#pragma once

#include <cstdint>
#include <vector>

#include "dentsph/bonds.hpp"
#include "dentsph/cure_state.hpp"
#include "dentsph/material.hpp"
#include "dentsph/pose.hpp"
#include "dentsph/vec3.hpp"

namespace dentsph {

struct Model;

// How a particle moves (docs/model.md, "Particles").
enum class Role : std::uint8_t {
  material = 0,  // integrated
  boundary = 1,  // static ghost particles (walls)
  tool = 2,      // kinematic: rigid transform of the tool pose
};
const char* role_name(Role r);

// One particle as the scene builder hands it in.
struct ParticleInit {
  Role role = Role::material;
  Vec3 pos;        // m (for tool particles: position in the tool frame)
  Vec3 vel;        // m/s (ignored for boundary and tool particles)
  real mass = 0;   // kg
  Material material;  // its values (the table's entry where material_index names one)
  // Its entry in Model::materials; kNoMaterial: the entry with the values of `material`.
  MaterialIndex material_index = kNoMaterial;
};

inline ParticleInit make_particle(Role role, const Vec3& pos, real mass, const Material& material,
                                  const Vec3& vel = {}, MaterialIndex material_index = kNoMaterial) {
  return {role, pos, vel, mass, material, material_index};
}

// The wrench the particles exert on the tool (docs/model.md, "Haptic force").
struct ToolWrench {
  Vec3 force;   // N, sum over tool particles of m_i a_i (without gravity)
  Vec3 torque;  // N m, about the tool pose's origin
};

// What the last step measured about itself.
struct StepDiagnostics {
  bool rebuilt = true;       // this step sorted the particles and rebuilt the neighbour lists
  real max_accel = 0;        // m/s^2, largest |a| of a material particle
  real max_speed = 0;        // m/s, largest |v| of a material particle after integration
  std::uint64_t non_finite = 0;  // material particles whose state became NaN or infinite
  // The iisph solver's own figures (zero after a paper step):
  int pressure_iterations = 0;  // pressure iterations this step took (within the model's budget)
  real density_error = 0;       // mean compression of the material at the end of the step: mean over
                                // material particles of max(0, rho_predicted - rho0) / rho0
  real pressure_residual = 0;   // the pressure solve's error: mean over material particles of
                                // |rho_predicted - rho0 - p / (k Kp)| / rho0 (where p = 0: its positive
                                // part; k = iisph.stiffness)
  real pressure_max_error = 0;  // the largest of those terms over material particles (cg solve; 0 after jacobi)
  // The compression the material has at the step's start, measured (the pair pass's density, not
  // the pressure solve's prediction, which the viscosity solve after it may undo): mean over
  // material particles of max(0, rho / rho0 - 1), and the largest.
  real compression_mean = 0, compression_max = 0;
  real viscous_pressure_max = 0;  // Pa, the largest viscous pressure after this step (iisph.viscous_pressure)
  bool pressure_on_budget = false;  // the pressure solve stopped at max_iterations, its error still over
                                    // iisph.density_error (pressure_residual says how far)
  bool on_deadline = false;         // a solve stopped at StepOptions::deadline, before its tolerance
  int viscosity_iterations = 0;     // conjugate-gradient iterations of the implicit viscosity
  real viscosity_residual = 0;      // its relative residual at the end: sqrt(r.D^-1 r / r0.D^-1 r0) (a fixed
                                    // count), sqrt(r.D^-1 r / b.D^-1 b) (iisph.viscosity_tolerance)
  // A non-Newtonian material's (docs/model.md, "Rheology"; 0 without one): the viscosity solves
  // this step took with updated effective viscosities (Picard iterations; viscosity_iterations
  // counts all their iterations), the largest relative change of a particle's viscosity at the last
  // update, and the range of the material's effective viscosities, Pa s.
  int rheology_iterations = 0;
  real rheology_change = 0;
  real viscosity_min = 0, viscosity_max = 0;
  std::uint64_t pair_overflow = 0;  // neighbours within h left out of a full pair row (never expected)
  std::uint64_t wall_projections = 0;  // material particles the wall field moved out this step (wall_field.hpp)
  int substeps = 1;                     // equal steps this step took (iisph: its velocity CFL limit under dt)
  std::uint64_t held = 0;               // material held at the domain's edge (Model::hold_outside_domain)
  std::uint32_t interface_capped = 0;   // paste whose pull from the instrument its contact's strength capped this step
};

// What the force pass reads of a neighbour, gathered in one record per particle by the density
// pass: one stream of memory per row of cells instead of six (the hardware prefetcher follows a
// few streams, not 54; measured on large scenes, where the rows no longer fit in the cache).
struct PairData {
  Vec3 pos, vel;
  real vol, pressure, mu, Ka;
};

// Scratch of the broad phase, sized with the particles (no allocation inside a step).
// Particles are sorted into buckets 2 * cell + (role == boundary): in each cell the moving
// particles (material, tool) come first and the static boundary particles after them, so a
// search that needs only moving neighbours skips the walls.
struct GridIndex {
  std::vector<std::uint32_t> key;           // [n] bucket of each particle (before sorting)
  std::vector<std::uint32_t> order;         // [n] sorted position -> old index
  std::vector<std::uint32_t> bucket_start;  // [2 cells + 1] first sorted index of each bucket
  std::vector<std::uint32_t> bucket_fill;   // [2 cells] counting-sort cursor
  // [n] m, positions as separate arrays for the searches of the grid: written by the reorder,
  // valid until the particles next move (a step that keeps its lists does not refresh them).
  std::vector<real> x, y, z;
  // Neighbours within h of each moving particle, found by the density pass for the force pass:
  // [n * kNeighbourStride] sorted indices (kNeighbourCapacity used, one scratch slot), and [n]
  // counts. A count above the capacity means the list overflowed and the force pass searches
  // the grid itself.
  static constexpr int kNeighbourStride = 64;
  static constexpr int kNeighbourCapacity = kNeighbourStride - 1;
  std::vector<std::uint32_t> neighbours;
  std::vector<std::uint16_t> neighbour_count;
  // Whether the lists are kept between steps (the model has a skin): only then are `within` and
  // `pos_at_build` sized (empty otherwise, where every list is rebuilt and is itself within h).
  bool keep_lists = false;
  // The entries of each moving particle's list within h this step, in list order: written by the
  // density pass (which computes every listed distance anyway) for the force pass. Valid where
  // the list did not overflow.
  std::vector<std::uint32_t> within;
  std::vector<std::uint16_t> within_count;
  // Positions when the lists were built (sorted order); the lists (radius h + skin) stay valid
  // until some particle has moved skin / 2 from there.
  std::vector<Vec3> pos_at_build;
  bool lists_valid = false;
  // [n] each particle's pair data this step (after its density and pressure), for the force pass.
  std::vector<PairData> pair_data;
};

// A number no State stamp has had (State::layout_stamp, order_stamp).
std::uint64_t new_state_stamp();

class State {
 public:
  // ---- particles, [size()] each, current order --------------------------------------------
  std::vector<std::uint32_t> id;     // stable id in [0, size())
  std::vector<Role> role;
  std::vector<Vec3> pos;             // m
  std::vector<Vec3> vel;             // m/s
  std::vector<real> mass;            // kg
  std::vector<MaterialIndex> material;  // entry of Model::materials (| kCuredMaterial: the cure's)
  // The material's values, a cache of the table the step reads (material.hpp): written from
  // Model::materials[material[i]] (or, where kCuredMaterial is set, CureState::cured[id]) by
  // refresh_materials and by the reorder, never permuted. The CUDA backend keeps its own copies.
  std::vector<real> mu;              // Pa s
  std::vector<real> Kp;              // m^2/s^2
  std::vector<real> rho0;            // kg/m^3
  std::vector<real> Ka;              // Pa
  std::vector<Vec3> anchor;          // m, tool particles: position in the tool frame
  std::vector<real> rho;             // kg/m^3, from the density stage
  std::vector<real> pressure;        // Pa, from the pressure stage
  std::vector<real> volume;          // m^3, m / rho, from the pressure stage (the pair terms' m_j/rho_j)
  std::vector<Vec3> force;           // N/m^3, internal force density (no gravity)

  // ---- by stable id -------------------------------------------------------------------------
  std::vector<std::uint32_t> index_of_id;  // [size()] current index of each id
  // kg/m^3, the density a boundary particle gets from the (static) boundary around it; 0 for
  // other roles. Computed once by the first step after particles are added.
  std::vector<real> rho_static;
  bool rho_static_valid = false;
  BondStore bonds;
  CureState cure;  // degree of conversion, dose, increment (include/dentsph/cure_state.hpp)
  // Pa, the iisph solver's viscous pressure of each particle (docs/model.md, "The viscous
  // pressure"), carried from step to step: this State's own, kept with it when it is copied; empty
  // until a step solves it, then one by id (add_particles appends 0, remove_particles re-keys it).
  std::vector<real> viscous_pressure;

  // ---- tool and time ------------------------------------------------------------------------
  Pose tool_pose;          // the pose the next step moves the tool to (set by the caller)
  Pose tool_pose_applied;  // the pose the tool particles are at now
  ToolWrench tool_wrench;  // from the last step
  real time = 0;         // s, simulated
  std::uint64_t steps = 0;
  StepDiagnostics diagnostics;

  // ---- scratch --------------------------------------------------------------------------------
  GridIndex grid;
  std::vector<Vec3> scratch_vec;
  std::vector<real> scratch_real;
  std::vector<std::uint32_t> scratch_u32;
  std::vector<Role> scratch_role;
  std::vector<MaterialIndex> scratch_material;
  // Stamps of what a solver's own buffers depend on (solver.hpp, StepSolver::resize): `layout_stamp`
  // is new after every add_particles and remove_particles, `order_stamp` also after every reorder
  // into cell order (stages::reorder). Unique across States: a copy shares its original's until
  // either changes.
  std::uint64_t layout_stamp = 0, order_stamp = 0;

  std::uint32_t size() const { return std::uint32_t(pos.size()); }
  // Filling material: a moving material particle, or paste that has set (now a static boundary
  // particle, cure.rigid). What the filling's assessment and the pictures count as paste.
  bool is_paste(std::uint32_t i) const { return role[i] == Role::material || cure.rigid[id[i]]; }

  // Appends particles (between steps only); tool particles are placed at tool_pose. Sizes every
  // buffer, the bond store and the grid scratch for `model`. Each particle's material is the
  // table entry its material_index names, else the entry with its values: with a const Model,
  // std::invalid_argument when there is none (nothing added); with a Model it may grow, the
  // values are added to the table first (MaterialTable::intern).
  void add_particles(const Model& model, const std::vector<ParticleInit>& particles);
  void add_particles(Model& model, const std::vector<ParticleInit>& particles);
  // Rewrites the cache mu, Kp, rho0, Ka of every particle from model.materials (and the cure's
  // parameters where kCuredMaterial is set): after an edit of the table, between steps.
  void refresh_materials(const Model& model);
  // Removes (between steps) the particles whose current index has remove[i] != 0. Ids stay
  // dense: the kept particles are renumbered in their id order; bonds between kept particles
  // survive, bonds to removed ones are dropped (not counted as broken).
  void remove_particles(const Model& model, const std::vector<std::uint8_t>& remove);
  // Number of particles of each role.
  std::uint32_t count(Role r) const;
  // Bonded pairs now. A pair of moving particles is in both lists, a bond to a boundary particle
  // only in the moving particle's list (boundary particles keep none).
  std::uint64_t bonded_pairs() const;
  // Bytes held per particle by every per-particle array, the bond store and the scratch
  // (the grid's per-cell arrays, which depend on the domain, not the particles, excluded).
  std::size_t bytes_per_particle() const;

 private:
  // Sizes index_of_id, the bond store and the scratch for n particles (after adding or removing).
  void size_by_id_and_scratch(const Model& model, std::uint32_t n);
};

}  // namespace dentsph
