#include "uwgrasp/segment/pipeline.hpp"

namespace uwgrasp::segment {

Scene segment_scene(const Cloud& input, const cloud::PreprocessConfig& pre,
                    const SegmentConfig& seg, std::uint64_t seed) {
  Scene s;
  Workspace ws;
  segment_scene(input, pre, seg, seed, s, ws);
  return s;
}

void segment_scene(const Cloud& input, const cloud::PreprocessConfig& pre, const SegmentConfig& seg,
                   std::uint64_t seed, Scene& s, Workspace& ws) {
  s.timer.clear();
  cloud::preprocess(input, pre, seed, s.timer, s.pre, ws.cloud, seg.region.k);
  s.timer.start("segment");
  if (s.pre.neighbours.count.empty())
    s.segmentation = grow_regions(s.pre.cloud, seg.region, seg.color);
  else
    grow_regions(s.pre.cloud, seg.region, seg.color, s.pre.neighbours, s.segmentation, ws.region);
  describe_segments(s.pre.cloud, s.segmentation, seg.object.color, s.info);
  s.timer.stop();
}

std::vector<std::int32_t> input_labels(const Scene& scene) {
  std::vector<std::int32_t> out(scene.pre.output_of_input.size(), -1);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto m = scene.pre.output_of_input[i];
    if (m >= 0) out[i] = scene.segmentation.label[static_cast<std::size_t>(m)];
  }
  return out;
}

}  // namespace uwgrasp::segment
