#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>

#include "shapes.hpp"
#include "uwgrasp/cloud/preprocess.hpp"
#include "uwgrasp/core/error.hpp"

namespace uwgrasp::cloud {

namespace {
// A floor 1.5 m below the camera (y down) with a 10 cm box on it, plus NaNs and a far point.
Cloud floor_scene() {
  Cloud c;
  for (float x = -1; x <= 1; x += 0.01f)
    for (float z = 1; z <= 3; z += 0.01f) c.points.emplace_back(x, 1.5f, z);
  test::append(c, test::box_surface({-0.05f, 1.4f, 1.95f}, {0.05f, 1.4999f, 2.05f}, 0.005f));
  c.points.emplace_back(std::nanf(""), 0.f, 0.f);
  c.points.emplace_back(0.f, 0.f, 9.f);
  make_unorganised(c);
  return c;
}
}  // namespace

TEST(Preprocess, RemovesTheFloorAndKeepsTheBox) {
  const Cloud c = floor_scene();
  StageTimer t;
  const Preprocessed p = preprocess(c, {}, 1, t);
  EXPECT_EQ(p.counts.input, c.size());
  EXPECT_EQ(p.counts.finite, c.size() - 1);
  EXPECT_EQ(p.counts.in_range, c.size() - 2);  // 9 m is beyond the 6 m limit
  ASSERT_TRUE(p.plane.found);
  EXPECT_LT(test::angle_deg(p.plane.coefficients.head<3>(), {0, -1, 0}), 0.1);
  EXPECT_NEAR(p.plane.coefficients[3], 1.5f, 1e-3f);
  // What is left is the box above the floor (more than the plane tolerance away).
  ASSERT_GT(p.cloud.size(), 500u);
  for (const auto& q : p.cloud.points) EXPECT_LT(q.y(), 1.5f - 0.009f);
  EXPECT_EQ(p.cloud.normals.size(), p.cloud.size());
  // The map from input to output is consistent.
  for (std::size_t i = 0; i < c.size(); ++i) {
    const auto m = p.output_of_input[i];
    if (m >= 0) {
      EXPECT_EQ(p.cloud.points[std::size_t(m)], c.points[i]);
    }
    if (p.plane_of_input[i]) {
      EXPECT_EQ(m, -1);
    }
  }
  for (const char* s : {"finite", "range", "outliers", "plane", "normals"})
    EXPECT_GT(t.ms(s) + 1e-9, 0.0) << s;
}

// Outliers and normals share one search: their results must be those of the two stages run on
// their own. Stray points 1-2 cm off the box are removed as outliers while they sit in the box
// points' lists, so those lists are completed by the wider search. The grids are jittered: on a
// regular grid equal distances tie at the k-th place, and either search may take either point.
TEST(Preprocess, SharedSearchGivesWhatTheStagesGiveAlone) {
  Cloud c = floor_scene();
  Rng r(3);
  for (auto& p : c.points) p += 1e-4f * Eigen::Vector3f(r.uniform(), r.uniform(), r.uniform());
  for (int i = 0; i < 40; ++i)
    c.points.emplace_back(0.06f + 0.01f * r.uniform(), 1.4f + 0.09f * r.uniform(),
                          1.95f + 0.1f * r.uniform());
  make_unorganised(c);
  StageTimer t;
  const Preprocessed shared = preprocess(c, {}, 1, t, 30);
  PreprocessConfig before_outliers;
  before_outliers.outliers.enabled = false;
  const Cloud seen = preprocess(c, before_outliers, 1, t).cloud;
  const Filtered alone = remove_outliers(seen, {});
  ASSERT_LT(alone.cloud.size(), seen.size());
  ASSERT_EQ(shared.cloud.points, alone.cloud.points);
  Cloud ref = alone.cloud;
  const KdTree tree(ref.points);
  const Neighbours nb = knn_all(tree, ref.points, 30);
  compute_normals(ref, {}, nb);
  ASSERT_EQ(shared.neighbours.k, 30u);
  EXPECT_EQ(shared.neighbours.indices, nb.indices);
  EXPECT_EQ(shared.neighbours.sq_dists, nb.sq_dists);
  // The same lists in the same order give bit-identical normals and curvature.
  EXPECT_EQ(shared.cloud.normals, ref.normals);
  EXPECT_EQ(shared.cloud.curvature, ref.curvature);
}

TEST(Preprocess, FewerPointsLeftThanTheNormalNeighbourhood) {
  // Five points above a floor: fewer than normals.k survive the plane stage.
  Cloud c = test::plane_grid(60, 1.0f, 2.0f);
  for (int i = 0; i < 5; ++i) c.points.emplace_back(0.01f * float(i), 0.02f * float(i % 2), 1.8f + 0.01f * float(i));
  make_unorganised(c);
  PreprocessConfig cfg;
  cfg.outliers.enabled = false;
  StageTimer t;
  const Preprocessed p = preprocess(c, cfg, 1, t, 30);
  ASSERT_EQ(p.cloud.size(), 5u);
  for (const auto& n : p.cloud.normals) EXPECT_NEAR(n.norm(), 1.0f, 1e-5f);
}

TEST(Preprocess, BadInputsNameTheProblem) {
  StageTimer t;
  EXPECT_THROW(preprocess(Cloud{}, {}, 1, t), Error);
  Cloud nan;
  nan.points.assign(50, Eigen::Vector3f::Constant(std::nanf("")));
  make_unorganised(nan);
  try {
    preprocess(nan, {}, 1, t);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("finite"), std::string::npos);
  }
  Cloud far;
  far.points.assign(10, Eigen::Vector3f(0, 0, 50));
  make_unorganised(far);
  EXPECT_THROW(preprocess(far, {}, 1, t), Error);
  PreprocessConfig need_plane;
  need_plane.plane.required = true;
  need_plane.plane.distance = 0.001f;  // no 2 mm slab holds 5 % of a 20 cm sphere
  EXPECT_THROW(preprocess(test::sphere(2000, 0.2f, {0, 0, 2}), need_plane, 1, t), Error);
}

}  // namespace uwgrasp::cloud

