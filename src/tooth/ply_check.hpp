// The checks a PLY file passes before assimp reads it (mesh_load.cpp): its header, and its body
// (ASCII or binary) against what the header declares.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace dentsph {

// Throws MeshError, naming the file as `name` and the line, when a file that begins with "ply"
// (or is named .ply) is not a complete, well-formed PLY file. Returns the count its header gives
// the element "face" (each face at least a triangle), 0 for other files.
std::uint64_t check_ply(const std::filesystem::path& file, const std::string& name, std::uintmax_t size);

}  // namespace dentsph
