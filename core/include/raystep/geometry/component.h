// Indexed access to a glm vector's components without a branch. glm's operator[] is a switch on the index:
// where the index varies at run time (the 3D-DDA's axis, the watertight test's permutation, a kd-tree node's
// split axis) each access is a conditional branch, and a mispredicted one costs more than the arithmetic.
#pragma once

#include <glm/gtc/type_ptr.hpp>
#include <glm/vec3.hpp>

namespace raystep {

inline float component(const glm::vec3& v, int k) { return glm::value_ptr(v)[k]; }

}  // namespace raystep
