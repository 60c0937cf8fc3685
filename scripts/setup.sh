#!/usr/bin/env bash
# Installs every Debian 12 package freeplay-sim needs. Non-interactive, idempotent, silent when nothing is missing.
# Usage: scripts/setup.sh [--with-ros] [--with-slurm]   (runs apt-get through sudo when not root)
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git ccache
  libmujoco-dev libmujoco-samples libosmesa6-dev libegl-dev
  libbox2d-dev libompl-dev libopencv-dev libeigen3-dev libyaml-cpp-dev
  libgtest-dev libgmock-dev libbenchmark-dev libbenchmark-tools python3-scipy
  libcli11-dev nlohmann-json3-dev libspdlog-dev libfmt-dev libboost-math-dev
  librosbag-storage-dev libsensor-msgs-dev libtf2-msgs-dev libgeometry-msgs-dev libstd-msgs-dev
  libvisualization-msgs-dev librcpputils-dev librcutils-dev libament-index-cpp-dev python3-rosbag
  libmp3lame-dev libssl-dev libroslz4-dev libbz2-dev
  libespeak-ng-dev espeak-ng-data  # the optional espeak-ng voice (voice_espeak/, GPL-3; babble without it)
  # ROS 1 on a live graph (ros/: freeplay serve / robot) and its message generators and tests
  libroscpp-dev libactionlib-dev libactionlib-msgs-dev libnav-msgs-dev libros-rosgraph-msgs-dev python3-genmsg
  python3-gencpp python3-genpy ros-std-msgs ros-geometry-msgs ros-nav-msgs ros-actionlib-msgs python3-rospy
  python3-rosmaster python3-rostopic python3-actionlib python3-tf2-msgs python3-sensor-msgs python3-geometry-msgs
  python3-visualization-msgs python3-actionlib-msgs python3-nav-msgs
  zlib1g-dev libpng-dev linux-perf valgrind
  pybind11-dev python3-dev python3-numpy python3-pandas python3-pytest  # the freeplay Python module (python/)
  clang libclang-rt-14-dev
  libopencv-contrib-dev  # ArUco markers for the fiducial localisation (localisation/)
  # the experimenter's web page (web/: websocketpp over Boost.Asio) and its headless-browser test (tests/web/)
  libwebsocketpp-dev libasio-dev libboost-system-dev chromium nodejs
)
command -v npm >/dev/null 2>&1 || packages+=(npm)  # Debian's npm (a NodeSource nodejs ships its own)
for arg in "$@"; do
  case "$arg" in
    --with-ros) ;;  # the ROS 1 bag packages are in the default list now (recording and its tests need them)
    --with-slurm) packages+=(slurm-wlm munge) ;;
    -h|--help) sed -n '2,3p' "$0"; exit 0 ;;
    *) echo "setup.sh: unknown option '$arg' (allowed: --with-ros, --with-slurm)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
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
