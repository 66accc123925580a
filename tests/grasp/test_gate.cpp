// The checks before scoring one candidate at a time (gate.hpp), the one-candidate gripper check
// (Checker), and the antipodal sampler that tries a draw's turns until the checks pass.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>

#include "objects.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/rng.hpp"
#include "uwgrasp/grasp/frames.hpp"
#include "uwgrasp/grasp/gate.hpp"
#include "uwgrasp/grasp/samplers.hpp"

namespace uwgrasp::grasp {

namespace {
// The barbell's visible side, its shape model and the seafloor it rests on (world z = 0).
struct Barbell {
  fixtures::ObjectCloud obj = fixtures::render_object(fixtures::Object::barbell, {}, 20000);
  Frames frames;
  std::vector<Eigen::Vector3f> level, model, model_normals;
  ObjectShape shape;
  PointBvh bvh;
  Gripper gripper = make_gripper({});
  Surroundings scene;
  OcclusionConfig occlusion;
  ReachConfig reach;
  Shadow shadow;

  Barbell() {
    FrameConfig fc;
    fc.camera.rpy.y() = obj.camera_pitch;
    frames = make_frames(fc);
    level = points_to_level(obj.cloud.points, frames);
    const Eigen::Vector3d n = obj.camera_from_world.linear().col(2);
    const FloorPlane floor_c(float(n.x()), float(n.y()), float(n.z()),
                             float(-n.dot(obj.camera_from_world.translation())));
    scene = {obj.cloud.points, true, floor_c};
    shape = complete_shape(level, obj.cloud.points, frames, level_plane(scene, frames), ShapeConfig{});
    model = level;
    model.insert(model.end(), shape.points.begin(), shape.points.end());
    model_normals = directions_to_level(obj.cloud.normals, frames);
    model_normals.insert(model_normals.end(), shape.normals.begin(), shape.normals.end());
    bvh = build_bvh(model);
    shadow = {make_depth_map(obj.cloud.points, occlusion.resolution), part_samples(gripper, occlusion.spacing)};
  }
  GateInputs inputs() const {
    return {bvh, gripper, gripper, shape, frames, &shadow, occlusion, reach, scene};
  }
  std::vector<Candidate> antipodal(const std::function<bool(const Candidate&)>& clear, std::uint32_t count,
                                   std::uint32_t enough = UINT32_MAX, SamplerConfig cfg = {},
                                   std::vector<char>* passed = nullptr) const {
    const Box& palm = gripper.solids[int(Part::palm)];
    ClearFn by_slot;
    if (clear) by_slot = [&](const Candidate& c, std::uint32_t) { return clear(c); };
    return sample_antipodal(model, model_normals, shape, cfg, frames.body_from_gripper.linear(),
                            max_grasp_width(gripper), -palm.hi.x(), palm.half().y(), palm.half().z(), 7,
                            count, 0, by_slot, enough, passed);
  }
};

bool same(const Candidate& a, const Candidate& b) {
  return a.position == b.position && a.rotation == b.rotation && a.source == b.source;
}
}  // namespace

// One candidate at a time gives exactly what the batch check gives.
TEST(Gate, CheckerIsTheBatchCheckOneAtATime) {
  const Barbell s;
  const auto c = sample_normal(s.level, SamplerConfig{}, s.frames.body_from_gripper.linear(), 3, 1500);
  const std::vector<Check> batch = check_candidates(s.bvh, s.gripper, c);
  const Checker one(s.bvh, s.gripper);
  std::size_t feasible = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const Check k = one(c[i]);
    ASSERT_EQ(k.reason, batch[i].reason) << i;
    EXPECT_EQ(k.inliers, batch[i].inliers);
    EXPECT_EQ(k.width, batch[i].width);
    EXPECT_EQ(k.left, batch[i].left);
    EXPECT_EQ(k.right, batch[i].right);
    // solids() names the same part, or none where the closing region decides
    const Reject r = one.solids(c[i]);
    EXPECT_TRUE(r == k.reason || (r == Reject::none && int(k.reason) > int(Reject::collision_body))) << i;
    feasible += k.feasible();
  }
  EXPECT_GT(feasible, 0u);
  EXPECT_LT(feasible, c.size());
}

// The cheap screens (voxels, the seafloor plane) only ever reject what the full checks reject.
TEST(Gate, PassesIsTheCheckThenTheRest) {
  const Barbell s;
  const Gate gate(s.inputs());
  const Checker check(s.bvh, s.gripper);
  SamplerConfig sc;
  sc.sigma_theta = Eigen::Vector3d::Constant(0.6);
  const auto c = sample_uniform(s.level, sc, s.frames.body_from_gripper.linear(), 5, 3000);
  std::array<std::size_t, kRejectKinds> why{};
  std::size_t passed = 0;
  for (const Candidate& k : c) {
    const Check first = check(k);
    const Reject full = first.feasible() ? gate.after_check(k) : first.reason;
    ++why[std::size_t(full)];
    ASSERT_EQ(gate.passes(k), full == Reject::none);
    passed += gate.passes(k);
  }
  EXPECT_GT(passed, 0u);
  EXPECT_GT(why[std::size_t(Reject::hull_collision)], 0u);  // the seafloor and the scene took part
  EXPECT_GT(why[std::size_t(Reject::collision_palm)], 0u);
}

