// The names of the bounding volume hierarchies, as the command line, traces, lessons and the debugger spell
// them: the binary "bvh" (binned SAH), "bvh-sweep", "bvh-median" and "bvh-sbvh" (spatial splits), and the
// wide "bvh4" and "bvh8" collapsed from the binned tree or, as "bvh4-sbvh" and "bvh8-sbvh", from the SBVH.
// One place that reads a name, so that a builder is added here and not in every list.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "raystep/accel/bvh_build.h"

namespace raystep {

struct BvhName {
  int width = 2;  // 2: the binary BVH; 4 or 8: the wide BVH
  BvhBuilder builder = BvhBuilder::binned;
};

// nullopt for a name that is not a BVH's.
std::optional<BvhName> parse_bvh_name(std::string_view name);
std::string bvh_name(BvhName name);
bool is_bvh_name(std::string_view name);
bool is_wide_bvh_name(std::string_view name);
// Every BVH name: the binary ones, then the wide ones.
const std::vector<std::string>& bvh_names();
const std::vector<std::string>& binary_bvh_names();

}  // namespace raystep
