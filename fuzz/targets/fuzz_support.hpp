// What the fuzz targets share: a private temporary folder per process, files written into it.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace dentsph::fuzz {

inline const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path d = [] {
    const std::filesystem::path p =
        std::filesystem::temp_directory_path() / ("dentsph_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(p);
    return p;
  }();
  return d;
}

inline void write_file(const std::filesystem::path& f, const std::uint8_t* data, std::size_t size) {
  std::ofstream out(f, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
}

inline std::string text_of(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace dentsph::fuzz
