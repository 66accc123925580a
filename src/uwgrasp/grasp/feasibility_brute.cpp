// The thesis's brute-force feasibility check (6.1, 8.4): the reference the BVH walk is tested
// against, and the closing region for pictures.
#include "uwgrasp/grasp/feasibility.hpp"
#include "uwgrasp/grasp/feasibility_closing.hpp"
#include "uwgrasp/grasp/lanes.hpp"

namespace uwgrasp::grasp {

using closing_detail::Closing, closing_detail::solid_at;

Check check_brute(std::span<const Eigen::Vector3f> points, const Gripper& g, const Candidate& c) {
  Check out;
  const lanes::Frame4 to_gripper(c.rotation.transpose(), c.position);
  Closing acc{out};
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Eigen::Vector3f p = to_gripper.point(points[k]);
    const Reject r = solid_at(g, p);
    if (r != Reject::none) return Check{r};
    if (g.closing.contains(p)) acc.add(p, static_cast<std::uint32_t>(k));
  }
  acc.finish(g);
  return out;
}

std::vector<std::uint32_t> closing_points(std::span<const Eigen::Vector3f> points,
                                          const Gripper& g, const Candidate& c) {
  std::vector<std::uint32_t> out;
  const lanes::Frame4 to_gripper(c.rotation.transpose(), c.position);
  for (std::size_t k = 0; k < points.size(); ++k)
    if (g.closing.contains(to_gripper.point(points[k]))) out.push_back(static_cast<std::uint32_t>(k));
  return out;
}

}  // namespace uwgrasp::grasp
