// The C++20 side of the bridge (engine.hpp): plain types in, uwgrasp's engine, plain types out.
#include "engine.hpp"
#include "engine_config.hpp"

#include <cmath>

#include "uwgrasp/core/pose.hpp"
#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/grasp/gripper.hpp"
#include "uwgrasp/io/config.hpp"
#include "uwgrasp/io/grasps_json.hpp"

namespace uwgrasp_ros {

using uwgrasp::Error;
using uwgrasp::Pose;

namespace {
Pose to_pose(const Pose7& a) {
  return uwgrasp::make_pose({a.p[0], a.p[1], a.p[2]}, Eigen::Quaterniond(a.q[3], a.q[0], a.q[1], a.q[2]).normalized());
}
}  // namespace

Pose7 pose7(const Pose& T) {
  const Eigen::Quaterniond q(T.linear());
  return {{T.translation().x(), T.translation().y(), T.translation().z()}, {q.x(), q.y(), q.z(), q.w()}};
}
PlainCloud plain_cloud(const uwgrasp::Cloud& c) {
  PlainCloud p;
  p.width = c.width, p.height = c.height;
  for (const auto& x : c.points) p.xyz.insert(p.xyz.end(), {x.x(), x.y(), x.z()});
  for (const auto& k : c.colors) p.rgb.insert(p.rgb.end(), {k.r, k.g, k.b});
  return p;
}

namespace {
std::array<double, 3> arr(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// `c` made width x height points, its buffers' memory kept: what Stream::frame hands a reader.
void shape_frame(std::uint32_t width, std::uint32_t height, bool colours, uwgrasp::Cloud& c) {
  const std::size_t n = std::size_t(width) * height;
  c.points.resize(n);
  c.colors.resize(colours ? n : 0);
  c.normals.clear(), c.curvature.clear(), c.labels.clear();
  c.width = height > 1 ? width : static_cast<std::uint32_t>(n);
  c.height = height > 1 ? height : 1;
}

// The checks of a frame as read, before the engine sees it.
void check_frame(const uwgrasp::Cloud& c) {
  uwgrasp::check_consistent(c, "PointCloud2");
  const uwgrasp::BehindCount behind = uwgrasp::behind_camera(c);
  if (behind.finite == 0)
    throw Error("PointCloud2: no finite point (" + std::to_string(c.size()) +
                " points, all NaN or inf)");
  if (behind.share() >= 0.01)
    throw Error(
        "1 % or more of the points lie behind the camera: the cloud's frame is not a camera "
        "optical frame (z forward); publish the cloud in the camera's frame");
}

// Into `c`, reusing its buffers. Its points as given, then its layout: check_frame names a width x
// height that is not the point count.
void to_cloud(const PlainCloud& in, uwgrasp::Cloud& c) {
  const std::size_t n = in.size();
  shape_frame(static_cast<std::uint32_t>(n), 1, in.rgb.size() == 3 * n, c);
  for (std::size_t i = 0; i < n; ++i)
    c.points[i] = {in.xyz[3 * i], in.xyz[3 * i + 1], in.xyz[3 * i + 2]};
  for (std::size_t i = 0; i < c.colors.size(); ++i)
    c.colors[i] = {in.rgb[3 * i], in.rgb[3 * i + 1], in.rgb[3 * i + 2]};
  if (in.height > 1) c.width = in.width, c.height = in.height;
}

PlainGrasp plain(const uwgrasp::grasp::Grasp& g, const uwgrasp::grasp::Frames& f, const uwgrasp::grasp::Gripper& model) {
  const Pose T_CG = uwgrasp::grasp::camera_from_gripper(g, f);
  const Pose T_CL = f.level_from_camera.inverse();
  const bool priced = std::isfinite(g.hold_cost);
  const double nan = std::nan("");
  PlainGrasp p;
  p.pose = pose7(T_CG);
  p.approach = arr(T_CG.linear().col(0));
  p.closing = arr(T_CG.linear().col(1));
  p.width = g.width;
  for (int k = 0; k < 2; ++k) p.contacts[k] = arr(T_CL * g.contacts[k]), p.contact_seen[k] = g.contact_seen[k];
  p.inliers = static_cast<std::uint32_t>(g.inliers);
  p.score = g.scores.total, p.normal = g.scores.normal, p.orientation = g.scores.orientation;
  p.contact_left = g.scores.contact_left, p.contact_right = g.scores.contact_right, p.inlier_score = g.scores.inliers;
  p.vehicle_score = priced ? g.scores.vehicle : nan;
  p.hold_cost = priced ? g.hold_cost : nan;
  p.antipodal = g.friction.ok;
  p.mu_required = g.friction.mu_required, p.robustness = g.robustness, p.force_closure = g.force_closure;
  p.vehicle_pose = pose7(T_CL * g.level_from_vehicle);
  p.vehicle_rpy = arr(g.vehicle_rpy);
  for (const auto& e : uwgrasp::grasp::gripper_edges(T_CG, model, false))
    p.edges.push_back({e[0].x(), e[0].y(), e[0].z(), e[1].x(), e[1].y(), e[1].z()});
  return p;
}
}  // namespace

Pose7 compose(const Pose7& a, const Pose7& b) { return pose7(to_pose(a) * to_pose(b)); }
Pose7 inverse(const Pose7& a) { return pose7(to_pose(a).inverse()); }

Pose7 fossen_from_ros_body() { return {{0, 0, 0}, {1, 0, 0, 0}}; }  // half turn about x

std::array<double, 2> roll_pitch_from(const std::array<double, 4>& qa) {
  const Eigen::Quaterniond q(qa[3], qa[0], qa[1], qa[2]);
  if (!q.coeffs().allFinite() || std::abs(q.norm() - 1.0) > 1e-2) throw Error("orientation is not a unit quaternion");
  Eigen::Matrix3d ned_from_enu;
  ned_from_enu << 0, 1, 0, 1, 0, 0, 0, 0, -1;
  // R_NED,B = R_NED,ENU * R_ENU,FLU * R_FLU,B; roll and pitch do not depend on the heading.
  const Eigen::Matrix3d R = ned_from_enu * q.normalized().toRotationMatrix() * to_pose(fossen_from_ros_body()).linear();
  const Eigen::Vector3d rpy = uwgrasp::rpy_from_matrix(R);
  return {rpy.x(), rpy.y()};
}

MountRpy mount_from(const Pose7& ros_body_from_optical) {
  const Pose T_BC = to_pose(fossen_from_ros_body()) * to_pose(ros_body_from_optical);
  return {arr(T_BC.translation()), arr(uwgrasp::rpy_from_matrix(T_BC.linear() * uwgrasp::body_from_optical().transpose()))};
}

struct Engine::Impl {
  uwgrasp::io::Config config;
};

struct Stream::Impl {
  uwgrasp::Cloud cloud;
  uwgrasp::grasp::Detection detection;
  uwgrasp::segment::Workspace workspace;
};
Stream::Stream() : impl_(std::make_unique<Impl>()) {}
Stream::~Stream() = default;
Stream::Stream(Stream&&) noexcept = default;
Stream& Stream::operator=(Stream&&) noexcept = default;

// A point and a colour are their values and nothing more, so the vectors are plain arrays of
// floats and bytes (as Eigen's own Map reads them).
static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float) && sizeof(uwgrasp::Rgb8) == 3);
FrameBuffers Stream::frame(std::uint32_t width, std::uint32_t height, bool colours) {
  uwgrasp::Cloud& c = impl_->cloud;
  shape_frame(width, height, colours, c);
  if (c.points.empty()) return {};
  return {c.points.front().data(), colours ? &c.colors.front().r : nullptr};
}

