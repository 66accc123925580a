#include "uwgrasp/grasp/gripper.hpp"

#include <cmath>
#include <string>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::grasp {

namespace {
void require_positive(float v, const char* name) {
  if (!(v > 0.0f) || !std::isfinite(v))
    throw Error(std::string("gripper.") + name + " must be positive, got " + std::to_string(v));
}

Box box(float x0, float x1, float y0, float y1, float z0, float z1) {
  return Box{Eigen::Vector3f(x0, y0, z0), Eigen::Vector3f(x1, y1, z1)};
}
}  // namespace

Gripper make_gripper(const GripperConfig& c) {
  require_positive(c.max_aperture, "max_aperture");
  require_positive(c.finger_length, "finger_length");
  require_positive(c.finger_width, "finger_width");
  require_positive(c.finger_height, "finger_height");
  require_positive(c.palm_depth, "palm_depth");
  require_positive(c.palm_height, "palm_height");
  require_positive(c.body_length, "body_length");
  require_positive(c.body_width, "body_width");
  require_positive(c.body_height, "body_height");
  if (!(c.min_aperture >= 0.0f))
    throw Error("gripper.min_aperture must be >= 0, got " + std::to_string(c.min_aperture));
  if (c.min_aperture >= c.max_aperture)
    throw Error("gripper.min_aperture (" + std::to_string(c.min_aperture) +
                ") must be below gripper.max_aperture (" + std::to_string(c.max_aperture) + ")");
  if (!(c.clearance >= 0.0f) || c.max_aperture - 2.0f * c.clearance <= c.min_aperture)
    throw Error("gripper.clearance " + std::to_string(c.clearance) +
                " leaves no graspable width between min_aperture and max_aperture");

  Gripper g;
  g.config = c;
  const float L = c.finger_length, A = c.max_aperture, w = c.finger_width, H = c.finger_height;
  const float outer = A / 2 + w;  // outer face of a fully open finger
  g.closing = box(-L / 2, L / 2, -A / 2, A / 2, -H / 2, H / 2);
  const auto at = [&](Part p) -> Box& { return g.solids[static_cast<int>(p)]; };
  at(Part::left_finger) = box(-L / 2, L / 2, -outer, -A / 2, -H / 2, H / 2);
  at(Part::right_finger) = box(-L / 2, L / 2, A / 2, outer, -H / 2, H / 2);
  const float palm_back = -L / 2 - c.palm_depth;
  at(Part::palm) = box(palm_back, -L / 2, -outer, outer, -c.palm_height / 2, c.palm_height / 2);
  at(Part::body) = box(palm_back - c.body_length, palm_back, -c.body_width / 2, c.body_width / 2,
                       -c.body_height / 2, c.body_height / 2);
  g.bounds = g.closing;
  for (const Box& s : g.solids) {
    g.bounds.lo = g.bounds.lo.cwiseMin(s.lo);
    g.bounds.hi = g.bounds.hi.cwiseMax(s.hi);
  }
  return g;
}

Gripper grow_solids(const Gripper& g, float margin) {
  Gripper out = g;
  for (Box& b : out.solids) b.lo.array() -= margin, b.hi.array() += margin;
  out.bounds = out.closing;
  for (const Box& b : out.solids) out.bounds.lo = out.bounds.lo.cwiseMin(b.lo), out.bounds.hi = out.bounds.hi.cwiseMax(b.hi);
  return out;
}

const char* part_name(Part p) {
  static const char* names[kParts] = {"left_finger", "right_finger", "palm", "body"};
  return names[static_cast<int>(p)];
}

float max_grasp_width(const Gripper& g) {
  return g.config.max_aperture - 2.0f * g.config.clearance;
}

std::vector<std::array<Eigen::Vector3f, 2>> gripper_edges(const Eigen::Isometry3d& T, const Gripper& g,
                                                          bool body) {
  const Eigen::Isometry3f Tf = T.cast<float>();
  std::vector<std::array<Eigen::Vector3f, 2>> out;
  for (int part = 0; part < (body ? kParts : kParts - 1); ++part) {
    const Box& box = g.solids[static_cast<std::size_t>(part)];
    for (int a = 0; a < 8; ++a)  // each corner to the corners one bit away: the 12 edges
      for (int bit = 0; bit < 3; ++bit)
        if (const int b = a | (1 << bit); b != a) out.push_back({Tf * box.corner(a), Tf * box.corner(b)});
  }
  return out;
}

}  // namespace uwgrasp::grasp
