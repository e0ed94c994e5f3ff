#!/usr/bin/env bash
# Install every dependency of raystep from Debian 12's packages: the whole list, the GUI's included, so
# that the set-up never changes under its users. Idempotent: does nothing when all are installed.
set -euo pipefail

PACKAGES=(
  # toolchain
  g++ cmake ninja-build pkg-config git ca-certificates
  # compiler cache: its cache lives outside the clone (~/.cache/ccache), so a second test run rebuilds fast
  ccache
  # the fuzz harnesses (scripts/fuzz.sh): clang with libFuzzer and the sanitizers' runtimes
  clang libclang-rt-14-dev
  # core
  libglm-dev nlohmann-json3-dev libtinyobjloader-dev libpng-dev libstb-dev libtbb-dev libgmp-dev
  # the lessons' number expressions ({{cost.primitives}}: docs/lesson-format.md)
  libmuparser-dev
  # command line, tests, benchmarks (Embree 3 is the speed yardstick)
  libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev libembree-dev valgrind
  # the reports' plots (gnuplot draws PNG without a display)
  gnuplot-nox
  # flatland figures as PDF and PNG (cairo), and the check that their SVG is well-formed (xmllint)
  libcairo2-dev libxml2-utils
  # the step-debugger (Qt5 + VTK 9.1) and GUI tests under a virtual X server
  libvtk9-qt-dev libgl1-mesa-dri xvfb xauth x11-apps imagemagick
  # the browser player (raystep export-html): its page data is gzip-compressed, and its tests drive
  # Debian's Chromium with Playwright (web/package.json; Node.js and npm below)
  zlib1g-dev chromium
  # a lesson's Markdown in its browser page (CommonMark's reference library)
  libcmark-dev
)
# Node.js and npm from Debian, unless the machine has them already (another Node.js, which brings its npm).
command -v node > /dev/null || PACKAGES+=(nodejs)
command -v npm > /dev/null || PACKAGES+=(npm)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages are installed"
else
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  echo "setup: installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# The browser tests' npm packages, exactly as web/package-lock.json pins them (Playwright uses Debian's
# Chromium: its own browser download is never run).
(cd "$(dirname "$0")/../web" && PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund --loglevel=error)
echo "setup: done"
