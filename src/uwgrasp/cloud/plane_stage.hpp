#pragma once
// The plane stage's refinements of the RANSAC plane (thesis 4.1.4 and what it adds): whether
// the plane supports the rest or is a face of the object, the inlier band widened to the measured
// depth noise, and points of that band kept off the plane when their normal turns away from it.
#include "uwgrasp/cloud/organised.hpp"
#include "uwgrasp/cloud/preprocess.hpp"
#include "uwgrasp/cloud/workspace.hpp"

namespace uwgrasp::cloud {

// The last arguments are a Workspace's buffers (workspace.hpp).

// Whether the points clearly off the plane (beyond three inlier distances) and over its inliers
// (their projection along the normal within a cell of an inlier's) lie mostly on the sensor's
// side of it, as objects standing on a support do, rather than behind it, as the rest of an
// object does behind one of its own faces. Points beyond the plane's edge (the room behind a
// table) do not count either way.
bool supports_the_rest(const Cloud& cur, const PlaneConfig& cfg, const PlaneResult& plane);
bool supports_the_rest(const Cloud& cur, const PlaneConfig& cfg, const PlaneResult& plane,
                       PlaneScratch& scratch);

// The plane's inliers again, within max(distance, noise_sigmas x sigma(range)) of it; sets
// out.noise and out.plane.inliers.
void widen_to_noise(const Cloud& cur, const PlaneConfig& cfg, Preprocessed& out,
                    PlaneScratch& scratch);

// Of the widened band's points beyond the fixed tolerance, those whose window normal turns more
// than normal_angle from the plane's leave the inliers.
void keep_turned_points(const Cloud& cur, const PixelMap& map, const PreprocessConfig& cfg,
                        PlaneResult& plane, PlaneScratch& scratch, WindowScratch& window);

}  // namespace uwgrasp::cloud
