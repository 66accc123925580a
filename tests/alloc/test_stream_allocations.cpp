// A stream of organised frames segmented into one Scene through one Workspace
// (segment/pipeline.hpp) asks the allocator for nothing after its first frames, and gives every
// frame the one-shot call's result. This binary counts the heap allocations, so it holds this
// test alone: in a plain build every one (alloc_count.hpp: glibc's malloc family replaced, so
// operator new's, Eigen's and TBB's blocks all count); under the sanitizers, which replace malloc
// themselves, the calls of the global operator new (every standard container's allocation).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <Eigen/Core>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <new>
#include <vector>

#include "uwgrasp/io/config.hpp"
#include "uwgrasp/segment/pipeline.hpp"
#include "uwgrasp/sim/render.hpp"
#include "uwgrasp/sim/scene.hpp"

#ifdef UWGRASP_COUNT_MALLOC
#include "alloc_count.hpp"
namespace {
constexpr const char* kCounted = "heap allocations (malloc and its family)";
std::size_t allocations_in(const std::function<void()>& f) {
  return uwgrasp::alloc_count::count(f).calls;
}
}  // namespace
#else
namespace {
constexpr const char* kCounted = "operator new calls";
std::atomic<std::size_t> g_calls{0};

void* counted(std::size_t n) {
  g_calls.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}

std::size_t allocations_in(const std::function<void()>& f) {
  const std::size_t before = g_calls.load();
  f();
  return g_calls.load() - before;
}
}  // namespace

void* operator new(std::size_t n) { return counted(n); }
void* operator new[](std::size_t n) { return counted(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
#endif

namespace {
using namespace uwgrasp;

// The built-in thesis scene seen by the simulator's camera (320 x 240, for the sanitizer
// builds' sake), with the depth camera's noise.
Cloud noisy_frame(std::uint64_t seed) {
  const sim::Scene scene = sim::builtin_scene("thesis");
  const sim::World world(scene);
  sim::RenderConfig rc;
  rc.noise.enabled = true;
  rc.camera.width = 320, rc.camera.height = 240;
  return sim::render_rgbd(world, sim::camera_pose(scene, {}), rc, seed).cloud;
}

// Bit for bit (a point without a normal has a NaN one, which == would call different).
template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

bool same(const segment::Scene& a, const segment::Scene& b) {
  return a.pre.output_of_input == b.pre.output_of_input &&
         same_bits(a.pre.cloud.points, b.pre.cloud.points) &&
         same_bits(a.pre.cloud.normals, b.pre.cloud.normals) &&
         same_bits(a.pre.cloud.curvature, b.pre.cloud.curvature) &&
         a.segmentation.label == b.segmentation.label &&
         a.segmentation.segments == b.segmentation.segments && a.info.size() == b.info.size();
}

void stream_allocates_nothing(std::size_t threads) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  std::vector<Cloud> frames;
  for (std::uint64_t s = 0; s < 4; ++s) frames.push_back(noisy_frame(20 + s));
  const io::Config cfg;
  std::vector<segment::Scene> once;
  for (const Cloud& f : frames)
    once.push_back(segment::segment_scene(f, cfg.preprocess, cfg.segment, 3));
  segment::Scene scene;
  segment::Workspace ws;
  std::size_t after_first_round = 0;
  for (int i = 0; i < 200; ++i) {
    const std::size_t k = std::size_t(i) % frames.size();
    const std::size_t n = allocations_in(
        [&] { segment::segment_scene(frames[k], cfg.preprocess, cfg.segment, 3, scene, ws); });
    if (i >= int(frames.size())) after_first_round += n;
    ASSERT_TRUE(same(scene, once[k])) << "frame " << i;
    ASSERT_TRUE(scene.pre.organised);
    ASSERT_FALSE(scene.segmentation.segments.empty());
  }
  EXPECT_EQ(after_first_round, 0u) << kCounted << " over frames 5-200 at " << threads << " threads";
}

TEST(StreamAllocations, OrganisedFramesIntoOneSceneAllocateNothingAfterTheFirstRound) {
  stream_allocates_nothing(1);
  stream_allocates_nothing(2);
}

// The counter sees this binary's allocations: a test that cannot fail would pass without it.
// Eigen's own blocks count too where malloc is what is counted.
TEST(StreamAllocations, TheCounterSeesAnAllocation) {
  std::vector<int> v;
  EXPECT_GT(allocations_in([&] {
              v.assign(1000, 1);
              asm volatile("" : : "g"(v.data()) : "memory");  // the allocation may not be elided
            }),
            0u);
  EXPECT_EQ(v[999], 1);
#ifdef UWGRASP_COUNT_MALLOC
  Eigen::VectorXd x;
  EXPECT_EQ(allocations_in([&] { x.setOnes(1000); }), 1u);
  EXPECT_EQ(x.sum(), 1000.0);
#endif
}

}  // namespace
