// Exact box-filtered coverage: the area of a polygon inside a pixel, i.e. the pixel value a perfect
// pre-filter (the lecture's "area sampling") gives a white polygon on black. The polygon, in raster
// coordinates, is clipped to the pixel's square by Sutherland-Hodgman (Sutherland and Hodgman 1974) and the
// clipped area taken by the shoelace formula. Exact for convex and simple polygons: clipping a simple polygon
// against a convex window may leave zero-area bridges, which add nothing to the signed area.
#pragma once

#include <vector>

#include <glm/vec2.hpp>

namespace raystep {

// Signed area (counter-clockwise positive in a y-up frame) by the shoelace formula.
double signed_area(const std::vector<glm::dvec2>& polygon);

// The part of the polygon inside the axis-aligned box [lo, hi] (Sutherland-Hodgman, one edge at a time).
std::vector<glm::dvec2> clip_to_box(const std::vector<glm::dvec2>& polygon, const glm::dvec2& lo,
                                    const glm::dvec2& hi);

// Area of polygon ∩ [x, x+1] x [y, y+1], in [0, 1], whatever the polygon's orientation.
double pixel_coverage(const std::vector<glm::dvec2>& polygon, int x, int y);

// The tent pre-filter's value for pixel (x, y) of a white polygon on black: the integral over the polygon of
// (1 - |u|)(1 - |v|), (u, v) the offset from the pixel's centre within [-1, 1]^2 (render/pixel_filter.h), in
// [0, 1]. Exact up to rounding: in each quadrant around the centre the tent is the polynomial
// 1 - |u| - |v| + |u||v|, whose integral over the polygon clipped to the quadrant is a sum over its edges
// (Green's theorem: the polygon's area and its first moments and product moment, from its vertices).
double pixel_tent_coverage(const std::vector<glm::dvec2>& polygon, int x, int y);

}  // namespace raystep
