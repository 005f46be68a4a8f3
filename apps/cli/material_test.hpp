// `dentsph material-test`: virtual material tests. depth-of-cure: the ISO 4049 depth of cure of a
// cure preset (include/dentsph/depth_of_cure.hpp).
#pragma once

#include <CLI/CLI.hpp>

#include "dentsph/depth_of_cure.hpp"

namespace dentsph::cli {

class MaterialTestCommand {
 public:
  // Adds the "material-test" subcommand (with "depth-of-cure") to `app`.
  void add_to(CLI::App& app);
  // Whether the command line chose it.
  bool chosen() const;
  // Runs it: prints the report; exit status 0.
  int run() const;

 private:
  CLI::App* command_ = nullptr;
  CLI::App* depth_of_cure_ = nullptr;
  DepthOfCureOptions options_;
  double irradiance_mw_ = 1000, spacing_mm_ = 0.1, length_mm_ = 10;
};

}  // namespace dentsph::cli
