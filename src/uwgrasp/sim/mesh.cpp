#include "uwgrasp/sim/mesh.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <numbers>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::sim {

namespace {
constexpr double kPi = std::numbers::pi;

std::uint32_t add_vertex(Mesh& m, const Eigen::Vector3d& v) {
  m.vertices.push_back(v.cast<float>());
  return static_cast<std::uint32_t>(m.vertices.size() - 1);
}

// A grid of (nu + 1) x (nv + 1) vertices from f(u, v), u, v in [0, 1], stitched into quads;
// wrap_u/wrap_v join the last column/row to the first (closed surfaces of revolution).
template <class F>
void grid(Mesh& m, int nu, int nv, bool wrap_u, bool wrap_v, F f) {
  const auto base = static_cast<std::uint32_t>(m.vertices.size());
  const int cu = wrap_u ? nu : nu + 1, cv = wrap_v ? nv : nv + 1;
  for (int i = 0; i < cu; ++i)
    for (int j = 0; j < cv; ++j) add_vertex(m, f(double(i) / nu, double(j) / nv));
  const auto id = [&](int i, int j) {
    return base + static_cast<std::uint32_t>((i % cu) * cv + (j % cv));
  };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
}
}  // namespace

Mesh make_box(const Eigen::Vector3d& size) {
  Mesh m;
  const Eigen::Vector3d h = 0.5 * size;
  for (int k = 0; k < 8; ++k)
    add_vertex(m, Eigen::Vector3d((k & 1) ? h.x() : -h.x(), (k & 2) ? h.y() : -h.y(),
                                  (k & 4) ? h.z() : -h.z()));
  // Faces -x, +x, -y, +y, -z, +z, outward counter-clockwise.
  const std::uint32_t f[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                 {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : f) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

Mesh make_cylinder(double radius, double length, int segments) {
  Mesh m;
  const double h = 0.5 * length;
  grid(m, segments, 1, true, false, [&](double u, double v) {
    return Eigen::Vector3d(radius * std::cos(2 * kPi * u), radius * std::sin(2 * kPi * u),
                           -h + v * length);
  });
  for (int side = 0; side < 2; ++side) {
    const double z = side ? h : -h;
    const std::uint32_t centre = add_vertex(m, Eigen::Vector3d(0, 0, z));
    for (int i = 0; i < segments; ++i) {
      const std::uint32_t a = static_cast<std::uint32_t>(2 * i + side);
      const std::uint32_t b = static_cast<std::uint32_t>(2 * ((i + 1) % segments) + side);
      m.triangles.push_back(side ? std::array{centre, a, b} : std::array{centre, b, a});
    }
  }
  return m;
}

Mesh make_torus(double major, double minor, int segments, int sides) {
  Mesh m;
  grid(m, segments, sides, true, true, [&](double u, double v) {
    const double a = 2 * kPi * u, b = 2 * kPi * v;
    const double rho = major + minor * std::cos(b);
    return Eigen::Vector3d(rho * std::cos(a), rho * std::sin(a), minor * std::sin(b));
  });
  return m;
}

Mesh make_sphere(double radius, int levels) {
  Mesh m;
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  const double v[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (const auto& p : v) add_vertex(m, Eigen::Vector3d(p[0], p[1], p[2]).normalized() * radius);
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      if (auto it = mid.find(key); it != mid.end()) return it->second;
      const Eigen::Vector3d p = (m.vertices[a] + m.vertices[b]).cast<double>().normalized();
      return mid[key] = add_vertex(m, p * radius);
    };
    std::vector<std::array<std::uint32_t, 3>> next;
    for (const auto& [a, b, c] : m.triangles) {
      const auto ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    m.triangles = std::move(next);
  }
  return m;
}

Mesh make_plane(double size, double cell) {
  Mesh m;
  const int n = std::max(1, static_cast<int>(std::ceil(size / cell)));
  grid(m, n, n, false, false, [&](double u, double v) {
    return Eigen::Vector3d((u - 0.5) * size, (v - 0.5) * size, 0.0);
  });
  return m;
}

void transform(Mesh& mesh, const Pose& pose) {
  const Eigen::Isometry3f t = pose.cast<float>();
  for (auto& v : mesh.vertices) v = t * v;
}

void append(Mesh& to, const Mesh& from) {
  const auto base = static_cast<std::uint32_t>(to.vertices.size());
  to.vertices.insert(to.vertices.end(), from.vertices.begin(), from.vertices.end());
  for (const auto& [a, b, c] : from.triangles) to.triangles.push_back({a + base, b + base, c + base});
}

std::array<Eigen::Vector3f, 2> bounds(const Mesh& mesh) {
  if (mesh.vertices.empty()) return {Eigen::Vector3f::Zero(), Eigen::Vector3f::Zero()};
  Eigen::Vector3f lo = mesh.vertices[0], hi = lo;
  for (const auto& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  return {lo, hi};
}

double volume(const Mesh& mesh) {
  double v = 0;
  for (const auto& [a, b, c] : mesh.triangles)
    v += mesh.vertices[a].cast<double>().dot(
        mesh.vertices[b].cast<double>().cross(mesh.vertices[c].cast<double>()));
  return v / 6.0;
}

double area(const Mesh& mesh) {
  double s = 0;
  for (const auto& [a, b, c] : mesh.triangles)
    s += 0.5 * (mesh.vertices[b] - mesh.vertices[a])
                   .cast<double>()
                   .cross((mesh.vertices[c] - mesh.vertices[a]).cast<double>())
                   .norm();
  return s;
}

}  // namespace uwgrasp::sim
