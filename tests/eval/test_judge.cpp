// The judge on boxes with known answers: a square grasp holds at every friction coefficient, a
// 30-degree tilt needs mu >= tan 30, and every verdict has a scene that produces it.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <numbers>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/eval/exists.hpp"
#include "uwgrasp/eval/judge.hpp"

namespace {
using namespace uwgrasp;
using namespace uwgrasp::eval;
using V3 = Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;

Pose at(const V3& t, const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) {
  Pose p = Pose::Identity();
  p.translation() = t;
  p.linear() = R;
  return p;
}

sim::SceneObject box(const std::string& name, const V3& size, const Pose& pose) {
  return {name, {{sim::Shape{.size = size}, Pose::Identity()}}, pose, {200, 30, 30}, false};
}

sim::Scene scene(std::vector<sim::SceneObject> objects, bool floor = false) {
  sim::Scene s;
  s.name = "judge";
  s.seafloor.enabled = floor;
  s.objects = std::move(objects);
  return s;
}

// Gripper frame G at `centre`: x = approach, y = closing, z = x cross y.
Pose grasp_at(const V3& centre, const V3& approach, const V3& closing) {
  Eigen::Matrix3d R;
  R.col(0) = approach.normalized();
  R.col(1) = closing.normalized();
  R.col(2) = R.col(0).cross(R.col(1));
  return at(centre, R);
}

// A camera 1 m from the origin looking along W +x (optical z = x, x = -y, y = -z).
Camera camera_along_x() {
  Camera c;
  Eigen::Matrix3d R;
  R << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  c.world_from_camera = at(V3(-1, 0, 0), R);
  c.intrinsics = sim::make_intrinsics({});
  return c;
}

const grasp::Gripper kGripper = grasp::make_gripper({});
const V3 kDown = -V3::UnitZ();

TEST(Judge, SquareGraspOnA4cmBoxHoldsAtEveryMu) {
  const sim::World w(scene({box("cube", V3::Constant(0.04), at(V3(0, 0, 0.3)))}));
  const Judgement j = judge(w, camera_along_x(), kGripper, grasp_at(V3(0, 0, 0.3), kDown, V3::UnitY()), 0);
  ASSERT_EQ(j.verdict, Verdict::closes) << verdict_name(j.verdict);
  EXPECT_NEAR(j.width, 0.04, 1e-5);
  EXPECT_NEAR(j.mu_min, 0.0, 1e-6);
  for (double mu : {0.05, 0.2, 0.4, 0.8}) EXPECT_TRUE(j.holds(mu)) << mu;
  EXPECT_NEAR(j.contacts[0].y(), -0.02, 1e-5);
  EXPECT_NEAR(j.contacts[1].y(), 0.02, 1e-5);
  EXPECT_NEAR(j.normals[0].y(), -1.0, 1e-9);
}

// Turned 30 degrees about the gripper's z: the pads first touch two corners (width 2 x 27.3 mm),
// and the line of action through the pads' centre meets two faces whose normals are 30 degrees
// off it, so force closure needs mu >= tan 30.
TEST(Judge, BoxTurned30DegreesNeedsMuOfTan30) {
  const V3 approach = kDown, closing = V3::UnitY();
  const V3 axis = approach.cross(closing);  // the gripper's z
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(kPi / 6, axis).toRotationMatrix();
  const sim::World w(scene({box("cube", V3::Constant(0.04), at(V3(0, 0, 0.3), turn))}));
  // 5 mm back along the approach, so the corner (28.3 mm out) clears the palm (25 mm).
  const Pose T = grasp_at(V3(0, 0, 0.3) - 0.005 * approach, approach, closing);
  const Judgement j = judge(w, camera_along_x(), kGripper, T, 0);
  ASSERT_EQ(j.verdict, Verdict::closes) << verdict_name(j.verdict);
  EXPECT_NEAR(j.width, 2 * 0.02 * (std::cos(kPi / 6) + std::sin(kPi / 6)), 1e-5);
  EXPECT_NEAR(j.mu_min, std::tan(kPi / 6), 1e-4);
  EXPECT_FALSE(j.holds(0.55));
  EXPECT_TRUE(j.holds(0.6));
}

// A cylinder grasped off its axis: the pads press where they touch it, at its widest chord, so
// the line of action runs through the axis and the grasp holds (Dex-Net's line through the
// grasp centre would cross the cylinder 8 mm off its axis, at 32 degrees to its surface).
TEST(Judge, CylinderGraspedOffItsAxisHoldsWhereThePadsPress) {
  const V3 approach = kDown, closing = V3::UnitY();
  Pose cyl = at(V3(0, 0, 0.3));
  cyl.linear() = Eigen::AngleAxisd(kPi / 2, V3::UnitY()).toRotationMatrix();  // axis along W x (G's z)
  sim::Scene s = scene({});
  s.objects.push_back({"tube", {{sim::Shape{.kind = sim::ShapeKind::cylinder, .radius = 0.015, .length = 0.2}, Pose::Identity()}},
                       cyl, {200, 30, 30}, false});
  const sim::World w(s);
  const Judgement j = judge(w, camera_along_x(), kGripper, grasp_at(V3(0, 0, 0.3) - 0.008 * approach, approach, closing), 0);
  ASSERT_EQ(j.verdict, Verdict::closes) << verdict_name(j.verdict);
  EXPECT_NEAR(j.width, 0.03, 2e-4);
  EXPECT_LT(j.mu_min, std::tan(4.0 * kPi / 180));  // the 48-facet tessellation's slack
  EXPECT_NEAR(j.contacts[0].z(), 0.3, 1e-3);         // on the axis's height, not 8 mm off it
}

TEST(Judge, FingerInsideTheBoxIsACollisionNamingThatFinger) {
  // A 70 x 30 x 30 mm block around the left finger (50 x 10 x 15 mm): no surface crosses it.
  const Pose T = grasp_at(V3(0, 0, 0.3), kDown, V3::UnitY());
  const V3 left_centre = T * kGripper.solids[0].centre().cast<double>();
  const sim::World w(scene({box("block", V3(0.03, 0.03, 0.07), at(left_centre))}));
  const Judgement j = judge(w, camera_along_x(), kGripper, T, 0);
  ASSERT_EQ(j.verdict, Verdict::collision);
  EXPECT_EQ(j.part, int(grasp::Part::left_finger));
  EXPECT_EQ(j.object, 0);
  EXPECT_TRUE(j.inside);
  // The right finger cutting into the block's face instead: crossing, not inside.
  // Closing along -y puts the right finger on W's -y side, at y in [-35, -25] mm: across the
  // block's face at y = -30 mm.
  const Pose R = grasp_at(V3(0, 0.015, 0.3), kDown, -V3::UnitY());
  const Judgement k = judge(w, camera_along_x(), kGripper, R, 0);
  ASSERT_EQ(k.verdict, Verdict::collision);
  EXPECT_EQ(k.part, int(grasp::Part::right_finger));
  EXPECT_FALSE(k.inside);
}

TEST(Judge, GraspBesideTheBoxIsAMiss) {
  const sim::World w(scene({box("cube", V3::Constant(0.04), at(V3(0, 0, 0.3)))}));
  const Judgement j = judge(w, camera_along_x(), kGripper, grasp_at(V3(0.1, 0, 0.3), kDown, V3::UnitY()), 0);
  EXPECT_EQ(j.verdict, Verdict::miss);
}

TEST(Judge, BoxWiderThanTheUsableApertureIsTooWide) {
  // 75 mm in the default gripper (80 mm open, 70 mm usable).
  const sim::World w(scene({box("wide", V3(0.04, 0.075, 0.04), at(V3(0, 0, 0.3)))}));
  const Pose T = grasp_at(V3(0, 0, 0.3), kDown, V3::UnitY());
  const Judgement j = judge(w, camera_along_x(), kGripper, T, 0);
  EXPECT_EQ(j.verdict, Verdict::too_wide);
  EXPECT_NEAR(j.width, 0.075, 1e-5);
  // A 12 cm box: too wide for a gripper opening to 125 mm (115 usable), held by one of 150 mm.
  const sim::World w12(scene({box("big", V3(0.04, 0.12, 0.04), at(V3(0, 0, 0.3)))}));
  grasp::GripperConfig gc;
  gc.max_aperture = 0.125f;
  EXPECT_EQ(judge(w12, camera_along_x(), grasp::make_gripper(gc), T, 0).verdict, Verdict::too_wide);
  gc.max_aperture = 0.15f;
  const Judgement held = judge(w12, camera_along_x(), grasp::make_gripper(gc), T, 0);
  EXPECT_EQ(held.verdict, Verdict::closes);
  EXPECT_NEAR(held.width, 0.12, 1e-5);
  // With the default gripper the fingers, open to 80 mm, are inside the 12 cm box.
  EXPECT_EQ(judge(w12, camera_along_x(), kGripper, T, 0).verdict, Verdict::collision);
}

TEST(Judge, GraspThroughTheSeafloorCollidesWithTheSeafloor) {
  const sim::World w(scene({box("cube", V3::Constant(0.04), at(V3(0, 0, 0.02)))}, true));
  const Judgement ok = judge(w, camera_along_x(), kGripper, grasp_at(V3(0, 0, 0.03), kDown, V3::UnitY()), 0);
  EXPECT_EQ(ok.verdict, Verdict::closes) << verdict_name(ok.verdict);  // fingertips 5 mm above
  const Judgement j = judge(w, camera_along_x(), kGripper, grasp_at(V3(0, 0, 0.015), kDown, V3::UnitY()), 0);
  ASSERT_EQ(j.verdict, Verdict::collision);
  EXPECT_EQ(j.object, sim::kSeafloorObject);
  EXPECT_EQ(j.part, int(grasp::Part::left_finger));
  // Within the 1 mm tolerance the fingertips may touch the floor.
  const Judgement touch = judge(w, camera_along_x(), kGripper, grasp_at(V3(0, 0, 0.0245), kDown, V3::UnitY()), 0);
  EXPECT_EQ(touch.verdict, Verdict::closes);
}

TEST(Judge, AnotherObjectBetweenThePadsIsTouchedFirst) {
  const sim::World w(scene({box("cube", V3::Constant(0.02), at(V3(0, 0.01, 0.3))),
                            box("other", V3(0.02, 0.01, 0.02), at(V3(0, -0.025, 0.3)))}));
  const Judgement j = judge(w, camera_along_x(), kGripper, grasp_at(V3(0, 0, 0.3), kDown, V3::UnitY()), 0);
  EXPECT_EQ(j.verdict, Verdict::other_object);
  EXPECT_EQ(j.object, 1);
}

// The camera looks along +x at a cube: a finger cutting its front face crosses what the camera
// saw; one cutting its back face crosses what it could not see.
TEST(Judge, CollisionSaysWhetherTheCameraSawTheSurface) {
  const sim::World w(scene({box("cube", V3::Constant(0.06), at(V3(0, 0, 0)))}));
  const Camera cam = camera_along_x();
  // Approach along +x: the left finger (y in [0, 10] mm, x in [-55, -5] mm) cuts the front face.
  const Judgement front = judge(w, cam, kGripper, grasp_at(V3(-0.03, 0.05, 0), V3::UnitX(), V3::UnitY()), 0);
  ASSERT_EQ(front.verdict, Verdict::collision);
  EXPECT_EQ(front.part, int(grasp::Part::left_finger));
  EXPECT_TRUE(front.visible);
  // Approach along -x from behind: the left finger (z in [0, 10] mm, x in [25, 75] mm) cuts the
  // back face.
  const Judgement back = judge(w, cam, kGripper, grasp_at(V3(0.05, 0, 0.05), -V3::UnitX(), V3::UnitZ()), 0);
  ASSERT_EQ(back.verdict, Verdict::collision);
  EXPECT_EQ(back.part, int(grasp::Part::left_finger));
  EXPECT_FALSE(back.visible);
}

TEST(Judge, ForceClosureMuFromTheContactAngles) {
  const V3 y = V3::UnitY();
  EXPECT_NEAR(force_closure_mu(V3(0, -1, 0), -y, V3(0, 1, 0), y, y), 0.0, 1e-12);
  const V3 n(std::sin(0.3), -std::cos(0.3), 0);
  EXPECT_NEAR(force_closure_mu(V3(0, -1, 0), n, V3(0, 1, 0), y, y), std::tan(0.3), 1e-12);
  EXPECT_TRUE(std::isinf(force_closure_mu(V3(0, -1, 0), V3::UnitX(), V3(0, 1, 0), y, y)));
  EXPECT_TRUE(std::isinf(force_closure_mu(V3(0, -1, 0), y, V3(0, 1, 0), y, y)));  // facing away
}

TEST(Judge, RobustShareIsSeededAndHighForASquareGrasp) {
  const sim::World w(scene({box("cube", V3::Constant(0.04), at(V3(0, 0, 0.3)))}));
  // 3 mm up from the centre: the palm 8 mm above the cube's top (noise of 5 mm per axis).
  const Pose T = grasp_at(V3(0, 0, 0.303), kDown, V3::UnitY());
  const RobustConfig rc;
  const double a = robust_share(w, camera_along_x(), kGripper, T, 0, rc, 5, 0);
  double b = 0;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    b = robust_share(w, camera_along_x(), kGripper, T, 0, rc, 5, 0);
  }
  EXPECT_EQ(a, b);
  EXPECT_GE(a, 0.9);
  // Perturbations have the configured spread.
  double sq = 0;
  for (std::uint32_t k = 0; k < 400; ++k) sq += (perturbed(T, rc, 1, 2, k).translation() - T.translation()).squaredNorm();
  EXPECT_NEAR(std::sqrt(sq / 400 / 3), rc.sigma_position, 0.0008);
  // Fingertips 3 mm over the cube's top edge: the same noise often lifts them off it.
  const double edge = robust_share(w, camera_along_x(), kGripper, grasp_at(V3(0, 0, 0.342), kDown, V3::UnitY()), 0, rc, 5, 0);
  EXPECT_LT(edge, a);
}

