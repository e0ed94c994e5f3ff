// The debugger's colours, one meaning each, shared by the 3D view, its legend, the image view and the
// scripted mode's state dump (the GUI tests look for these exact colours in screenshots). Boxes, lines and
// primitive states are drawn unlit, so they appear on screen in exactly these colours.
#pragma once

#include <QColor>

namespace raystep::viz::palette {

inline const QColor currentCell{255, 214, 0};    // the cell the 3D-DDA is in, or the current kd node: yellow
inline const QColor visitedCell{90, 140, 255};   // cells already walked: faded blue
inline const QColor stackNode{255, 130, 170};   // kd-tree: nodes waiting on the stack: pink
inline const QColor splitPlane{255, 240, 150};   // kd-tree: the current node's split plane (translucent)
inline const QColor gridOutline{150, 150, 150};  // the grid's bounding box
inline const QColor ray{0, 230, 255};            // the ray up to where the walk is: cyan
inline const QColor rayAhead{0, 105, 125};       // the rest of the ray, not walked yet: dark cyan
inline const QColor segment{255, 255, 255};      // the current [tmin, tmax] interval: white, thick
inline const QColor hitFinal{255, 40, 200};      // the accepted hit point: magenta
// The primitive states and the hit markers share no hue with the Cornell box's red and green walls, and stay
// apart for deuteranopes and protanopes (tests/viz/palette_test.cpp: CIE76 distance >= 15 between the walk's
// colours, >= 20 among the primitive states, the markers and the walls, under Machado et al.'s matrices).
inline const QColor hitCandidate{255, 240, 140};  // the nearest hit so far, not yet accepted: pale yellow
inline const QColor primPending{150, 150, 150};   // referenced by the current cell, not reached yet: grey
inline const QColor primTesting{255, 255, 255};   // being tested now: white outline (the face shows the result)
inline const QColor primHit{40, 220, 60};         // tested: hit
inline const QColor primMissed{70, 80, 110};      // tested: missed: dark slate
inline const QColor primSkipped{170, 90, 255};    // skipped: already tested (mailbox)
inline const QColor builtPlane{195, 240, 180};    // kd-tree: planes split before the selected node: pale green
inline const QColor selectedNode{0, 158, 115};    // kd-tree: the node chosen in the tree view / inspector: teal
inline const QColor background{28, 30, 36};
// BVH: the current inner node's children's boxes, translucent so that where they overlap ("bounding volumes
// can overlap") both tints add up, the overlap itself outlined, and the popped nodes skipped beyond the hit.
inline const QColor bvhChildFirst{255, 150, 30};  // the first child tested (binary BVH: the left one): orange
inline const QColor bvhChildOther{160, 0, 255};   // the other children: violet
inline const QColor bvhOverlap{255, 50, 50};      // where two children's boxes overlap: red outline
inline const QColor bvhSkipped{140, 180, 100};    // skipped: popped with t_near beyond the nearest hit: sage

// The SAH inspector's chart (drawn on white): the cost curves per split axis, the leaf cost, the chosen split.
inline const QColor sahX{220, 40, 40};           // candidates on x: red
inline const QColor sahY{30, 160, 50};           // candidates on y: green
inline const QColor sahZ{40, 80, 230};           // candidates on z: blue
inline const QColor sahLeafCost{110, 110, 110};  // N * t_i, the cost of not splitting: grey
inline const QColor sahChosen{0, 0, 0};          // the chosen split plane: black
// A general BSP node's candidates by orientation (the axes keep sahX, sahY, sahZ: the kd-tree's planes).
inline const QColor sahFaceDiagonal{235, 140, 0};  // the 6 face diagonals (x+y, x-y, ...): orange
inline const QColor sahBodyDiagonal{150, 60, 210};  // the 4 body diagonals (x+y+z, ...): violet
inline const QColor sahOwnPlane{0, 150, 150};       // the primitives' own planes (autopartition): teal

}  // namespace raystep::viz::palette
