#pragma once
// Geometric queries on the simulator's world (its Embree scene of exact object surfaces): what
// ground-truth judging (eval/) asks of the truth - rays that name the object they meet, which
// object surfaces cross a box, whether a point is inside an object, and the nearest surface.
// The seafloor is the plane z = 0 of W: rays meet it (object kSeafloor), but box, inside and
// nearest queries cover the objects only; callers treat the seafloor as the half-space z < 0.
#include <Eigen/Core>
#include <span>
#include <vector>

#include "uwgrasp/sim/render.hpp"

namespace uwgrasp::sim {

inline constexpr int kSeafloorObject = -1;  // RayHit::object for the seafloor
inline constexpr int kNoObject = -2;        // RayHit::object when nothing was hit

struct Ray {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // unit
  double tmax = 1e3;                                     // m along the direction
};

struct RayHit {
  bool hit = false;
  double t = 0.0;  // m along the unit direction
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit, outward (the triangle's winding)
  int object = kNoObject;                            // index into scene().objects, or kSeafloor
};

// The first surface along each ray (rays traced as one stream). Throws Error for a direction
// that is not unit length or a negative tmax.
RayHit first_hit(const World& world, const Ray& ray);
void first_hits(const World& world, std::span<const Ray> rays, std::span<RayHit> hits);

// An oriented box in W: p = centre + rotation * q with |q_i| <= half_i.
struct OrientedBox {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d half = Eigen::Vector3d::Zero();
};

// A piece of an object's surface inside a box: the centroid of the triangle clipped to the box.
struct BoxContact {
  int object = kNoObject;
  Eigen::Vector3d witness = Eigen::Vector3d::Zero();
};

// Every object triangle that meets the box (exact: the triangle clipped by the box's six planes
// is not empty), at most `limit` per object, ordered by object then triangle. Empty when no
// object surface crosses the box (it may still lie wholly inside one: see inside_objects).
std::vector<BoxContact> surfaces_in_box(const World& world, const OrientedBox& box,
                                        std::size_t limit = 16);

// The part of every triangle inside the box, as a polygon in the box's frame (q of OrientedBox),
// ordered by object then triangle; the seafloor (object kSeafloorObject) only when asked. The
// extremes of these polygons along an axis are exactly where a plane sweeping along that axis
// through the box first meets the surfaces (eval/: where a finger pad stops).
struct ClippedTriangle {
  int object = kNoObject;
  std::vector<Eigen::Vector3d> polygon;
};
std::vector<ClippedTriangle> clip_to_box(const World& world, const OrientedBox& box,
                                         bool with_seafloor = false);

// Objects whose solid contains p: inside any of its parts. Primitive parts are tested
// analytically, mesh parts by the winding number along three rays (majority).
std::vector<int> inside_objects(const World& world, const Eigen::Vector3d& p);

// `count` points spread over object `object`'s surface by area (seeded), with outward normals.
struct SurfaceSample {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
};
std::vector<SurfaceSample> sample_object_surface(const World& world, int object, std::size_t count,
                                                 std::uint64_t seed);

struct NearestSurface {
  double distance = 0.0;  // +inf when no object surface lies within the search radius
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  int object = kNoObject;
};
// The nearest object surface point to p within `radius`.
NearestSurface nearest_surface(const World& world, const Eigen::Vector3d& p, double radius);

}  // namespace uwgrasp::sim
