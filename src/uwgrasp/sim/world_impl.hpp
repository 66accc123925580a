#pragma once
// Internal to sim/: the Embree objects behind World and a ray query that renders share.
#include <embree3/rtcore.h>

#include <Eigen/Core>
#include <array>
#include <span>
#include <vector>

#include "uwgrasp/sim/render.hpp"

namespace uwgrasp::sim {

struct Surface {
  Eigen::Vector3f albedo = Eigen::Vector3f::Zero();  // 0-1 per channel
  float texture = 0.0f;    // albedo modulation amplitude
  std::uint16_t label = kLabelWater;
  // A checkerboard target (scene.hpp's Checker): its squares in the part's frame.
  Checker checker{};
  Eigen::Matrix4f part_from_world = Eigen::Matrix4f::Identity();
};

// The albedo of a checkerboard target at world point p: black or white squares, white margin.
Eigen::Vector3f checker_albedo(const Surface& s, const Eigen::Vector3f& p);

// What an Embree geometry is: one part of one object (each part is a closed surface of its own,
// so inside tests and crossings are per part), or the seafloor (object -1).
struct GeometryOwner {
  int object = -1;
  int part = -1;
};

struct World::Impl {
  Scene scene;
  RTCDevice device = nullptr;
  RTCScene rtc = nullptr;
  std::vector<Surface> surfaces;  // by Embree geometry id
  std::vector<GeometryOwner> owners;  // by Embree geometry id
  std::vector<Mesh> meshes;           // by Embree geometry id, in W (for the queries of query.hpp)
  // By geometry id: a scene holding that mesh part alone, for its inside test (query.hpp), so
  // crossings of other parts - coincident faces where parts meet - cannot hide its own; null
  // for primitives and the seafloor.
  std::vector<RTCScene> part_scenes;
  std::vector<RTCGeometry> geometries;  // retained, to attach to per-frame scenes with snow
  std::size_t triangles = 0;
  ~Impl();
};

// The world's geometries plus marine-snow particles (icosahedra) in one committed Embree scene,
// released on destruction; the world's own scene when there are no particles.
struct SnowScene {
  RTCScene rtc = nullptr;
  bool owned = false;
  unsigned snow_geometry = RTC_INVALID_GEOMETRY_ID;  // the world's ids stay the same
  SnowScene() = default;
  SnowScene(const SnowScene&) = delete;
  SnowScene& operator=(const SnowScene&) = delete;
  ~SnowScene();
};

struct Hit {
  bool hit = false;
  float t = 0.0f;                          // along the (unnormalised) ray direction
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();  // unit, facing the ray
  Surface surface;
};

// Particles in the frustum of `world_from_camera` up to the water's snow range, seeded; none
// when the sensor noise is off (the perfect sensor).
void make_snow(const World& world, const Pose& world_from_camera, const Intrinsics& k,
               const RenderConfig& cfg, std::uint64_t seed, SnowScene& out);
// Traces rays from one origin (a row of pixels: coherent, so Embree packs them), or from one
// origin per ray (`origins` the size of `dirs`: rays leaving a flat port).
void trace(const World& world, const SnowScene& snow, std::span<const Eigen::Vector3f> origins,
           std::span<const Eigen::Vector3f> dirs, float tfar, std::span<Hit> hits);
// Albedo texture factor in [1 - amp, 1 + amp] at a world point with surface normal n (hashed
// value noise).
float texture_factor(const Eigen::Vector3f& p, const Eigen::Vector3f& n, float amp);

// Triangle `prim` of geometry `geom`, in W (double precision).
inline std::array<Eigen::Vector3d, 3> triangle(const World::Impl& w, unsigned geom, unsigned prim) {
  const Mesh& m = w.meshes[geom];
  const auto& t = m.triangles[prim];
  return {m.vertices[t[0]].cast<double>(), m.vertices[t[1]].cast<double>(),
          m.vertices[t[2]].cast<double>()};
}

}  // namespace uwgrasp::sim
