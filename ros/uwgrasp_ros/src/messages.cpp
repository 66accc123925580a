#include "messages.hpp"

#include <algorithm>
#include <limits>

#include "convert.hpp"

namespace uwgrasp_ros {

namespace {
// A geometry_msgs Point or Vector3 from three coordinates.
template <class Msg = geometry_msgs::Point, class T>
Msg xyz(const T& v) {
  Msg p;
  p.x = v[0], p.y = v[1], p.z = v[2];
  return p;
}
template <class T>
geometry_msgs::Point point(const T& v) { return xyz(v); }
geometry_msgs::Vector3 vector(const std::array<double, 3>& v) { return xyz<geometry_msgs::Vector3>(v); }

uwgrasp_msgs::Grasp grasp_msg(const PlainGrasp& g, std::size_t rank) {
  uwgrasp_msgs::Grasp m;
  m.rank = static_cast<std::uint32_t>(rank);
  m.pose = pose_msg(g.pose);
  m.approach = vector(g.approach);
  m.closing = vector(g.closing);
  m.width = g.width;
  for (int k = 0; k < 2; ++k) m.contacts[k] = point(g.contacts[k]), m.contact_seen[k] = g.contact_seen[k];
  m.inliers = g.inliers;
  m.score = g.score;
  m.score_normal = g.normal;
  m.score_orientation = g.orientation;
  m.score_contact_left = g.contact_left;
  m.score_contact_right = g.contact_right;
  m.score_inliers = g.inlier_score;
  m.score_vehicle = g.vehicle_score;
  m.antipodal = g.antipodal;
  m.mu_required = g.mu_required;
  m.robustness = g.robustness;
  m.force_closure = g.force_closure;
  m.hold_cost = g.hold_cost;
  m.vehicle_pose = pose_msg(g.vehicle_pose);
  m.vehicle_rpy = vector(g.vehicle_rpy);
  return m;
}

std_msgs::ColorRGBA colour(double t, float alpha) {  // t in [0, 1]: red, yellow, green
  std_msgs::ColorRGBA c;
  c.r = static_cast<float>(std::min(1.0, 2.0 * (1.0 - t)));
  c.g = static_cast<float>(std::min(1.0, 2.0 * t));
  c.b = 0.1f;
  c.a = alpha;
  return c;
}

visualization_msgs::Marker marker(const std_msgs::Header& h, const std::string& ns, int id, int type) {
  visualization_msgs::Marker m;
  m.header = h;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.pose.orientation.w = 1.0;
  return m;
}
}  // namespace

uwgrasp_msgs::GraspArray grasp_array(const PlainDetection& d, const std_msgs::Header& header) {
  uwgrasp_msgs::GraspArray m;
  m.header = header;
  m.sampler = d.sampler;
  m.points_in = static_cast<std::uint32_t>(d.points_in);
  m.object_points = static_cast<std::uint32_t>(d.object_points);
  m.object_centroid = point(d.object_centroid);
  m.candidates = static_cast<std::uint32_t>(d.candidates);
  m.feasible = static_cast<std::uint32_t>(d.feasible);
  for (std::size_t i = 0; i < d.grasps.size(); ++i) m.grasps.push_back(grasp_msg(d.grasps[i], i + 1));
  return m;
}

geometry_msgs::PoseArray pose_array(const uwgrasp_msgs::GraspArray& grasps) {
  geometry_msgs::PoseArray a;
  a.header = grasps.header;
  for (const auto& g : grasps.grasps) a.poses.push_back(g.pose);
  return a;
}

visualization_msgs::MarkerArray markers(const PlainDetection& d, const std_msgs::Header& header) {
  visualization_msgs::MarkerArray out;
  visualization_msgs::Marker clear = marker(header, "", 0, visualization_msgs::Marker::LINE_LIST);
  clear.action = visualization_msgs::Marker::DELETEALL;
  out.markers.push_back(clear);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& g : d.grasps) lo = std::min(lo, g.score), hi = std::max(hi, g.score);
  for (std::size_t i = d.grasps.size(); i-- > 0;) {
    auto m = marker(header, "grippers", static_cast<int>(i + 1), visualization_msgs::Marker::LINE_LIST);
    m.scale.x = i == 0 ? 0.004 : 0.0015;
    m.color = colour(hi > lo ? (d.grasps[i].score - lo) / (hi - lo) : 1.0, i == 0 ? 1.0f : 0.6f);
    for (const auto& e : d.grasps[i].edges) m.points.push_back(point(&e[0])), m.points.push_back(point(&e[3]));
    out.markers.push_back(std::move(m));
  }
  auto obj = marker(header, "object", 0, visualization_msgs::Marker::POINTS);
  obj.scale.x = obj.scale.y = 0.004;
  obj.color.r = 0.2f, obj.color.g = 0.8f, obj.color.b = 1.0f, obj.color.a = 0.8f;
  for (std::size_t i = 0; i + 2 < d.object_xyz.size(); i += 3) obj.points.push_back(point(&d.object_xyz[i]));
  out.markers.push_back(std::move(obj));
  return out;
}

}  // namespace uwgrasp_ros
