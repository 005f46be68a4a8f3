// load_mesh(): STL, OBJ and PLY through assimp, then repair_mesh(). Assimp triangulates and
// joins exactly identical vertices; it keeps vertices that differ only in their normals apart
// (every STL corner carries its face's normal), so repair_mesh() merges by position itself.
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>
#include <system_error>
#include <vector>

#include "dentsph/limits.hpp"
#include "dentsph/tooth.hpp"
#include "ply_check.hpp"

namespace dentsph {

namespace {

// Every face of the file names vertices it has (assimp's validation says so too; this check does
// not depend on which of its steps ran).
void check_face_indices(const aiScene& scene, const std::string& name) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh* mesh = scene.mMeshes[m];
    if (!mesh || (mesh->mNumFaces > 0 && !mesh->mFaces) || (mesh->mNumVertices > 0 && !mesh->mVertices))
      throw MeshError(fmt::format("{}: mesh {} is incomplete; the file is damaged: export it again", name, m));
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      // A face of no vertex (a PLY face list of length 0) passes assimp's validation and then
      // aborts its triangulation (an assertion in TriangulateProcess: found by fuzz_mesh).
      if (face.mNumIndices == 0 || (face.mNumIndices > 0 && !face.mIndices))
        throw MeshError(fmt::format("{}: face {} has no vertices; the file is damaged: export it again", name, f));
      for (unsigned k = 0; k < face.mNumIndices; ++k)
        if (face.mIndices[k] >= mesh->mNumVertices)
          throw MeshError(fmt::format("{}: face {} refers to vertex {} of {}; the file is damaged: export it again",
                                      name, f, face.mIndices[k], mesh->mNumVertices));
    }
  }
}

// An OBJ file is text whose face lines name vertices it has: assimp 5.2's OBJ importer freed memory
// twice on a face line of garbage indices (" f444444444", found by fuzz_mesh: heap corruption
// inside assimp, before anything is handed back to be checked), so the file is read here first:
// text, every statement one this knows by its full name (assimp goes by the first letter), and
// every face's vertices `i`, `i/t`, `i//n` or `i/t/n` with i a vertex defined before it (1-based,
// or negative: counted back from the last).
// Returns the triangles its faces make (a face of k corners, k - 2).
std::uint64_t check_obj_text(const std::filesystem::path& file, const std::string& name) {
  std::ifstream in(file, std::ios::binary);
  std::string line;
  long long vertices = 0, number = 0;
  std::uint64_t triangles = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    for (const unsigned char c : line)
      if (c < 0x20 && c != '\t')
        throw MeshError(fmt::format("{}: line {} is not text (byte {:#04x}); an OBJ file is text: export it again",
                                    name, number, int(c)));
    std::istringstream words(line);
    std::string word;
    if (!(words >> word) || word[0] == '#') continue;
    // Assimp takes a line by its first letter ("f444" is a face): every statement is named in full.
    static const char* const known[] = {"v", "vt", "vn", "vp", "f", "l", "p", "o", "g", "s", "usemtl", "mtllib"};
    if (std::find(std::begin(known), std::end(known), word) == std::end(known))
      throw MeshError(fmt::format("{}: line {} begins with \"{}\", not an OBJ statement this reads (v, vt, vn, "
                                  "f, l, p, o, g, s, usemtl, mtllib, #); export the mesh again",
                                  name, number, word.size() > 40 ? word.substr(0, 40) + "..." : word));
    if (word == "v") {
      ++vertices;
    } else if (word == "f" || word == "l" || word == "p") {
      std::string corner;
      std::uint64_t corners = 0;
      while (words >> corner) {
        ++corners;
        std::size_t used = 0;
        long long index = 0;
        try {
          index = std::stoll(corner, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        const bool rest_ok = used > 0 && (used == corner.size() || corner[used] == '/') &&
                             corner.find_first_not_of("0123456789/-", used) == std::string::npos;
        const long long at = index < 0 ? vertices + index + 1 : index;
        if (!rest_ok || index == 0 || at < 1 || at > vertices)
          throw MeshError(fmt::format("{}: line {}: \"{}\" names no vertex of the {} defined before it; the file "
                                      "is damaged: export it again",
                                      name, number, corner.size() > 40 ? corner.substr(0, 40) + "..." : corner,
                                      vertices));
      }
      if (word == "f" && corners > 2) triangles += corners - 2;
    }
  }
  return triangles;
}

// The triangles of an STL file: a binary one's count, where its size is the count's (84 + 50 n
// bytes), else an ASCII one's facets, counted by their "endfacet".
std::uint64_t stl_triangles(const std::filesystem::path& file, std::uintmax_t size) {
  std::ifstream in(file, std::ios::binary);
  char head[84] = {};
  in.read(head, sizeof head);
  if (in.gcount() == 84) {
    std::uint32_t n = 0;
    std::memcpy(&n, head + 80, 4);
    if (size == 84 + 50 * std::uintmax_t(n)) return n;
  }
  in.clear();
  in.seekg(0);
  static constexpr std::string_view word = "endfacet";
  // Read in chunks, each after the last one's final 7 characters: a word the chunk's end cut is
  // found whole in the next (7 characters cannot hold one whole).
  std::string chunk;
  std::uint64_t facets = 0;
  for (;;) {
    const std::size_t keep = std::min(chunk.size(), word.size() - 1);
    chunk.erase(0, chunk.size() - keep);
    chunk.resize(keep + (1 << 20));
    in.read(chunk.data() + keep, std::streamsize(chunk.size() - keep));
    if (in.gcount() <= 0) break;
    chunk.resize(keep + std::size_t(in.gcount()));
    for (std::size_t at = chunk.find(word); at != std::string::npos; at = chunk.find(word, at + word.size())) ++facets;
  }
  return facets;
}

// Refuses a mesh of more triangles than the limit, or than the memory its loading takes allows,
// before assimp reads it.
void check_mesh_size(const std::string& name, std::uint64_t triangles) {
  if (triangles > limits::max_mesh_triangles)
    throw MeshError(fmt::format("{}: holds {} triangles, more than the {} a tooth mesh may have (README, \"Resource "
                                "limits\"; a CBCT molar has about 44,000); decimate it (e.g. MeshLab's Quadric Edge "
                                "Collapse Decimation) and load it again",
                                name, triangles, limits::max_mesh_triangles));
  const std::uint64_t need = triangles * limits::mesh_bytes_per_triangle, limit = limits::memory_limit_bytes();
  if (need > limit)
    throw MeshError(fmt::format("{}: its {} triangles take about {} MB to load, more than the {} MB this run may use "
                                "(the machine's memory, ulimit -v, DENTSPH_MEMORY_LIMIT_MB); decimate it or allow "
                                "more memory",
                                name, triangles, need >> 20, limit >> 20));
}

}  // namespace

