// Whole-vehicle feasibility: hand-placed obstacles with known answers, the seafloor plane, the
// all-points oracle on random clutter, and the frames of the plane.
#include <gtest/gtest.h>

#include <random>

#include "grasp_helpers.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/grasp/reach.hpp"

namespace uwgrasp::grasp {
namespace {

using test::candidate;

FrameConfig mount(double x, double z) {
  FrameConfig fc;
  fc.gripper.position = Eigen::Vector3d(x, 0.0, z);
  return fc;
}

struct Rig {
  Gripper g = make_gripper(GripperConfig{});
  Frames f = make_frames(mount(0.35, 0.12));  // gripper at (0.35, 0, 0.12) in B, no rotation
  ReachConfig cfg;
  std::vector<Solid> solids = vehicle_solids(g, f, cfg);
  Candidate c = candidate(Eigen::Vector3f::Zero(), Eigen::Vector3f::UnitX(), Eigen::Vector3f::UnitY());

  Reject with_points(const std::vector<Eigen::Vector3f>& pts) const {
    Obstacles o;
    o.bvh = build_bvh(pts);
    const Reject fast = reach_check(o, solids, c, cfg);
    EXPECT_EQ(fast, reach_brute(pts, o, solids, c, cfg));
    return fast;
  }
  Reject with_floor(float depth) const {  // a horizontal seafloor this far below G (L: z down)
    Obstacles o;
    o.has_plane = true;
    o.plane << 0, 0, -1, depth;  // -z + depth >= 0 above the floor
    return reach_check(o, solids, c, cfg);
  }
};

TEST(Reach, HullSitsBehindTheGripperThroughTheMount) {
  const Rig s;
  // The hull's centre is B's origin: 0.35 m behind and 0.12 m above G.
  EXPECT_TRUE(s.solids[0].centre.isApprox(Eigen::Vector3f(-0.35f, 0.0f, -0.12f)));
  EXPECT_NEAR(s.solids[0].half.x(), 0.457 / 2 + 0.02, 1e-6);
  EXPECT_EQ(s.solids.size(), 1u + kParts);
}

TEST(Reach, PointsAroundTheVehicleGiveTheirReasons) {
  const Rig s;
  const float back = -0.35f - 0.2285f - 0.02f;  // the hull's rear face (with margin) in G
  EXPECT_EQ(s.with_points({{-0.35f, 0.0f, -0.12f}}), Reject::hull_collision);
  EXPECT_EQ(s.with_points({{-0.035f, 0.0f, 0.0f}}), Reject::scene_collision);  // in the palm
  EXPECT_EQ(s.with_points({{back - 0.1f, 0.0f, -0.12f}}), Reject::approach_blocked);
  EXPECT_EQ(s.with_points({{back - 0.31f, 0.0f, -0.12f}}), Reject::none);  // past the standoff
  EXPECT_EQ(s.with_points({{0.2f, 0.0f, 0.0f}}), Reject::none);  // ahead: the way is backwards
  EXPECT_EQ(s.with_points({{-0.35f, 0.4f, -0.12f}}), Reject::none);  // beside the hull
}

TEST(Reach, TheFingersSweepWhatLiesBehindThem) {
  Rig s;
  s.cfg.standoff = 0.3;
  // Between the palm and the hull's front face, beside the body (|y| > 0.03) but in line with a
  // finger (y = 0.045): free at the grasp, hit when palm and finger pass on the way in.
  const Eigen::Vector3f p(-0.09f, 0.045f, 0.0f);
  EXPECT_EQ(s.with_points({p}), Reject::approach_blocked);
  s.cfg.standoff = 0.0;
  EXPECT_EQ(s.with_points({p}), Reject::none);
}

TEST(Reach, SeafloorPlane) {
  Rig s;
  // Hull bottom (with margin) at 0.027 m below G, gripper body at 0.03; no tolerance.
  EXPECT_EQ(s.with_floor(0.05f), Reject::none);
  EXPECT_EQ(s.with_floor(0.031f), Reject::none);
  EXPECT_EQ(s.with_floor(0.029f), Reject::scene_collision);  // the gripper's body 1 mm in
  EXPECT_EQ(s.with_floor(0.012f), Reject::hull_collision);
  s.cfg.floor_tolerance = 0.01;  // parts may sink 1 cm into the floor's inlier band
  EXPECT_EQ(s.with_floor(0.025f), Reject::none);
  // Approaching upwards (pitch up 30 degrees): the hull's rear corner drops to 0.323 m below G
  // at the grasp, and the standoff is 0.15 m lower still.
  Rig up;
  up.c = candidate(Eigen::Vector3f::Zero(), Eigen::Vector3f(0.866f, 0.0f, -0.5f), Eigen::Vector3f::UnitY());
  EXPECT_EQ(up.with_floor(0.3f), Reject::hull_collision);
  EXPECT_EQ(up.with_floor(0.4f), Reject::approach_blocked);
  EXPECT_EQ(up.with_floor(0.5f), Reject::none);
}

TEST(Reach, HierarchyAgreesWithEveryPointOnClutter) {
  Rig s;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), small(-0.04f, 0.04f);
  std::vector<Eigen::Vector3f> pts;  // 25 clumps of 120 points, 8 cm across, in a 2 m cube
  for (int k = 0; k < 25; ++k) {
    const Eigen::Vector3f centre(u(rng), u(rng), u(rng));
    for (int i = 0; i < 120; ++i) pts.push_back(centre + Eigen::Vector3f(small(rng), small(rng), small(rng)));
  }
  Obstacles o;
  o.bvh = build_bvh(pts);
  o.has_plane = true;
  o.plane << 0.1f, 0.2f, -0.97f, 0.9f;
  o.plane.head<3>().normalize();
  std::size_t reasons[kRejectKinds] = {};
  for (int i = 0; i < 400; ++i) {
    const Candidate c = candidate(Eigen::Vector3f(u(rng), u(rng), u(rng)),
                                  Eigen::Vector3f(u(rng), u(rng), u(rng)),
                                  Eigen::Vector3f(u(rng), u(rng), u(rng)));
    s.cfg.standoff = 0.05 + 0.5 * (i % 5) / 4.0;
    const Reject r = reach_check(o, s.solids, c, s.cfg);
    ASSERT_EQ(r, reach_brute(pts, o, s.solids, c, s.cfg)) << "candidate " << i;
    ++reasons[static_cast<int>(r)];
  }
  // The clutter is dense enough that every reason occurs; sparse enough that some pass.
  for (Reject r : {Reject::none, Reject::hull_collision, Reject::scene_collision, Reject::approach_blocked})
    EXPECT_GT(reasons[static_cast<int>(r)], 0u) << reject_name(r);
}

// The seafloor verdict corner by corner, as the plane check computed it before its closed form.
Reject plane_by_corners(const Obstacles& o, const std::vector<Solid>& solids, const Candidate& c,
                        const ReachConfig& cfg) {
  const auto below = [&](const Solid& b, float t) {
    for (const auto& p : corners(b, c, t))
      if (o.plane.head<3>().dot(p) + o.plane[3] < -float(cfg.floor_tolerance)) return true;
    return false;
  };
  bool blocked = false;
  for (const Solid& b : solids) {
    if (below(b, 0.0f)) return b.at_grasp;
    blocked = blocked || below(b, float(cfg.standoff));
  }
  return blocked ? Reject::approach_blocked : Reject::none;
}

TEST(Reach, PlaneCheckIsTheCornerByCornerVerdict) {
  Rig s;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::size_t reasons[kRejectKinds] = {}, on_a_corner = 0;
  for (int i = 0; i < 4000; ++i) {
    const Candidate c =
        candidate(Eigen::Vector3f(u(rng), u(rng), u(rng)), Eigen::Vector3f(u(rng), u(rng), u(rng)),
                  Eigen::Vector3f(u(rng), u(rng), u(rng)));
    s.cfg.standoff = 0.5 * (i % 5) / 4.0;
    s.cfg.floor_tolerance = (i % 3) * 0.005;
    Obstacles o;
    o.has_plane = true;
    o.plane << u(rng), u(rng), -1.0f, 0.0f;
    o.plane.head<3>().normalize();
    // Half the planes through a corner of a solid, at the tolerance: the verdict turns on rounding.
    const Solid& b = s.solids[std::size_t(i) % s.solids.size()];
    const Eigen::Vector3f corner =
        corners(b, c, (i / 7) % 2 ? float(s.cfg.standoff) : 0.0f)[std::size_t(i) % 8];
    o.plane[3] =
        i % 2 ? -o.plane.head<3>().dot(corner) - float(s.cfg.floor_tolerance) : 0.3f * u(rng);
    on_a_corner += i % 2;
    const Reject r = reach_plane_check(o, s.solids, c, s.cfg);
    ASSERT_EQ(r, plane_by_corners(o, s.solids, c, s.cfg)) << "candidate " << i;
    ++reasons[static_cast<int>(r)];
  }
  for (Reject r :
       {Reject::none, Reject::hull_collision, Reject::scene_collision, Reject::approach_blocked})
    EXPECT_GT(reasons[static_cast<int>(r)], 0u) << reject_name(r);
  EXPECT_EQ(on_a_corner, 2000u);
}

TEST(Reach, PlaneIsMovedToTheLevelFrameWithTheCameraAbove) {
  FrameConfig fc;
  fc.capture_pitch = 0.3;
  const Frames f = make_frames(fc);
  // A plane 1.2 m in front of the camera along its optical axis, normal given towards it.
  Surroundings s;
  s.has_plane = true;
  s.plane << 0, 0, 1, -1.2f;
  const Obstacles o = make_obstacles(s, f);
  ASSERT_TRUE(o.has_plane);
  const Eigen::Vector3f cam = f.level_from_camera.translation().cast<float>();
  EXPECT_NEAR(o.plane.head<3>().dot(cam) + o.plane[3], 1.2f, 1e-5);
  const Eigen::Vector3f on = (f.level_from_camera * Eigen::Vector3d(0.3, -0.2, 1.2)).cast<float>();
  EXPECT_NEAR(o.plane.head<3>().dot(on) + o.plane[3], 0.0f, 1e-5);
}

TEST(Reach, BadConfigIsAnError) {
  Rig s;
  s.cfg.hull_size.x() = 0;
  EXPECT_THROW(vehicle_solids(s.g, s.f, s.cfg), Error);
  s.cfg = ReachConfig{};
  s.cfg.standoff = -0.1;
  EXPECT_THROW(vehicle_solids(s.g, s.f, s.cfg), Error);
  s.cfg = ReachConfig{};
  EXPECT_THROW(vehicle_solids(s.g, make_frames(mount(0.1, 0.05)), s.cfg), Error);  // inside
  EXPECT_NO_THROW(vehicle_solids(s.g, make_frames(mount(0.1, 0.2)), s.cfg));     // below it
}

}  // namespace
}  // namespace uwgrasp::grasp
