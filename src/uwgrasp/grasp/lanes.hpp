#pragma once
// Four float lanes (GCC/Clang vector extensions: SSE on x86-64, NEON on arm64), so that the BVH
// walks test a node's four child boxes, or four points, in one go. Internal to grasp/. Every
// constant a walk compares against is broadcast to four lanes once (Box4, Frame4), not per test.
#include <Eigen/Core>
#include <cstring>

namespace uwgrasp::grasp::lanes {

using F4 = float __attribute__((vector_size(16)));
using M4 = int __attribute__((vector_size(16)));  // per lane: -1 true, 0 false

inline F4 load(const float* p) {
  F4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline F4 splat(float x) { return F4{x, x, x, x}; }
inline F4 abs(F4 v) { return reinterpret_cast<F4>(reinterpret_cast<M4>(v) & 0x7fffffff); }
// Bit c set when lane c is true.
inline int bits(M4 m) { return (m[0] & 1) | (m[1] & 2) | (m[2] & 4) | (m[3] & 8); }

// Three coordinates, four lanes each: four points, four box corners, centres or half extents.
struct V3 {
  F4 x, y, z;
  static V3 splat(const Eigen::Vector3f& v) { return {lanes::splat(v.x()), lanes::splat(v.y()), lanes::splat(v.z())}; }
  Eigen::Vector3f lane(int k) const { return {x[k], y[k], z[k]}; }
};

// Four lanes from each of three coordinate arrays (points, node centres or half extents).
inline V3 load(const float* x, const float* y, const float* z) { return {load(x), load(y), load(z)}; }

// Four boxes as lower and upper corners; or one box broadcast to four lanes.
struct Box4 {
  V3 lo, hi;
  static Box4 splat(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi) { return {V3::splat(lo), V3::splat(hi)}; }
};

// Lanes where box a overlaps box b (closed). NaN lanes (unused children) are never true.
inline M4 overlap(const Box4& a, const Box4& b) {
  return (a.lo.x <= b.hi.x) & (a.hi.x >= b.lo.x) & (a.lo.y <= b.hi.y) & (a.hi.y >= b.lo.y) &
         (a.lo.z <= b.hi.z) & (a.hi.z >= b.lo.z);
}
// Lanes where box a lies wholly inside box b.
inline M4 inside(const Box4& a, const Box4& b) {
  return (a.lo.x >= b.lo.x) & (a.hi.x <= b.hi.x) & (a.lo.y >= b.lo.y) & (a.hi.y <= b.hi.y) &
         (a.lo.z >= b.lo.z) & (a.hi.z <= b.hi.z);
}
// Lanes where point p lies in box b (closed).
inline M4 contains(const V3& p, const Box4& b) {
  return (p.x >= b.lo.x) & (p.x <= b.hi.x) & (p.y >= b.lo.y) & (p.y <= b.hi.y) & (p.z >= b.lo.z) &
         (p.z <= b.hi.z);
}
// Lanes where boxes (centre c, half extents h) and (centre d, half extents e) are not apart
// along any axis.
inline M4 near(const V3& c, const V3& h, const V3& d, const V3& e) {
  return (abs(c.x - d.x) <= h.x + e.x) & (abs(c.y - d.y) <= h.y + e.y) & (abs(c.z - d.z) <= h.z + e.z);
}

// A rigid map p -> R (p - t) applied to four points, and |R| h to four half extents.
class Frame4 {
 public:
  Frame4(const Eigen::Matrix3f& rotation, const Eigen::Vector3f& translation) : R_(rotation), t_(translation) {
    for (int i = 0; i < 9; ++i) {
      r_[i] = splat(rotation(i / 3, i % 3));
      a_[i] = splat(std::abs(rotation(i / 3, i % 3)));
    }
    t4_ = V3::splat(translation);
  }
  V3 point(const V3& p) const {
    const F4 dx = p.x - t4_.x, dy = p.y - t4_.y, dz = p.z - t4_.z;
    return {r_[0] * dx + r_[1] * dy + r_[2] * dz, r_[3] * dx + r_[4] * dy + r_[5] * dz,
            r_[6] * dx + r_[7] * dy + r_[8] * dz};
  }
  // One point, by the same arithmetic as the lanes (so a brute-force oracle agrees bit for bit).
  Eigen::Vector3f point(const Eigen::Vector3f& p) const {
    const float dx = p.x() - t_.x(), dy = p.y() - t_.y(), dz = p.z() - t_.z();
    return {R_(0, 0) * dx + R_(0, 1) * dy + R_(0, 2) * dz, R_(1, 0) * dx + R_(1, 1) * dy + R_(1, 2) * dz,
            R_(2, 0) * dx + R_(2, 1) * dy + R_(2, 2) * dz};
  }
  // Conservative bounds of four boxes (centres c, half extents h) after the map.
  Box4 boxes(const V3& c, const V3& h) const {
    const V3 lc = point(c);
    const V3 lh{a_[0] * h.x + a_[1] * h.y + a_[2] * h.z, a_[3] * h.x + a_[4] * h.y + a_[5] * h.z,
                a_[6] * h.x + a_[7] * h.y + a_[8] * h.z};
    return {{lc.x - lh.x, lc.y - lh.y, lc.z - lh.z}, {lc.x + lh.x, lc.y + lh.y, lc.z + lh.z}};
  }

 private:
  Eigen::Matrix3f R_;
  Eigen::Vector3f t_;
  F4 r_[9], a_[9];
  V3 t4_;
};

}  // namespace uwgrasp::grasp::lanes
