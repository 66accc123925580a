#include <gtest/gtest.h>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/grasp/gripper.hpp"

namespace uwgrasp::grasp {

TEST(Gripper, DefaultBoxesFollowTheGeometry) {
  const Gripper g = make_gripper({});
  const auto& c = g.config;
  // Closing region: finger length x aperture x finger height (1.5 cm tall, 8.4), centred.
  EXPECT_FLOAT_EQ(g.closing.hi.x() - g.closing.lo.x(), c.finger_length);
  EXPECT_FLOAT_EQ(g.closing.hi.y() - g.closing.lo.y(), c.max_aperture);
  EXPECT_FLOAT_EQ(g.closing.hi.z() - g.closing.lo.z(), 0.015f);
  EXPECT_TRUE(g.closing.contains(Eigen::Vector3f::Zero()));
  // Fingers touch the closing region at y = -/+ A/2; the palm sits behind, the body behind it.
  const Box& left = g.solids[int(Part::left_finger)];
  const Box& right = g.solids[int(Part::right_finger)];
  EXPECT_FLOAT_EQ(left.hi.y(), g.closing.lo.y());
  EXPECT_FLOAT_EQ(right.lo.y(), g.closing.hi.y());
  EXPECT_FLOAT_EQ(right.hi.y() - right.lo.y(), c.finger_width);
  EXPECT_FLOAT_EQ(g.solids[int(Part::palm)].hi.x(), g.closing.lo.x());
  EXPECT_FLOAT_EQ(g.solids[int(Part::body)].hi.x(), g.solids[int(Part::palm)].lo.x());
  EXPECT_FLOAT_EQ(g.solids[int(Part::body)].hi.x() - g.solids[int(Part::body)].lo.x(), c.body_length);
  // The outer collision box encloses everything and reaches back along the arm (6.1).
  EXPECT_FLOAT_EQ(g.bounds.lo.x(), -c.finger_length / 2 - c.palm_depth - c.body_length);
  EXPECT_FLOAT_EQ(g.bounds.hi.x(), c.finger_length / 2);
  EXPECT_FLOAT_EQ(g.bounds.hi.y(), c.max_aperture / 2 + c.finger_width);
  EXPECT_FLOAT_EQ(max_grasp_width(g), c.max_aperture - 2 * c.clearance);
  // Solid parts never overlap the closing region's interior.
  for (const Box& s : g.solids) EXPECT_FALSE(s.contains(Eigen::Vector3f(0, 0.039f, 0)));
}

TEST(Gripper, RejectsImpossibleGeometryNamingTheField) {
  const auto message = [](GripperConfig c) {
    try {
      make_gripper(c);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  GripperConfig c;
  c.max_aperture = -0.01f;
  EXPECT_NE(message(c).find("gripper.max_aperture"), std::string::npos);
  c = {};
  c.finger_height = 0;
  EXPECT_NE(message(c).find("gripper.finger_height"), std::string::npos);
  c = {};
  c.min_aperture = 0.09f;
  EXPECT_NE(message(c).find("gripper.min_aperture"), std::string::npos);
  c = {};
  c.clearance = 0.05f;
  EXPECT_NE(message(c).find("gripper.clearance"), std::string::npos);
  EXPECT_EQ(message(GripperConfig{}), "");
}

}  // namespace uwgrasp::grasp
