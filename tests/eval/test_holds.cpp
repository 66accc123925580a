// The failure modes grasps used to have, each on a scene that reproduced it, judged against the
// true shapes (eval/): fingers through the unseen back, closing on space assumed but never seen,
// widths measured on one side, the seafloor, a grasp offered where none exists, a fragment taken
// for the object, and surfaces hidden by our own outlier filter. Where the
// thesis's one-sided pipeline (grasp.shape off, score.mode thesis, normal sampler) still fails on
// the scene, it is run too, to show the scene provokes the failure.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "holds_scenes.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/eval/exists.hpp"
#include "uwgrasp/sim/builtin_scenes.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::holds;

// The thesis's pipeline: its sampler along the normals and q_tot on the one-sided cloud.
io::Config thesis_scoring() {
  io::Config c;
  c.grasp.shape.enabled = false;
  c.grasp.score.mode = grasp::ScoreMode::thesis;
  c.grasp.sampler.kind = grasp::SamplerKind::normal;
  return c;
}

std::size_t count(const Judged& j, eval::Verdict v) {
  std::size_t n = 0;
  for (const auto& k : j.evaluation.judgements) n += k.verdict == v;
  return n;
}
}  // namespace

// A can 6 cm across and 15 cm tall standing on the seafloor: the camera sees its front half. On
// the completed shape no returned grasp collides with the can (its unseen back included), and
// the best one holds.
TEST(Holds, NoFingerThroughTheUnseenBack) {
  const sim::Shape can{.kind = sim::ShapeKind::cylinder, .radius = 0.03, .length = 0.15};
  const sim::Scene s = on_floor(solid("can", can, V3(0, 0, 0.075)));
  const Judged after = detect_and_judge(s, io::Config{});
  ASSERT_FALSE(after.evaluation.judgements.empty());
  EXPECT_EQ(count(after, eval::Verdict::collision), 0u);
  EXPECT_TRUE(top1_holds(after));
}

// A bottle's curved back, which one view never sees: the YCB mustard bottle standing and lying on
// its side turned 50 degrees to the view (built-in scenes of the shared mesh). The unseen volume
// under and behind what was seen stops short of the true back (20-25 mm on the turned bottle), so
// grasps closing across the bottle put a finger through its back or close on its curve outside
// the friction cone. Mirrored about the bottle's symmetry planes (one tilted 27 degrees from the
// vertical on the turned bottle), the seen side gives the back, and the best grasp holds.
TEST(Holds, ACurvedBackFromTheObjectsSymmetry) {
  for (const char* name : {"mustard_bottle", "mustard_bottle_turned"}) {
    UWGRASP_MESH_SCENE_OR_SKIP(s, name);
    io::Config without = io::Config{};
    without.grasp.shape.symmetry.enabled = false;
    int held = 0, held_without = 0;
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      held += top1_holds(detect_and_judge(s, io::Config{}, seed, false));
      held_without += top1_holds(detect_and_judge(s, without, seed, false));
    }
    EXPECT_EQ(held, 4) << name;
    EXPECT_LE(held_without, 2) << name << ": the scene no longer provokes the failure";
  }
}

// The standing mustard bottle in clear water with the sensor's noise: grasps close across it from
// the seen front to the mirrored back. The back is mirrored about the bottle's second symmetry
// plane, which sends the front behind the bottle and so lands few points on the seen surface:
// searched freely within 20 degrees of perpendicular to the first plane, it came out 10-24
// degrees off, the mirrored back turned by twice that, and closings the model put in force
// closure needed mu 0.4-1.5 on the true bottle (3 of these 12 seeds). Square to the first plane,
// and turned together with it, the back is where the bottle's is. The seeds reproduced the
// failure with the organised frames' depth rule of the time (2 % of the range per pixel step);
// the pair is compared there, and the default must hold on every seed too.
TEST(Holds, TheSecondSymmetryPlaneIsSquareToTheFirst) {
  constexpr int seeds = 12;
  UWGRASP_MESH_SCENE_OR_SKIP(s, "mustard_bottle");
  io::Config square = io::Config{};
  square.preprocess.organised.depth_change = 0.02f;
  io::Config free = square;
  free.grasp.shape.symmetry.perpendicular = false;
  int held = 0, held_square = 0, held_free = 0;
  for (std::uint64_t seed = 1; seed <= std::uint64_t(seeds); ++seed) {
    held += top1_holds(detect_and_judge(s, io::Config{}, seed, false, "clear"));
    held_square += top1_holds(detect_and_judge(s, square, seed, false, "clear"));
    held_free += top1_holds(detect_and_judge(s, free, seed, false, "clear"));
  }
  EXPECT_EQ(held, seeds);
  EXPECT_EQ(held_square, seeds);
  EXPECT_LE(held_free, seeds - 3) << "the scene no longer provokes the failure";
}

