#pragma once
// The object's whole shape from one view (thesis 7.4.3 assumed the visible side is enough; it is
// not: most grasps that fail put a finger into the object's unseen back). An occupancy grid in
// the level frame L (z along gravity) holds:
//   seen     - voxels with an object point;
//   assumed  - voxels the camera could not see (in the object's shadow: the object's visible
//              surface lies between them and the camera) that are either under the object's
//              visible surface (gravity prior: what is seen rests on something below it, down to
//              the seafloor) or within `min_thickness` behind a visible point (a face seen
//              head-on, without a top in view, still has some depth);
//   mirrored - voxels holding the seen surface mirrored about the object's symmetry planes
//              (symmetry.hpp) where the camera could not see: the curved back of a bottle or a
//              can, which neither rule above reaches; the space under them is assumed too;
//   free     - everything else: seen through, or beside and behind the object where nothing of
//              it is above.
// The voxels within `min_thickness` behind a visible point are `thin`, the rest of the assumed
// volume `assumed`: together they are the most the unseen part can be, thin alone the least
// (a shell behind what was seen). The unseen boundary of the whole volume becomes virtual
// surface points with outward normals, so that the collision check, the width at closure and
// the contacts see both sides of the object; a gripper part wholly inside the volume is found
// by its centre's voxel. The boundary of the thin core alone gives the `core` points: a grasp
// whose contacts hold on both surfaces holds whatever the unseen part turns out to be between
// them, and one that closes on assumed volume alone closes on nothing the camera saw.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "uwgrasp/grasp/frames.hpp"
#include "uwgrasp/grasp/symmetry.hpp"

namespace uwgrasp::grasp {

struct ShapeConfig {
  bool enabled = true;
  float voxel = 0.0025f;          // grid spacing, m (grown for large objects, see max_voxels)
  std::uint32_t max_voxels = 4000000;
  float min_thickness = 0.015f;   // m of object behind any visible point, in its shadow
  float shadow_tolerance = 0.002f;  // m (plus the noise): nearer than this is not behind
  float floor_clearance = 0.002f;   // m: the unseen part stops this far above the seafloor
  float resolution = 0.003f;        // the shadow map's bin in normalised image units (~rad)
  // The gripper's solid parts are grown by max(min_margin, margin_sigmas x the measured surface
  // noise) for the collision check: a noisy surface may lie that much deeper than its points.
  float margin_sigmas = 2.0f;
  float min_margin = 0.001f;
  // m at 1 m depth, growing with depth^2: the sensor's own depth error where its cloud looks
  // smoother than it is right (a stereo rig's sub-pixel disparity error, camera::depth_error;
  // detecting from a stereo pair sets it). The surface noise is taken as at least this at the
  // object's median depth. 0: the measured noise alone (a depth camera's scatter shows its error).
  float depth_error = 0.0f;
  SymmetryConfig symmetry;  // the back from the object's mirror symmetry (needs the scene's view)
};

enum class Occupancy : std::uint8_t { free, seen, thin, assumed, mirrored };

struct ObjectShape {
  Eigen::Vector3f origin = Eigen::Vector3f::Zero();  // centre of voxel (0, 0, 0), L
  float voxel = 0.0f;
  int nx = 0, ny = 0, nz = 0;
  std::vector<Occupancy> cells;  // x fastest
  // The unseen surface: centres of assumed voxels next to a free one, in L, with outward normals.
  std::vector<Eigen::Vector3f> points, normals;
  // The least unseen surface: thin voxels next to a free or assumed one, normals away from the
  // seen and thin mass.
  std::vector<Eigen::Vector3f> core_points, core_normals;
  // The mirrored back (one point per voxel, L, with the seen normals mirrored) and its planes.
  std::vector<Eigen::Vector3f> mirrored_points, mirrored_normals;
  std::vector<MirrorPlane> planes;
  float noise = 0.0f;           // the surface's noise (sigma, m): the larger of the two below
  float measured_noise = 0.0f;  // the scatter of the seen points, see surface_noise
  float sensor_noise = 0.0f;    // ShapeConfig::depth_error at the object's median depth

