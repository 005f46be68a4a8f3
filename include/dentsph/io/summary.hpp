// summary.json and tool_force.csv of a run (docs/outputs.md).
#pragma once

#include <cstdio>
#include <filesystem>
#include <string>

#include "dentsph/run.hpp"

namespace dentsph::io {

// The summary as JSON text (keys: steps, sim_time_s, wall_time_s, steps_per_second, particles,
// bonds, stability, tool, status).
std::string summary_json(const RunSummary& s);
void write_summary(const std::filesystem::path& file, const RunSummary& s);

// tool_force.csv: columns t,fx,fy,fz,tx,ty,tz, one row per step (N and N m).
class ToolForceCsv {
 public:
  explicit ToolForceCsv(const std::filesystem::path& file);
  ~ToolForceCsv();
  ToolForceCsv(const ToolForceCsv&) = delete;
  ToolForceCsv& operator=(const ToolForceCsv&) = delete;
  void add(real t, const ToolWrench& w);

 private:
  std::FILE* f_ = nullptr;
};

}  // namespace dentsph::io
