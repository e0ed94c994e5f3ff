// `raystep replay`: a trace's replay states, the storyboard every front end reads (core/replay/storyboard.h,
// docs/replay-format.md), as JSON or as text for a reader.
#include <cstdio>
#include <iostream>

#include "commands.h"
#include "raystep/replay/storyboard.h"
#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"

namespace raystep::cli {

int run_replay(const ReplayArgs& a) {
  if (a.step && *a.step < 0)
    throw InputError("", 0, "replay: --step " + std::to_string(*a.step) + ": a step is 0 or more");
  if (a.walk && *a.walk < 0)
    throw InputError("", 0, "replay: --walk " + std::to_string(*a.walk) + ": a walk is 0 or more");
  if (a.ray && *a.ray < 0)
    throw InputError("", 0, "replay: --ray " + std::to_string(*a.ray) + ": a ray is 0 or more");
  const MultiTrace trace = read_any_trace_json(a.trace);
  replay::StoryboardRequest r;
  r.walk = a.walk.value_or(-1);
  r.ray = a.ray.value_or(-1);
  r.step = a.step.value_or(-1);
  auto write = [&](std::ostream& out) {
    try {
      if (a.format == "json")
        replay::write_storyboard(out, trace, a.trace, r);
      else
        replay::write_storyboard_text(out, trace, r);
    } catch (const InputError& e) {
      throw InputError(a.trace, 0, e.what());
    }
  };
  if (a.output.empty()) {
    write(std::cout);
    std::cout.flush();
  } else {
    write_file_atomically(a.output, write);
    std::fprintf(stderr, "wrote %s\n", a.output.c_str());
  }
  return 0;
}

}  // namespace raystep::cli
