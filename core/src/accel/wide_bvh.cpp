#include "raystep/accel/wide_bvh.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <limits>

#include "raystep/accel/bvh_names.h"
#include "raystep/util/error.h"
#include "wide_bvh_impl.h"

namespace raystep {

namespace {

#if defined(__x86_64__)
WideSimd detect_simd() {
  return __builtin_cpu_supports("avx2") ? WideSimd::avx2 : WideSimd::sse;
}
#else
WideSimd detect_simd() {
  return WideSimd::scalar;
}
#endif

}  // namespace

std::atomic<int> g_wide_simd{int(detect_simd())};

namespace {

// Collapses the binary tree into W-wide nodes (after Embree's and madmann91/bvh's collapse): a wide node's
// children start as the binary node's two, and the child with the largest surface area that is not a leaf is
// opened (replaced by its two children) until there are W of them. The largest box is the one a ray most
// likely enters (Crofton: probability S_child / S_parent), so opening it saves the most node visits.
template <int W>
class Collapser {
 public:
  Collapser(const BvhData& bin, const Geometry& g, WideBvh::Impl& m) : bin_(bin), g_(g), m_(m) {}

  void run() {
    // Primitives under each binary node (preorder: children come after their parent).
    subtree_.assign(bin_.nodes.size(), 0);
    for (size_t i = bin_.nodes.size(); i-- > 0;) {
      const BvhNode& n = bin_.nodes[i];
      subtree_[i] = n.is_leaf() ? n.prim_count() : subtree_[i + 1] + subtree_[n.second_child()];
    }
    m_.node_id.push_back(0);  // the root wide node is id 0
    m_.id_count = 1;
    emit(0, 0, 0);
    while (m_.prims.size() % kWidePacket) m_.prims.push_back(kWideEmpty);
  }

 private:
  uint32_t emit(uint32_t b, int32_t id, int32_t depth) {
    m_.max_depth = std::max(m_.max_depth, depth);
    if (depth > kBvhMaxDepth) throw InputError("", 0, "bvh: deeper than " + std::to_string(kBvhMaxDepth));
    uint32_t kids[W];
    int n = 0;
    const BvhNode& node = bin_.nodes[b];
    if (leaf_like(b)) {
      kids[n++] = b;  // the root is a leaf: one child
    } else {
      kids[n++] = b + 1;
      kids[n++] = node.second_child();
    }
    while (n < W) {
      int best = -1;
      float best_area = -1.f;
      for (int i = 0; i < n; ++i) {
        if (leaf_like(kids[i])) continue;
        const BvhNode& k = bin_.nodes[kids[i]];
        float a = bin_.space.measure(k.box);
        if (a > best_area) best_area = a, best = i;
      }
      if (best < 0) break;
      uint32_t opened = kids[best];
      // Keep the binary tree's order: the opened node's children take its place.
      for (int i = n; i > best + 1; --i) kids[i] = kids[i - 1];
      kids[best] = opened + 1;
      kids[best + 1] = bin_.nodes[opened].second_child();
      ++n;
    }

    uint32_t index = 0;
    if constexpr (W == 4) {
      index = uint32_t(m_.nodes4.size());
      m_.nodes4.emplace_back();
    } else {
      index = uint32_t(m_.nodes8.size());
      m_.nodes8.emplace_back();
    }
    if (index > 0) m_.node_id.push_back(id);
    m_.node_depth.push_back(depth);
    m_.slot_id.resize(size_t(index + 1) * W, -1);
    WideNode<W> wn;
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < W; ++i) {
        wn.box[2 * a][i] = std::numeric_limits<float>::infinity();
        wn.box[2 * a + 1][i] = -std::numeric_limits<float>::infinity();
      }
    for (int i = 0; i < W; ++i) wn.child[i] = kWideEmpty, wn.count[i] = 0;

