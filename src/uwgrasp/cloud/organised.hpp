#pragma once
// Neighbourhoods on an organised frame (one point per pixel): the neighbours of a pixel are the
// pixels around it, so the k-d tree searches that dominate the unorganised chain are not needed.
// A window pixel is a neighbour when it is still in play and its range is continuous with the
// centre's: |r_q - r_p| <= depth_change * r_p * d, d the pixels between them (Chebyshev). The
// allowance grows with range, as a depth sensor's noise and pixel footprint do, and with d, so a
// slanted surface stays one neighbourhood while a step to the background does not.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/cloud/normals.hpp"
#include "uwgrasp/core/cloud.hpp"

namespace uwgrasp::cloud {

struct OrganisedConfig {
  bool enabled = true;       // take the organised path for frames (height > 1) without a voxel grid
  std::uint32_t half_window = 2;  // pixels on each side of the centre: 2 is a 5 x 5 window
  // The normals' window: 7 x 7. On a frame with 1 mm depth noise at 1 m it halves the normals'
  // median error of the 5 x 5 window (3.3 against 6.5 degrees) at the same cost per pixel.
  std::uint32_t normal_half_window = 3;
  // The normals' window grows while its plane fit's slope error over the frame's depth noise
  // exceeds this, rad (normal_window below), up to max_normal_half_window; 0: the window above.
  float max_normal_slope = 0.16f;
  std::uint32_t max_normal_half_window = 4;  // 9 x 9 (wider lost grasps: normal_window)
  // Range continuity per pixel step, as a share of the range. 1 %: on the labelled mOSD frames
  // 2 % joined touching objects (best-segment IoU 0.815 against 0.824), and the judged grasps
  // on the simulated scenes were the same (docs/benchmarks.md).
  float depth_change = 0.01f;
  // On a frame whose normals' window grew (normal_window), each point is moved along its ray
  // onto a quadratic fitted to its window's ranges and the normals are computed again from the
  // moved points (move_onto_quadrics). Judged at two to four times the simulated sensor's noise
  // (docs/results/grasps-that-hold.md): 2,815 of 2,880 top-1s held or rightly found none
  // (2,555 unmoved, 2,678 moved onto the windows' planes, which bend a rod's or a bottle's
  // side flat); frames that keep 7 x 7 are not moved.
  bool move_onto_quadrics = true;
};

// Which pixels hold the points still in play: pixel[j] is the pixel of point j (ascending), and
// slot[p] the point at pixel p or -1.
struct PixelMap {
  std::uint32_t width = 0, height = 0;
  std::vector<std::int32_t> slot;
  std::vector<std::uint32_t> pixel;
};

// The pixel windows' buffers (window_neighbours, window_normals, window_normals_of), for a
// caller that keeps them over a stream of frames (workspace.hpp).
struct WindowScratch {
  std::vector<float> range;              // each point's distance from the viewpoint
  std::vector<char> full;                // the points the normals take from running sums
  std::vector<float> image, lo, hi;      // the range image and its sliding minima and maxima
  std::vector<std::size_t> first, last;  // each image row's in-play columns
  // The running sums' per-column moments (n, x, y, z, xx, xy, xz, yy, yz, zz), a frame row of
  // them per block of rows, and which rows of each block hold a point to compute.
  std::vector<std::array<double, 10>> columns;
  std::vector<char> wanted;
  std::vector<float> sample;  // normal_window's samples of pixel pitches and second differences
  std::vector<float> move;    // move_onto_quadrics's moves along the rays
};

// The map of `pixels` (ascending pixel indices of a width x height frame).
PixelMap pixel_map(std::uint32_t width, std::uint32_t height, std::vector<std::uint32_t> pixels);

// For every point of the map (points[j] at pixel[j]): itself first, then the continuous pixels
// of its window ring by ring (nearest pixels first, not nearest in space), as indices into
// `points`. Rows hold up to (2 half_window + 1)^2 entries; the lists are marked `window` (see kdtree.hpp).
// `viewpoint` is the sensor origin the ranges are measured from.
Neighbours window_neighbours(std::span<const Eigen::Vector3f> points, const PixelMap& map,
                             const OrganisedConfig& cfg, const Eigen::Vector3f& viewpoint);
void window_neighbours(std::span<const Eigen::Vector3f> points, const PixelMap& map,
                       const OrganisedConfig& cfg, const Eigen::Vector3f& viewpoint,
                       Neighbours& out, WindowScratch& scratch);

// The statistic of statistical outlier removal (4.1.3) over the window: each point's mean
// distance to its k nearest points among every pixel of its window still in play (continuous or
// not, as a k-d tree search would find them). A window holding fewer than k such pixels grows
// ring by ring (to 3 x half_window) until it holds k; infinity when even that holds none: a
// flying pixel, removed, and left out of the statistic's mean and deviation, which a few such
// pixels would otherwise widen (PCL's k-d tree statistic takes them in: on a simulated frame its
// threshold is 16 mm where this one is 4.5 mm, and it keeps 121 more points, 87 of the object,
// the noisiest; judged grasps were the better without them, docs/benchmarks.md).
std::vector<float> window_mean_distances(std::span<const Eigen::Vector3f> points,
                                         const PixelMap& map, std::uint32_t half_window,
                                         std::uint32_t k);
void window_mean_distances(std::span<const Eigen::Vector3f> points, const PixelMap& map,
                           std::uint32_t half_window, std::uint32_t k, std::vector<float>& mean);

// Normals and curvature (4.2.1, eq. 4.4-4.7) over each point's window of normal_half_window:
// its continuous in-play pixels, as for window_neighbours. A point whose whole window qualifies
// takes the covariance from separable running sums over the frame (the cost does not depend on
// the window size); the others sum their pixels. Fills cloud.normals and cloud.curvature;
// map.pixel[j] is the pixel of cloud.points[j].
void window_normals(Cloud& cloud, const PixelMap& map, const OrganisedConfig& cfg);
void window_normals(Cloud& cloud, const PixelMap& map, const OrganisedConfig& cfg,
                    WindowScratch& scratch);

// The same normals (summing the pixels, for a few points) of points[which[i]] only, into out[i].
void window_normals_of(std::span<const Eigen::Vector3f> points, const PixelMap& map,
                       const OrganisedConfig& cfg, const Eigen::Vector3f& viewpoint,
                       std::span<const std::uint32_t> which, std::vector<PointNormal>& out,
                       WindowScratch& scratch);

// The slope error (rad, along one axis) of a plane fitted to a (2h+1)^2 pixel window whose
// depth noise is `noise_per_pixel` pixel footprints.
double normal_slope_error(double noise_per_pixel, std::uint32_t h);

// The frame's depth noise along the rays in pixel footprints (sigma / (pitch x range)), from the
// ranges' second differences along every 8th row (triples stepping by more than 3 x the
// depth_change allowance are edges, not noise); 0 when fewer than 100 such triples. Real
// sensors' noise, smooth over pixels, measures less than independent noise of its size.
double noise_per_pixel(std::span<const Eigen::Vector3f> points, const PixelMap& map,
                       const Eigen::Vector3f& viewpoint, float depth_change,
                       WindowScratch& scratch);

// The normals' half window for a frame `noise_footprints` footprints noisy: cfg.normal_half_window,
// grown (to cfg.max_normal_half_window, at most 7) until normal_slope_error is at most
// cfg.max_normal_slope. At 0.16 rad a frame keeps 7 x 7 up to 2.24 footprints: the simulated
// depth camera (1.2 mm + 1.9 mm/m^2 r^2) measures 1.5-2.1, one with twice its sigma_k 2.3-3.8.
// Judged top-1s (docs/results/grasps-that-hold.md): with the default noise 7 x 7 held the most
// (9 x 9: 5 fewer of 1,080); with twice the noise 9 x 9 held 14-26 more of 360; with three and
// four times the noise no window did better than 7 x 7, and 9 x 9 and wider held 1-12 fewer.
std::uint32_t normal_window(double noise_footprints, const OrganisedConfig& cfg);

// A least-squares quadratic's value at the centre of a whole (2h+1)^2 pixel window is a fixed
// weighting of the window's values, alpha + beta (du^2 + dv^2) at offset (du, dv); its squared
// weights sum to alpha, so independent noise sigma per pixel leaves sigma sqrt(alpha) at the
// centre (9 x 9: 0.211 sigma; a plane's fit would leave sigma / 9 but bend a curved surface).
struct QuadraticKernel {
  double alpha = 0.0, beta = 0.0;
};
QuadraticKernel quadratic_kernel(std::uint32_t h);

// The depth noise move_onto_quadrics measured, as sigma at 1 m of a law growing with range^2
// (a depth camera's, and ShapeConfig::depth_error's): what the moves took out, and what is left
// in a point whose window held whole. Both 0 when no point moved.
struct MovedOntoQuadrics {
  double noise = 0.0, left = 0.0;
};

// Each point moved along its ray (from cloud.viewpoint) to the range, at its own pixel, of a
// least-squares quadratic in the pixel offsets fitted to the ranges of its window of
// cfg.normal_half_window (its continuous in-play pixels, as for window_neighbours): a local
// regression of the range image, which averages the window's depth noise (it lies along the
// rays) and, unlike a plane, follows a surface's curvature (a rod, a bottle's side). A whole
// window takes the fixed weights of quadratic_kernel; a cut one (a depth step, a hole, the
// frame's edge) solves its own fit and stays when under 12 pixels or singular. A point also
// stays where the move would exceed three continuity allowances (3 x depth_change x range: the
// window straddles a crease or a thin part). Every move is taken from the ranges as they were.
// The normals are then stale: compute them again.
MovedOntoQuadrics move_onto_quadrics(Cloud& cloud, const PixelMap& map, const OrganisedConfig& cfg,
                                     WindowScratch& scratch);

}  // namespace uwgrasp::cloud
