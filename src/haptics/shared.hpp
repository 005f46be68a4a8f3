// What the runtime's threads share: the triple buffers between them and the stop flag. The
// haptic thread only ever touches these, its device and its own objects, never the State.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "haptics/exchange.hpp"
#include "haptics/messages.hpp"

namespace dentsph::haptics {

// Particle positions for the consumer, preallocated (positions.size() is the capacity).
struct Snapshot {
  std::vector<Vec3> positions;
  std::uint32_t count = 0;
  double sim_time = 0;
  std::int64_t published_ns = 0;
  std::uint64_t step = 0;
};

struct RuntimeShared {
  RuntimeShared(const Snapshot& empty_snapshot, const ContactWorld& world, const RigidInput& rigid)
      : snapshots(empty_snapshot), contact(world), rigid(rigid) {}
  TripleBuffer<ToolCommand> command;  // haptic -> simulation
  TripleBuffer<SimOutput> output;     // simulation -> haptic
  TripleBuffer<Snapshot> snapshots;   // simulation -> consumer
  TripleBuffer<ContactWorld> contact;   // contact loop -> haptic: the rigid surfaces and the instrument
  TripleBuffer<RigidInput> rigid;       // simulation -> contact loop: what is rigid, the instrument
  std::atomic<bool> stop{false};
  std::atomic<bool> device_finished{false};
};

}  // namespace dentsph::haptics