Engine::Engine(const std::string& path, const std::vector<std::string>& sets) : impl_(std::make_unique<Impl>()) {
  if (path.empty()) uwgrasp::io::apply_overrides(impl_->config, sets);
  else impl_->config = uwgrasp::io::load_config(path, sets);
}
Engine::~Engine() = default;

Engine make_engine(const uwgrasp::io::Config& cfg) {
  Engine e("", {});
  e.impl_->config = cfg;
  return e;
}
Engine::Engine(const Engine& o) : impl_(std::make_unique<Impl>(*o.impl_)) {}
Engine& Engine::operator=(const Engine& o) {
  *impl_ = *o.impl_;
  return *this;
}

void Engine::update(const std::vector<std::string>& sets) {
  uwgrasp::io::Config cfg = impl_->config;
  uwgrasp::io::apply_overrides(cfg, sets);
  impl_->config = cfg;
}

std::uint32_t Engine::threads() const { return impl_->config.threads; }

PlainDetection Engine::detect(const PlainCloud& in, const Capture& capture, const std::string& input,
                              const std::string& version) const {
  Stream fresh;
  return detect(in, capture, input, version, fresh);
}

PlainDetection Engine::detect(const PlainCloud& in, const Capture& capture,
                              const std::string& input, const std::string& version,
                              Stream& stream) const {
  to_cloud(in, stream.impl_->cloud);
  return detect_frame(capture, input, version, stream);
}

PlainDetection Engine::detect_frame(const Capture& capture, const std::string& input,
                                    const std::string& version, Stream& stream) const {
  const uwgrasp::Cloud& cloud = stream.impl_->cloud;
  check_frame(cloud);
  uwgrasp::io::Config cfg = impl_->config;
  if (capture.ros_body_from_camera) {
    const MountRpy m = mount_from(*capture.ros_body_from_camera);
    cfg.grasp.frames.camera.position = {m.position[0], m.position[1], m.position[2]};
    cfg.grasp.frames.camera.rpy = {m.rpy[0], m.rpy[1], m.rpy[2]};
  }
  if (capture.roll_pitch)
    uwgrasp::grasp::given_attitude(cfg.grasp.frames, (*capture.roll_pitch)[0],
                                   (*capture.roll_pitch)[1]);
  PlainDetection out;
  out.points_in = cloud.size();
  uwgrasp::grasp::Detection& d = stream.impl_->detection;
  try {
    uwgrasp::grasp::detect(cloud, cfg.preprocess, cfg.segment, cfg.grasp, cfg.seed, d,
                           stream.impl_->workspace);
  } catch (const Error& e) {
    out.warning = e.what();
    return out;
  }
  const auto& r = d.result;
  out.sampler = uwgrasp::grasp::sampler_name(r.sampler);
  out.object_points = d.object.size();
  out.colours_restored = d.restored_colours;
  out.candidates = r.candidates;
  out.feasible = r.feasible();
  out.object_centroid = arr(uwgrasp::centroid(d.object));
  for (const auto& p : d.object.points) out.object_xyz.insert(out.object_xyz.end(), {p.x(), p.y(), p.z()});
  const uwgrasp::grasp::Gripper model = uwgrasp::grasp::make_gripper(cfg.grasp.gripper);
  for (const auto& g : r.grasps) out.grasps.push_back(plain(g, r.frames, model));
  for (const auto& st : d.timer.stages()) out.stage_ms.emplace_back(st.name, st.ms);
  out.total_ms = d.timer.total_ms();
  out.json = uwgrasp::io::grasps_to_json(d, cfg, input, version).dump();
  return out;
}

}  // namespace uwgrasp_ros