    for (int i = 0; i < n; ++i) {
      const BvhNode& k = bin_.nodes[kids[i]];
      int32_t child_id = m_.id_count++;
      m_.slot_id[size_t(index) * W + i] = child_id;
      m_.id_slot.resize(size_t(m_.id_count), -1);
      m_.id_slot[size_t(child_id)] = int32_t(index) * W + i;
      if (!k.box.empty())
        for (int a = 0; a < 3; ++a) {
          wn.box[2 * a][i] = k.box.lo[a];
          wn.box[2 * a + 1][i] = k.box.hi[a];
        }
      if (leaf_like(kids[i])) {
        // Leaves share packets: a leaf starts where the previous one ended, unless that would make it span
        // more packets than it needs (then it starts a packet). The lanes of other leaves are masked off.
        const uint32_t count = subtree_[kids[i]], P = uint32_t(kWidePacket);
        const uint32_t lane = uint32_t(m_.prims.size()) % P;
        if (lane != 0 && (lane + count + P - 1) / P > (count + P - 1) / P)
          while (m_.prims.size() % P) m_.prims.push_back(kWideEmpty);
        uint32_t first = uint32_t(m_.prims.size());
        if (first >= kWideLeaf) throw InputError("", 0, "bvh: too many primitives for the wide BVH");
        gather(kids[i]);
        // A leaf's primitives in id order, each once (an SBVH subtree may reference a primitive twice).
        std::sort(m_.prims.begin() + first, m_.prims.end());
        m_.prims.erase(std::unique(m_.prims.begin() + first, m_.prims.end()), m_.prims.end());
        wn.child[i] = kWideLeaf | first;
        wn.count[i] = uint32_t(m_.prims.size()) - first;
        ++m_.leaf_count;
        m_.max_depth = std::max(m_.max_depth, depth + 1);
      } else {
        wn.child[i] = emit(kids[i], child_id, depth + 1);
      }
    }
    if constexpr (W == 4)
      m_.nodes4[index] = wn;
    else
      m_.nodes8[index] = wn;
    return index;
  }

  // A binary leaf, or a subtree with no more primitives than a packet holds: they cost one SIMD test
  // together, which is cheaper than the node visits that would separate them.
  bool leaf_like(uint32_t b) const { return bin_.nodes[b].is_leaf() || subtree_[b] <= uint32_t(kWidePacket); }

  void gather(uint32_t b) {
    const BvhNode& n = bin_.nodes[b];
    if (n.is_leaf()) {
      for (uint32_t j = 0; j < n.prim_count(); ++j) m_.prims.push_back(bin_.prim_index[n.first_prim() + j]);
      return;
    }
    gather(b + 1);
    gather(n.second_child());
  }

  std::vector<uint32_t> subtree_;
  const BvhData& bin_;
  const Geometry& g_;
  WideBvh::Impl& m_;
};

void lay_out_packets(WideBvh::Impl& m) {
  const Geometry& g = *m.geometry;
  m.packets_ok = g.all_triangles();
  m.packets.clear();
  if (!m.packets_ok) return;
  m.packets.resize(m.prims.size() / kWidePacket);
  for (size_t p = 0; p < m.packets.size(); ++p) {
    TriPacket& tp = m.packets[p];
    for (int lane = 0; lane < kWidePacket; ++lane) {
      uint32_t prim = m.prims[p * kWidePacket + size_t(lane)];
      tp.prim[lane] = prim;
      for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a) tp.v[3 * k + a][lane] = prim == kWideEmpty ? 0.f : g.vertex(prim, k)[a];
    }
  }
}

}  // namespace

WideBvh::WideBvh(int width, BvhOptions options) : width_(width), options_(options) {
  if (width != 4 && width != 8) throw InputError("", 0, "bvh: the wide BVH is 4 or 8 wide");
  impl_ = new Impl;
}

WideBvh::~WideBvh() {
  delete impl_;
}

std::string WideBvh::name() const {
  return bvh_name({width_, options_.builder});
}

void WideBvh::build(const Geometry& geometry) {
  build(geometry, build_bvh(geometry, options_));
}

