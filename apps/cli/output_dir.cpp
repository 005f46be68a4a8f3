#include "output_dir.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>

#include <fmt/format.h>

namespace dentsph::cli {

namespace {

[[noreturn]] void refuse(std::string_view option, const std::filesystem::path& dir, const std::string& why) {
  throw std::invalid_argument(fmt::format("{} {}: {}; give a folder that can be created and written (nothing was run)",
                                          option, dir.string(), why));
}

void make_dir(const std::filesystem::path& d, std::string_view option) {
  std::error_code ec;
  if (std::filesystem::exists(d, ec) && !std::filesystem::is_directory(d, ec))
    refuse(option, d, "is a file, not a folder");
  std::filesystem::create_directories(d, ec);
  if (ec) refuse(option, d, fmt::format("cannot create it: {}", ec.message()));
}

}  // namespace

void prepare_output_dir(const std::filesystem::path& dir, std::string_view option,
                        std::initializer_list<std::string_view> subdirs) {
  if (dir.empty()) refuse(option, "\"\"", "an empty path writes nothing");
  make_dir(dir, option);
  for (std::string_view sub : subdirs) make_dir(dir / sub, option);
  const std::filesystem::path probe = dir / fmt::format(".dentsph_write_check_{}", ::getpid());
  std::FILE* f = std::fopen(probe.c_str(), "w");
  const bool written = f != nullptr && std::fputs("ok\n", f) >= 0;
  const int err = errno;
  if (f != nullptr && std::fclose(f) != 0 && written) refuse(option, dir, "cannot write a file in it");
  std::error_code ec;
  std::filesystem::remove(probe, ec);
  if (!written) refuse(option, dir, fmt::format("cannot write a file in it: {}", std::strerror(err)));
}

}  // namespace dentsph::cli
