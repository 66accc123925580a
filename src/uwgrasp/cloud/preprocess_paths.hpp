#pragma once
// What the two paths of the preprocessing chain (preprocess.hpp) share, and the paths
// themselves: preprocess_organised.cpp (pixel windows) and preprocess_kdtree.cpp (k-d tree
// neighbourhoods); preprocess.cpp picks one. Internal to cloud/.
#include <cstdint>
#include <vector>

#include "uwgrasp/cloud/organised.hpp"
#include "uwgrasp/cloud/preprocess.hpp"
#include "uwgrasp/cloud/workspace.hpp"
#include "uwgrasp/core/timer.hpp"

namespace uwgrasp::cloud::preprocess_detail {

// After a filter that kept `kept` (indices into a cloud of `previous_size` points), re-points
// the input map; `pos` is scratch.
void remap_filtered(std::vector<std::int32_t>& map, const std::vector<std::uint32_t>& kept,
                    std::size_t previous_size, std::vector<std::int32_t>& pos);
void remap_filtered(std::vector<std::int32_t>& map, const std::vector<std::uint32_t>& kept,
                    std::size_t previous_size);

// Keeps the points of `cur` whose ws.mask entry is set (through ws.next, swapped in) and
// re-points the map: a filter without a buffer of its own.
void keep_masked(Cloud& cur, Workspace& ws, std::vector<std::int32_t>& map);

// The plane stage (4.1.4) on the running cloud `cur`; `map` (organised frames) lets the normals
// keep an object's foot.
void remove_plane(Cloud& cur, const PreprocessConfig& cfg, std::uint64_t seed, Preprocessed& out,
                  Workspace& ws, const PixelMap* map = nullptr);

// Throws Error when a stage left no point.
void require_points(const Cloud& c, const char* stage);

// The chain on an organised frame, into `out` (reset for the input), through `ws`.
void preprocess_organised(const Cloud& in, const PreprocessConfig& cfg, std::uint64_t seed,
                          StageTimer& timer, Preprocessed& out, Workspace& ws);
// The chain on any other cloud, with k-d tree neighbourhoods.
void preprocess_unorganised(const Cloud& in, const PreprocessConfig& cfg, std::uint64_t seed,
                            StageTimer& timer, std::size_t share_k, Preprocessed& out,
                            Workspace& ws);

}  // namespace uwgrasp::cloud::preprocess_detail