  bool empty() const { return cells.empty(); }
  // The voxel p_level falls in (possibly outside the grid): floor(q + 1/2), not lround, which
  // is a call.
  Eigen::Vector3i cell_of(const Eigen::Vector3f& p_level) const {
    const Eigen::Vector3f q = (p_level - origin) / voxel + Eigen::Vector3f::Constant(0.5f);
    return {int(std::floor(q.x())), int(std::floor(q.y())), int(std::floor(q.z()))};
  }
  // The index of the cell p_level falls in, -1 outside the grid (or NaN). The same cell as
  // cell_of: floor(q) lies in [0, n) exactly when q does, and there truncation is floor;
  // without SSE4.1 a floor is a dozen instructions (9 % of a whole detect's time).
  std::ptrdiff_t index_of(const Eigen::Vector3f& p_level) const {
    const Eigen::Vector3f q = (p_level - origin) / voxel + Eigen::Vector3f::Constant(0.5f);
    if (!(q.x() >= 0.0f && q.y() >= 0.0f && q.z() >= 0.0f && q.x() < float(nx) && q.y() < float(ny) &&
          q.z() < float(nz)))
      return -1;
    return std::ptrdiff_t((std::size_t(q.z()) * std::size_t(ny) + std::size_t(q.y())) * std::size_t(nx) +
                          std::size_t(q.x()));
  }
  // Free outside the grid. Inline: the samplers and checks ask millions of times a frame.
  Occupancy at(const Eigen::Vector3f& p_level) const {
    const std::ptrdiff_t i = cells.empty() ? -1 : index_of(p_level);
    return i < 0 ? Occupancy::free : cells[std::size_t(i)];
  }
  bool occupied(const Eigen::Vector3f& p_level) const { return at(p_level) != Occupancy::free; }
  std::size_t count(Occupancy o) const;
};

// The seafloor in L as n.p + d = 0, |n| = 1, with the camera on the positive side.
using FloorPlane = Eigen::Vector4f;

// What the camera saw around the object, for the symmetry search: every processed point of the
// scene (camera frame) and the seafloor plane there (n.p + d = 0), if any.
struct SceneSight {
  std::span<const Eigen::Vector3f> points;
  std::optional<Eigen::Vector4f> floor;
};

// k-d trees the caller already has, over complete_shape's `level` and `camera` points (either
// may be null: complete_shape builds what it needs).
struct ShapeTrees {
  const cloud::KdTree* level = nullptr;
  const cloud::KdTree* camera = nullptr;
};

// Builds the shape of an object seen by the camera of `frames`: `level` and `camera` are the
// same points in L and in the camera frame, `normals` their normals in L (may be empty: no
// mirrored normals). With `scene` and cfg.symmetry on, the back is also mirrored from the
// seen side, about planes searched upright to `floor` when it is 2-60 degrees from L's level
// (objects rest on the seafloor: on a sloping one, or in a frame whose attitude is wrong, their
// symmetry is square to it, not to L). Throws Error for an empty object, a non-positive voxel or
// resolution, or negative lengths.
ObjectShape complete_shape(std::span<const Eigen::Vector3f> level,
                           std::span<const Eigen::Vector3f> camera, const Frames& frames,
                           const std::optional<FloorPlane>& floor, const ShapeConfig& cfg,
                           std::span<const Eigen::Vector3f> normals = {},
                           const SceneSight* scene = nullptr, ShapeTrees trees = {});

// How far the model reaches from p along u (unit) before more than `gap` of free space, up to
// `limit`: the last occupied of the points p + t u, t = step, 2 step, ... (step half a voxel, t
// summed step by step, up to limit + gap) before more than `gap` of free ones; 0 when none is.
float extent_along(const ObjectShape& shape, const Eigen::Vector3f& p, const Eigen::Vector3f& u,
                   float limit, float gap);

// The largest i in [first, last] whose point base - i step u is occupied (ObjectShape::occupied),
// first - 1 when none is: the sampler's palm back-off scans its lines with it, four points a go.
int last_occupied(const ObjectShape& shape, const Eigen::Vector3f& base, const Eigen::Vector3f& u,
                  float step, int first, int last);

// The sensor's depth error at the median depth of the object's points (camera frame, z along
// the optical axis): depth_error z^2 (ShapeConfig::depth_error); 0 when depth_error is 0.
float sensor_noise(std::span<const Eigen::Vector3f> camera, float depth_error);

// The surface's noise: the median RMS distance of a point's k nearest neighbours from their
// least-squares plane (on up to `samples` points). 0 for fewer than k points. `tree`, when
// given, is a k-d tree over `points`.
float surface_noise(std::span<const Eigen::Vector3f> points, std::size_t k = 12,
                    std::size_t samples = 1500, const cloud::KdTree* tree = nullptr);

}  // namespace uwgrasp::grasp