// A T shape: a wide block held 6 cm above the seafloor on a thin 1 cm post. Under the block the
// gravity prior assumes volume the camera never saw; a grasp closing on that volume alone closes
// on nothing (a miss) or on the post at a slant. Grasps must close on what the least model -
// the seen surface and a thin shell behind it - holds too.
TEST(Holds, NoGraspClosesOnAssumedVolumeAlone) {
  sim::SceneObject o = solid("post", sim::Shape{.size = V3(0.01, 0.01, 0.08)}, V3(0, 0, 0.04));
  o.parts.push_back({sim::Shape{.size = V3(0.05, 0.12, 0.03)}, Pose::Identity()});
  o.parts.back().pose.translation() = V3(0, 0, 0.055);
  const Judged after = detect_and_judge(on_floor(o), io::Config{});
  ASSERT_TRUE(after.exists);
  ASSERT_FALSE(after.evaluation.judgements.empty());
  EXPECT_EQ(count(after, eval::Verdict::miss), 0u);
  EXPECT_TRUE(top1_holds(after));
}

// A can 8 cm across standing on the seafloor is wider than the usable aperture (7 cm) however it
// is grasped across its body, and its top is too close to the seafloor for anything else: no
// grasp exists. Seen from one side, its width along the view is a few millimetres; one-sided
// scoring offers grasps the judge finds too wide or colliding. The completed shape offers none.
TEST(Holds, AWideCanIsNotOfferedAGraspThatCannotClose) {
  sim::Shape can{.kind = sim::ShapeKind::cylinder, .radius = 0.04, .length = 0.05};
  const sim::Scene s = on_floor(solid("can", can, V3(0, 0, 0.025)));
  const Judged before = detect_and_judge(s, thesis_scoring());
  ASSERT_FALSE(before.exists);
  EXPECT_FALSE(before.evaluation.judgements.empty()) << "one-sided scoring no longer offers grasps here";
  const Judged after = detect_and_judge(s, io::Config{});
  EXPECT_EQ(after.detection.result.grasps.size(), 0u);
}

// A flat slab lying on the seafloor: nothing to close on. The detector answers "no grasp" and
// says why (not_robust: nothing it predicts holds), and the judge's search agrees.
TEST(Holds, NoGraspWhereNoneExists) {
  const sim::Scene s = on_floor(solid("slab", sim::Shape{.size = V3(0.15, 0.15, 0.03)}, V3(0, 0, 0.015)));
  const Judged after = detect_and_judge(s, io::Config{});
  EXPECT_FALSE(after.exists);
  EXPECT_TRUE(after.detection.result.grasps.empty());
}

// A 5 cm cube on the seafloor: no returned grasp reaches into the seafloor (floor tolerance 0),
// and the best one holds.
TEST(Holds, NothingThroughTheSeafloor) {
  const Judged after =
      detect_and_judge(on_floor(solid("cube", sim::Shape{.size = V3(0.05, 0.05, 0.05)}, V3(0, 0, 0.025))), io::Config{});
  ASSERT_FALSE(after.evaluation.judgements.empty());
  for (const auto& j : after.evaluation.judgements)
    EXPECT_FALSE(j.verdict == eval::Verdict::collision && j.object == sim::kSeafloorObject);
  EXPECT_TRUE(top1_holds(after));
}

