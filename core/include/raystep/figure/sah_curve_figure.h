// The SAH inspector's chart as a figure (figure.h), for pages and slides: a node's cost
// C = t_t + p_a N_a t_i + p_b N_b t_i for every candidate plane the builder evaluated, against the plane's
// position across the node's box (0: its min, 1: its max) on x, y and z, one dot per candidate and a line
// through each axis's; the leaf cost N t_i dashed (a split must come below it); the chosen split's line and
// its words, or the reason the node stayed a leaf, with the class "answer" (a page hides them while a
// question asks for the plane).
#pragma once

#include "raystep/accel/bvh_sah_curve.h"
#include "raystep/accel/kdtree_sah_curve.h"
#include "raystep/figure/figure.h"

namespace raystep {

// path: the node's "LRL" from the root, for the caption ("": not named; node 0 is called the root).
Figure sah_curve_figure(const SahCurve& curve, const std::string& path);
Figure sah_curve_figure(const BvhSahCurve& curve, const std::string& path);

}  // namespace raystep
