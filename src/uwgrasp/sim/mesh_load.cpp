// Mesh files through assimp (ARCHITECTURE.md: sim/ depends on assimp).
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cmath>
#include <filesystem>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/sim/mesh.hpp"

namespace uwgrasp::sim {

Mesh load_mesh(const std::string& path, double scale) {
  if (!(scale > 0.0) || !std::isfinite(scale))
    throw Error(path + ": mesh scale must be a positive number");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path + ": mesh file not found");
  Assimp::Importer importer;
  // PreTransformVertices bakes every node's transform (and the COLLADA unit) into the vertices.
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices |
                aiProcess_SortByPType);
  if (scene == nullptr || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0)
    throw Error(path + ": cannot read mesh: " + importer.GetErrorString());
  Mesh out;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      out.vertices.emplace_back(static_cast<float>(p.x * scale), static_cast<float>(p.y * scale),
                                static_cast<float>(p.z * scale));
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines carry no surface
      out.triangles.push_back(
          {base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
    }
  }
  if (out.triangles.empty()) throw Error(path + ": mesh has no triangles");
  for (const auto& v : out.vertices)
    if (!v.allFinite()) throw Error(path + ": mesh has a non-finite vertex");
  return out;
}

}  // namespace uwgrasp::sim
