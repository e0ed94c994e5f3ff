#!/usr/bin/env bash
# The main job: set up, build, and render the default scene (the GUI will open here once it exists).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
mkdir -p out
./build/cli/raystep render scenes/cornell.json -o out/cornell.png "$@"