namespace {
// The object's points the camera saw (labelled in the frame) and those the detector took as the
// object, for a scene rendered with the perfect sensor.
std::pair<std::size_t, std::size_t> seen_and_taken(const sim::Scene& scene, const io::Config& cfg,
                                                   bool noise = false) {
  const sim::World world(scene);
  sim::RenderConfig rc;
  rc.noise.enabled = noise;
  const sim::Frame f = sim::render_rgbd(world, sim::camera_pose(scene, {}), rc, 1);
  const auto seen = std::size_t(std::count(f.labels.begin(), f.labels.end(), sim::kLabelFirstObject));
  io::Config c = cfg;
  c.grasp.frames.camera = *scene.camera_mount;
  grasp::given_attitude(c.grasp.frames, scene.vehicle.rpy.x(), scene.vehicle.rpy.y());
  return {seen, grasp::detect(f.cloud, c.preprocess, c.segment, c.grasp, 1).object.size()};
}
}  // namespace

// A box turned 30 degrees to the view, seen by the noisy sensor: region growing over k-nearest
// neighbours shatters it into fragments and the thesis's selection takes one as the object (84
// of its 8,006 points), so the grasp engine never sees the box. The whole connected object is
// the box. (The organised path's 7 x 7 normals shatter it less - it takes a face of 4,371 points
// - so the fragment is reproduced on the k-d tree path the thesis used.)
TEST(Holds, TheWholeObjectNotOneFace) {
  sim::SceneObject o = solid("box", sim::Shape{.size = V3(0.05, 0.09, 0.12)}, V3(0, 0, 0.06));
  o.pose.linear() = Eigen::AngleAxisd(0.52, V3::UnitZ()).toRotationMatrix();
  io::Config thesis;
  thesis.segment.object.whole = false;
  thesis.preprocess.organised.enabled = false;
  const auto [seen, face] = seen_and_taken(on_floor(o), thesis, true);
  const auto [seen2, whole] = seen_and_taken(on_floor(o), io::Config{}, true);
  ASSERT_GT(seen, 2000u);
  EXPECT_LT(face, seen / 10) << "the thesis's selection takes the whole box here";  // 84 of 8006
  EXPECT_GT(whole, seen * 9 / 10);  // 94 %: the lowest centimetre goes with the seafloor
  EXPECT_TRUE(top1_holds(detect_and_judge(on_floor(o), io::Config{})));
}

// The same box's faces seen at a grazing angle have sparse points; the thesis's outlier filter
// (mean + 1 sigma of the k-NN distances) removes them, and the grasp check, running on what is
// left, lets a finger into a surface the camera saw. Mean + 3 sigma keeps them, and what the
// filter still removes stays an obstacle: no returned grasp collides with a seen surface.
TEST(Holds, NoFingerInASurfaceTheFilterRemoved) {
  sim::SceneObject o = solid("box", sim::Shape{.size = V3(0.05, 0.09, 0.12)}, V3(0, 0, 0.06));
  o.pose.linear() = Eigen::AngleAxisd(1.3, V3::UnitZ()).toRotationMatrix();
  io::Config thesis_filter;
  thesis_filter.preprocess.outliers.std_mul = 1.0;
  const auto [seen, kept1] = seen_and_taken(on_floor(o), thesis_filter);
  const auto [seen2, kept3] = seen_and_taken(on_floor(o), io::Config{});
  EXPECT_LT(kept1, seen * 85 / 100) << "mu + sigma no longer drops the grazing face's points";  // 76 %
  EXPECT_GT(kept3, seen * 90 / 100);  // 94 %
  const Judged after = detect_and_judge(on_floor(o), io::Config{});
  ASSERT_FALSE(after.evaluation.judgements.empty());
  for (const auto& j : after.evaluation.judgements)
    EXPECT_FALSE(j.verdict == eval::Verdict::collision && j.visible) << "a part in a seen surface";
}

// The torque tool standing upright in coastal water: only its thin post and foot can be held.
// Marine snow in front of the lens (particles of a few millimetres; near the lens one covers a
// hundred pixels) survived every filter and stood where the vehicle's hull must be for grasps
// on the post: 95 % of the draws failed the reach check, and the detector offered no grasp on
// 7 of 20 frames (seeds 4-8 among them) where the judge's own search finds one. Small detached
// blobs off the seafloor are not obstacles for the vehicle (grasp/debris.hpp).
TEST(Holds, MarineSnowDoesNotBlockTheVehicle) {
  UWGRASP_MESH_SCENE_OR_SKIP(s, "torque_tool");
  io::Config every_point;
  every_point.grasp.reach.debris_size = 0.0;
  int held = 0, held_before = 0;
  for (std::uint64_t seed = 4; seed <= 7; ++seed) {
    held += top1_holds(detect_and_judge(s, io::Config{}, seed, false, "coastal"));
    held_before += top1_holds(detect_and_judge(s, every_point, seed, false, "coastal"));
  }
  EXPECT_GE(held, 3);
  EXPECT_LE(held_before, 1) << "the scene no longer provokes the failure";
}