LoadedMesh load_mesh(const std::filesystem::path& file, MeshUnits units) {
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::exists(file, ec))
    throw MeshError(
        fmt::format("{}: no such file; check the path (a relative path starts at "
                    "the working directory, {})",
                    name, std::filesystem::current_path(ec).string()));
  if (std::filesystem::is_directory(file, ec))
    throw MeshError(fmt::format("{}: is a folder; name a mesh file (.stl, .obj or .ply)", name));
  if (!std::ifstream(file, std::ios::binary))
    throw MeshError(fmt::format("{}: cannot be opened for reading; check its permissions", name));
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (size == 0) throw MeshError(fmt::format("{}: is empty (0 bytes); export the mesh again", name));
  // STL, OBJ and PLY only: assimp reads dozens of formats, each an importer to trust.
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".stl" && ext != ".obj" && ext != ".ply")
    throw MeshError(fmt::format("{}: is not an STL, OBJ or PLY file (by its name); save it as one, with its extension",
                                name));
  const std::uint64_t ply_faces = check_ply(file, name, size);
  check_mesh_size(name, ext == ".obj" ? check_obj_text(file, name) : ext == ".stl" ? stl_triangles(file, size) : ply_faces);

  Assimp::Importer importer;
  // Read first with no processing but assimp's own validation, which refuses a face that names a
  // vertex the file does not have (the later steps would index past the vertex array: a crash or
  // a garbage vertex); then the processing. Points and lines are split off (SortByPType) and
  // ignored: only triangles bound a solid.
  const aiScene* scene = importer.ReadFile(name, aiProcess_ValidateDataStructure);
  const std::string why = importer.GetErrorString();
  if (!scene && why.find("Validation failed") != std::string::npos)
    throw MeshError(fmt::format("{}: is damaged ({}); export it again", name, why));
  if (!scene || !scene->mRootNode)
    throw MeshError(
        fmt::format("{}: cannot be read as a mesh ({}); save it as STL (binary or "
                    "ASCII), OBJ or PLY",
                    name, importer.GetErrorString()));
  check_face_indices(*scene, name);
  scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                       aiProcess_SortByPType | aiProcess_PreTransformVertices);
  if (!scene || !scene->mRootNode)
    throw MeshError(fmt::format("{}: cannot be processed as a mesh ({}); save it as STL (binary or ASCII), OBJ or PLY",
                                name, importer.GetErrorString()));

  const real scale = units == MeshUnits::millimetres ? 1e-3 : 1.0;
  TriMesh soup;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const auto base = std::uint32_t(soup.vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      soup.vertices.push_back(Vec3{real(p.x), real(p.y), real(p.z)} * scale);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;
      soup.triangles.push_back(
          {base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
    }
  }
  if (soup.triangles.empty())
    throw MeshError(
        fmt::format("{}: holds no triangles (only points or lines, or nothing); "
                    "export the tooth as a triangle surface",
                    name));
  return repair_mesh(std::move(soup), name);
}

}  // namespace dentsph
