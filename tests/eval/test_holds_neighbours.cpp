// Neighbours close beside the object (grasp.score.robust.scene): a grasp whose finger passes
// a millimetre from a neighbour clears it at the nominal pose, but the vehicle never reaches the
// nominal pose exactly. Judged against the true shapes, such top-1s put a finger into the
// neighbour; measured on the perturbed poses against the rest of the scene too, they lose their
// robustness to grasps with room on both sides.
#include <gtest/gtest.h>

#include "holds_scenes.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::holds;

// A red can between two grey ones, 1.5 cm apart across the view: a finger (1 cm thick, the
// gripper 8 cm open) fits between them with 2.5 mm to spare at best.
sim::Scene can_between_cans() {
  const sim::Shape can{.kind = sim::ShapeKind::cylinder, .radius = 0.03, .length = 0.11};
  sim::Scene s = on_floor(solid("can", can, V3(0, 0, 0.055)));
  for (const double y : {-0.075, 0.075}) {
    sim::SceneObject n = solid(y < 0 ? "right" : "left", can, V3(0, y, 0.055));
    n.color = {120, 120, 120};
    n.interest = false;
    s.objects.push_back(n);
  }
  return s;
}

// The top-1s (seeds 1-16, clear water with sensor noise) whose parts hit anything but the can.
int into_a_neighbour(bool scene) {
  io::Config cfg;
  cfg.grasp.score.robust.scene = scene;
  int n = 0;
  for (std::uint64_t seed = 1; seed <= 16; ++seed) {
    const Judged j = detect_and_judge(can_between_cans(), cfg, seed, false, "clear");
    if (j.evaluation.judgements.empty()) continue;
    const eval::Judgement& top = j.evaluation.judgements.front();
    n += top.verdict == eval::Verdict::collision && top.object != 0;
  }
  return n;
}
}  // namespace

TEST(HoldsBesideNeighbours, PerturbedPosesClearTheNeighboursToo) {
  const int with_scene = into_a_neighbour(true), without = into_a_neighbour(false);
  EXPECT_GE(without, 2) << "the scene no longer provokes the failure";
  EXPECT_LE(with_scene, 0) << "without the scene's check: " << without;
}
