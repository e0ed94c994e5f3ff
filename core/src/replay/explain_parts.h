// The pieces the Why texts of the grid (explain.cpp), the kd, BSP and octree walks (explain_tree.cpp) and the
// BVH walk (explain_bvh.cpp) share: numbers, names and the primitive test's and mailbox's sentences.
#pragma once

#include <cstdint>
#include <string>

#include "raystep/replay/replay_state.h"

namespace raystep::replay::detail {

std::string num(float v);                               // "%.4g"
std::string vec(const glm::vec3& v);                    // "(1, 2, 3)"
std::string side(bool below);                           // "below the plane" / "above the plane"
std::string node_name(const Trace* trace, int32_t id);  // "node 2 (LL)"
// A primitive test in a cell or leaf (`where`), with the watertight test against Möller–Trumbore.
std::string explain_prim_test(const Trace* trace, const TracedRay& ray, const Event& e, const ReplayState& s,
                              const std::string& where);
// A mailbox skip's mechanism: the ray's number in the primitive's mailbox.
std::string mailbox_stamp(const Trace* trace, const TracedRay& ray, int32_t prim);

std::string explain_grid_rule(const Trace* trace, const TracedRay& ray, const ReplayState& s);
std::string explain_tree_rule(const Trace* trace, const TracedRay& ray, const ReplayState& s);
std::string explain_octree_rule(const Trace* trace, const TracedRay& ray, const ReplayState& s);
std::string explain_bvh_rule(const Trace* trace, const TracedRay& ray, const ReplayState& s);

}  // namespace raystep::replay::detail
