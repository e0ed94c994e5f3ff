// The tree of nodes drawn as the slides draw it: the root at the top, each inner node's children below it
// (L, the child below the plane, on the left; R on the right; an octree's eight in octant order), a box per
// node with its id, each edge labelled with its side. The walk's marks in the 3D view's colours: the current
// node yellow, the nodes on the stack pink, the nodes already visited blue, the selected node teal. A small
// tree is drawn whole; a big one only along the walk: the marked nodes, their ancestors and those ancestors'
// children (so that every far child is in the picture), the rest of each subtree a stub. For the handout's
// figure of a step about the tree (`show: tree`).
#pragma once

#include <vector>

#include <QImage>

namespace raystep::viz {

class TreeShape;

struct TreeMarks {
  int current = -1;            // the walk's current node
  std::vector<int> stack;      // waiting on the stack
  std::vector<int> visited;    // left already
  int selected = -1;           // chosen in the tree view (a lesson's node)
};

// Trees of at most `whole` nodes are drawn whole.
QImage drawTreeDiagram(const TreeShape& tree, const TreeMarks& marks, int whole = 63);

}  // namespace raystep::viz
