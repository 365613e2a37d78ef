#!/usr/bin/env bash
# The MeshLab 2025.07 check, in a Debian forky (testing) chroot, which ships meshlab 2025.07:
#   1. a forky root from debootstrap, cached in $SLIM_FORKY_ROOT (made once, reused after);
#   2. inside it, Debian's meshlab 2025.07 and the build tools, and MeshLab's upstream sources
#      (the orig tarball of Debian's source package) for its plugin headers and vcglib;
#   3. this checkout, bind-mounted read-only at /src, built for the FilterPlugin API;
#   4. ctest -L meshlab2025: the plugin harness (QPluginLoader, offscreen) on the sample bunny and
#      the GUI smoke check (meshlab on a private Xvfb with the plugin in its extra-plugins folder).
# The machinery is scripts/lib/debian-chroot.sh, shared with scripts/test-meshlab2022.sh. Every
# stage prints how long it took; any failure exits non-zero. Needs root and data/bunny.ply
# (scripts/setup.sh fetches it; run here when missing).
#
# Usage: scripts/test-meshlab2025.sh [--clean | --prepare-only]
#   --clean: rebuild the plugin from scratch; --prepare-only: make the root, install its packages
#   and fetch the sources, then stop
# Environment:
#   SLIM_FORKY_ROOT      the chroot (default /var/cache/support-slimming/forky; ~1.7 GB)
#   SLIM_DEBIAN_MIRROR   default: the Debian mirror this machine's apt uses
set -euo pipefail

# Everything MeshLab 2025.07, the build and the tests need. The four libraries after dpkg-dev are
# system plugins' dependencies that Debian's meshlab only recommends: without them MeshLab shows a
# blocking error dialog and loads no extra plugin. TetGen is 1.6 in forky (libtet-dev).
PACKAGES=(
  meshlab cmake g++ ninja-build qtbase5-dev libqt5opengl5-dev libglew-dev libeigen3-dev xvfb xauth dpkg-dev help2man
  lib3ds-1-3 libmuparser2v5 libopenctm1 libqhull-r8.0
  libsuitesparse-dev libopenblas0-pthread libtet-dev lib3mf-dev libzip-dev
  libgtest-dev xdotool lintian ccache
)

source "$(dirname "${BASH_SOURCE[0]}")/lib/debian-chroot.sh"
meshlab_chroot_check meshlab2025 forky SLIM_FORKY_ROOT /var/cache/support-slimming/forky "$@"
