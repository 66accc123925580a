#pragma once
// What `uwgrasp detect` prints and draws about one detection: the object, its shape model, the
// sampler's counts, the best grasp in every frame the user may read it in, and the picture.
#include <opencv2/core.hpp>
#include <string>

#include "uwgrasp/core/cloud.hpp"
#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/io/config.hpp"
#include "uwgrasp/io/grasps_json.hpp"

namespace uwgrasp::app {

// The attitude the grasps were found in, when it came from the seafloor plane; a hint when the
// plane is far from the configured level and the configuration keeps it (level_from_floor=false).
void print_level(const grasp::Detection& d, const grasp::FrameConfig& f);

// The object, its shape model, the sampler's counts and rejections, then the best grasp (in the
// camera, level and vehicle frames, and in `frame` when that is not the camera's) and the ranks.
void print_detection(const std::string& name, const grasp::Detection& d, const io::Config& cfg,
                     const io::OutputFrame& frame);

// The cloud with the ranked grasps coloured by score, and the object's mirrored back in cyan.
cv::Mat detection_picture(const Cloud& input, const grasp::Detection& d, const io::Config& cfg,
                          const std::string& name);

}  // namespace uwgrasp::app
