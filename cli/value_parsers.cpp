// The command line's hand-typed values. See value_parsers.h.
#include "value_parsers.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <regex>
#include <sstream>

#include "raystep/util/error.h"

namespace raystep::cli {

// "a,b,c,..." as exactly n finite numbers.
std::vector<float> parse_numbers(const std::string& option, const std::string& spec, size_t n) {
  std::vector<float> out;
  std::stringstream ss(spec);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    float v = std::strtof(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(v)) break;
    out.push_back(v);
  }
  if (out.size() != n || std::count(spec.begin(), spec.end(), ',') != long(n - 1))
    throw InputError(
        "", 0, option + " '" + spec + "': expected " + std::to_string(n) + " comma-separated finite numbers");
  return out;
}

RayText parse_ray(const std::string& spec, bool plane) {
  const long commas = std::count(spec.begin(), spec.end(), ',');
  RayText r{};
  if (commas == 3) {
    if (!plane)
      throw InputError("", 0,
                       "--ray '" + spec +
                           "': four numbers are a ray in the plane of a 2D scene; this scene is 3D: give "
                           "ox,oy,oz,dx,dy,dz");
    const std::vector<float> v = parse_numbers("--ray", spec, 4);
    r = RayText{{v[0], v[1], 0.f}, {v[2], v[3], 0.f}};
  } else {
    const std::vector<float> v = parse_numbers("--ray", spec, 6);
    r = RayText{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
  }
  if (r.direction[0] == 0.f && r.direction[1] == 0.f && r.direction[2] == 0.f)
    throw InputError("", 0, "--ray: the direction is zero");
  return r;
}

// "WxH" with 1 <= W, H <= 16384.
void parse_size(const std::string& spec, int* w, int* h) {
  static const std::regex re("([0-9]{1,5})x([0-9]{1,5})");
  std::smatch m;
  if (std::regex_match(spec, m, re)) {
    int ww = std::stoi(m[1]), hh = std::stoi(m[2]);
    if (ww >= 1 && hh >= 1 && ww <= 16384 && hh <= 16384) {
      *w = ww;
      *h = hh;
      return;
    }
  }
  throw InputError("", 0, "--size '" + spec + "': expected WxH with 1 <= W, H <= 16384");
}

// "a,b,c": non-empty names.
std::vector<std::string> parse_names(const std::string& option, const std::string& spec) {
  std::vector<std::string> out;
  std::stringstream ss(spec);
  for (std::string item; std::getline(ss, item, ',');) {
    if (item.empty()) throw InputError("", 0, option + " '" + spec + "': an empty name in the list");
    out.push_back(item);
  }
  if (out.empty() || spec.back() == ',') throw InputError("", 0, option + " '" + spec + "': an empty list");
  return out;
}

// The grid densities: finite numbers in (0, 64].
std::vector<float> parse_densities(const std::string& spec) {
  std::vector<float> out;
  for (const std::string& item : parse_names("--densities", spec)) {
    char* end = nullptr;
    float v = std::strtof(item.c_str(), &end);
    if (*end != '\0' || !(v > 0.f && v <= 64.f))
      throw InputError("", 0, "--densities '" + spec + "': '" + item + "' is not a number in (0, 64]");
    out.push_back(v);
  }
  return out;
}

}  // namespace raystep::cli
