#include "raystep/accel/bvh_names.h"

namespace raystep {

namespace {

const char* suffix(BvhBuilder b) {
  switch (b) {
    case BvhBuilder::sweep:
      return "-sweep";
    case BvhBuilder::median:
      return "-median";
    case BvhBuilder::sbvh:
      return "-sbvh";
    case BvhBuilder::binned:
    default:
      return "";
  }
}

}  // namespace

const std::vector<std::string>& binary_bvh_names() {
  static const std::vector<std::string> names = {"bvh", "bvh-sweep", "bvh-median", "bvh-sbvh"};
  return names;
}

const std::vector<std::string>& bvh_names() {
  static const std::vector<std::string> names = {"bvh",  "bvh-sweep", "bvh-median", "bvh-sbvh",
                                                 "bvh4", "bvh8",      "bvh4-sbvh",  "bvh8-sbvh"};
  return names;
}

std::string bvh_name(BvhName n) {
  return (n.width == 2 ? std::string("bvh") : "bvh" + std::to_string(n.width)) + suffix(n.builder);
}

std::optional<BvhName> parse_bvh_name(std::string_view name) {
  for (int width : {2, 4, 8})
    for (BvhBuilder b : {BvhBuilder::binned, BvhBuilder::sweep, BvhBuilder::median, BvhBuilder::sbvh}) {
      // The wide BVH collapses the binned tree or the SBVH.
      if (width != 2 && b != BvhBuilder::binned && b != BvhBuilder::sbvh) continue;
      if (name == bvh_name({width, b})) return BvhName{width, b};
    }
  return std::nullopt;
}

bool is_bvh_name(std::string_view name) {
  return parse_bvh_name(name).has_value();
}

bool is_wide_bvh_name(std::string_view name) {
  std::optional<BvhName> n = parse_bvh_name(name);
  return n && n->width != 2;
}

}  // namespace raystep
