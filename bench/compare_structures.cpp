// raystep_bench_structures: build time and single-thread ray throughput of raystep's structures against
// Embree 3 in the same run, on the same rays (primary rays of the mesh's default camera, and random rays).
// Usage: raystep_bench_structures [MESH.obj|SCENE.json] [--accel a,b,...] [--size N] [--random N] [--reps N]
//        [--embree-robust]
// (an --accel entry kd:D or kd-median:D sets the kd-tree's depth limit to D; bvh:axis / bvh:entry the
// BVH's child order, bvh:leafN its leaf size, bvh:tiX its t_i, for bvh, bvh-sweep and bvh-median;
// octree:leafK and octree:depthD the octree's leaf size and depth limit; bsp:kdop, bsp:autopartition, bsp:both
// the BSP tree's candidate directions, bsp:cN its candidates per direction).
// Without a mesh argument it uses ../shared/meshes/stanford-bunny.obj beside the repository, and skips
// (exit 0, with a message) when that file is absent.
#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "bench_util.h"
#include "raystep/accel/structure_options.h"
#include "raystep/render/camera.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/io/scene_loader.h"
#include "raystep/util/error.h"

using namespace raystep;
using Clock = std::chrono::steady_clock;

namespace {

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// One pass over the rays; its time in ms.
template <class Trace>
double time_pass(const std::vector<Ray>& rays, std::vector<Hit>& hits, Trace trace) {
  hits.assign(rays.size(), Hit{});
  auto t0 = Clock::now();
  for (size_t i = 0; i < rays.size(); ++i) trace(rays[i], &hits[i]);
  return ms_since(t0);
}

// Embree 3, one thread, high-quality build, single-ray queries (rtcIntersect1).
class EmbreeScene {
 public:
  explicit EmbreeScene(const Geometry& g, bool robust) {
    device_ = rtcNewDevice("threads=1");
    scene_ = rtcNewScene(device_);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    // Robust mode: Embree's watertight triangle test and conservative traversal, the same guarantees as
    // raystep's; by default Embree may miss a ray through a shared edge.
    if (robust) rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    size_t n = g.size();
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
    auto* idx = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
    for (uint32_t id = 0; id < n; ++id)
      for (int k = 0; k < 3; ++k) {
        glm::vec3 p = g.vertex(id, k);
        std::memcpy(v + 9 * id + 3 * k, &p, sizeof p);
        idx[3 * id + k] = 3 * id + k;
      }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene_, geom);
    rtcReleaseGeometry(geom);
  }
  ~EmbreeScene() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  void build() { rtcCommitScene(scene_); }
  void intersect(const Ray& r, Hit* hit) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray.org_x = r.origin.x;
    rh.ray.org_y = r.origin.y;
    rh.ray.org_z = r.origin.z;
    rh.ray.dir_x = r.direction.x;
    rh.ray.dir_y = r.direction.y;
    rh.ray.dir_z = r.direction.z;
    rh.ray.tnear = r.tmin;
    rh.ray.tfar = r.tmax;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.flags = 0;
    rh.ray.time = 0.f;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context, &rh);
    *hit = Hit{};
    if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
      hit->prim = int32_t(rh.hit.primID);
      hit->t = rh.ray.tfar;
    }
  }

 private:
  RTCDevice device_;
  RTCScene scene_;
};

// Same primitive, or both miss, or (ties at shared edges) the same t within a relative 1e-5.
size_t agreement(const std::vector<Hit>& a, const std::vector<Hit>& b) {
  size_t same = 0;
  for (size_t i = 0; i < a.size(); ++i)
    same += a[i].prim == b[i].prim ||
            (a[i].found() && b[i].found() && std::fabs(a[i].t - b[i].t) <= 1e-5f * std::fabs(a[i].t));
  return same;
}

}  // namespace

