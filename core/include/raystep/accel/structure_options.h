// Build options of every acceleration structure, as the command line and the debugger's structure panel set
// them, and the factory that takes them.
#pragma once

#include <memory>
#include <string>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/bsp_build.h"
#include "raystep/accel/bvh.h"
#include "raystep/accel/grid.h"
#include "raystep/accel/kdtree_build.h"
#include "raystep/accel/octree_build.h"

namespace raystep {

struct StructureOptions {
  GridOptions grid;
  KdOptions kd;  // the builder is chosen by the name: "kd" (SAH) or "kd-median"
  bool kd_mailboxes = true;  // also the BSP tree's
  BvhOptions bvh;  // the builder is chosen by the name: "bvh" (binned SAH), "bvh-sweep" or "bvh-median"
  BvhOrder bvh_order = BvhOrder::entry_distance;
  OctreeOptions octree;
  BspOptions bsp;  // the general BSP tree ("bsp")
};

// Throws InputError("", 0, "unknown accelerator ...") for an unknown name.
std::unique_ptr<Accelerator> make_accelerator(const std::string& name, const StructureOptions& options);

// Every build option of the named structure, as text: equal keys build equal structures (caches key on it).
std::string structure_key(const std::string& accel, const StructureOptions& options);

}  // namespace raystep
