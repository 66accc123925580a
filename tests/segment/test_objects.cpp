// Whole objects (objects.hpp) on analytic scenes: the failure mode "wrong or partial object" - a
// bright fragment taken for the object, one face of a box taken for the box, a handle left
// behind - and what joins or keeps apart.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <queue>

#include "shapes.hpp"
#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/cloud/organised.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/rng.hpp"
#include "uwgrasp/segment/objects.hpp"

namespace uwgrasp::segment {

namespace {
cloud::Neighbours neighbours(const Cloud& c, std::size_t k = 16) {
  const cloud::KdTree tree(c.points);
  return cloud::knn_all(tree, c.points, k);
}

Cloud painted(Cloud c, Rgb8 col) {
  test::paint(c, col);
  return c;
}

// Which object holds most of the points [from, to) of the cloud.
std::size_t object_of_range(const Objects& o, std::size_t from, std::size_t to) {
  std::vector<std::size_t> votes(o.points.size(), 0);
  for (std::size_t i = from; i < to; ++i)
    if (o.object_of_point[i] >= 0) ++votes[std::size_t(o.object_of_point[i])];
  return std::size_t(std::max_element(votes.begin(), votes.end()) - votes.begin());
}
}  // namespace

TEST(Objects, TwoBoxesApartAreTwoObjectsAndEachBoxIsOne) {
  Cloud c = test::box_surface({0, 0, 1}, {0.06f, 0.06f, 1.06f}, 0.004f);
  const std::size_t first = c.size();
  test::append(c, test::box_surface({0.1f, 0, 1}, {0.16f, 0.06f, 1.06f}, 0.004f));  // 4 cm apart
  const auto nb = neighbours(c);
  const float gap = connection_gap(nb);
  EXPECT_NEAR(gap, 0.012f, 0.002f);  // three times the 4 mm spacing
  const Objects o = connected_objects(c, nb, gap, 10);
  ASSERT_EQ(o.points.size(), 2u);
  EXPECT_EQ(o.points[object_of_range(o, 0, first)].size(), first);  // every face of the box
  EXPECT_EQ(o.points[object_of_range(o, first, c.size())].size(), c.size() - first);
  // Too small a gap leaves points apart; components under min_points are not objects.
  const Objects torn = connected_objects(c, nb, 0.001f, 10);
  EXPECT_TRUE(torn.points.empty());
  EXPECT_THROW(connected_objects(c, neighbours(test::sphere(50, 0.1f, {0, 0, 1})), gap, 10), Error);
}

TEST(Objects, TheGapStaysWithinItsBounds) {
  EXPECT_FLOAT_EQ(connection_gap(neighbours(test::plane_grid(40, 0.04f, 1.0f))), 0.004f);  // 1 mm grid
  EXPECT_FLOAT_EQ(connection_gap(neighbours(test::plane_grid(20, 1.0f, 1.0f))), 0.015f);   // 5 cm grid
}

// The case: a small, brightly red fragment (a chip on the seafloor) beside the dull red
// body of the object of interest. By colour intensity alone the fragment wins; an object needs a
// quarter of the most coloured object's coloured points to count, so the body is chosen.
TEST(Objects, ABrightFragmentIsNotTakenForTheObject) {
  Cloud c = painted(test::box_surface({0, 0, 1}, {0.08f, 0.12f, 1.08f}, 0.004f), {150, 40, 40});
  const std::size_t body = c.size();
  test::append(c, painted(test::box_surface({0.2f, 0, 1}, {0.22f, 0.02f, 1.02f}, 0.004f), {250, 10, 10}));
  const auto nb = neighbours(c);
  const Objects o = connected_objects(c, nb, connection_gap(nb), 10);
  ASSERT_EQ(o.points.size(), 2u);
  const ObjectConfig cfg;  // by colour, red
  ASSERT_GT(color_intensity({250, 10, 10}, "red"), 2 * color_intensity({150, 40, 40}, "red"));
  const std::size_t k = select_whole_object(c, o, Segmentation{}, cfg);
  EXPECT_EQ(k, object_of_range(o, 0, body));
  EXPECT_EQ(o.points[k].size(), body);
  // Alone, the fragment is the object (nothing else is red).
  ObjectConfig green = cfg;
  green.color = "green";
  EXPECT_THROW(select_whole_object(c, o, Segmentation{}, green), Error);
}

// A red handle seen apart from its red body (the joint is hidden) is a part of the object; a
// blue object as close and a red object farther than part_reach are not.
TEST(Objects, PartsOfTheSameColourJoinOthersDoNot) {
  Cloud c = painted(test::box_surface({0, 0, 1}, {0.08f, 0.08f, 1.08f}, 0.004f), {200, 30, 30});
  const std::size_t body = c.size();
  test::append(c, painted(test::box_surface({0.03f, 0.11f, 1.0f}, {0.05f, 0.2f, 1.02f}, 0.004f), {200, 30, 30}));
  const std::size_t handle = c.size();
  test::append(c, painted(test::box_surface({0.11f, 0, 1}, {0.15f, 0.04f, 1.04f}, 0.004f), {30, 30, 200}));
  const std::size_t blue = c.size();
  test::append(c, painted(test::box_surface({-0.2f, 0, 1}, {-0.15f, 0.05f, 1.05f}, 0.004f), {200, 30, 30}));
  const auto nb = neighbours(c);
  const Objects o = connected_objects(c, nb, connection_gap(nb), 10);
  ASSERT_EQ(o.points.size(), 4u);
  ObjectConfig cfg;
  const std::size_t k = select_whole_object(c, o, Segmentation{}, cfg);
  ASSERT_EQ(k, object_of_range(o, 0, body));
  const auto parts = gather_parts(c, o, k, cfg, cfg.part_reach);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0], k);
  EXPECT_EQ(parts[1], object_of_range(o, body, handle));
  // Selecting by anything but colour gathers every object within reach, the blue one too.
  cfg.by = ObjectBy::largest;
  const auto any = gather_parts(c, o, k, cfg, cfg.part_reach);
  ASSERT_EQ(any.size(), 3u);
  EXPECT_EQ(any[2], object_of_range(o, handle, blue));
  EXPECT_NE(std::count(any.begin(), any.end(), object_of_range(o, blue, c.size())), 1);
}

