#!/usr/bin/env bash
# Installs every Debian 12 package uwgrasp needs to build, test, benchmark and run its ROS node.
# Idempotent: packages already present are skipped by apt; runs as root or through sudo.
set -euo pipefail

PACKAGES=(
  # toolchain
  build-essential cmake pkg-config git
  # grasp engine: core, cloud, segment, grasp, vehicle
  libeigen3-dev libnanoflann-dev libtbb-dev
  # io, viz, camera, sim
  libpcl-dev libyaml-cpp-dev nlohmann-json3-dev libcli11-dev
  libopencv-dev libpng-dev libembree-dev libassimp-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev
  # ROS 1 node (optional at build time, UWGRASP_BUILD_ROS)
  catkin libroscpp-dev librosbag-dev libsensor-msgs-dev libgeometry-msgs-dev
  libvisualization-msgs-dev libpcl-conversions-dev libstd-msgs-dev libstd-srvs-dev
  libnav-msgs-dev libdiagnostic-msgs-dev ros-message-generation ros-std-msgs ros-geometry-msgs
  libtf2-dev libtf2-ros-dev libtf2-msgs-dev libtf2-geometry-msgs-dev
  # ROS 1 integration test: roscore, roslaunch, rostopic, rosbag play
  ros-core python3-rosbag python3-rostopic
  # fuzzing (fuzz/, UWGRASP_BUILD_FUZZ): clang, libFuzzer, llvm-symbolizer for readable stacks
  clang libclang-rt-14-dev llvm-14
)

SUDO=""
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "install-deps: run as root or install sudo" >&2; exit 1; }
  SUDO="sudo"
fi

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${#missing[@]} packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done"
