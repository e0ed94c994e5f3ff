#include "raystep/util/memory_limit.h"

#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "raystep/util/error.h"

namespace raystep {

namespace {

constexpr const char* kLimitVariable = "RAYSTEP_MEMORY_LIMIT";

// Peak resident bytes per byte of the file, measured (bench/README.md, "Load") and rounded up. An OBJ file:
// its text, tinyobjloader's arrays, the mesh and the scene made of it: the 2.2-million-triangle mesh of 88 MB
// peaks at 495 MB (5.6 bytes per byte; a file of short lines, with small indices, has more faces per byte,
// hence 8). A trace is streamed (its text is never held whole, its events are kept as they are parsed): the
// events, 88 bytes each against at least 28 bytes of text each (a bare {"seq":0,"type":"ray_begin"}), and the
// tape of the rest: the ten-million-event trace of 536 MB peaks at 0.92 GB in `raystep trace-info` (1.7 bytes
// per byte), at most about 3.2 for events alone, hence 4.
constexpr uint64_t kReadFactor[] = {8, 4};

// Peak bytes per primitive of a process that holds the scene and builds the structure over it (the peak RSS
// of `raystep cast` on the 2.2-million-triangle mesh divided by its triangles, rounded up): the grid 233,
// kd 347, the BVHs 315, the octree 329, the BSP tree 699 (kd-median taken as kd, bvh-sweep and bvh-median as
// bvh: not measured apart; the SBVH's references and its per-level copies of them taken as twice the BVH's).
struct BuildCost {
  const char* name;
  uint64_t bytes_per_primitive;
};
constexpr BuildCost kBuildCosts[] = {
    {"grid", 240},       {"kd", 360},   {"kd-median", 360}, {"bvh", 320},    {"bvh-sweep", 320},
    {"bvh-median", 320}, {"bvh4", 320}, {"bvh8", 320},      {"octree", 340}, {"bsp", 720},
    {"bvh-sbvh", 640},   {"bvh4-sbvh", 640}, {"bvh8-sbvh", 640},
};

uint64_t saturating_mul(uint64_t a, uint64_t b) {
  if (a != 0 && b > std::numeric_limits<uint64_t>::max() / a) return std::numeric_limits<uint64_t>::max();
  return a * b;
}

// "3/4 of the 23.5 GiB of physical memory" or "RAYSTEP_MEMORY_LIMIT=512M".
std::string limit_source() {
  if (const char* v = std::getenv(kLimitVariable); v && *v) return std::string(kLimitVariable) + "=" + v;
  return "3/4 of the " + format_bytes(physical_memory_bytes()) + " of physical memory; " + kLimitVariable +
         " sets another";
}

[[noreturn]] void refuse(const std::string& file, const std::string& what, uint64_t need) {
  throw InputError(file, 0,
                   what + " would need about " + format_bytes(need) + " of memory, more than the limit of " +
                       format_bytes(memory_limit_bytes()) + " (" + limit_source() + ")");
}

}  // namespace

uint64_t physical_memory_bytes() {
  long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : 0;
}

uint64_t memory_limit_bytes() {
  const char* v = std::getenv(kLimitVariable);
  if (!v || !*v) {
    uint64_t physical = physical_memory_bytes();
    return physical ? physical / 4 * 3 : std::numeric_limits<uint64_t>::max();
  }
  // Digits, then at most one binary unit.
  const std::string s = v;
  size_t i = 0;
  uint64_t n = 0;
  bool overflow = false;
  for (; i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])); ++i) {
    overflow |= n > (std::numeric_limits<uint64_t>::max() - 9) / 10;
    n = n * 10 + uint64_t(s[i] - '0');
  }
  int shift = -1;
  if (i + 1 == s.size()) {
    switch (std::toupper(static_cast<unsigned char>(s[i]))) {
      case 'K':
        shift = 10;
        break;
      case 'M':
        shift = 20;
        break;
      case 'G':
        shift = 30;
        break;
      case 'T':
        shift = 40;
        break;
      default:
        break;
    }
  } else if (i == s.size()) {
    shift = 0;
  }
  if (i == 0 || shift < 0 || n == 0 || overflow || n > (std::numeric_limits<uint64_t>::max() >> shift))
    throw InputError(
        kLimitVariable, 0,
        "'" + s + "': expected a number of bytes above 0, optionally with K, M, G or T (e.g. 512M)");
  return n << shift;
}

uint64_t read_memory_estimate(InputKind kind, uint64_t file_bytes) {
  return saturating_mul(kReadFactor[int(kind)], file_bytes);
}

void check_read_memory(const std::string& path, InputKind kind, uint64_t file_bytes) {
  const uint64_t need = read_memory_estimate(kind, file_bytes);
  if (need > memory_limit_bytes())
    refuse(path,
           "too large to read: its " + format_bytes(file_bytes) +
               (kind == InputKind::obj_mesh ? " of OBJ" : " of trace"),
           need);
}

uint64_t build_memory_estimate(const std::string& structure, uint64_t primitives) {
  for (const BuildCost& c : kBuildCosts)
    if (structure == c.name) return saturating_mul(c.bytes_per_primitive, primitives);
  return 0;
}

void check_build_memory(const std::string& scene, const std::string& structure, uint64_t primitives) {
  const uint64_t need = build_memory_estimate(structure, primitives);
  if (need > memory_limit_bytes())
    refuse(scene,
           "too large for " + structure + ": building it over " + std::to_string(primitives) + " primitives",
           need);
}

std::string format_bytes(uint64_t bytes) {
  char buf[64];
  if (bytes >= (uint64_t(1) << 30))
    std::snprintf(buf, sizeof buf, "%.1f GiB", double(bytes) / double(uint64_t(1) << 30));
  else if (bytes >= (uint64_t(1) << 20))
    std::snprintf(buf, sizeof buf, "%.0f MiB", double(bytes) / double(uint64_t(1) << 20));
  else if (bytes >= 1024)
    std::snprintf(buf, sizeof buf, "%.0f KiB", double(bytes) / 1024.0);
  else
    std::snprintf(buf, sizeof buf, "%llu bytes", static_cast<unsigned long long>(bytes));
  return buf;
}

}  // namespace raystep
