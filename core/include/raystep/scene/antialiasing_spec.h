// Anti-aliasing as a one-word spec, as typed on the command line and in a scene file's "render.aa":
//   none | regular:K | jitter:K | random:N | adaptive:T | adaptive:T:D, optionally followed by +tent
// regular: K x K samples on a grid; jitter: one random sample in each of the K x K cells (stratified);
// random: N uniformly random samples; adaptive: Whitted's subdivision where corner contrast exceeds T,
// at most D levels deep. The samples are box-filtered over the pixel, or with "+tent" (not after adaptive)
// weighed by the tent filter over the pixel and its neighbours (render/pixel_filter.h).
#pragma once

#include <string>

#include "raystep/scene/scene.h"

namespace raystep {

// Field use in AntiAliasing:
//   regular, jitter: k = K (1..64), K x K samples per pixel;
//   random:          k = N (1..4096), the number of samples itself (not N x N);
//   adaptive:        threshold = T in (0, 1], max_depth = D (1..6, default 3);
//   none:            k = 1, one sample at the pixel centre;
//   +tent:           filter = tent (box without it; "+box" is read too).
// Throws InputError("", 0, "bad anti-aliasing 'x': expected ...") on anything else.
AntiAliasing parse_antialiasing(const std::string& spec);

// The spec that parse_antialiasing reads back to the same settings ("adaptive" always names D; "+tent" only
// for the tent filter).
std::string to_string(const AntiAliasing& aa);

}  // namespace raystep