// The same scene as turbid water shows it: every colour dimmed below min_intensity (the red
// body's intensity 0.10, the handle's 0.08). The object is still the red one and its handle
// still joins it (half the body's mean intensity, not an absolute share); the dimmed blue
// object does not. A scene whose reddest objects barely differ from each other (a seafloor's
// tint) has no red object.
TEST(Objects, PartsJoinAsTheWaterDimsTheirColourAlike) {
  Cloud c = painted(test::box_surface({0, 0, 1}, {0.08f, 0.08f, 1.08f}, 0.004f), {70, 45, 40});
  const std::size_t body = c.size();
  test::append(c, painted(test::box_surface({0.03f, 0.11f, 1.0f}, {0.05f, 0.2f, 1.02f}, 0.004f), {65, 45, 40}));
  const std::size_t handle = c.size();
  test::append(c, painted(test::box_surface({0.11f, 0, 1}, {0.15f, 0.04f, 1.04f}, 0.004f), {40, 45, 70}));
  const auto nb = neighbours(c);
  const Objects o = connected_objects(c, nb, connection_gap(nb), 10);
  ASSERT_EQ(o.points.size(), 3u);
  const ObjectConfig cfg;
  ASSERT_LT(color_intensity({70, 45, 40}, "red"), cfg.min_intensity);
  const std::size_t k = select_whole_object(c, o, Segmentation{}, cfg);
  ASSERT_EQ(k, object_of_range(o, 0, body));
  const auto parts = gather_parts(c, o, k, cfg, cfg.part_reach);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[1], object_of_range(o, body, handle));
  // Two objects of the seafloor's tint (red intensity 0.02 and 0.03): nothing stands out.
  Cloud tint = painted(test::box_surface({0, 0, 1}, {0.08f, 0.08f, 1.08f}, 0.004f), {60, 55, 50});
  test::append(tint, painted(test::box_surface({0.2f, 0, 1}, {0.28f, 0.08f, 1.08f}, 0.004f), {62, 55, 50}));
  const auto nt = neighbours(tint);
  EXPECT_THROW(select_whole_object(tint, connected_objects(tint, nt, connection_gap(nt), 10), Segmentation{}, cfg),
               Error);
}

