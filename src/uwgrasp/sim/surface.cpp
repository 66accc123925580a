// Points on an object's surface and the surface nearest a point (query.hpp), on the world's
// meshes and Embree scene.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/core/rng.hpp"
#include "uwgrasp/sim/query.hpp"
#include "uwgrasp/sim/world_impl.hpp"

namespace uwgrasp::sim {

namespace {
using V3 = Eigen::Vector3d;

// Ericson's closest point on triangle abc to p (Real-Time Collision Detection, 5.1.5).
V3 closest_on_triangle(const V3& p, const V3& a, const V3& b, const V3& c) {
  const V3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const V3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const V3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

struct NearestQuery {
  const World::Impl& w;
  V3 p;
  NearestSurface best;
};

bool nearest_callback(RTCPointQueryFunctionArguments* args) {
  auto& q = *static_cast<NearestQuery*>(args->userPtr);
  const int object = q.w.owners[args->geomID].object;
  if (object < 0) return false;
  const auto [a, b, c] = triangle(q.w, args->geomID, args->primID);
  const V3 x = closest_on_triangle(q.p, a, b, c);
  const double d = (x - q.p).norm();
  if (d < q.best.distance || (d == q.best.distance && object < q.best.object)) {
    q.best = {d, x, object};
    args->query->radius = float(d);
    return true;  // the search radius shrank
  }
  return false;
}
}  // namespace

std::vector<SurfaceSample> sample_object_surface(const World& world, int object, std::size_t count,
                                                 std::uint64_t seed) {
  const World::Impl& w = world.impl();
  std::vector<std::pair<std::size_t, std::size_t>> tris;  // (geometry, triangle)
  std::vector<double> cumulative;
  double total = 0.0;
  for (std::size_t g = 0; g < w.meshes.size(); ++g) {
    if (w.owners[g].object != object) continue;
    for (std::size_t t = 0; t < w.meshes[g].triangles.size(); ++t) {
      const auto [a, b, c] = triangle(w, unsigned(g), unsigned(t));
      total += 0.5 * (b - a).cross(c - a).norm();
      tris.emplace_back(g, t);
      cumulative.push_back(total);
    }
  }
  if (tris.empty() || !(total > 0.0))
    throw Error("sim: object " + std::to_string(object) + " has no surface to sample");
  Rng rng(seed, 0x5AAF1E);
  std::vector<SurfaceSample> out(count);
  for (SurfaceSample& s : out) {
    const std::size_t k = std::size_t(std::lower_bound(cumulative.begin(), cumulative.end(), rng.uniform() * total) -
                                      cumulative.begin());
    const auto [a, b, c] = triangle(w, unsigned(tris[std::min(k, tris.size() - 1)].first),
                                    unsigned(tris[std::min(k, tris.size() - 1)].second));
    double u = rng.uniform(), v = rng.uniform();
    if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
    s.point = a + u * (b - a) + v * (c - a);
    s.normal = (b - a).cross(c - a).normalized();
  }
  return out;
}

NearestSurface nearest_surface(const World& world, const V3& p, double radius) {
  const World::Impl& w = world.impl();
  NearestQuery q{w, p, {std::numeric_limits<double>::infinity(), V3::Zero(), kNoObject}};
  RTCPointQuery pq{};
  pq.x = float(p.x()), pq.y = float(p.y()), pq.z = float(p.z());
  pq.radius = float(radius);
  pq.time = 0.0f;
  RTCPointQueryContext ctx;
  rtcInitPointQueryContext(&ctx);
  rtcPointQuery(w.rtc, &pq, &ctx, nearest_callback, &q);
  return q.best;
}

}  // namespace uwgrasp::sim