void WideBvh::build(const Geometry& geometry, const BvhData& binary) {
  Impl fresh;
  fresh.width = width_;
  fresh.geometry = &geometry;
  fresh.empty = geometry.size() == 0 || binary.nodes.empty();
  if (!fresh.empty) {
    fresh.root_box = binary.nodes[0].box;
    if (width_ == 4)
      Collapser<4>(binary, geometry, fresh).run();
    else
      Collapser<8>(binary, geometry, fresh).run();
    lay_out_packets(fresh);
  }
  *impl_ = std::move(fresh);
}

size_t WideBvh::memory_bytes() const {
  const Impl& m = *impl_;
  return m.nodes4.capacity() * sizeof(WideNode<4>) + m.nodes8.capacity() * sizeof(WideNode<8>) +
         m.prims.capacity() * sizeof(uint32_t) + m.packets.capacity() * sizeof(TriPacket) +
         (m.node_id.capacity() + m.node_depth.capacity() + m.slot_id.capacity() + m.id_slot.capacity()) *
             sizeof(int32_t);
}

WideSimd WideBvh::best_simd() {
  return detect_simd();
}

bool WideBvh::force_simd(WideSimd level) {
  if (int(level) > int(detect_simd())) return false;
  g_wide_simd = int(level);
  return true;
}

const char* WideBvh::simd_level() {
  switch (wide_simd_in_use()) {
    case WideSimd::avx2:
      return "avx2";
    case WideSimd::sse:
      return "sse";
    default:
      return "scalar";
  }
}

bool WideBvh::intersect(const Ray& ray, Hit* hit) const {
  NullRecorder rec;
  return traverse(ray, hit, false, rec);
}

bool WideBvh::occluded(const Ray& ray) const {
  NullRecorder rec;
  Hit hit;
  return traverse(ray, &hit, true, rec);
}

bool WideBvh::intersect_counted(const Ray& ray, Hit* hit, CountingRecorder& counters) const {
  return traverse(ray, hit, false, counters);
}

bool WideBvh::occluded_counted(const Ray& ray, CountingRecorder& counters) const {
  Hit hit;
  return traverse(ray, &hit, true, counters);
}

WideBvhView::Node WideBvh::describe_node(int32_t id) const {
  const Impl& m = *impl_;
  if (id < 0 || id >= m.id_count) throw InputError("", 0, "bvh: no node " + std::to_string(id));
  const int W = width_;
  auto box_of = [&](size_t n, int lane) {
    Bounds3 b;
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = W == 4 ? m.nodes4[n].box[2 * a][lane] : m.nodes8[n].box[2 * a][lane];
      b.hi[a] = W == 4 ? m.nodes4[n].box[2 * a + 1][lane] : m.nodes8[n].box[2 * a + 1][lane];
    }
    return b;
  };
  WideBvhView::Node node;
  uint32_t ref = 0;  // the wide node below it (inner) or its primitives (leaf)
  uint32_t count = 0;
  if (id == 0) {
    node.box = m.root_box;
  } else {
    const size_t slot = size_t(m.id_slot[size_t(id)]), n = slot / size_t(W);
    const int lane = int(slot % size_t(W));
    node.box = box_of(n, lane);
    node.parent = m.node_id[n];
    node.depth = m.node_depth[n] + 1;
    ref = W == 4 ? m.nodes4[n].child[lane] : m.nodes8[n].child[lane];
    count = W == 4 ? m.nodes4[n].count[lane] : m.nodes8[n].count[lane];
  }
  if (ref & kWideLeaf) {
    node.leaf = true;
    const uint32_t first = ref & ~kWideLeaf;
    node.prims.assign(m.prims.begin() + first, m.prims.begin() + first + count);
  } else {
    for (int i = 0; i < W; ++i)
      if (int32_t c = m.slot_id[size_t(ref) * size_t(W) + size_t(i)]; c >= 0) node.children.push_back(c);
  }
  return node;
}

size_t WideBvh::node_count() const {
  return size_t(impl_->id_count);
}
size_t WideBvh::leaf_count() const {
  return size_t(impl_->leaf_count);
}

WideBvhView WideBvh::describe() const {
  WideBvhView view;
  view.nodes.reserve(node_count());
  for (size_t id = 0; id < node_count(); ++id) view.nodes.push_back(describe_node(int32_t(id)));
  return view;
}

}  // namespace raystep
