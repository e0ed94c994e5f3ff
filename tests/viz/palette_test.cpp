// The debugger's colours for colour-blind viewers (about 1 in 12 men in a lecture room): each colour is seen
// as a deuteranope and a protanope would see it (Machado, Oliveira and Fernandes 2009, severity 1, applied in
// linear RGB), and every pair of colours that must be told apart keeps a CIE76 distance (CIELAB, D65) of at
// least 15 between the walk's colours, and 20 among the primitive states, the hit markers and the Cornell
// box's red and green walls as the 3D view draws them. No display needed: plain arithmetic on palette.h.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "common/palette.h"

namespace {

using Rgb = std::array<double, 3>;  // 0..255, sRGB
using Matrix = std::array<std::array<double, 3>, 3>;

const Matrix kNormal = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
const Matrix kProtanopia = {
    {{0.152286, 1.052583, -0.204868}, {0.114503, 0.786281, 0.099216}, {-0.003882, -0.048116, 1.051998}}};
const Matrix kDeuteranopia = {
    {{0.367322, 0.860646, -0.227968}, {0.280085, 0.672501, 0.047413}, {-0.011820, 0.042940, 0.968881}}};

double toLinear(double c) {
  c /= 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}
double toSrgb(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return 255.0 * (c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055);
}

Rgb simulate(const Rgb& c, const Matrix& m) {
  Rgb lin{toLinear(c[0]), toLinear(c[1]), toLinear(c[2])}, out;
  for (int i = 0; i < 3; ++i) out[size_t(i)] = toSrgb(m[i][0] * lin[0] + m[i][1] * lin[1] + m[i][2] * lin[2]);
  return out;
}

std::array<double, 3> lab(const Rgb& c) {
  double r = toLinear(c[0]), g = toLinear(c[1]), b = toLinear(c[2]);
  double x = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047, y = 0.2126 * r + 0.7152 * g + 0.0722 * b,
         z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883;
  auto f = [](double t) { return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0; };
  return {116 * f(y) - 16, 500 * (f(x) - f(y)), 200 * (f(y) - f(z))};
}

double deltaE(const Rgb& a, const Rgb& b) {
  auto p = lab(a), q = lab(b);
  return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
}

Rgb rgb(const QColor& c) {
  return {double(c.red()), double(c.green()), double(c.blue())};
}

using Named = std::vector<std::pair<std::string, Rgb>>;

// Every pair in `a` (and each of `a` against each of `b`) at least `threshold` apart for every viewer.
void expectApart(const Named& a, const Named& b, double threshold) {
  for (auto [viewer, m] : {std::pair{"normal", kNormal}, std::pair{"protanopia", kProtanopia},
                           std::pair{"deuteranopia", kDeuteranopia}}) {
    for (size_t i = 0; i < a.size(); ++i) {
      for (size_t j = i + 1; j < a.size(); ++j)
        EXPECT_GE(deltaE(simulate(a[i].second, m), simulate(a[j].second, m)), threshold)
            << viewer << ": " << a[i].first << " and " << a[j].first;
      for (const auto& [name, c] : b)
        EXPECT_GE(deltaE(simulate(a[i].second, m), simulate(c, m)), threshold)
            << viewer << ": " << a[i].first << " and " << name;
    }
  }
}

// The Cornell box's walls as the 3D view colours them (the diffuse colour, gamma-encoded, lit and in shadow).
Named cornellWalls() {
  auto wall = [](double r, double g, double b, double light) {
    return Rgb{255 * light * std::pow(r, 1 / 2.2), 255 * light * std::pow(g, 1 / 2.2),
               255 * light * std::pow(b, 1 / 2.2)};
  };
  return {{"red wall", wall(0.65, 0.06, 0.05, 1.0)},
          {"red wall in shade", wall(0.65, 0.06, 0.05, 0.55)},
          {"green wall", wall(0.12, 0.45, 0.09, 1.0)}};
}

TEST(Palette, PrimitiveStatesAndHitMarkersStayApartForColourBlindViewers) {
  using namespace raystep::viz::palette;
  Named states = {{"not reached", rgb(primPending)},
                  {"being tested", rgb(primTesting)},
                  {"hit", rgb(primHit)},
                  {"missed", rgb(primMissed)},
                  {"skipped", rgb(primSkipped)},
                  {"nearest hit so far", rgb(hitCandidate)},
                  {"accepted hit", rgb(hitFinal)}};
  expectApart(states, cornellWalls(), 20.0);
}

TEST(Palette, WalkColoursStayApartForColourBlindViewers) {
  using namespace raystep::viz::palette;
  Named walk = {{"current cell", rgb(currentCell)},
                {"visited", rgb(visitedCell)},
                {"ray", rgb(ray)},
                {"ray ahead", rgb(rayAhead)},
                {"segment", rgb(segment)},
                {"accepted hit", rgb(hitFinal)},
                {"nearest hit so far", rgb(hitCandidate)},
                {"stack", rgb(stackNode)},
                {"selected node", rgb(selectedNode)},
                {"built plane", rgb(builtPlane)},
                {"BVH first child", rgb(bvhChildFirst)},
                {"BVH other child", rgb(bvhChildOther)},
                {"BVH overlap", rgb(bvhOverlap)},
                {"BVH skipped", rgb(bvhSkipped)}};
  expectApart(walk, {}, 15.0);
}

// The check itself: a red and a green of equal lightness are far apart for most viewers and close for both
// kinds of red-green colour blindness (what the simulation is for).
TEST(Palette, SimulationMergesRedAndGreen) {
  Rgb red{180, 100, 50}, green{120, 135, 45};
  EXPECT_GT(deltaE(red, green), 40.0);
  EXPECT_LT(deltaE(simulate(red, kProtanopia), simulate(green, kProtanopia)), 15.0);
  EXPECT_LT(deltaE(simulate(red, kDeuteranopia), simulate(green, kDeuteranopia)), 15.0);
}

}  // namespace