int main(int argc, char** argv) {
  std::string mesh = bench::bunny_path();
  std::string accels_list = "grid";
  int size = 512, reps = 7;
  size_t random_count = 262144;
  bool robust = false;
  bench::Args args(argc, argv);
  for (std::string a; args.next(&a);) {
    if (a == "--accel") accels_list = args.value();
    else if (a == "--size") size = int(args.number(1));
    else if (a == "--random") random_count = size_t(args.number(1));
    else if (a == "--reps") reps = int(args.number(1));
    else if (a == "--embree-robust")
      robust = true;
    else if (a.rfind("--", 0) == 0)
      bench::Args::fail("unknown option " + a +
                        " (--accel a,b --size N --random N --reps N --embree-robust)");
    else mesh = a;
  }
  if (!std::filesystem::exists(mesh)) {
    std::printf("skipped: %s not found (the shared meshes are not part of the repository)\n", mesh.c_str());
    return 0;
  }
  try {
    Scene scene = load_scene(mesh);
    const Geometry& g = scene.geometry;
    std::vector<Ray> rays[2] = {camera_rays(scene.camera, size, size), random_rays(g.bounds(), random_count, 7)};
    std::printf("mesh: %s (%zu triangles); rays: camera %dx%d (%zu), random %zu; one thread, median of %d\n",
                mesh.c_str(), g.size(), size, size, rays[0].size(), rays[1].size(), reps);

    // Every structure is built first; then each pass of Embree is followed at once by a pass of each
    // structure on the same rays, so that a slow spell of this shared machine falls on both sides of a ratio.
    // A ratio is the median over the passes of (Embree's time / the structure's time) in the same round.
    EmbreeScene embree(g, robust);
    auto t0 = Clock::now();
    embree.build();
    double embree_build_ms = ms_since(t0);
    std::vector<std::string> names;
    std::vector<std::unique_ptr<Accelerator>> accels;
    std::vector<double> build_ms;
    std::stringstream list(accels_list);
    for (std::string name; std::getline(list, name, ',');) {
      // NAME, or kd:D / kd-median:D, a kd-tree with the depth limit D (the sweep behind the default limit).
      StructureOptions options;
      options.bvh.threads = 1;  // one thread, as Embree's device
      std::string kind = name;
      if (size_t colon = name.find(':'); colon != std::string::npos) {
        kind = name.substr(0, colon);
        char* end = nullptr;
        long depth = std::strtol(name.c_str() + colon + 1, &end, 10);
        std::string tail = name.substr(colon + 1);
        bool is_bvh = kind == "bvh" || kind == "bvh-sweep" || kind == "bvh-median";
        if (is_bvh && (tail == "axis" || tail == "entry")) {
          options.bvh_order = tail == "axis" ? BvhOrder::split_axis : BvhOrder::entry_distance;
        } else if (is_bvh && tail.rfind("leaf", 0) == 0) {
          options.bvh.leaf_size = std::atoi(tail.c_str() + 4);
          options.bvh.max_leaf_size = std::max(options.bvh.max_leaf_size, options.bvh.leaf_size);
        } else if (is_bvh && tail.rfind("ti", 0) == 0) {
          options.bvh.t_i = float(std::atof(tail.c_str() + 2));
        } else if (kind == "octree" && tail.rfind("leaf", 0) == 0) {  // octree:leafK, the leaf size K
          options.octree.leaf_size = std::atoi(tail.c_str() + 4);
        } else if (kind == "octree" && tail.rfind("depth", 0) == 0) {  // octree:depthD, the depth limit D
          options.octree.max_depth = std::atoi(tail.c_str() + 5);
        } else if (kind == "bsp" && parse_bsp_directions(tail, &options.bsp.directions)) {
        } else if (kind == "bsp" && tail.rfind("c", 0) == 0 && std::atoi(tail.c_str() + 1) >= 1) {
          options.bsp.candidates = std::atoi(tail.c_str() + 1);
        } else {
          if ((kind != "kd" && kind != "kd-median") || *end != '\0' || depth < 1 || depth > kKdMaxDepth)
            bench::Args::fail("--accel " + name + ": expected kd:D or kd-median:D with D in 1.." +
                              std::to_string(kKdMaxDepth) +
                              ", or bvh:axis, bvh:entry, bvh:leafN, bvh:tiX, octree:leafK, octree:depthD, " +
                              "bsp:kdop, bsp:autopartition, bsp:cN");
          options.kd.max_depth = int(depth);
        }
      }
      names.push_back(name);
      accels.push_back(make_accelerator(kind, options));
      std::vector<double> builds;
      for (int r = 0; r < 3; ++r) {
        auto t1 = Clock::now();
        accels.back()->build(g);
        builds.push_back(ms_since(t1));
      }
      build_ms.push_back(median(builds));
    }

    const size_t n = accels.size();
    std::vector<Hit> embree_hits[2];
    std::vector<std::vector<Hit>> hits[2];
    std::vector<double> embree_ms[2];
    std::vector<std::vector<double>> ms[2], ratio[2];
    for (int k = 0; k < 2; ++k) {
      hits[k].resize(n);
      ms[k].resize(n);
      ratio[k].resize(n);
      for (int r = 0; r < reps; ++r) {
        double e =
            time_pass(rays[k], embree_hits[k], [&](const Ray& ray, Hit* h) { embree.intersect(ray, h); });
        embree_ms[k].push_back(e);
        // The structures take turns at coming first after Embree's pass.
        for (size_t i = 0; i < n; ++i) {
          size_t a = (i + size_t(r)) % n;
          double t =
              time_pass(rays[k], hits[k][a], [&](const Ray& ray, Hit* h) { accels[a]->intersect(ray, h); });
          ms[k][a].push_back(t);
          ratio[k][a].push_back(e / t);
        }
      }
    }
    auto mrays = [](size_t count, const std::vector<double>& times) {
      return double(count) / (median(times) * 1e3);
    };

    std::printf("%-14s %10s %14s %8s %14s %8s %16s %16s\n", "structure", "build_ms", "primary_Mray/s",
                "ratio", "random_Mray/s", "ratio", "agree_primary", "agree_random");
    std::printf("%-14s %10.1f %14.3f %8s %14.3f %8s %16s %16s\n", robust ? "embree-robust" : "embree-high",
                embree_build_ms, mrays(rays[0].size(), embree_ms[0]), "1",
                mrays(rays[1].size(), embree_ms[1]), "1", "-", "-");
    for (size_t a = 0; a < n; ++a)
      std::printf("%-14s %10.1f %14.3f %8.3f %14.3f %8.3f %9zu/%-6zu %9zu/%-6zu\n", names[a].c_str(),
                  build_ms[a], mrays(rays[0].size(), ms[0][a]), median(ratio[0][a]),
                  mrays(rays[1].size(), ms[1][a]), median(ratio[1][a]), agreement(hits[0][a], embree_hits[0]),
                  rays[0].size(), agreement(hits[1][a], embree_hits[1]), rays[1].size());
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  return 0;
}
