// load_mesh(): STL, OBJ and PLY through assimp, then repair_mesh(). Assimp triangulates and
// joins exactly identical vertices; it keeps vertices that differ only in their normals apart
// (every STL corner carries its face's normal), so repair_mesh() merges by position itself.
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include <assimp/Importer.hpp>
#include <fstream>
#include <system_error>

#include "dentsph/tooth.hpp"

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
      for (unsigned k = 0; k < face.mNumIndices; ++k)
        if (face.mIndices[k] >= mesh->mNumVertices)
          throw MeshError(fmt::format("{}: face {} refers to vertex {} of {}; the file is damaged: export it again",
                                      name, f, face.mIndices[k], mesh->mNumVertices));
    }
  }
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
  if (std::filesystem::file_size(file, ec) == 0)
    throw MeshError(fmt::format("{}: is empty (0 bytes); export the mesh again", name));

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
