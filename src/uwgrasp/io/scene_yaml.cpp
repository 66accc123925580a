#include "uwgrasp/io/scene_yaml.hpp"

#include <filesystem>

#include "uwgrasp/io/yaml_reader.hpp"

namespace uwgrasp::io {

namespace {
namespace fs = std::filesystem;
using yaml::Ctx, yaml::load_yaml, yaml::read_file, yaml::refusing_yaml_errors;

sim::Shape shape(const Ctx& c, const YAML::Node& n, const std::string& path) {
  c.keys(n, path, {"shape", "size", "radius", "length", "major", "file", "scale", "pose", "checker"});
  if (!n["shape"]) c.fail(path, "missing key 'shape' (box, cylinder, sphere, torus, mesh)");
  const std::string kind = c.text(n["shape"], path + ".shape");
  sim::Shape s;
  const auto need = [&](const char* k) {
    if (!n[k]) c.fail(path, std::string("a ") + kind + " needs '" + k + "'");
    return n[k];
  };
  if (kind == "box") {
    s.kind = sim::ShapeKind::box;
    s.size = c.vec3(need("size"), path + ".size", 1e-4, 1e3);
  } else if (kind == "cylinder" || kind == "sphere" || kind == "torus") {
    s.kind = kind == "cylinder" ? sim::ShapeKind::cylinder
             : kind == "sphere" ? sim::ShapeKind::sphere : sim::ShapeKind::torus;
    s.radius = c.num(need("radius"), path + ".radius", 1e-4, 1e3);
    if (kind == "cylinder") s.length = c.num(need("length"), path + ".length", 1e-4, 1e3);
    if (kind == "torus") s.major = c.num(need("major"), path + ".major", 1e-4, 1e3);
    if (kind == "torus" && s.major <= s.radius) c.fail(path + ".major", "must exceed radius");
  } else if (kind == "mesh") {
    s.kind = sim::ShapeKind::mesh;
    const fs::path f = c.text(need("file"), path + ".file");
    s.file = (f.is_absolute() ? f : fs::path(c.base) / f).lexically_normal().string();
    if (n["scale"]) s.scale = c.num(n["scale"], path + ".scale", 1e-6, 1e6);
  } else {
    c.fail(path + ".shape", "unknown shape '" + kind + "' (box, cylinder, sphere, torus, mesh)");
  }
  return s;
}

sim::SceneObject object(const Ctx& c, const YAML::Node& n, const std::string& path) {
  c.keys(n, path, {"name", "label", "color", "interest", "pose", "parts"});
  sim::SceneObject o;
  if (!n["name"]) c.fail(path, "missing key 'name'");
  o.name = c.text(n["name"], path + ".name");
  if (n["color"]) o.color = c.color(n["color"], path + ".color");
  if (n["interest"]) o.interest = c.flag(n["interest"], path + ".interest");
  if (n["pose"]) o.pose = c.pose(n["pose"], path + ".pose");
  const YAML::Node parts = n["parts"];
  if (!parts || !parts.IsSequence() || parts.size() == 0) c.fail(path + ".parts", "expected a non-empty list");
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string p = path + ".parts[" + std::to_string(i) + "]";
    sim::Part part{shape(c, parts[i], p), Pose::Identity()};
    if (parts[i]["pose"]) part.pose = c.pose(parts[i]["pose"], p + ".pose");
    if (const YAML::Node k = parts[i]["checker"]) {
      c.keys(k, p + ".checker", {"cols", "rows", "square"});
      if (part.shape.kind != sim::ShapeKind::box) c.fail(p + ".checker", "only a box part carries a checkerboard");
      for (const char* key : {"cols", "rows", "square"})
        if (!k[key]) c.fail(p + ".checker." + key, "missing");
      part.shape.checker.cols = int(c.num(k["cols"], p + ".checker.cols", 2, 100));
      part.shape.checker.rows = int(c.num(k["rows"], p + ".checker.rows", 2, 100));
      part.shape.checker.square = c.num(k["square"], p + ".checker.square", 1e-4, 1.0);
    }
    o.parts.push_back(part);
  }
  return o;
}

sim::WaterConfig water(const Ctx& c, const YAML::Node& n, const std::string& path) {
  c.keys(n, path, {"preset", "attenuation", "veiling", "snow_density", "snow_radius", "snow_range"});
  sim::WaterConfig w;
  if (n["preset"]) {
    try {
      w = sim::water_preset(c.text(n["preset"], path + ".preset"));
    } catch (const Error& e) {
      c.fail(path + ".preset", e.what());
    }
  }
  if (n["attenuation"]) w.attenuation = c.vec3(n["attenuation"], path + ".attenuation", 0, 100);
  if (n["veiling"]) w.veiling = c.vec3(n["veiling"], path + ".veiling", 0, 1);
  if (n["snow_density"]) w.snow_density = c.num(n["snow_density"], path + ".snow_density", 0, 1e5);
  if (n["snow_radius"]) w.snow_radius = c.num(n["snow_radius"], path + ".snow_radius", 1e-5, 0.05);
  if (n["snow_range"]) w.snow_range = c.num(n["snow_range"], path + ".snow_range", 1e-3, 20);
  return w;
}

FlatPort port(const Ctx& c, const YAML::Node& n, const std::string& path) {
  c.keys(n, path, {"distance", "thickness", "n_air", "n_glass", "n_water"});
  FlatPort p;
  if (n["distance"]) p.distance = c.num(n["distance"], path + ".distance", 0, 10);
  if (n["thickness"]) p.thickness = c.num(n["thickness"], path + ".thickness", 0, 1);
  if (n["n_air"]) p.n_air = c.num(n["n_air"], path + ".n_air", 1, 3);
  if (n["n_glass"]) p.n_glass = c.num(n["n_glass"], path + ".n_glass", 1, 3);
  if (n["n_water"]) p.n_water = c.num(n["n_water"], path + ".n_water", 1, 3);
  return p;
}

void seafloor(const Ctx& c, const YAML::Node& n, sim::Seafloor& s) {
  c.keys(n, "seafloor", {"enabled", "size", "color", "texture"});
  if (n["enabled"]) s.enabled = c.flag(n["enabled"], "seafloor.enabled");
  if (n["size"]) s.size = c.num(n["size"], "seafloor.size", 0.01, 1e4);
  if (n["color"]) s.color = c.color(n["color"], "seafloor.color");
  if (n["texture"]) s.texture = c.num(n["texture"], "seafloor.texture", 0, 1);
}




sim::Scene parse_scene_yaml(const std::string& text, const std::string& source, const std::string& base) {
  const Ctx c{source, base};
  const YAML::Node root = load_yaml(text, source);
  // truth.yaml adds camera, noise, labels, sensor and seed: it stays a readable scene.
  c.keys(root, "", {"name", "seafloor", "vehicle", "camera_mount", "water", "port", "objects", "camera",
                    "noise", "labels", "sensor", "seed", "uwgrasp_version"});
  sim::Scene s;
  s.name = root["name"] ? c.text(root["name"], "name") : fs::path(source).stem().string();
  if (root["seafloor"]) seafloor(c, root["seafloor"], s.seafloor);
  if (root["vehicle"]) {
    const Pose p = c.pose(root["vehicle"], "vehicle");
    s.vehicle = {p.translation(), rpy_from_matrix(p.linear())};
  }
  if (root["camera_mount"]) s.camera_mount = c.mount(root["camera_mount"], "camera_mount");
  if (root["water"]) s.water = water(c, root["water"], "water");
  if (root["port"]) s.port = port(c, root["port"], "port");
  if (const YAML::Node objs = root["objects"]) {
    if (!objs.IsSequence()) c.fail("objects", "expected a list");
    for (std::size_t i = 0; i < objs.size(); ++i)
      s.objects.push_back(object(c, objs[i], "objects[" + std::to_string(i) + "]"));
  }
  try {
    sim::check_scene(s);
  } catch (const Error& e) {
    throw Error(source + ": " + e.what());
  }
  return s;
}
}  // namespace

sim::Scene parse_scene(const std::string& text, const std::string& source, const std::string& base) {
  return refusing_yaml_errors(source, [&] { return parse_scene_yaml(text, source, base); });
}

FlatPort load_port(const std::string& path) {
  return refusing_yaml_errors(path, [&] {
    const Ctx c{path, fs::path(path).parent_path().string()};
    const YAML::Node root = load_yaml(read_file(path, "port file"), path);
    if (!root.IsMap()) c.fail("", "expected distance, thickness, n_air, n_glass, n_water");
    return port(c, root, "port");
  });
}

sim::Scene load_scene(const std::string& name_or_path) {
  const fs::path p(name_or_path);
  const auto ext = p.extension().string();
  if (ext != ".yaml" && ext != ".yml") return sim::builtin_scene(name_or_path);
  return parse_scene(read_file(name_or_path, "scene file"), name_or_path, p.parent_path().string());
}


}  // namespace uwgrasp::io
