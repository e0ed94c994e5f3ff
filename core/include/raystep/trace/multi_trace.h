// Multi-walk traces: the same ray(s) recorded through two to six structures in one file, so that a class
// compares the lecture's variations (grid, kd-tree, octree, BSP tree, BVH) on one timeline over the ray's t.
// JSON version 5 (docs/trace-format.md): the scene once, then "walks", each what a version 4 trace holds
// below its scene (structure, rays with their events, geometry), read back by the same validating reader.
#pragma once

#include <string>
#include <vector>

#include "raystep/accel/accelerator.h"
#include "raystep/scene/geometry.h"
#include "raystep/trace/ray_request.h"
#include "raystep/trace/trace_file.h"
#include "raystep/trace/walk_cost.h"

namespace raystep {

constexpr int kMultiTraceVersion = 5;  // a multi-walk document; a single structure's trace stays version 4
constexpr int kMinWalks = 2;
constexpr int kMaxWalks = 6;

struct MultiTrace {
  int version = kMultiTraceVersion;  // read: the document's version (1 to 4: a single trace, one walk)
  std::string scene_path;
  std::string scene_hash;
  uint64_t scene_primitives = 0;
  // Each walk is a whole single-structure trace (its scene fields equal the above), the rays the same in all.
  std::vector<Trace> walks;
};

// Records the same rays through each built structure, in the order given: walk i equals
// record_trace(geometry, *accels[i], rays, ...). Throws InputError("", 0, ...) for fewer than kMinWalks or
// more than kMaxWalks structures, or one that records no events.
MultiTrace record_walks(const Geometry& geometry, const std::vector<const Accelerator*>& accels,
                        const std::vector<RayRequest>& rays, const std::string& scene_path,
                        const std::string& scene_hash);

// The names of a list "A,B,...", as `raystep trace --accel` and `raystep-gui --compare` take it: each a known
// structure that records events, none twice, min_count to max_count of them. Otherwise throws
// InputError("", 0, where + ": ...") with where naming the option, e.g. "trace: --accel 'grid,kd,grid'".
std::vector<std::string> parse_walk_list(const std::string& list, const std::string& where, int min_count,
                                         int max_count);

std::string multi_trace_to_json(const MultiTrace& trace);
void write_multi_trace_json(const std::string& path, const MultiTrace& trace);  // atomically
// One file, one event per row: a "walk" column (the walk's index) first, then the single trace's columns.
void write_multi_trace_csv(const std::string& path, const MultiTrace& trace);  // atomically

// Validating readers of the version 5 form: every walk is checked as a single trace is (ids, nodes, events),
// and every walk traces the same rays; InputError names the file, the line and the JSON path
// ("walks[1].rays[0].events[4].node: ...").
MultiTrace parse_multi_trace_json(const std::string& text, const std::string& name);
MultiTrace read_multi_trace_json(const std::string& path);
// Either form: a single structure's trace (versions 1 to 4) comes back as one walk with its version.
MultiTrace read_any_trace_json(const std::string& path);

// A human summary: per ray, a table of the walks (steps, primitive tests, mailbox hits, box tests, the hit,
// the cost at the hit and at four t values between the first entry and the furthest hit; '*' marks the
// cheapest at each), with every walk costed by model, or by its structure's own constants if own_costs.
std::string multi_trace_summary(const MultiTrace& trace, const CostModel& model, bool own_costs);

}  // namespace raystep
