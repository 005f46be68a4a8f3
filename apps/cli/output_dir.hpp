// The output folder of `dentsph run --out DIR`, made and checked before a run starts, so that a
// run whose outputs cannot be written is refused at once instead of losing them at its end.
#pragma once

#include <filesystem>
#include <string_view>

namespace dentsph::cli {

// Creates `dir` and each of `subdirs` in it, and writes and removes a file there. Throws
// std::invalid_argument naming `option`, the folder and the reason: an empty path, a file in the
// way, a folder that cannot be created or written.
void prepare_output_dir(const std::filesystem::path& dir, std::string_view option,
                        std::initializer_list<std::string_view> subdirs = {});

}  // namespace dentsph::cli
