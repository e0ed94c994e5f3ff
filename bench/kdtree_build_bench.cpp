// raystep_bench_kdtree_build: kd-tree build time (median of several builds, one thread) of the SAH sweep and
// the spatial-median builder on a mesh at 1x, 4x and 16x its triangles (each triangle split into four at its
// edge midpoints, repeatedly), to show the O(N log N) growth; with each tree's nodes, leaves, depth,
// references per primitive, SAH cost and a checksum of the whole tree (nodes, node info, prim_index), so that a
// faster build can be shown to build the very same tree.
// Usage: raystep_bench_kdtree_build [MESH.obj|SCENE.json] [--reps N] [--levels L] [--builders sah,median,...]
// Without a mesh argument it uses ../shared/meshes/stanford-bunny.obj beside the repository, and skips
// (exit 0, with a message) when that file is absent.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "bench_util.h"
#include "raystep/accel/kdtree_build.h"
#include "raystep/io/scene_loader.h"
#include "raystep/util/error.h"

using namespace raystep;

namespace {

// Each triangle into four at its edge midpoints (the same surface, 4x the triangles).
Geometry subdivide(const Geometry& g) {
  Geometry out;
  out.begin_object("subdivided", 0);
  for (uint32_t id = 0; id < g.size(); ++id) {
    if (g.type(id) != PrimType::triangle) {
      out.add_sphere(g.sphere(id));
      continue;
    }
    glm::vec3 a = g.vertex(id, 0), b = g.vertex(id, 1), c = g.vertex(id, 2);
    glm::vec3 ab = 0.5f * (a + b), bc = 0.5f * (b + c), ca = 0.5f * (c + a);
    out.add_triangle(a, ab, ca);
    out.add_triangle(ab, b, bc);
    out.add_triangle(ca, bc, c);
    out.add_triangle(ab, bc, ca);
  }
  return out;
}

// FNV-1a over every field of the tree: equal checksums, bit-identical trees (in all likelihood).
struct Fnv1a {
  uint64_t h = 14695981039346656037ull;
  void add(uint32_t v) {
    for (int i = 0; i < 4; ++i) h = (h ^ ((v >> (8 * i)) & 0xffu)) * 1099511628211ull;
  }
  void add(float f) {
    uint32_t v;
    std::memcpy(&v, &f, 4);
    add(v);
  }
};

uint64_t tree_checksum(const KdTreeData& t) {
  Fnv1a f;
  for (int a = 0; a < 3; ++a) f.add(t.bounds.lo[a]), f.add(t.bounds.hi[a]);
  for (size_t i = 0; i < t.nodes.size(); ++i) {
    f.add(t.nodes[i].first_prim);
    f.add(t.nodes[i].bits);
    const KdNodeInfo& info = t.info[i];
    for (int a = 0; a < 3; ++a) f.add(info.box.lo[a]), f.add(info.box.hi[a]);
    f.add(uint32_t(info.parent));
    f.add(uint32_t(info.depth));
    f.add(info.cost);
  }
  for (uint32_t p : t.prim_index) f.add(p);
  return f.h;
}

double median_ms(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  std::string mesh = bench::bunny_path();
  int reps = 5, levels = 2;
  std::string builders = "sah,median";
  bench::Args args(argc, argv);
  for (std::string a; args.next(&a);) {
    if (a == "--reps") reps = int(args.number(1));
    else if (a == "--levels") levels = int(args.number(0));
    else if (a == "--builders") builders = args.value();
    else if (a.rfind("--", 0) == 0) bench::Args::fail("unknown option " + a + " (--reps N --levels L --builders a,b)");
    else mesh = a;
  }
  if (!std::filesystem::exists(mesh)) {
    std::printf("skipped: %s not found (the shared meshes are not part of the repository)\n", mesh.c_str());
    return 0;
  }
  try {
    Scene scene = load_scene(mesh);
    std::vector<Geometry> scaled;
    scaled.push_back(std::move(scene.geometry));
    for (int l = 0; l < levels; ++l) scaled.push_back(subdivide(scaled.back()));

    std::printf("%s\n", mesh.c_str());
    std::printf("%-8s %6s %9s %10s %10s %9s %9s %8s %6s %9s %10s  %-16s\n", "builder", "scale", "prims", "build_ms",
                "min_ms", "nodes", "leaves", "empty", "depth", "refs/prim", "sah_cost", "checksum");
    std::stringstream list(builders);
    std::string name;
    while (std::getline(list, name, ',')) {
      KdOptions o;
      if (name == "sah") o.builder = KdBuilder::sah;
      else if (name == "median") o.builder = KdBuilder::median;
      else if (name == "reference") o.builder = KdBuilder::sah_reference;
      else {
        std::fprintf(stderr, "error: unknown builder %s\n", name.c_str());
        return 2;
      }
      for (size_t l = 0; l < scaled.size(); ++l) {
        const Geometry& g = scaled[l];
        std::vector<double> ms;
        KdTreeData tree;
        for (int r = 0; r < reps; ++r) {
          auto t0 = std::chrono::steady_clock::now();
          tree = build_kdtree(g, o);
          auto t1 = std::chrono::steady_clock::now();
          ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
        }
        KdTreeStats s = kd_tree_stats(tree, o);
        std::printf("%-8s %5zux %9zu %10.1f %10.1f %9zu %9zu %8zu %6d %9.2f %10.1f  %016llx\n", name.c_str(),
                    size_t(1) << (2 * l), g.size(), median_ms(ms), *std::min_element(ms.begin(), ms.end()), s.nodes,
                    s.leaves, s.empty_leaves, s.max_depth, double(s.references) / double(std::max<size_t>(g.size(), 1)),
                    s.sah_cost, (unsigned long long)tree_checksum(tree));
        std::fflush(stdout);
      }
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  return 0;
}