namespace uwgrasp::cloud {

namespace {
// The faces of a 20 x 30 x 10 cm box a camera at the origin sees (the three facing it), the box
// turned 30 deg about the camera's y and 1 m away: an object-only scan, no support anywhere.
Cloud box_scan() {
  Cloud all = test::box_surface({-0.1f, -0.15f, -0.05f}, {0.1f, 0.15f, 0.05f}, 0.004f), c;
  const Eigen::Matrix3f R = Eigen::AngleAxisf(0.52f, Eigen::Vector3f::UnitY()).toRotationMatrix() *
                            Eigen::AngleAxisf(0.3f, Eigen::Vector3f::UnitX()).toRotationMatrix();
  const Eigen::Vector3f centre(0.05f, 0.0f, 1.0f);
  const Eigen::Vector3f half(0.1f, 0.15f, 0.05f);
  for (const auto& q : all.points) {
    Eigen::Vector3f n = Eigen::Vector3f::Zero();  // the face's outward normal
    for (int a = 0; a < 3; ++a)
      if (std::abs(std::abs(q[a]) - half[a]) < 1e-4f) n[a] = q[a] > 0.0f ? 1.0f : -1.0f;
    const Eigen::Vector3f p = R * q + centre;
    if ((R * n).dot(p) < 0.0f) c.points.push_back(p);  // facing the camera
  }
  make_unorganised(c);
  return c;
}
}  // namespace

// An object-only scan keeps its largest face: the points off that plane lie behind it, seen from
// the camera, so it is the object's own face, not a support under it (preprocess.plane.support_only).
TEST(Preprocess, AnObjectOnlyScanKeepsItsFaces) {
  const Cloud c = box_scan();
  ASSERT_GT(c.size(), 3000u);
  StageTimer t;
  PreprocessConfig cfg;
  cfg.outliers.enabled = false;
  const Preprocessed p = preprocess(c, cfg, 1, t);
  EXPECT_TRUE(p.plane_is_face);
  EXPECT_FALSE(p.plane.found);
  EXPECT_EQ(p.counts.plane, 0u);
  // The thesis's rule removes the face.
  cfg.plane.support_only = false;
  const Preprocessed thesis = preprocess(c, cfg, 1, t);
  EXPECT_TRUE(thesis.plane.found);
  EXPECT_FALSE(thesis.plane_is_face);
  EXPECT_LT(thesis.cloud.size(), c.size() * 3 / 4);
  // A floor under a box is still a support (a table with the room beyond its edge: the real mug
  // scene, Pipeline.MugOnTableIsOneSegmentAfterTheTableIsRemoved).
  const Preprocessed floor = preprocess(floor_scene(), {}, 1, t);
  EXPECT_TRUE(floor.plane.found);
  EXPECT_FALSE(floor.plane_is_face);
}

// A pipe lying on the seafloor puts nothing clearly in front of the floor (its top is within
// three plane tolerances), and stereo leaves a few hundred mismatches behind it: the floor is
// still the support and is removed, not kept as the face of an object (the floor would then be
// segmented with the pipe).
TEST(Preprocess, AFloorWithALowObjectAndAFewMismatchesBehindItIsStillRemoved) {
  Cloud c;
  for (float x = -1; x <= 1; x += 0.01f)
    for (float z = 1; z <= 3; z += 0.01f) c.points.emplace_back(x, 1.5f, z);
  test::append(c, test::box_surface({-0.2f, 1.48f, 1.9f}, {0.2f, 1.4999f, 1.95f}, 0.005f));
  const std::size_t floor_and_objects = c.size();
  for (float x = -0.9f; x <= 0.9f; x += 0.1f)  // 19 x 19 mismatches, 5-41 cm behind the floor
    for (float z = 1.1f; z <= 2.9f; z += 0.1f) c.points.emplace_back(x, 1.55f + 0.2f * (x + 0.9f), z);
  make_unorganised(c);
  ASSERT_LT(double(c.size() - floor_and_objects), 0.01 * double(floor_and_objects));
  StageTimer t;
  PreprocessConfig cfg;
  cfg.outliers.enabled = false;
  const Preprocessed p = preprocess(c, cfg, 1, t);
  ASSERT_TRUE(p.plane.found);
  EXPECT_FALSE(p.plane_is_face);
  EXPECT_LT(test::angle_deg(p.plane.coefficients.head<3>(), {0, -1, 0}), 0.1);
  // Left: the pipe's top above the floor's tolerance and the mismatches, not the floor.
  EXPECT_LT(p.cloud.size(), c.size() / 10);
  const auto above = [](const Eigen::Vector3f& q) { return q.y() < 1.485f; };
  EXPECT_GT(std::count_if(p.cloud.points.begin(), p.cloud.points.end(), above), 500);
}

}  // namespace uwgrasp::cloud