TEST(Objects, EachCriterionPicksAWholeObject) {
  Cloud c = test::box_surface({0, 0, 1}, {0.1f, 0.1f, 1.1f}, 0.004f);  // large, far
  const std::size_t big = c.size();
  test::append(c, test::box_surface({0.3f, 0, 0.5f}, {0.34f, 0.04f, 0.54f}, 0.004f));  // small, near
  const auto nb = neighbours(c);
  const Objects o = connected_objects(c, nb, connection_gap(nb), 10);
  ASSERT_EQ(o.points.size(), 2u);
  const std::size_t a = object_of_range(o, 0, big), b = object_of_range(o, big, c.size());
  ObjectConfig cfg;
  cfg.by = ObjectBy::largest;
  EXPECT_EQ(select_whole_object(c, o, Segmentation{}, cfg), a);
  cfg.by = ObjectBy::nearest;
  EXPECT_EQ(select_whole_object(c, o, Segmentation{}, cfg), b);
  cfg.by = ObjectBy::point, cfg.point = Eigen::Vector3d(0.32, 0.02, 0.5);
  EXPECT_EQ(select_whole_object(c, o, Segmentation{}, cfg), b);
  Segmentation seg;
  seg.segments = {{std::uint32_t(big + 3), std::uint32_t(big + 4)}};
  cfg.by = ObjectBy::label, cfg.label = 0;
  EXPECT_EQ(select_whole_object(c, o, seg, cfg), b);
  cfg.label = 1;
  EXPECT_THROW(select_whole_object(c, o, seg, cfg), Error);
  EXPECT_THROW(select_whole_object(c, Objects{}, seg, cfg), Error);
}

// Parts gathered from the selected object are those a chain of parts, each within reach of one
// already taken, links to it - as a brute force over every pair of points finds them, in the
// same order: chains of blobs within reach of each other and blobs anywhere, at two reaches
// (the second so fine that the cells that spare the k-d tree its far points cover a wide box).
TEST(Objects, PartsWithinReachAreThoseABruteForceFinds) {
  Rng rng(11, 0);
  const auto uniform = [&](float lo, float hi) { return lo + (hi - lo) * float(rng.uniform()); };
  Cloud c;
  Objects o;
  for (std::uint32_t b = 0; b < 100; ++b) {
    // Two chains of ten blobs 7 cm apart (3 cm between neighbours), 30 cm apart; then blobs
    // anywhere in a wide box.
    const Eigen::Vector3f centre =
        b < 20 ? Eigen::Vector3f(0.07f * float(b % 10) + (b < 10 ? 0.0f : 1.0f), 0.0f, 1.0f)
               : Eigen::Vector3f(uniform(-1.0f, 2.0f), uniform(-1.0f, 1.0f), uniform(1.2f, 2.0f));
    o.points.emplace_back();
    for (int i = 0; i < 40; ++i) {
      o.points.back().push_back(std::uint32_t(c.size()));
      o.object_of_point.push_back(std::int32_t(b));
      c.points.push_back(centre + Eigen::Vector3f(uniform(-0.02f, 0.02f), uniform(-0.02f, 0.02f),
                                                  uniform(-0.02f, 0.02f)));
    }
  }
  c.width = std::uint32_t(c.size()), c.height = 1;
  ObjectConfig cfg;
  cfg.by = ObjectBy::largest;
  for (const float reach : {0.05f, 0.0004f}) {
    std::vector<std::size_t> want{0};
    std::vector<char> taken(o.points.size(), 0);
    taken[0] = 1;
    for (std::size_t next = 0; next < want.size(); ++next)
      for (std::size_t k = 0; k < o.points.size(); ++k) {
        bool near = false;
        for (const auto i : o.points[want[next]])
          for (const auto j : o.points[k]) near = near || (c.points[i] - c.points[j]).squaredNorm() <= reach * reach;
        if (!taken[k] && near) taken[k] = 1, want.push_back(k);
      }
    EXPECT_EQ(gather_parts(c, o, 0, cfg, reach), want) << "reach " << reach;
    if (reach > 0.01f) {
      EXPECT_GE(want.size(), 10u);  // the chain was followed
      EXPECT_LT(want.size(), 50u);  // and far blobs left out
    }
  }
}

// Two one-point parts just within and just beyond reach of each other, in each of the 26
// directions to the cells around, from random places in the cell grid.
TEST(Objects, APartJustWithinReachJoinsInEveryDirection) {
  Rng rng(12, 0);
  ObjectConfig cfg;
  cfg.by = ObjectBy::largest, cfg.min_extent = 0.0f;  // one-point parts: no width to ask of them
  const float reach = 0.05f;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if (!dx && !dy && !dz) continue;
        const Eigen::Vector3f dir = Eigen::Vector3f(float(dx), float(dy), float(dz)).normalized();
        for (int t = 0; t < 20; ++t) {
          const Eigen::Vector3f p(float(rng.uniform()), float(rng.uniform()), 1.0f + float(rng.uniform()));
          for (const float share : {0.99f, 1.01f}) {
            Cloud c;
            c.points = {p, p + share * reach * dir};
            c.width = 2, c.height = 1;
            const Objects o{{0, 1}, {{0}, {1}}};
            EXPECT_EQ(gather_parts(c, o, 0, cfg, reach).size(), share < 1.0f ? 2u : 1u)
                << dx << " " << dy << " " << dz << " share " << share;
          }
        }
      }
}

