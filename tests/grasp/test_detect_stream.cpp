// grasp::detect's stream form (detector.hpp): one Detection and one Workspace kept over frames of
// different sizes, kinds and outcomes give every frame exactly the one-shot detection's result.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/grasp/detector.hpp"
#include "uwgrasp/io/config.hpp"
#include "uwgrasp/sim/render.hpp"
#include "uwgrasp/sim/scene.hpp"

namespace uwgrasp::grasp {
namespace {

// The built-in thesis scene seen by the simulator's camera, with the depth camera's noise.
Cloud noisy_frame(std::uint64_t seed, std::uint32_t width, std::uint32_t height) {
  const sim::Scene scene = sim::builtin_scene("thesis");
  const sim::World world(scene);
  sim::RenderConfig rc;
  rc.noise.enabled = true;
  rc.camera.width = width, rc.camera.height = height;
  return sim::render_rgbd(world, sim::camera_pose(scene, {}), rc, seed).cloud;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void expect_same(const Detection& got, const Detection& want, std::size_t frame) {
  SCOPED_TRACE("frame " + std::to_string(frame));
  EXPECT_EQ(got.segment, want.segment);
  EXPECT_EQ(got.restored_colours, want.restored_colours);
  EXPECT_TRUE(same_bits(got.object.points, want.object.points));
  EXPECT_TRUE(same_bits(got.object.normals, want.object.normals));
  EXPECT_TRUE(same_bits(got.obstacles, want.obstacles));
  EXPECT_EQ(got.rests, want.rests);
  EXPECT_EQ(got.scene.segmentation.label, want.scene.segmentation.label);
  EXPECT_EQ(got.result.candidates, want.result.candidates);
  EXPECT_EQ(got.result.rejections, want.result.rejections);
  ASSERT_EQ(got.result.grasps.size(), want.result.grasps.size());
  for (std::size_t i = 0; i < got.result.grasps.size(); ++i) {
    const Grasp &a = got.result.grasps[i], &b = want.result.grasps[i];
    EXPECT_EQ(a.candidate, b.candidate);
    EXPECT_EQ(a.scores.total, b.scores.total);
    EXPECT_EQ(a.robustness, b.robustness);
    EXPECT_TRUE(a.level_from_gripper.matrix() == b.level_from_gripper.matrix());
  }
  for (const char* stage : {"plane", "segment", "select", "score"})
    EXPECT_GT(got.timer.ms(stage), 0.0) << stage;  // the timer is this frame's, not a sum
}

TEST(DetectStream, OneDetectionOverFramesOfEveryKindGivesTheOneShotResults) {
  io::Config cfg;
  cfg.segment.object.by = segment::ObjectBy::largest;
  const Cloud big = noisy_frame(5, 320, 240), small = noisy_frame(6, 160, 120);
  Cloud unorganised = noisy_frame(7, 320, 240);
  unorganised.width = std::uint32_t(unorganised.size()), unorganised.height = 1;
  Cloud nothing = small;  // a frame with no point: detect throws
  for (auto& p : nothing.points) p.setConstant(std::numeric_limits<float>::quiet_NaN());
  // Large after small and small after large, a failure in between, and back to the first.
  const std::vector<const Cloud*> frames{&small, &big, &nothing, &unorganised, &small, &big};
  Detection d;
  segment::Workspace ws;
  std::size_t done = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const Cloud& f = *frames[i];
    if (&f == &nothing) {
      EXPECT_THROW(detect(f, cfg.preprocess, cfg.segment, cfg.grasp, 3, d, ws), Error);
      EXPECT_THROW((void)detect(f, cfg.preprocess, cfg.segment, cfg.grasp, 3), Error);
      continue;
    }
    detect(f, cfg.preprocess, cfg.segment, cfg.grasp, 3, d, ws);
    const Detection once = detect(f, cfg.preprocess, cfg.segment, cfg.grasp, 3);
    ASSERT_FALSE(once.result.grasps.empty()) << "frame " << i;  // a comparison of real results
    EXPECT_EQ(d.scene.pre.organised, f.organised());
    expect_same(d, once, i);
    ++done;
  }
  EXPECT_EQ(done, 5u);
}

}  // namespace
}  // namespace uwgrasp::grasp
