#pragma once
// Shared by simulate, demo and experiments: a scene with its sensor, the detector config that
// matches it, output files and pictures.
#include <opencv2/core.hpp>

#include <string>
#include <vector>

#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/io/config.hpp"
#include "uwgrasp/io/scene_yaml.hpp"
#include "uwgrasp/sim/render.hpp"
#include "uwgrasp/vehicle/approach.hpp"
#include "uwgrasp/viz/picture.hpp"

namespace uwgrasp::app {

struct Simulation {
  sim::Scene scene;
  sim::RenderConfig render;
  Mount mount;                // the camera mount in use
  Pose world_from_camera;     // T_WC
};

// Scene (built-in name or file) with the sensor from the config; the water is `water` if given,
// else the scene's own, else the config's sim.water. Throws Error for bad input.
Simulation make_simulation(const io::Config& cfg, const std::string& scene, const std::string& water);

// The config's frames set to the simulated camera mount and the vehicle's attitude at capture,
// so detections on the simulated cloud use the level frame of the scene.
void use_simulation_frames(io::Config& cfg, const Simulation& s);

// Throws Error if the frame has no depth (the camera sees nothing within range).
void require_depth(const sim::Frame& f, const Simulation& s);

io::TruthInfo truth_info(const Simulation& s, const sim::Intrinsics& k, const std::string& sensor,
                         std::uint64_t seed);

// Centroid of the points of object i the frame sees (truth labels), camera frame; Throws Error
// if the object is not in view.
Eigen::Vector3d visible_centroid(const sim::Frame& f, const Simulation& s, std::size_t i);

// The detector config for object i of a simulated thesis scene: its Table 8.5 preset (the ring
// is the thesis's "circle"), then `sets`, the simulation's frames, and selection of the segment
// nearest the centroid of the object's visible points (truth labels; the scene has three red
// objects).
io::Config object_config(const Simulation& s, const sim::Frame& f, std::size_t i,
                         const std::vector<std::string>& sets, std::uint64_t seed);
// `cfg` with the simulation's frames and the seed, selecting the object nearest the centroid
// of object i's visible points (the detector's own settings otherwise).
io::Config pointed_at(io::Config cfg, const Simulation& s, const sim::Frame& f, std::size_t i,
                      std::uint64_t seed);

// The wireframe of a gripper (fingers, palm and, with `body`, the body behind the palm) at pose
// T (gripper frame in the picture's frame).
viz::Wire gripper_wire(const Pose& T, const grasp::Gripper& g, bool body = true);

// Gripper wireframes of ranked grasps in the camera frame, valued by score.
std::vector<viz::Wire> grasp_wires(const std::vector<grasp::Grasp>& grasps, const grasp::Frames& f,
                                   const grasp::GripperConfig& gripper, bool body = true);

// The approach onto a grasp (T_LB to reach, T_LG whose x is the approach axis) from where the
// vehicle took the picture: at rest at L's origin with the capture roll and pitch, the
// configured standoff, still water.
vehicle::ApproachTask approach_task(const Pose& level_from_vehicle, const Pose& level_from_gripper,
                                    const io::Config& cfg);

void write_png(const std::string& path, const cv::Mat& image);

}  // namespace uwgrasp::app