TEST(Judge, BadInputIsAnError) {
  const sim::World w(scene({box("cube", V3::Constant(0.04), at(V3(0, 0, 0.3)))}));
  EXPECT_THROW(judge(w, camera_along_x(), kGripper, Pose::Identity(), 1), Error);
  Pose bad = Pose::Identity();
  bad.translation().x() = NAN;
  EXPECT_THROW(judge(w, camera_along_x(), kGripper, bad, 0), Error);
  RobustConfig rc;
  rc.mu = 0;
  EXPECT_THROW(robust_share(w, camera_along_x(), kGripper, Pose::Identity(), 0, rc, 1, 0), Error);
  Pose sheared = grasp_at(V3(0, 0, 0.3), kDown, V3::UnitY());
  sheared.linear()(0, 1) += 0.01;  // not a rotation
  EXPECT_THROW(judge(w, camera_along_x(), kGripper, sheared, 0), Error);
  Pose mirrored = grasp_at(V3(0, 0, 0.3), kDown, V3::UnitY());
  mirrored.linear().col(2) *= -1.0;
  EXPECT_THROW(judge(w, camera_along_x(), kGripper, mirrored, 0), Error);
}

// A pose whose rotation is a few 1e-7 off orthonormal - float detectors, JSON digits and products
// of frames make them - is judged as the rotation it stands for, not refused (the pads' rays
// once failed their unit-direction check on such a pose, 1.2e-6 off).
TEST(Judge, AlmostOrthonormalPosesAreJudgedAsTheRotationTheyStandFor) {
  const sim::World w(scene({box("cube", V3::Constant(0.04), at(V3(0, 0, 0.3)))}));
  const Pose exact = grasp_at(V3(0, 0, 0.3), kDown, V3(0.2, 1, 0).normalized());
  Pose rounded = exact;
  rounded.linear() *= 1.0 + 2e-6;
  rounded.linear()(1, 2) += 1e-6;
  const Judgement a = judge(w, camera_along_x(), kGripper, exact, 0);
  const Judgement b = judge(w, camera_along_x(), kGripper, rounded, 0);
  ASSERT_EQ(b.verdict, a.verdict);
  EXPECT_NEAR(b.width, a.width, 1e-6);
  EXPECT_NEAR(b.mu_min, a.mu_min, 1e-5);
}

}  // namespace

