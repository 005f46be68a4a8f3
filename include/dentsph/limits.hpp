// The largest things a run accepts (docs/limits.md). Every input that could make a
// run take unbounded time or memory is checked against one of these before the work starts, and
// refused with the field that asks for it and the fix; the checks share these numbers and the
// functions below, so that a scene file, a procedure file, the command line and the library say
// the same.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "dentsph/vec3.hpp"

namespace dentsph::limits {

// ---- particles and memory -----------------------------------------------------------------------

// Particles the simulation holds at once: every block, the tool and every increment and
// instrument a scene's events bring (about 1 KB each in the state: 10 GiB).
inline constexpr std::uint64_t max_particles = 10'000'000;
// Particles one block of a scene file may produce.
inline constexpr std::uint64_t max_block_points = max_particles;
// Particles a scene holds as it is read: the simulation's, and every event's particles, which for
// a procedure file's increment are all its candidate sites (a few thousand each).
inline constexpr std::uint64_t max_held_particles = 20'000'000;
// Events (dispense, switch_tool) of one scene or procedure file.
inline constexpr std::size_t max_events = 1000;
// The memory a scene may need (its particles as read and the simulation's state), in bytes; and
// never more than the machine's physical memory.
inline constexpr std::uint64_t max_scene_bytes = std::uint64_t(16) << 30;  // 16 GiB
// Cells of the neighbour grid: a larger domain gets larger cells (the grid wraps beyond; this
// costs time, never correctness), so no domain is refused for its size.
inline constexpr std::int64_t max_grid_cells = std::int64_t(1) << 22;

// ---- meshes -------------------------------------------------------------------------------------

// Triangles of a tooth mesh (--mesh, a scene's tooth.mesh): the CBCT molars of ../shared/data have
// about 44,000; 2 million took 2.4 GB and 23 s to load and repair.
inline constexpr std::uint64_t max_mesh_triangles = 1'000'000;
// Bytes loading and repairing a mesh may take per triangle at its peak (assimp's scene, the soup,
// the repaired mesh), checked against memory_limit_bytes(): 2 million triangles were reported at
// 2.4 GB; measured here, a closed 1-million-triangle STL peaked at 630 MB resident against 44 MB
// for 10,000 triangles (0.6 KB a triangle), so this bound is twice that.
inline constexpr std::uint64_t mesh_bytes_per_triangle = 1200;

// ---- lattices -----------------------------------------------------------------------------------

// A lattice's spacing is at least h / 10 (about 4200 neighbours within h; finer lattices make
// the particle mass sum and every step's neighbour search run for hours) and at most h.
inline constexpr real min_spacing_per_h = 0.1;

// ---- forces and masses -----------------------------------------------------------------------------

// The largest gravity, m/s^2 (about 100 g: a centrifuge's, not a clinic's); beyond it the first step's
// speeds overflow the limits' arithmetic (1e308 made every particle NaN).
inline constexpr real max_gravity = 1e3;
// A block's given particle mass: within this factor of the lattice mass either way (5e-324 kg, a
// denormal, made 1 / m infinite).
inline constexpr real max_mass_factor = 1e6;

// ---- time ---------------------------------------------------------------------------------------

// The smallest time step, s.
inline constexpr real min_dt = 1e-9;
// The most steps of one offline run (--steps, --duration / dt, run.duration / dt, a procedure's
// duration / dt): 28 hours at 1000 steps/s.
inline constexpr std::uint64_t max_run_steps = 100'000'000;
// The longest realtime run, wall seconds (--realtime --duration; a run without one stops here).
inline constexpr double max_realtime_s = 3600;
// Steps a realtime run records (the tool pose and force of each, 96 bytes): the run ends here.
inline constexpr std::uint64_t max_recorded_steps = 20'000'000;

// ---- increments on request (the device's button 1, the viewer's D key) ---------------------------

// Presses of the device's button 1 counted in any one second (more are refused and counted).
inline constexpr int max_dispense_presses_per_s = 4;
// Presses of the device's button 2 (the curing light on or off) counted in any one second.
inline constexpr int max_light_presses_per_s = 4;
// The paste an increment may bring the scene to, in cavity volumes (a tooth's cavity holds one;
// without a tooth: the grid domain's volume).
inline constexpr real max_material_per_cavity = 2;

// ---- files read back ----------------------------------------------------------------------------

// A file larger than the program writes is not its file, and reading it would take the machine's
// memory (a 300 MB summary.json made a 944 MB report using 2.2 GB); each is refused, before it is
// read, at these sizes.
// A run's session folder, as `report` reads it: a summary of about 10 KB, pictures of a few
// hundred KB, a force log of about 100 bytes a step (1 GB: a run of 10 million steps).
inline constexpr std::uint64_t max_session_json_bytes = std::uint64_t(16) << 20;
inline constexpr std::uint64_t max_session_picture_bytes = std::uint64_t(64) << 20;
inline constexpr std::uint64_t max_session_csv_bytes = std::uint64_t(1) << 30;
// A realtime session's recording, as `replay` reads it: haptic.csv, at most 600 bytes a tick (23
// numbers), for 120 s of ticks (the runtime's recording capacity) at the 4 kHz it allows, 288 MB;
// steps.csv, at most 320 bytes a step (12 numbers), for max_recorded_steps, so that every
// recording the runtime writes is read back; session.json, under a kilobyte.
inline constexpr std::uint64_t max_recording_haptic_bytes = std::uint64_t(512) << 20;
inline constexpr std::uint64_t max_recording_steps_bytes = max_recorded_steps * 320;
inline constexpr std::uint64_t max_recording_json_bytes = std::uint64_t(1) << 20;
// The most haptic ticks a realtime run records (RealtimeOptions::record_capacity_s times its rate),
// so that its haptic.csv, at most 600 bytes a tick, stays under what `replay` reads.
inline constexpr std::uint64_t max_recorded_ticks = max_recording_haptic_bytes / 600;

// ---- shared checks: "" when fine, else the problem (the caller adds the field and the fix) -----

// A file of more than `limit_bytes`: "FILE: N MB, more than the L MB WHAT can be (README, "Resource
// limits")", else "" (also when its size cannot be read: opening it says why).
std::string file_size_problem(const std::string& file, std::uint64_t limit_bytes, const char* what);

// A lattice spacing (m) for a kernel of support h (m): finite, within [h * min_spacing_per_h, h];
// the message in `unit`, of `scale` m per unit.
std::string spacing_problem(real spacing, real h, const char* unit = "m", real scale = 1);
// The fix for a refused spacing, in `unit` with `scale` m per unit ("m", 1 or "mm", 1e-3).
std::string spacing_fix(real h, const char* unit = "m", real scale = 1);

// A run of `duration` s of simulated time in steps of dt: at most max_run_steps.
std::string run_length_problem(real duration, real dt);
// The steps of such a run (duration / dt rounded), or max_run_steps + 1 when over the limit.
std::uint64_t run_steps(real duration, real dt);

// Bytes the simulation's state takes per particle (every per-particle array, the bond lists of
// `max_bonds` each, the neighbour lists, with the skin's copies when `skin`, the iisph solver's
// scratch), an upper estimate for either solver.
std::uint64_t state_bytes_per_particle(int max_bonds, bool skin);
// The memory a scene needs: `held` particles as read and `simulated` in the state.
std::uint64_t scene_bytes(std::uint64_t held, std::uint64_t simulated, int max_bonds, bool skin);
// The memory a scene may take: max_scene_bytes, or the machine's physical memory when less, or
// three quarters of the process's address-space limit (ulimit -v) when less, or the environment's
// DENTSPH_MEMORY_LIMIT_MB (megabytes) when less.
std::uint64_t memory_limit_bytes();
// "" when a scene of `held` and `simulated` particles fits in `limit_bytes`, else the problem.
std::string memory_problem(std::uint64_t held, std::uint64_t simulated, int max_bonds, bool skin,
                           std::uint64_t limit_bytes);

}  // namespace dentsph::limits
