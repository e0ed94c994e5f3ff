// Recording rays through the octree into a Trace (kind "octree", format version 3): each ray walked with the
// event recorder (a node event per cell visited with its depth and [t_enter, t_exit], push and pop of the
// nodes whose children are walked, leaf, prim_test, mailbox_hit, hit_deferred, hit_accepted), plus every node
// its events name and the chain of parents of each up to the root (cell, the eight children or the
// primitives).
#pragma once

#include <string>
#include <vector>

#include "raystep/accel/octree.h"
#include "raystep/trace/ray_request.h"
#include "raystep/trace/trace_file.h"

namespace raystep {

// Shadow rays are walked as any-hit queries, the others as nearest-hit queries. The nodes' axis is -1 (an
// octree node splits all three axes at its centre).
Trace record_octree_trace(const Geometry& geometry, const Octree& tree, const std::vector<RayRequest>& rays,
                          const std::string& scene_path, const std::string& scene_hash);

}  // namespace raystep
