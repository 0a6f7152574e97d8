#!/bin/sh
# Installs what illum builds with, from Debian 12's own packages (run as root).
# The README's first command and CI (.ci/run) both call this script.
set -eu
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends \
    build-essential cmake pkg-config \
    libembree-dev libassimp-dev libopenexr-dev libstb-dev libcjson-dev \
    libglfw3-dev libepoxy-dev xvfb xauth libgl1-mesa-dri \
    libopenmpi-dev openmpi-bin >/dev/null
# The last two lines are optional: the viewer (illum view, its test under
# Xvfb) and MPI (mpirun -np N illum render); without them both are left out
# of the build.