namespace {
TEST(Exists, AFloatingCubeHasAGraspAFlatSlabOnTheFloorNone) {
  const sim::World cube(scene({box("cube", V3::Constant(0.04), at(V3(0, 0, 0.3)))}, true));
  const Existence e = find_any_grasp(cube, camera_along_x(), kGripper, 0);
  ASSERT_TRUE(e.exists);
  EXPECT_TRUE(judge(cube, camera_along_x(), kGripper, e.example, 0).holds(0.4));
  // 10 x 10 x 4 cm on the floor: across it is too wide for the 70 mm usable, and closing on its
  // 4 cm height puts a finger under the floor.
  const sim::World slab(scene({box("slab", V3(0.1, 0.1, 0.04), at(V3(0, 0, 0.02)))}, true));
  const Existence none = find_any_grasp(slab, camera_along_x(), kGripper, 0);
  EXPECT_FALSE(none.exists);
  EXPECT_GT(none.tried, 1000u);
  // The same slab raised off the floor can be held top to bottom.
  const sim::World raised(scene({box("slab", V3(0.1, 0.1, 0.04), at(V3(0, 0, 0.3)))}, true));
  EXPECT_TRUE(find_any_grasp(raised, camera_along_x(), kGripper, 0).exists);
  EXPECT_THROW(find_any_grasp(slab, camera_along_x(), kGripper, 3), Error);
}

// A bar 1 cm tall lying on the floor is held across its 3 cm width only with the contacts near
// the fingertips: with them in the middle half of the pads (the search before) the fingers reach
// under the floor, and no grasp was found below 1.2 cm.
TEST(Exists, ABarLyingFlatIsHeldNearTheFingertips) {
  const sim::World bar(scene({box("bar", V3(0.03, 0.2, 0.01), at(V3(0, 0, 0.005)))}, true));
  const Existence e = find_any_grasp(bar, camera_along_x(), kGripper, 0);
  ASSERT_TRUE(e.exists);
  EXPECT_TRUE(judge(bar, camera_along_x(), kGripper, e.example, 0).holds(0.4));
}
}  // namespace
