#!/usr/bin/env bash
# Installs the Debian 12 packages freeplay-sim needs. Non-interactive, idempotent, silent when nothing is missing.
# Usage: scripts/setup.sh [--main] [--with-ros] [--with-slurm]   (runs apt-get through sudo when not root)
#   --main  only what the main job needs (scripts/build.sh --main: `freeplay suite`, `freeplay run`), README command 1
set -euo pipefail

# The main job's packages: the compiler and build tools, and the libraries of core, sim, stage, planning, agents,
# policies, runner and the two executables `freeplay suite` runs. OpenCV's three modules come without libopencv-dev
# (cmake/FreeplayDependencies.cmake): that package pulls in every OpenCV module; libopengl-dev is for MuJoCo's CMake
# package (find_dependency(OpenGL)). Measured sizes: docs/performance.md.
main_packages=(
  build-essential cmake ninja-build pkg-config ccache
  libmujoco-dev libopengl-dev libosmesa6-dev libegl-dev libbox2d-dev libompl-dev libeigen3-dev libboost-dev
  libopencv-core-dev libopencv-imgproc-dev libopencv-videoio-dev
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libspdlog-dev libfmt-dev zlib1g-dev libpng-dev
)
# Everything else: the tests, benchmarks, fuzzing, recording, ROS, the web page and the tools (command 2, CI).
other_packages=(
  git libmujoco-samples libopencv-dev libboost-math-dev
  libgtest-dev libgmock-dev libbenchmark-dev libbenchmark-tools python3-scipy
  librosbag-storage-dev libsensor-msgs-dev libtf2-msgs-dev libgeometry-msgs-dev libstd-msgs-dev
  libvisualization-msgs-dev librcpputils-dev librcutils-dev libament-index-cpp-dev python3-rosbag
  libmp3lame-dev libssl-dev libroslz4-dev libbz2-dev
  libespeak-ng-dev espeak-ng-data  # the optional espeak-ng voice (voice_espeak/, GPL-3; babble without it)
  # ROS 1 on a live graph (ros/: freeplay serve / robot) and its message generators and tests
  libroscpp-dev libactionlib-dev libactionlib-msgs-dev libnav-msgs-dev libros-rosgraph-msgs-dev python3-genmsg
  python3-gencpp python3-genpy ros-std-msgs ros-geometry-msgs ros-nav-msgs ros-actionlib-msgs python3-rospy
  python3-rosmaster python3-rostopic python3-actionlib python3-tf2-msgs python3-sensor-msgs python3-geometry-msgs
  python3-visualization-msgs python3-actionlib-msgs python3-nav-msgs
  linux-perf valgrind
  pybind11-dev python3-dev python3-numpy python3-pandas python3-pytest  # the freeplay Python module (python/)
  python3-matplotlib  # the figures of examples/python (not the main job)
  clang libclang-rt-14-dev
  libopencv-contrib-dev  # ArUco markers for the fiducial localisation (localisation/)
  # the experimenter's web page (web/: websocketpp over Boost.Asio) and its headless-browser test (tests/web/)
  libwebsocketpp-dev libasio-dev libboost-system-dev chromium nodejs
)
command -v npm >/dev/null 2>&1 || other_packages+=(npm)  # Debian's npm (a NodeSource nodejs ships its own)
packages=("${main_packages[@]}" "${other_packages[@]}")
extra_packages=()
for arg in "$@"; do
  case "$arg" in
    --main) packages=("${main_packages[@]}") ;;
    --with-ros) ;;  # the ROS 1 bag packages are in the default list now (recording and its tests need them)
    --with-slurm) extra_packages+=(slurm-wlm munge) ;;
    -h|--help) sed -n '2,4p' "$0"; exit 0 ;;
    *) echo "setup.sh: unknown option '$arg' (allowed: --main, --with-ros, --with-slurm)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}" "${extra_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then SUDO=sudo; else
    echo "setup.sh: missing packages (${missing[*]}); run as root or install sudo" >&2; exit 1
  fi
else
  SUDO=
fi
echo "setup.sh: installing ${#missing[@]} package(s): ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup.sh: done"
