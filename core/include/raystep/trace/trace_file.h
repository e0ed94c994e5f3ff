// Trace files: the recorded traversal of one or more rays, the contract between core and the debugger and
// the way students take a traversal elsewhere. JSON (format "raystep-trace", version 4: version 2 added an
// anti-aliased pixel's samples, version 3 the bounding volume hierarchies' box tests, skips and node
// children, version 4 the general BSP tree's planes; docs/trace-format.md lists every field) read back by a
// validating reader that also reads versions 1 to 3, and CSV with one event per row. Version 5, the same rays
// through several structures in one file, is trace/multi_trace.h.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "raystep/accel/kdtree_build.h"
#include "raystep/geometry/bounds.h"
#include "raystep/render/pixel_samples.h"
#include "raystep/scene/geometry.h"
#include "raystep/record/events.h"

namespace raystep {

constexpr const char* kTraceFormat = "raystep-trace";
constexpr int kTraceVersion = 4;        // what the writer writes
constexpr int kTraceOldestVersion = 1;  // the oldest version the reader reads

// A build parameter of the structure: a number or a text.
struct TraceParam {
  std::string key;
  bool is_text = false;
  double number = 0.0;
  std::string text;
};

struct TraceStructure {
  // "grid", "kd", "kd-median", and since version 3 "bvh", "bvh-sweep", "bvh-median" (binary), "bvh4", "bvh8"
  // and "octree", since version 4 "bsp"
  std::string kind;
  Bounds3 bounds;
  std::array<int, 3> resolution{1, 1, 1};  // grid only
  std::vector<TraceParam> params;          // every build parameter, sorted by key
};

struct TracedRay {
  Ray ray;
  RayKind kind = RayKind::primary;
  int depth = 0;
  bool has_pixel = false;
  int pixel[2] = {0, 0};
  int sample = -1;  // a pixel trace's ray: the index of the sample (Trace::pixel) whose ray tree it belongs to
  std::vector<Event> events;  // seq 0..n-1, starting with ray_begin and ending with ray_end
};

// Geometry the events refer to, so that a trace replays without the scene's build.
struct TraceCell {
  int cell[3];
  Bounds3 box;
};
// A tree node that an event names (visited, pushed, popped or, in a BVH, its box tested), for a BVH also the
// chain of its parents up to the root: its cell, and its split plane or its primitives. kd-tree: the box is
// the cell, axis and split the plane. BVH (version 3): the box is the node's tight bounding box, axis the
// builder's split axis (-1: none, the wide BVH), split unused, and an inner node lists its children. Octree:
// the box is the cell, axis -1, and an inner node lists its eight children (child i: bit 0 upper in x, 1 y, 2 z).
struct TraceNode {
  int32_t id = 0;
  int32_t parent = -1;  // -1: the root
  int32_t depth = 0;
  Bounds3 box;
  bool leaf = false;
  int axis = 0;        // inner: the split plane's axis (0, 1, 2) and position
  float split = 0.f;
  // Version 4, a BSP inner node: its plane dot(normal, p) = offset (then axis and split are unused; the box
  // is the bounding box of the node's convex cell). The child below (dot < offset) is the next node.
  bool has_plane = false;
  glm::vec3 normal{0.f};
  float offset = 0.f;
  std::vector<int32_t> prims;     // leaf: its primitive ids
  std::vector<int32_t> children;  // BVH inner node: its children's ids (2 binary, up to 8 wide); octree: 8
};
struct TracePrimitive {
  int32_t id = 0;
  PrimType type = PrimType::triangle;
  glm::vec3 v[3]{};  // triangle vertices; for a sphere v[0] is the centre
  float radius = 0.f;
};

// A kd-tree build event (trace ... --build-events): a candidate plane of a node, the split chosen, or a leaf made.
struct TraceBuildEvent {
  EventType type = EventType::split;  // sah_candidate, split or leaf_made
  uint32_t node = 0;
  SahCandidate candidate;             // sah_candidate
  int32_t depth = 0;                  // split, leaf_made: the node's depth, box and primitive count
  Bounds3 box;
  uint32_t prims = 0;
  int axis = 0;                       // split: the plane and its cost
  float position = 0.f, cost = 0.f;
  float leaf_cost = 0.f;              // split, leaf_made: N * t_i
  LeafReason reason = LeafReason::few_primitives;  // leaf_made
};
// leaf_reason_name is in kdtree_build.h.
bool parse_leaf_reason(const std::string& name, LeafReason* reason);

// An anti-aliased pixel (version 2): its samples, adaptive decisions and value, so that the pixel replays without
// the scene. Each sample's rays are in Trace::rays with TracedRay::sample set.
struct TracePixel {
  PixelSampling sampling;          // aa, x, y, samples, squares, value
  int width = 0, height = 0;       // the image the pixel belongs to
  uint64_t seed = 0;               // the sampling seed
  std::optional<glm::vec3> exact;  // the exact pre-filtered value, when the scene has one
};

struct Trace {
  int version = kTraceVersion;  // read: the document's version; the writer always writes kTraceVersion
  std::string scene_path;
  std::string scene_hash;  // "fnv1a64:<16 hex digits>" of the scene file's bytes
  uint64_t scene_primitives = 0;
  TraceStructure structure;
  std::vector<TracedRay> rays;
  std::vector<TraceCell> cells;            // grid: every visited cell, once
  std::vector<TraceNode> nodes;            // trees: every node an event names, once, by id
  std::vector<TracePrimitive> primitives;  // every primitive an event names, once, by id
  std::vector<TraceBuildEvent> build;      // the whole build's events, when recorded (--build-events)
  std::optional<TracePixel> pixel;         // version 2: an anti-aliased pixel's samples
};

const char* ray_kind_name(RayKind kind);

// FNV-1a 64 of a file's bytes, as "fnv1a64:<hex>". Throws InputError if unreadable.
std::string file_content_hash(const std::string& path);

std::string trace_to_json(const Trace& trace);
// The document in two parts, for a writer that streams the "build" section while the tree is built: the opening
// (format, version, scene) and the rest (the build events, if any, then structure, rays and geometry).
std::string trace_json_opening(const Trace& trace);
std::string trace_json_rest(const Trace& trace);
// One build event as the one-line JSON object of the "build" array (seq: its position there).
std::string build_event_json(const TraceBuildEvent& event, size_t seq);
void write_trace_json(const std::string& path, const Trace& trace);  // atomically
void write_trace_csv(const std::string& path, const Trace& trace);   // atomically; one event per row

// Validating readers: throw InputError naming the file, the line, the JSON path and what is wrong
// (wrong format or version, truncation, unknown event type, ids out of range, NaN or missing numbers).
Trace parse_trace_json(const std::string& text, const std::string& name);
Trace read_trace_json(const std::string& path);

// A human summary: rays, events by type, counters.
std::string trace_summary(const Trace& trace);

}  // namespace raystep
