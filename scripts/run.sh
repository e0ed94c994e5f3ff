#!/usr/bin/env bash
# The main job: set up, build, and open the step-debugger on the default scene with the grid.
# Without a display ($DISPLAY empty) it renders the default scene to out/cornell.png instead and says how to
# run the debugger under a virtual X server. Extra arguments go to raystep-gui (e.g. --pixel 160,200).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
scene=scenes/cornell.json
if [ -n "${DISPLAY:-}" ] && [ -x build/viz/raystep-gui ]; then
  exec ./build/viz/raystep-gui "$scene" --accel grid "$@"
fi
mkdir -p out
./build/cli/raystep render "$scene" -o out/cornell.png
if [ ! -x build/viz/raystep-gui ]; then
  echo "run.sh: raystep-gui was not built (Qt5 or VTK missing); rendered out/cornell.png instead"
else
  echo "run.sh: no display (\$DISPLAY is empty); rendered out/cornell.png instead."
  echo "  The debugger under a virtual X server, as a screenshot:"
  echo "    xvfb-run -a -s '-screen 0 1280x800x24' ./build/viz/raystep-gui $scene --pixel 160,200 --step-to cell:3 --screenshot out/debugger.png --quit"
fi
