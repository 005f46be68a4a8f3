// The GPU backend's data, as plain structs of raw pointers ("views") that the stage bodies read and
// write. The same structs point at device memory in the CUDA build (cudaMalloc) and at host memory
// in the emulation (std::vector), so every stage body runs, and is tested, on the CPU too.
//
// Layout (docs/cuda.md): two sets of per-particle arrays take turns, one holding the particles in
// the order of the previous step (the sort's input), the other in this step's cell order; every
// stage after the reorder works on the sorted set in place. Bonds are kept by stable id, a fixed
// number of slots per particle, exactly as BondStore keeps them on the CPU.
#pragma once

#include <cstdint>

#include "dentsph/config.hpp"
#include "dentsph/model.hpp"
#include "dentsph/state.hpp"

namespace dentsph::gpu {

// One set of per-particle arrays, [n] each.
struct ParticleArrays {
  std::uint32_t* id = nullptr;  // stable id
  Role* role = nullptr;
  Vec3* pos = nullptr;          // m
  Vec3* vel = nullptr;          // m/s
  Vec3* anchor = nullptr;       // m, tool particles: position in the tool frame
  real* mass = nullptr;         // kg
  MaterialIndex* material = nullptr;  // State::material (carried for the host's cache; unread here)
  real* mu = nullptr;           // Pa s
  real* Kp = nullptr;           // m^2/s^2
  real* rho0 = nullptr;         // kg/m^3
  real* Ka = nullptr;           // Pa
};

// The tool pose a step moves the tool to, as a rigid transform p = R anchor + t (row-major R, from
// the pose's quaternion on the host), and the position the torque is taken about (the pose the
// tool particles are at when the step starts). Written by the host into pinned memory each step.
struct ToolInput {
  real R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  Vec3 t;         // m
  Vec3 applied;   // m, tool_pose_applied.position
};

// Per-block partial sums of the step's reductions (tool wrench, integration diagnostics).
struct StepSums {
  Vec3 force;                     // N
  Vec3 torque;                    // N m
  real a2max = 0;                 // (m/s^2)^2
  real v2max = 0;                 // (m/s)^2
  unsigned long long non_finite = 0;

  DENTSPH_HD void add(const StepSums& o) {
    force += o.force;
    torque += o.torque;
    a2max = a2max > o.a2max ? a2max : o.a2max;
    v2max = v2max > o.v2max ? v2max : o.v2max;
    non_finite += o.non_finite;
  }
};

// Bond events since the upload: formed, broken, overflowed (each counted as BondStore counts them).
struct BondEvents {
  unsigned long long formed = 0, broken = 0, overflowed = 0;
};

// What each step hands back to the host: one small copy into pinned memory.
struct StepOutput {
  StepSums sums;       // the tool wrench and the integration diagnostics of this step
  BondEvents events;   // cumulative since the upload
};

// Everything one step reads and writes. Passed by value to every kernel: the model's constants
// travel with it (no __constant__ state).
struct StepView {
  std::uint32_t n = 0;            // particles
  std::uint32_t buckets = 0;      // 2 * grid cells: moving and boundary bucket of each cell
  ParticleArrays src;             // the previous step's order: input of the reorder
  ParticleArrays p;               // this step's cell order: every stage after the reorder
  std::uint32_t* key = nullptr;          // [n] bucket of src particle i
  std::uint32_t* key_sorted = nullptr;   // [n] the keys in sorted order
  std::uint32_t* iota = nullptr;         // [n] 0, 1, ..., n - 1 (the sort's values)
  std::uint32_t* order = nullptr;        // [n] sorted position -> src index
  std::uint32_t* bucket_begin = nullptr; // [buckets] first sorted index of a bucket (0 if empty)
  std::uint32_t* bucket_end = nullptr;   // [buckets] one past its last (0 if empty); follows
                                         // bucket_begin in memory, so one memset clears both
  std::uint32_t* index_of_id = nullptr;  // [n] sorted index of each stable id
  real* rho = nullptr;            // [n] kg/m^3
  real* pressure = nullptr;       // [n] Pa
  real* volume = nullptr;         // [n] m^3, m / rho
  Vec3* force = nullptr;          // [n] N/m^3, internal force density
  real* rho_static = nullptr;     // [n] by id: boundary-boundary density of boundary particles
  std::uint32_t* bond_count = nullptr;    // [n] by id
  std::uint32_t* bond_partner = nullptr;  // [n * bond_capacity] by id, partner ids
  int bond_capacity = 0;
  BondEvents* events = nullptr;   // [1] cumulative bond events
  StepSums* partials = nullptr;   // [blocks of the reduction] per-block sums
  std::uint32_t partial_count = 0;
  const ToolInput* tool = nullptr;  // [1] this step's tool pose
  StepOutput* out = nullptr;      // [1] this step's output (then copied to the host)

  // Threads per block of the neighbour passes (launch shape only; the emulation ignores it).
  std::uint32_t neighbour_block = 64;

  // The model's constants the stages need.
  GridSpec grid;
  KernelCoeffs kernel;
  AdhesionParams adhesion;
  Vec3 gravity;
  real dt = 0;
};

// Threads per block of every kernel, and so the particles per partial sum of the reductions.
inline constexpr std::uint32_t kBlock = 256;

DENTSPH_HD inline constexpr std::uint32_t blocks_for(std::uint32_t n) { return (n + kBlock - 1) / kBlock; }

}  // namespace dentsph::gpu
