// Geometric queries on the world's Embree scene (query.hpp).
#include "uwgrasp/sim/query.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/sim/world_impl.hpp"

namespace uwgrasp::sim {

namespace {
using V3 = Eigen::Vector3d;

void check_ray(const Ray& r) {
  if (!r.origin.allFinite() || !(std::abs(r.direction.norm() - 1.0) < 1e-6) || !(r.tmax >= 0.0))
    throw Error("sim: a query ray needs a finite origin, a unit direction and tmax >= 0");
}

RTCRayHit embree_ray(const Ray& r, float tnear) {
  RTCRayHit rh{};
  rh.ray.org_x = float(r.origin.x()), rh.ray.org_y = float(r.origin.y()), rh.ray.org_z = float(r.origin.z());
  rh.ray.dir_x = float(r.direction.x()), rh.ray.dir_y = float(r.direction.y());
  rh.ray.dir_z = float(r.direction.z());
  rh.ray.tnear = tnear;
  rh.ray.tfar = float(std::min(r.tmax, 1e30));
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

RayHit to_hit(const World::Impl& w, const Ray& r, const RTCRayHit& rh) {
  RayHit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.hit = true;
  h.t = rh.ray.tfar;
  h.point = r.origin + h.t * r.direction;
  const auto [a, b, c] = triangle(w, rh.hit.geomID, rh.hit.primID);
  h.normal = (b - a).cross(c - a).normalized();
  const int object = w.owners[rh.hit.geomID].object;
  h.object = object < 0 ? kSeafloorObject : object;
  return h;
}

// Sutherland-Hodgman: the polygon clipped to |q_axis| <= half along each axis of the box frame.
using Polygon = std::vector<V3>;
Polygon clip(Polygon poly, int axis, double bound, double sign) {
  Polygon out;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const V3& a = poly[i];
    const V3& b = poly[(i + 1) % poly.size()];
    const double da = bound - sign * a[axis], db = bound - sign * b[axis];  // >= 0: inside
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

// The triangle's part inside the box (box frame); empty when there is none.
Polygon clipped(const std::array<V3, 3>& tri_local, const V3& half) {
  Polygon poly(tri_local.begin(), tri_local.end());
  for (int axis = 0; axis < 3 && !poly.empty(); ++axis) {
    poly = clip(std::move(poly), axis, half[axis], 1.0);
    if (!poly.empty()) poly = clip(std::move(poly), axis, half[axis], -1.0);
  }
  return poly;
}

struct BoxQuery {
  const World::Impl& w;
  const OrientedBox& box;
  bool seafloor = false;
  // (object, geometry and triangle) -> clipped polygon: ordered independently of the traversal
  std::map<std::pair<int, std::uint64_t>, Polygon> found;
};

bool box_callback(RTCPointQueryFunctionArguments* args) {
  auto& q = *static_cast<BoxQuery*>(args->userPtr);
  const int owner = q.w.owners[args->geomID].object;
  if (owner < 0 && !q.seafloor) return false;
  std::array<V3, 3> local = triangle(q.w, args->geomID, args->primID);
  for (V3& v : local) v = q.box.rotation.transpose() * (v - q.box.centre);
  // Separating axes that cost nothing: the box's faces, then the triangle's plane (most of the
  // triangles near a box's bounding sphere miss the box).
  const V3 lo = local[0].cwiseMin(local[1]).cwiseMin(local[2]);
  const V3 hi = local[0].cwiseMax(local[1]).cwiseMax(local[2]);
  if ((lo.array() > q.box.half.array()).any() || (hi.array() < -q.box.half.array()).any()) return false;
  const V3 n = (local[1] - local[0]).cross(local[2] - local[0]);
  if (std::abs(n.dot(local[0])) > n.cwiseAbs().dot(q.box.half)) return false;
  Polygon poly = clipped(local, q.box.half);
  if (poly.empty()) return false;
  const int object = owner < 0 ? kSeafloorObject : owner;
  q.found.emplace(std::make_pair(object, (std::uint64_t(args->geomID) << 32) | args->primID),
                  std::move(poly));
  return false;
}

// Signed crossings of mesh part g's surface along a ray to infinity (+1 leaving, -1 entering),
// traced in the part's own scene: the winding number of p for a closed, outward-wound surface.
int winding_along(const World::Impl& w, std::size_t g, const V3& p, const V3& dir) {
  const Ray r{p, dir, 1e3};
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  int winding = 0;
  float tnear = 0.0f;
  for (int guard = 0; guard < 100000; ++guard) {
    RTCRayHit rh = embree_ray(r, tnear);
    rtcIntersect1(w.part_scenes[g], &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;
    const auto [a, b, c] = triangle(w, rh.hit.geomID, rh.hit.primID);
    winding += (b - a).cross(c - a).dot(dir) > 0 ? 1 : -1;
    tnear = rh.ray.tfar + 1e-5f;  // past this crossing (10 um)
  }
  return winding;
}

bool inside_primitive(const Shape& s, const V3& q) {
  switch (s.kind) {
    case ShapeKind::box: return (q.cwiseAbs().array() <= 0.5 * s.size.array()).all();
    case ShapeKind::cylinder:
      return std::abs(q.z()) <= 0.5 * s.length && q.head<2>().norm() <= s.radius;
    case ShapeKind::sphere: return q.norm() <= s.radius;
    case ShapeKind::torus: {
      const double rho = q.head<2>().norm() - s.major;
      return rho * rho + q.z() * q.z() <= s.radius * s.radius;
    }
    case ShapeKind::mesh: break;
  }
  return false;
}

bool in_bounds(const Mesh& m, const V3& p) {
  const auto [lo, hi] = bounds(m);
  const Eigen::Vector3f f = p.cast<float>();
  return (f.array() >= lo.array()).all() && (f.array() <= hi.array()).all();
}

}  // namespace

RayHit first_hit(const World& world, const Ray& ray) {
  RayHit h;
  first_hits(world, std::span<const Ray>(&ray, 1), std::span<RayHit>(&h, 1));
  return h;
}

void first_hits(const World& world, std::span<const Ray> rays, std::span<RayHit> hits) {
  if (hits.size() != rays.size()) throw Error("sim: first_hits needs one hit per ray");
  const World::Impl& w = world.impl();
  std::vector<RTCRayHit> rh(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    check_ray(rays[i]);
    rh[i] = embree_ray(rays[i], 0.0f);
  }
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  rtcIntersect1M(w.rtc, &ctx, rh.data(), static_cast<unsigned>(rh.size()), sizeof(RTCRayHit));
  for (std::size_t i = 0; i < rays.size(); ++i) hits[i] = to_hit(w, rays[i], rh[i]);
}

std::vector<ClippedTriangle> clip_to_box(const World& world, const OrientedBox& box,
                                         bool with_seafloor) {
  if (!box.centre.allFinite() || !box.rotation.allFinite() || !(box.half.array() >= 0).all())
    throw Error("sim: a query box needs a finite pose and non-negative half extents");
  BoxQuery q{world.impl(), box, with_seafloor, {}};
  RTCPointQuery pq{};
  pq.x = float(box.centre.x()), pq.y = float(box.centre.y()), pq.z = float(box.centre.z());
  pq.radius = float(box.half.norm()) * 1.0001f + 1e-6f;  // the box's bounding sphere
  pq.time = 0.0f;
  RTCPointQueryContext ctx;
  rtcInitPointQueryContext(&ctx);
  rtcPointQuery(world.impl().rtc, &pq, &ctx, box_callback, &q);
  std::vector<ClippedTriangle> out;
  out.reserve(q.found.size());
  for (auto& [key, poly] : q.found) out.push_back({key.first, std::move(poly)});
  return out;
}

std::vector<BoxContact> surfaces_in_box(const World& world, const OrientedBox& box,
                                        std::size_t limit) {
  std::vector<BoxContact> out;
  int object = kNoObject;
  std::size_t count = 0;
  for (const ClippedTriangle& c : clip_to_box(world, box)) {
    count = c.object == object ? count + 1 : 1;
    object = c.object;
    if (count > limit) continue;
    V3 centroid = V3::Zero();
    for (const V3& p : c.polygon) centroid += p;
    out.push_back({c.object, box.centre + box.rotation * (centroid / double(c.polygon.size()))});
  }
  return out;
}

std::vector<int> inside_objects(const World& world, const V3& p) {
  const World::Impl& w = world.impl();
  static const std::array<V3, 3> kDirs = {V3(0.5773, 0.4115, 0.7053).normalized(),
                                          V3(-0.6231, 0.5347, -0.5710).normalized(),
                                          V3(0.3319, -0.8122, 0.4798).normalized()};
  std::vector<int> out;
  for (std::size_t g = 0; g < w.meshes.size(); ++g) {
    const GeometryOwner& own = w.owners[g];
    if (own.object < 0 || (!out.empty() && out.back() == own.object)) continue;
    const SceneObject& o = w.scene.objects[std::size_t(own.object)];
    const Part& part = o.parts[std::size_t(own.part)];
    bool in = false;
    if (part.shape.kind != ShapeKind::mesh) {
      in = inside_primitive(part.shape, (o.pose * part.pose).inverse() * p);
    } else if (in_bounds(w.meshes[g], p)) {
      int votes = 0;
      for (const V3& d : kDirs) votes += winding_along(w, g, p, d) > 0 ? 1 : 0;
      in = votes >= 2;
    }
    if (in) out.push_back(own.object);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace uwgrasp::sim
