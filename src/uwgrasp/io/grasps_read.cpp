// Reading one grasp back from grasps.json (for `uwgrasp approach`).
#include <cmath>
#include <fstream>
#include <algorithm>
#include <sstream>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/grasps_json.hpp"

namespace uwgrasp::io {

namespace {
using nlohmann::json;

struct Reader {
  std::string file;
  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw Error(file + ": " + field + ": " + what);
  }
  const json& at(const json& j, const char* key, const std::string& field) const {
    if (!j.is_object() || !j.contains(key)) fail(field, "missing");
    return j.at(key);
  }
  Eigen::VectorXd numbers(const json& j, std::size_t n, const std::string& field) const {
    if (!j.is_array() || j.size() != n) fail(field, "expected " + std::to_string(n) + " numbers");
    Eigen::VectorXd v(static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i) {
      if (!j[i].is_number() || !std::isfinite(j[i].get<double>())) fail(field, "expected finite numbers");
      v[static_cast<Eigen::Index>(i)] = j[i].get<double>();
    }
    return v;
  }
  Pose pose(const json& j, const std::string& field, bool unit = false) const {
    const Eigen::VectorXd t = numbers(at(j, "position", field + ".position"), 3, field + ".position");
    const Eigen::VectorXd q = numbers(at(j, "orientation_xyzw", field + ".orientation_xyzw"), 4,
                                      field + ".orientation_xyzw");
    if (q.norm() < 1e-9) fail(field + ".orientation_xyzw", "is not a rotation (zero quaternion)");
    // Written quaternions carry at least six digits; a norm off by more is not a rotation.
    if (unit && std::abs(q.norm() - 1.0) > 1e-3)
      fail(field + ".orientation_xyzw", "is not a unit quaternion (norm " + std::to_string(q.norm()) + ")");
    return make_pose(t, Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized());
  }
  double number(const json& j, const char* key, const std::string& field) const {
    const json& v = at(j, key, field + "." + key);
    if (!v.is_number() || !std::isfinite(v.get<double>())) fail(field + "." + key, "expected a finite number");
    return v.get<double>();
  }
};

json load(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw Error(path + ": cannot open");
  try {
    return json::parse(f);
  } catch (const json::exception& e) {
    throw Error(path + ": not valid JSON (" + std::string(e.what()) + ")");
  }
}

// The detection entry: the file itself, or one of a demo file's objects.
const json& entry(const json& root, const std::string& object, const Reader& r, std::string& name) {
  if (!root.is_object()) r.fail("(top level)", "expected an object");
  if (!root.contains("objects")) {
    if (!object.empty()) r.fail("objects", "not a demo file, so --object does not apply");
    return root;
  }
  const json& objects = root.at("objects");
  if (!objects.is_array() || objects.empty()) r.fail("objects", "expected a non-empty list");
  std::string names;
  for (const json& o : objects) {
    const std::string n = o.value("name", std::string());
    if (object.empty() || n == object) {
      name = n;
      return o;
    }
    names += (names.empty() ? "" : ", ") + n;
  }
  r.fail("objects", "no object named '" + object + "' (the file has " + names + ")");
}

// The gripper of a detection's config, through the validating config reader; other config
// sections (possibly another detector's) are not read.
grasp::GripperConfig file_gripper(const json& e, const std::string& path, bool& found) {
  found = e.is_object() && e.contains("config") && e["config"].is_object() &&
          e["config"].contains("grasp") && e["config"]["grasp"].is_object() &&
          e["config"]["grasp"].contains("gripper");
  if (!found) return {};
  const json sub = {{"grasp", {{"gripper", e["config"]["grasp"]["gripper"]}}}};
  return parse_config(sub.dump(), path + " (config)").grasp.gripper;
}
}  // namespace

GraspList read_grasp_list(const std::string& path, const std::string& object) {
  const Reader r{path};
  const json root = load(path);
  GraspList out;
  if (root.is_object() && root.contains("objects") && object.empty())
    r.fail("objects", "a demo file holds several objects; name one with --object");
  const json& e = entry(root, object, r, out.object);
  if (e.contains("frame")) {
    if (!e["frame"].is_string()) r.fail("frame", "expected a string");
    out.frame = e["frame"].get<std::string>();
    if (out.frame != "camera_optical" && out.frame != "world")
      r.fail("frame", "'" + out.frame + "' is neither camera_optical nor world");
  }
  out.gripper = file_gripper(e, path, out.gripper_from_file);
  const json& grasps = r.at(e, "grasps", "grasps");
  if (!grasps.is_array()) r.fail("grasps", "expected a list");
  for (std::size_t i = 0; i < grasps.size(); ++i) {
    const std::string field = "grasps[" + std::to_string(i) + "]";
    GraspList::Entry g;
    g.pose = r.pose(grasps[i], field, true);
    g.score = r.number(grasps[i], "score", field);
    g.rank = grasps[i].contains("rank") ? std::size_t(r.number(grasps[i], "rank", field)) : i + 1;
    out.grasps.push_back(g);
  }
  std::stable_sort(out.grasps.begin(), out.grasps.end(), [](const auto& a, const auto& b) {
    return a.score != b.score ? a.score > b.score : a.rank < b.rank;
  });
  return out;
}

GraspRecord read_grasp(const std::string& path, std::size_t rank, const std::string& object,
                       const std::vector<std::string>& sets) {
  const Reader r{path};
  const json root = load(path);
  GraspRecord g;
  g.rank = rank;
  const json& e = entry(root, object, r, g.object);
  const json& grasps = r.at(e, "grasps", "grasps");
  if (!grasps.is_array()) r.fail("grasps", "expected a list");
  if (rank < 1 || rank > grasps.size())
    r.fail("grasps", "rank " + std::to_string(rank) + " asked, the file has " +
                         std::to_string(grasps.size()) + " grasps");
  const json& x = grasps[rank - 1];
  const std::string field = "grasps[" + std::to_string(rank - 1) + "]";
  g.level_from_vehicle = r.pose(r.at(x, "vehicle_pose", field + ".vehicle_pose"), field + ".vehicle_pose");
  g.level_from_gripper = r.pose(r.at(x, "level", field + ".level"), field + ".level");
  const json& score = r.at(x, "score", field + ".score");
  g.score = score.is_number() ? score.get<double>() : 0.0;
  // JSON is YAML, so the embedded config goes through the same validating reader.
  g.config = parse_config(r.at(e, "config", "config").dump(), path + " (config)", sets);
  return g;
}

}  // namespace uwgrasp::io
