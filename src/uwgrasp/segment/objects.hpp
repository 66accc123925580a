#pragma once
// Whole objects from segments. Region growing (4.2.2) splits an object into a segment per face
// and leaves its edges unlabelled; under sensor noise it shatters into fragments. Selecting one
// segment as "the object" then hands the grasp engine a face or a fragment (an 87-point face
// over the object's 2,667-point body). Here the processed cloud's points are joined into
// objects where they touch (Euclidean connectivity over the neighbour graph, gaps up to `gap`),
// and the object of interest is chosen among those: by colour (the highest mean intensity of the
// colour among its coloured points, over objects with at least a quarter as many coloured points
// as the most coloured one: fragments are not objects), by segment label (the object holding
// it), nearest, largest, or the object holding the point nearest a given point (these three
// among objects wider than min_extent: select.hpp, extent_of).
#include <cstdint>
#include <vector>

#include "uwgrasp/cloud/kdtree.hpp"
#include "uwgrasp/core/cloud.hpp"
#include "uwgrasp/segment/region_growing.hpp"
#include "uwgrasp/segment/select.hpp"

namespace uwgrasp::segment {

struct Objects {
  std::vector<std::int32_t> object_of_point;       // -1: none (isolated points)
  std::vector<std::vector<std::uint32_t>> points;  // ascending point indices per object
};

// Connected components of the points: i and j join when j is among i's neighbours (nb, over
// this cloud) no farther than `gap`. Components smaller than min_points are left out.
Objects connected_objects(const Cloud& cloud, const cloud::Neighbours& nb, float gap,
                          std::uint32_t min_points);

// The gap that joins a surface's own points but not two objects: `spacing_mul` times the median
// nearest-neighbour distance, within [lo, hi].
float connection_gap(const cloud::Neighbours& nb, float spacing_mul = 3.0f, float lo = 0.004f,
                     float hi = 0.015f);

// Whether some object has points of cfg.color at the intensity selecting by colour asks
// (select_whole_object would find one).
bool has_colour_object(const Cloud& cloud, const Objects& objects, const ObjectConfig& cfg);

// The index of the object of interest. Throws Error naming the criterion when nothing matches.
std::size_t select_whole_object(const Cloud& cloud, const Objects& objects, const Segmentation& seg,
                                const ObjectConfig& cfg);

// The selected object with the parts of the same object the camera sees apart (a handle under a
// body hides the joint between them): every object within `reach` of it (nearest points) whose
// points are mostly (>= half) over min_intensity or whose mean intensity of the configured colour
// is at least half the selected object's (the water dims them alike) when selecting by colour -
// any object otherwise - joined transitively. Returns the object indices, the selected one first.
std::vector<std::size_t> gather_parts(const Cloud& cloud, const Objects& objects, std::size_t selected,
                                      const ObjectConfig& cfg, float reach);

}  // namespace uwgrasp::segment