// The shape's cell lookup (truncation after a float bounds test) is the floor of cell_of's
// coordinates, bounds-tested as integers: points in, around and far outside the grid, on cell
// boundaries, and NaN.
TEST(Gate, ShapeLookupIsTheFloorOfItsCell) {
  const Barbell s;
  const ObjectShape& g = s.shape;
  ASSERT_FALSE(g.empty());
  const auto reference = [&](const Eigen::Vector3f& p) {
    const Eigen::Vector3i c = g.cell_of(p);
    if ((c.array() < 0).any() || c.x() >= g.nx || c.y() >= g.ny || c.z() >= g.nz) return Occupancy::free;
    return g.cells[(std::size_t(c.z()) * std::size_t(g.ny) + std::size_t(c.y())) * std::size_t(g.nx) + std::size_t(c.x())];
  };
  Rng rng(4);
  const Eigen::Vector3f size = g.voxel * Eigen::Vector3f(float(g.nx), float(g.ny), float(g.nz));
  std::size_t occupied = 0;
  for (int i = 0; i < 200000; ++i) {
    Eigen::Vector3f p = g.origin + Eigen::Vector3f(float(rng.uniform() * 1.2 - 0.1), float(rng.uniform() * 1.2 - 0.1),
                                                   float(rng.uniform() * 1.2 - 0.1)).cwiseProduct(size);
    if (i % 4 == 0)  // on a boundary between cells
      p = g.origin + g.voxel * (Eigen::Vector3f(float(std::floor(rng.uniform() * g.nx)), float(std::floor(rng.uniform() * g.ny)),
                                                float(std::floor(rng.uniform() * g.nz))) - Eigen::Vector3f::Constant(0.5f));
    ASSERT_EQ(g.at(p), reference(p)) << p.transpose();
    occupied += g.occupied(p);
  }
  EXPECT_GT(occupied, 1000u);
  EXPECT_EQ(g.at(Eigen::Vector3f::Constant(NAN)), Occupancy::free);
  EXPECT_EQ(g.at(Eigen::Vector3f::Constant(1e30f)), Occupancy::free);
  EXPECT_EQ(g.at(Eigen::Vector3f::Constant(-1e30f)), Occupancy::free);
}

// The gate keeps the gripper check of a candidate that passes (the detector does not check it
// again): the batch check's, field by field; a candidate that fails leaves the given check as it was.
TEST(Gate, KeepsTheCheckOfWhatPasses) {
  const Barbell s;
  const Gate gate(s.inputs());
  const auto c = s.antipodal({}, 600);
  const std::vector<Check> batch = check_candidates(s.bvh, s.gripper, c);
  std::size_t passed = 0, failed = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    Check k;
    k.inliers = 12345;  // a marker: left alone unless the candidate passes
    if (!gate.passes(c[i], &k)) {
      EXPECT_EQ(k.inliers, 12345u) << i;
      ++failed;
      continue;
    }
    ++passed;
    ASSERT_TRUE(batch[i].feasible()) << i;
    EXPECT_EQ(k.reason, batch[i].reason);
    EXPECT_EQ(k.inliers, batch[i].inliers) << i;
    EXPECT_EQ(k.nearest, batch[i].nearest);
    EXPECT_EQ(k.left, batch[i].left);
    EXPECT_EQ(k.right, batch[i].right);
    EXPECT_EQ(k.width, batch[i].width);
  }
  EXPECT_GT(passed, 20u);
  EXPECT_GT(failed, 20u);
}

// A gate given the hull and obstacles made beforehand (the detector makes them beside the shape
// model) is the gate that makes them itself: the same verdict and the same reason for every draw.
TEST(Gate, MadeWithPrebuiltObstaclesIsTheSameGate) {
  const Barbell s;
  ASSERT_TRUE(s.reach.enabled);
  const Gate own(s.inputs());
  const Gate given(s.inputs(), vehicle_solids(s.gripper, s.frames, s.reach),
                   make_obstacles(s.scene, s.frames, s.reach));
  std::size_t passed = 0, reach_rejects = 0;
  for (const Candidate& c : s.antipodal({}, 600)) {
    const bool p = own.passes(c);
    EXPECT_EQ(given.passes(c), p);
    const Reject r = own.after_check(c);
    EXPECT_EQ(given.after_check(c), r);
    passed += p;
    reach_rejects += r == Reject::hull_collision || r == Reject::scene_collision ||
                     r == Reject::approach_blocked;
  }
  EXPECT_GT(passed, 20u);
  EXPECT_GT(reach_rejects, 5u) << "the obstacles decide some verdicts";
}

