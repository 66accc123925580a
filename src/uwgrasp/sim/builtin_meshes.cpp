// Built-in scenes of real objects' meshes (../shared/data/meshes; not shipped with uwgrasp): the
// YCB sugar box and mustard bottle and three subsea intervention tools of uuv_simulator, each
// alone on the seafloor in three poses:
//   upright: longest side vertical, middle side across the camera's view;
//   lying:   shortest side vertical, longest across the view;
//   turned:  on its side (middle side vertical), turned 50 degrees about the vertical.
// The poses come from each mesh's bounding box alone, so no object is placed by hand.
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <numbers>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/sim/builtin_scenes.hpp"

namespace uwgrasp::sim {

namespace {
using V = Eigen::Vector3d;

struct MeshObject {
  const char* name;
  const char* file;  // under the data folder
};
constexpr MeshObject kMeshObjects[] = {
    {"sugar_box", "meshes/ycb/004_sugar_box_textured.obj"},
    {"mustard_bottle", "meshes/ycb/006_mustard_bottle_textured.obj"},
    {"t_bar", "meshes/uuv_simulator/t_bar_fork_tool/meshes/TBarForkTool.dae"},
    {"torque_tool", "meshes/uuv_simulator/torque_tool/meshes/TorqueTool.dae"},
    {"hot_stab", "meshes/uuv_simulator/hot_stab/meshes/HotStab.dae"},
};
constexpr const char* kPoses[] = {"upright", "lying", "turned"};

// The rotation taking the file's axes, sorted by extent, to the pose's world axes.
Eigen::Matrix3d pose_rotation(const V& extent, const std::string& pose) {
  std::array<int, 3> axis = {0, 1, 2};  // shortest, middle, longest
  std::sort(axis.begin(), axis.end(), [&](int a, int b) { return extent[a] < extent[b]; });
  // World x is along the built-in camera's view, y across it, z up.
  std::array<V, 3> to;  // world direction of the shortest, middle, longest side
  if (pose == "upright") to = {V::UnitX(), V::UnitY(), V::UnitZ()};
  else if (pose == "lying") to = {V::UnitZ(), V::UnitX(), V::UnitY()};
  else to = {V::UnitX(), V::UnitZ(), V::UnitY()};  // turned: on its side
  Eigen::Matrix3d R;
  for (int k = 0; k < 3; ++k) R.col(axis[std::size_t(k)]) = to[std::size_t(k)];
  if (R.determinant() < 0) R.col(axis[0]) = -R.col(axis[0]);  // a rotation, not a mirror
  if (pose == "turned") R = Eigen::AngleAxisd(50.0 * std::numbers::pi / 180.0, V::UnitZ()) * R;
  return R;
}
}  // namespace

std::string data_dir() {
  if (const char* env = std::getenv("UWGRASP_DATA"); env != nullptr && *env != '\0') return env;
  return UWGRASP_DEFAULT_DATA_DIR;
}

std::vector<std::string> mesh_scene_names() {
  std::vector<std::string> out;
  for (const auto& m : kMeshObjects)
    for (const char* p : kPoses) out.push_back(std::string(m.name) + (p == kPoses[0] ? "" : std::string("_") + p));
  return out;
}

std::optional<Scene> mesh_scene(const std::string& name) {
  for (const auto& m : kMeshObjects)
    for (const char* p : kPoses) {
      if (name != std::string(m.name) + (p == kPoses[0] ? "" : std::string("_") + p)) continue;
      const std::string file = (std::filesystem::path(data_dir()) / m.file).string();
      std::error_code ec;
      if (!std::filesystem::is_regular_file(file, ec))
        throw Error("scene " + name + " needs the mesh " + file +
                    " (set UWGRASP_DATA to the folder that holds meshes/)");
      const Mesh mesh = load_mesh(file);
      const auto [lo, hi] = bounds(mesh);
      const Eigen::Matrix3d R = pose_rotation((hi - lo).cast<double>(), p);
      Mesh placed = mesh;
      transform(placed, Pose(R));
      const auto [plo, phi] = bounds(placed);
      const V centre = 0.5 * (plo + phi).cast<double>();
      Pose pose = Pose::Identity();
      pose.linear() = R;
      pose.translation() = V(-centre.x(), -centre.y(), -double(plo.z()));  // resting on the seafloor
      SceneObject o{m.name, {{Shape{.kind = ShapeKind::mesh, .file = file}, Pose::Identity()}}, pose,
                    {210, 25, 25}, true};
      const V size = (phi - plo).cast<double>();
      const double distance = std::max(0.75, 2.0 * size.maxCoeff());
      return Scene{name, {o}, {}, looking_at(V(0, 0, 0.5 * size.z()), distance), tilted_camera()};
    }
  return std::nullopt;
}

}  // namespace uwgrasp::sim
