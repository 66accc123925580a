#include "uwgrasp/camera/pinax.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/core/utility.hpp>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::camera {

namespace {
using V3 = Eigen::Vector3d;

PortRay water_ray(const Pinhole& air, const FlatPort& port, const Eigen::Vector2d& px) {
  const auto r = refract_through_port(port, air.unproject(px));
  if (!r) throw Error("port: rays inside the camera's field of view reflect totally at the port");
  return *r;
}

// The point on the optical axis closest, in the least-squares sense, to the in-water rays of a
// grid of pixels (the axial camera's best single viewpoint): minimises sum |P_i (c - o_i)|^2
// over c = (0, 0, z), P_i projecting out the ray's direction.
double best_centre(const Pinhole& air, const FlatPort& port, double& spread) {
  double num = 0.0, den = 0.0;
  std::vector<PortRay> rays;
  for (int v = 0; v <= air.height; v += std::max(1, air.height / 24))
    for (int u = 0; u <= air.width; u += std::max(1, air.width / 32))
      rays.push_back(water_ray(air, port, {u, v}));
  for (const PortRay& r : rays) {
    const V3 d = r.direction.normalized(), e = V3::UnitZ() - d * d.z(),
             a = -r.origin + d * d.dot(r.origin);
    num -= e.dot(a), den += e.dot(e);
  }
  const double z = den > 1e-15 ? num / den : 0.0;
  double s = 0.0;
  for (const PortRay& r : rays) {
    const V3 d = r.direction.normalized(), w = V3(0, 0, z) - r.origin;
    s += (w - d * d.dot(w)).squaredNorm();
  }
  spread = std::sqrt(s / double(rays.size()));
  return z;
}

// The virtual focal length that keeps the raw image's left, right, top and bottom edges in view.
double virtual_focal(const Pinax& p) {
  const Pinhole& a = p.air;
  double f = 1e300;
  const Eigen::Vector2d edges[4] = {
      {0.0, a.cy}, {a.width - 1.0, a.cy}, {a.cx, 0.0}, {a.cx, a.height - 1.0}};
  for (int i = 0; i < 4; ++i) {
    const PortRay r = water_ray(a, p.port, edges[i]);
    const V3 x = r.origin + r.direction * (p.reference - r.origin.z()) - V3(0, 0, p.centre_z);
    const double offset = i < 2 ? std::abs(edges[i].x() - a.cx) : std::abs(edges[i].y() - a.cy);
    const double tan = (i < 2 ? std::abs(x.x()) : std::abs(x.y())) / x.z();
    if (tan > 1e-12) f = std::min(f, offset / tan);
  }
  return f;
}
}  // namespace

Pinax make_pinax(const Pinhole& air, const FlatPort& port, double reference) {
  check(air, "camera");
  check_port(port);
  if (!(reference > port.distance + port.thickness) || !std::isfinite(reference))
    throw Error("port: the Pinax reference distance must lie beyond the port");
  Pinax p;
  p.air = air, p.port = port, p.reference = reference;
  p.centre_z = best_centre(air, port, p.spread);
  const double f = virtual_focal(p);
  p.virtual_camera = {air.width, air.height, f, f, air.cx, air.cy, {}};
  p.map_x.create(air.height, air.width, CV_32FC1);
  p.map_y.create(air.height, air.width, CV_32FC1);
  cv::parallel_for_(cv::Range(0, air.height), [&](const cv::Range& rows) {
    for (int v = rows.start; v < rows.end; ++v)
      for (int u = 0; u < air.width; ++u) {
        // The virtual pixel's ray from the virtual centre, to the reference depth; the raw pixel
        // is where the real camera sees that point through the port.
        const V3 x = V3(0, 0, p.centre_z) +
                     V3((u - air.cx) / f, (v - air.cy) / f, 1.0) * (reference - p.centre_z);
        const auto a = direction_to(port, x);
        const Eigen::Vector2d raw = a ? air.project(*a) : Eigen::Vector2d(-1.0, -1.0);
        p.map_x.at<float>(v, u) = float(raw.x()), p.map_y.at<float>(v, u) = float(raw.y());
      }
  });
  return p;
}

std::optional<Eigen::Vector2d> virtual_pixel(const Pinax& p, const Eigen::Vector2d& raw) {
  const auto r = refract_through_port(p.port, p.air.unproject(raw));
  if (!r) return std::nullopt;
  const V3 x = r->origin + r->direction * (p.reference - r->origin.z()) - V3(0, 0, p.centre_z);
  const Pinhole& k = p.virtual_camera;
  return Eigen::Vector2d(k.fx * x.x() / x.z() + k.cx, k.fy * x.y() / x.z() + k.cy);
}

}  // namespace uwgrasp::camera
