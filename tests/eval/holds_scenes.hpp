#pragma once
// Scenes that reproduce the failure modes of grasps (test_holds*.cpp): one object on the
// seafloor, rendered by the simulator, detected with a given configuration and every returned
// grasp judged against the true shapes.
#include <cstdint>
#include <string>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/eval/evaluate.hpp"
#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/io/config.hpp"
#include "uwgrasp/sim/builtin_scenes.hpp"
#include "uwgrasp/sim/render.hpp"
#include "uwgrasp/sim/scene.hpp"

namespace uwgrasp::holds {

using V3 = Eigen::Vector3d;

// A red object of interest of one solid part centred at `centre` (W).
sim::SceneObject solid(const std::string& name, const sim::Shape& shape, const V3& centre);

// One object of interest on the seafloor, seen from 0.7 m by the built-in tilted camera.
sim::Scene on_floor(const sim::SceneObject& o);

struct Judged {
  sim::Frame frame;  // what the camera gave the detector
  grasp::Detection detection;
  eval::Evaluation evaluation;
  bool exists = false;  // the judge's own search finds a grasp that holds
};

// Renders with the perfect sensor (or `water`, with sensor noise), detects with `cfg` and
// judges every returned grasp.
Judged detect_and_judge(const sim::Scene& scene, io::Config cfg, std::uint64_t seed = 1,
                        bool search_exists = true, const std::string& water = "");

// `var` = the built-in mesh scene `name`; the test skips when the shared meshes are absent.
#define UWGRASP_MESH_SCENE_OR_SKIP(var, name)                            \
  sim::Scene var;                                                      \
  try {                                                                \
    var = sim::builtin_scene(name);                                    \
  } catch (const Error& e) {                                           \
    GTEST_SKIP() << "shared data not found: " << e.what();             \
  }

// Whether the best-ranked grasp holds at mu 0.4.
bool top1_holds(const Judged& j);

}  // namespace uwgrasp::holds