// The thesis's future work (9.3): a sampler that keeps most of its candidates feasible on every
// object. The YCB mustard bottle lying on its side is wider than the gripper's aperture along
// its body and can be grasped at its neck only: drawn uniformly, about 1 candidate in 10 passes
// the checks; drawing later blocks near the passes (grasp.sampler.focus) keeps most, and the
// best grasp still holds.
TEST(Holds, MostCandidatesFeasibleWhereFewPlacesAreGraspable) {
  UWGRASP_MESH_SCENE_OR_SKIP(s, "mustard_bottle_lying");
  io::Config uniform = io::Config{};
  uniform.grasp.sampler.focus = false;
  const auto share = [](const Judged& j) {
    return double(j.detection.result.feasible()) / double(j.detection.result.candidates);
  };
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    const Judged focused = detect_and_judge(s, io::Config{}, seed, false);
    EXPECT_GE(share(focused), 0.5) << "seed " << seed;
    EXPECT_TRUE(top1_holds(focused)) << "seed " << seed;
    EXPECT_LT(share(detect_and_judge(s, uniform, seed, false)), 0.3)
        << "seed " << seed << ": the scene no longer provokes the failure";
  }
}

// A bar lying on the seafloor, lower than the finger pads are long, can be held only near the
// fingertips. Drawn with the pads' centres on the bar, the fingers reached the floor: most draws
// failed the reach check and those that passed had their tips within a few millimetres of the
// floor, so the robust ranking found none that held when perturbed and the detector offered no
// grasp where the judge finds many (the T-bar, perfect sensor, 13 of 60 seeds). Draws tried
// again backed off until the gripper clears the floor (grasp.sampler.floor_clearance) give a
// top-1 that holds, also under the judge's perturbation, and most candidates pass.
TEST(Holds, ABarLyingOnTheSeafloorIsHeldNearTheFingertips) {
  UWGRASP_MESH_SCENE_OR_SKIP(s, "t_bar_lying");
  io::Config unlifted;
  unlifted.grasp.sampler.floor_clearance = 0.0;
  int offered_unlifted = 0;
  for (const std::uint64_t seed : {3, 10}) {
    const Judged after = detect_and_judge(s, io::Config{}, seed, false);
    EXPECT_TRUE(top1_holds(after)) << "seed " << seed;
    EXPECT_GE(after.evaluation.robust_top1, 0.4) << "seed " << seed;
    EXPECT_GE(double(after.detection.result.feasible()), 0.3 * double(after.detection.result.candidates));
    offered_unlifted += !detect_and_judge(s, unlifted, seed, false).detection.result.grasps.empty();
  }
  EXPECT_EQ(offered_unlifted, 0) << "the scene no longer provokes the failure";
}

// The lift is for objects lower than the fingers are long. On the barbell (plates 7.5 cm tall, a
// bar between them 2.5 cm over the floor) lifted draws closed on the bar's edges, out of force
// closure on the true shape though not by our prediction (noisy water): every grasp of a taller
// object is drawn as it is without the lift.
TEST(Holds, AnObjectTallerThanTheFingersIsNotLifted) {
  const sim::Scene s = sim::builtin_scene("barbell");
  io::Config unlifted;
  unlifted.grasp.sampler.floor_clearance = 0.0;
  for (const std::uint64_t seed : {2, 5}) {
    const auto with = detect_and_judge(s, io::Config{}, seed, false, "clear").detection.result.grasps;
    const auto without = detect_and_judge(s, unlifted, seed, false, "clear").detection.result.grasps;
    ASSERT_FALSE(with.empty()) << "seed " << seed;
    ASSERT_EQ(with.size(), without.size()) << "seed " << seed;
    for (std::size_t i = 0; i < with.size(); ++i)
      EXPECT_TRUE(with[i].level_from_gripper.isApprox(without[i].level_from_gripper)) << "seed " << seed << " rank " << i;
  }
}
