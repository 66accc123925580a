#pragma once
// Suspended particles are not obstacles. In coastal and turbid water the camera sees marine snow
// (particles of a few millimetres, thousands per cubic metre) as small blobs of points floating
// between it and the scene; near the lens one particle covers a hundred pixels, so neither the
// outlier filter nor the segmentation's minimum size removes it. The vehicle sweeps them aside,
// and a hull checked against them finds no room where the camera itself just was: on the torque
// tool in coastal water they rejected most grasps on its post. A detached cluster of points
// (gaps up to `gap`) is debris when it fits in a box of diagonal `size` and does not rest on the
// seafloor (no point within `gap` of the plane). Anything larger, or lying on the floor, stays an
// obstacle.
#include <Eigen/Core>
#include <optional>
#include <span>
#include <vector>

namespace uwgrasp::grasp {

// 1 for the points of debris clusters, 0 for the rest. Clusters join points in the same or
// adjacent cells of a `gap` grid (a gap of up to 2 * sqrt(3) * gap may join; never less than
// `gap` splits). `plane`: n.p + d = 0 with |n| = 1, in the points' frame. size <= 0: no debris.
std::vector<char> debris(std::span<const Eigen::Vector3f> points, const std::optional<Eigen::Vector4f>& plane,
                         float gap, float size);

}  // namespace uwgrasp::grasp