// The objects are the connected components of the neighbour graph (edges within the gap, either
// direction), numbered by their lowest point, as a breadth-first search finds them, on one thread
// and on two: an organised frame of blocks at five depths with holes (window lists, each pair
// joined once) and a plane with a chain of points off its edge (k-nearest lists, not symmetric).
TEST(Objects, ComponentsAreABreadthFirstSearchsOnAnyNumberOfThreads) {
  Rng rng(13, 0);
  Cloud frame;
  frame.width = 160, frame.height = 120;
  std::vector<std::uint32_t> pixels;
  for (std::uint32_t v = 0; v < frame.height; ++v)
    for (std::uint32_t u = 0; u < frame.width; ++u) {
      const float z = 1.0f + 0.05f * float((u / 20 * 7 + v / 15 * 3) % 5);  // blocks at five depths
      if (rng.uniform() < 0.05) continue;  // a hole
      pixels.push_back(v * frame.width + u);
      frame.points.emplace_back((float(u) - 80.0f) * z / 500.0f, (float(v) - 60.0f) * z / 500.0f, z);
    }
  const cloud::PixelMap map = cloud::pixel_map(frame.width, frame.height, pixels);
  const cloud::Neighbours window = cloud::window_neighbours(frame.points, map, {}, Eigen::Vector3f::Zero());
  frame.width = std::uint32_t(frame.points.size()), frame.height = 1;
  // A plane on a 2 mm grid, then a chain of points 5 mm apart leading away from its edge: the
  // chain's lists hold the plane's edge, the plane's 8 nearest never the chain (a pair listed by
  // its higher index only).
  Cloud chain = test::plane_grid(30, 0.06f, 1.0f);
  float edge = 0.0f;
  for (const auto& p : chain.points) edge = std::max(edge, p.x());
  const std::size_t plane = chain.size();
  for (int m = 0; m < 12; ++m) chain.points.emplace_back(edge + 0.0045f + 0.005f * float(m), 0.0f, 1.0f);
  make_unorganised(chain);
  const cloud::Neighbours knn = neighbours(chain, 8);
  bool down = false, up = false;
  for (std::uint32_t i = 0; i < chain.size(); ++i)
    for (std::size_t k = 0; k < knn.of(i).size(); ++k) {
      if (knn.dists_of(i)[k] > 0.0055f * 0.0055f) continue;
      down = down || (i >= plane && knn.of(i)[k] < plane);
      up = up || (i < plane && knn.of(i)[k] >= plane);
    }
  ASSERT_TRUE(down && !up);
  for (const auto& [c, nb, gap] : {std::tuple<const Cloud*, cloud::Neighbours, float>{&frame, window, 0.006f},
                                   {&chain, knn, 0.0055f}}) {
    std::vector<std::vector<std::uint32_t>> adjacent(c->size());
    for (std::uint32_t i = 0; i < c->size(); ++i)
      for (std::size_t k = 0; k < nb.of(i).size(); ++k)
        if (nb.dists_of(i)[k] <= gap * gap) adjacent[i].push_back(nb.of(i)[k]), adjacent[nb.of(i)[k]].push_back(i);
    std::vector<std::vector<std::uint32_t>> want;
    std::vector<char> seen(c->size(), 0);
    for (std::uint32_t s = 0; s < c->size(); ++s) {
      if (seen[s]) continue;
      std::vector<std::uint32_t> part{s};
      seen[s] = 1;
      for (std::size_t h = 0; h < part.size(); ++h)
        for (const auto q : adjacent[part[h]])
          if (!seen[q]) seen[q] = 1, part.push_back(q);
      std::sort(part.begin(), part.end());
      if (part.size() >= 10) want.push_back(part);
    }
    ASSERT_FALSE(want.empty());
    EXPECT_EQ(connected_objects(*c, nb, gap, 10).points, want);
    const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    EXPECT_EQ(connected_objects(*c, nb, gap, 10).points, want);
  }
}

}  // namespace uwgrasp::segment
