#pragma once
// A generated scene like the thesis's (8.2): a camera on the vehicle looking 45 degrees down at a
// flat seafloor 1.2 m below, with a few objects on it, ray-cast analytically into an organised
// cloud of ~400k points in the camera optical frame.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "uwgrasp/core/cloud.hpp"

namespace uwgrasp::bench {

// width x height pixels (default 730 x 550 = 401,500); depth noise sigma = noise * z^2. With
// `truth`, also each pixel's true surface normal (optical frame, towards the camera; NaN where
// the pixel is).
Cloud seafloor_scene(std::uint32_t width = 730, std::uint32_t height = 550, float noise = 0.001f,
                     std::uint64_t seed = 1, std::vector<Eigen::Vector3f>* truth = nullptr);

}  // namespace uwgrasp::bench
