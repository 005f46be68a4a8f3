// `dentsph material-test`: virtual material tests. depth-of-cure: the ISO 4049 depth of cure of a
// cure preset (include/dentsph/depth_of_cure.hpp); rheometer, slump, packing, tack and
// condensation: the paste presets' handling tests (include/dentsph/handling.hpp), each figure beside its published range.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "dentsph/depth_of_cure.hpp"

namespace dentsph::cli {

class MaterialTestCommand {
 public:
  // Adds the "material-test" subcommand (with "depth-of-cure" and the handling tests) to `app`.
  void add_to(CLI::App& app);
  // Whether the command line chose it.
  bool chosen() const;
  // Runs it: prints the report (and with --out writes result.json and the plots); exit status 0.
  // Throws std::invalid_argument for a refused option (an output folder that cannot be written).
  int run() const;

 private:
  // The options of a handling test's subcommand.
  struct Handling {
    std::string name;  // one of handling_test_names()
    CLI::App* command = nullptr;
    std::string material = "universal";
    double temperature_c = 23;
    std::string out{};
    std::string instrument = "steel";
    int threads = 1;
    std::vector<double> shear_rates{};  // rheometer: 1/s at the rim (empty: RheometerOptions')
  };
  void add_handling(CLI::App& parent, const std::string& description, Handling& h);
  int run_handling(const Handling& h) const;

  CLI::App* command_ = nullptr;
  CLI::App* depth_of_cure_ = nullptr;
  DepthOfCureOptions options_;
  double irradiance_mw_ = 1000, spacing_mm_ = 0.1, length_mm_ = 10;
  std::array<Handling, 5> handling_{
      {{"rheometer"}, {"slump"}, {"packing"}, {"tack"}, {"condensation", nullptr, "amalgam"}}};
};

}  // namespace dentsph::cli
