#include "raystep/scene/antialiasing_spec.h"

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "raystep/util/error.h"

namespace raystep {
namespace {

const char* kExpected =
    "expected none, regular:K, jitter:K (K 1..64), random:N (N 1..4096) or adaptive:T[:D] "
    "(T in (0,1], D 1..6), each but adaptive optionally followed by +tent";

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts(1);
  for (char c : s) {
    if (c == sep) parts.emplace_back();
    else parts.back() += c;
  }
  return parts;
}

// A whole decimal integer in [lo, hi], digits only (no sign, no spaces).
bool parse_int(const std::string& s, int lo, int hi, int* out) {
  if (s.empty() || s.size() > 9) return false;
  for (char c : s)
    if (c < '0' || c > '9') return false;
  int v = std::atoi(s.c_str());
  if (v < lo || v > hi) return false;
  *out = v;
  return true;
}

// A whole decimal number in (0, 1]. from_chars also accepts "nan" and "inf", which the range test rejects.
bool parse_threshold(const std::string& s, float* out) {
  if (s.empty() || !((s[0] >= '0' && s[0] <= '9') || s[0] == '.')) return false;
  float v;
  auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return false;
  if (!(v > 0.f && v <= 1.f)) return false;
  *out = v;
  return true;
}

// The shortest decimal that reads back as the same float.
std::string shortest(float v) {
  char buf[32];
  for (int precision = 1; precision <= 9; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, double(v));
    if (std::strtof(buf, nullptr) == v) break;
  }
  return buf;
}

}  // namespace

AntiAliasing parse_antialiasing(const std::string& spec) {
  AntiAliasing aa;
  std::string pattern = spec;
  if (const size_t plus = spec.find('+'); plus != std::string::npos) {
    const std::string filter = spec.substr(plus + 1);
    pattern = spec.substr(0, plus);
    if (filter == "tent") aa.filter = AntiAliasing::Filter::tent;
    else if (filter != "box") throw InputError("", 0, "bad anti-aliasing '" + spec + "': " + kExpected);
  }
  std::vector<std::string> p = split(pattern, ':');
  const std::string& mode = p[0];
  bool ok = false;
  if (mode == "none") {
    aa.mode = AntiAliasing::Mode::none;
    ok = p.size() == 1;
  } else if (mode == "regular" || mode == "jitter") {
    aa.mode = mode == "regular" ? AntiAliasing::Mode::regular : AntiAliasing::Mode::jitter;
    ok = p.size() == 2 && parse_int(p[1], 1, 64, &aa.k);
  } else if (mode == "random") {
    aa.mode = AntiAliasing::Mode::random;
    ok = p.size() == 2 && parse_int(p[1], 1, 4096, &aa.k);
  } else if (mode == "adaptive") {
    aa.mode = AntiAliasing::Mode::adaptive;
    ok = (p.size() == 2 || p.size() == 3) && parse_threshold(p[1], &aa.threshold) &&
         (p.size() == 2 || parse_int(p[2], 1, 6, &aa.max_depth));
  }
  if (!ok) throw InputError("", 0, "bad anti-aliasing '" + spec + "': " + kExpected);
  if (aa.mode == AntiAliasing::Mode::adaptive && aa.filter == AntiAliasing::Filter::tent)
    throw InputError("", 0,
                     "bad anti-aliasing '" + spec +
                         "': the tent filter needs samples spread evenly over the pixel (regular, jitter, "
                         "random), and adaptive sampling crowds them at edges");
  return aa;
}

namespace {

std::string pattern_string(const AntiAliasing& aa) {
  switch (aa.mode) {
    case AntiAliasing::Mode::none: return "none";
    case AntiAliasing::Mode::regular: return "regular:" + std::to_string(aa.k);
    case AntiAliasing::Mode::jitter: return "jitter:" + std::to_string(aa.k);
    case AntiAliasing::Mode::random: return "random:" + std::to_string(aa.k);
    case AntiAliasing::Mode::adaptive:
      return "adaptive:" + shortest(aa.threshold) + ":" + std::to_string(aa.max_depth);
  }
  return "none";
}

}  // namespace

std::string to_string(const AntiAliasing& aa) {
  return pattern_string(aa) + (aa.filter == AntiAliasing::Filter::tent ? "+tent" : "");
}

}  // namespace raystep