// The thesis's future work (9.3): a sampler whose candidates are mostly feasible. Drawn on the
// object's model alone, most antipodal draws still put a part into the object or the hull into
// the seafloor; trying each draw's turns against the checks keeps most of them.
TEST(Gate, AntipodalDrawsThatTryTheChecksAreMostlyFeasible) {
  const Barbell s;
  const Gate gate(s.inputs());
  const auto passes = [&](const Candidate& c) { return gate.passes(c); };
  const auto share = [&](const std::vector<Candidate>& c) {
    return double(std::count_if(c.begin(), c.end(), passes)) / double(c.size());
  };
  const double blind = share(s.antipodal({}, 1000));
  const double tried = share(s.antipodal(passes, 1000));
  EXPECT_GE(tried, 0.5);
  EXPECT_GT(tried, 2.0 * blind) << "blind " << blind;
}

// Drawing stops at a block boundary once enough passed; the draws do not depend on threads.
TEST(Gate, EarlyStopIsSeededAndIndependentOfThreadCount) {
  const Barbell s;
  const Gate gate(s.inputs());
  const auto passes = [&](const Candidate& c) { return gate.passes(c); };
  const auto many = s.antipodal(passes, 3000, 300);
  ASSERT_LT(many.size(), 3000u);
  EXPECT_EQ(many.size() % 256, 0u);
  EXPECT_GE(std::count_if(many.begin(), many.end(), passes), 300);
  std::vector<Candidate> one;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = s.antipodal(passes, 3000, 300);
  }
  ASSERT_EQ(one.size(), many.size());
  for (std::size_t i = 0; i < one.size(); ++i) ASSERT_TRUE(same(one[i], many[i])) << i;
}

// Finer turns about the closing axis find an approach that clears everything for more draws:
// the share of candidates that pass grows with the number of turns tried, and every candidate
// reported as passed does pass.
TEST(Gate, MoreTurnsPassMoreDraws) {
  const Barbell s;
  const Gate gate(s.inputs());
  const auto passes = [&](const Candidate& c) { return gate.passes(c); };
  std::vector<double> share;
  for (std::uint32_t turns : {1u, 6u, 12u}) {
    SamplerConfig cfg;
    cfg.turns = turns;
    std::vector<char> passed;
    const auto c = s.antipodal(passes, 768, UINT32_MAX, cfg, &passed);
    ASSERT_EQ(passed.size(), c.size());
    for (std::size_t i = 0; i < c.size(); ++i) {
      if (!passed[i]) continue;
      ASSERT_TRUE(passes(c[i])) << "turns " << turns << ", candidate " << i;
    }
    share.push_back(double(std::count(passed.begin(), passed.end(), 1)) / double(c.size()));
  }
  EXPECT_LT(share[0], share[1]);
  EXPECT_LE(share[1], share[2]);
  SamplerConfig bad;
  bad.turns = 0;
  EXPECT_THROW(check_sampler(bad), Error);
}


// Adaptive drawing (SamplerConfig::focus): where only a small part of the object can be grasped
// (here: only grasps centred within 3 cm of one that passes the checks), uniform draws keep a
// small share; once the first block keeps under half, later blocks drawn near the passes keep
// most. The pool grows between blocks only: the same candidates on one thread as on two.
TEST(Gate, FocusDrawsNearThePassesWhereFewPlacesPass) {
  const Barbell s;
  const Gate gate(s.inputs());
  const auto anywhere = [&](const Candidate& c) { return gate.passes(c); };
  const std::vector<Candidate> some = s.antipodal(anywhere, 256);
  const auto first = std::find_if(some.begin(), some.end(), anywhere);
  ASSERT_NE(first, some.end());
  const Eigen::Vector3f place = first->position;
  const auto passes = [&](const Candidate& c) { return (c.position - place).norm() < 0.03f && gate.passes(c); };
  const auto draw = [&](bool focus, std::vector<char>& passed) {
    SamplerConfig cfg;
    cfg.focus = focus;
    return s.antipodal(passes, 1024, UINT32_MAX, cfg, &passed);
  };
  const auto share = [](const std::vector<char>& p) { return double(std::count(p.begin(), p.end(), 1)) / double(p.size()); };
  std::vector<char> uniform, focused, single;
  (void)draw(false, uniform);
  const auto many = draw(true, focused);
  EXPECT_LT(share(uniform), 0.5);
  EXPECT_GE(share(focused), 0.5) << "uniform " << share(uniform);
  EXPECT_GT(share(focused), 1.5 * share(uniform));
  std::vector<Candidate> one;
  {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
    one = draw(true, single);
  }
  ASSERT_EQ(one.size(), many.size());
  for (std::size_t i = 0; i < one.size(); ++i) ASSERT_TRUE(same(one[i], many[i])) << i;
  EXPECT_EQ(single, focused);
}
}  // namespace uwgrasp::grasp
