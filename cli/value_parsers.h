// The command line's values typed by hand (--size WxH, --ray and --pixel number lists, --accel name lists,
// --densities), parsed apart from CLI11 so that they can be tested and fuzzed alone
// (fuzz/cli_values_fuzz.cpp). Every refusal is an InputError naming the option and the text given.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace raystep::cli {

// "WxH" (--size) into *w and *h, with 1 <= W, H <= 16384; anything else throws InputError.
void parse_size(const std::string& spec, int* w, int* h);
// "a,b,c,..." as exactly n finite numbers; InputError naming the option otherwise.
std::vector<float> parse_numbers(const std::string& option, const std::string& spec, size_t n);
// --ray: "ox,oy,oz,dx,dy,dz", or in the plane of a 2D scene (plane = true) also "ox,oy,dx,dy" (z = 0); a
// non-zero direction. InputError naming the option otherwise.
struct RayText {
  float origin[3], direction[3];
};
RayText parse_ray(const std::string& spec, bool plane);
// "a,b,c": one or more non-empty names; InputError naming the option otherwise.
std::vector<std::string> parse_names(const std::string& option, const std::string& spec);
// --densities "d1,d2,...": finite numbers in (0, 64].
std::vector<float> parse_densities(const std::string& spec);

}  // namespace raystep::cli
