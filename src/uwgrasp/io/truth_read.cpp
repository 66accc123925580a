// truth.yaml reading (INTERFACE.md): a scene file with the camera that saw it and the sensor.
#include <filesystem>

#include "uwgrasp/io/scene_yaml.hpp"
#include "uwgrasp/io/yaml_reader.hpp"

namespace uwgrasp::io {

namespace {
namespace fs = std::filesystem;
using yaml::Ctx;

// truth.yaml's camera block: its pose in W, intrinsics and range.
void truth_camera(const Ctx& c, const YAML::Node& n, TruthInfo& t) {
  if (!n) c.fail("camera", "missing (the camera that saw the scene)");
  c.keys(n, "camera", {"world_from_camera", "intrinsics", "min_range", "max_range", "baseline"});
  const auto need = [&](const YAML::Node& m, const char* key, const std::string& path) {
    if (!m[key]) c.fail(path + "." + key, "missing");
    return m[key];
  };
  t.world_from_camera = c.pose(need(n, "world_from_camera", "camera"), "camera.world_from_camera");
  const YAML::Node k = need(n, "intrinsics", "camera");
  c.keys(k, "camera.intrinsics", {"width", "height", "fx", "fy", "cx", "cy"});
  const auto num = [&](const char* key, double lo, double hi) {
    return c.num(need(k, key, "camera.intrinsics"), std::string("camera.intrinsics.") + key, lo, hi);
  };
  t.intrinsics.width = int(num("width", 1, 1e5)), t.intrinsics.height = int(num("height", 1, 1e5));
  t.intrinsics.fx = num("fx", 1e-6, 1e9), t.intrinsics.fy = num("fy", 1e-6, 1e9);
  t.intrinsics.cx = num("cx", -1e6, 1e6), t.intrinsics.cy = num("cy", -1e6, 1e6);
  t.camera.width = std::uint32_t(t.intrinsics.width), t.camera.height = std::uint32_t(t.intrinsics.height);
  if (n["min_range"]) t.camera.min_range = c.num(n["min_range"], "camera.min_range", 0, 1e4);
  if (n["max_range"]) t.camera.max_range = c.num(n["max_range"], "camera.max_range", 1e-6, 1e4);
  if (n["baseline"]) t.camera.baseline = c.num(n["baseline"], "camera.baseline", 0, 1e3);
}

// Every mesh part's file must exist: named by its key path, before any geometry is built.
void require_mesh_files(const Ctx& c, const sim::Scene& s) {
  for (std::size_t i = 0; i < s.objects.size(); ++i)
    for (std::size_t p = 0; p < s.objects[i].parts.size(); ++p) {
      const sim::Shape& shape = s.objects[i].parts[p].shape;
      std::error_code ec;
      if (shape.kind == sim::ShapeKind::mesh && !fs::is_regular_file(shape.file, ec))
        c.fail("objects[" + std::to_string(i) + "].parts[" + std::to_string(p) + "].file",
               shape.file + ": mesh file not found");
    }
}
}  // namespace

Truth load_truth(const std::string& path) {
  const std::string text = yaml::read_file(path, "truth file");
  return yaml::refusing_yaml_errors(path, [&] {
    Truth t;
    t.scene = parse_scene(text, path, fs::path(path).parent_path().string());
    const Ctx c{path, fs::path(path).parent_path().string()};
    const YAML::Node root = yaml::load_yaml(text, path);
    truth_camera(c, root["camera"], t.info);
    require_mesh_files(c, t.scene);
    if (root["sensor"]) t.info.sensor = c.text(root["sensor"], "sensor");
    return t;
  });
}

}  // namespace uwgrasp::io
