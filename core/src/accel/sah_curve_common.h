// What the kd-tree's, the BVH's and the BSP tree's SAH curves share (kdtree_, bvh_, bsp_sah_curve.cpp):
// finding a node by its path from the root (L the first child, which follows its parent; R the second), and
// the CSVs' numbers. Internal to raystep_core.
#pragma once

#include <cctype>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "raystep/util/error.h"

namespace raystep::sah_curve {

// The node at the end of path (--path): children names what L and R stand for in the message of a bad letter,
// second_child(node) gives an inner node's second child.
template <class Node, class SecondChild>
uint32_t node_by_path(const std::vector<Node>& nodes, const std::string& path, const char* children,
                      SecondChild second_child) {
  if (nodes.empty()) throw InputError("", 0, "--path: the tree is empty");
  uint32_t id = 0;
  for (size_t i = 0; i < path.size(); ++i) {
    char c = char(std::toupper(static_cast<unsigned char>(path[i])));
    if (c != 'L' && c != 'R') throw InputError("", 0, "--path '" + path + "': use " + children);
    const Node& n = nodes[id];
    if (n.is_leaf())
      throw InputError("", 0,
                       "--path '" + path + "': node " + std::to_string(id) + " (after '" + path.substr(0, i) +
                           "') is a leaf");
    id = c == 'L' ? id + 1 : second_child(n);
  }
  return id;
}

// A number as the CSVs write it: enough digits to read the float back.
inline std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

}  // namespace raystep::sah_curve
