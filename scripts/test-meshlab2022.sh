#!/usr/bin/env bash
# The MeshLab 2022.02 check, in a Debian 13 (trixie) chroot:
#   1. a trixie root from debootstrap, cached in $SLIM_TRIXIE_ROOT (made once, reused after);
#   2. inside it, Debian's meshlab 2022.02 and the build tools, and MeshLab's upstream sources
#      (the orig tarball of Debian's source package) for its plugin headers and vcglib;
#   3. this checkout, bind-mounted read-only at /src, built for the 2022.02 plugin API;
#   4. ctest -L meshlab2022: the plugin harness (QPluginLoader, offscreen) on the sample bunny and
#      the GUI smoke check (meshlab on a private Xvfb with the plugin in its extra-plugins folder).
# The machinery is scripts/lib/debian-chroot.sh, shared with scripts/test-meshlab2025.sh. Every
# stage prints how long it took; any failure exits non-zero. Needs root (debootstrap, chroot,
# mounts) and data/bunny.ply (scripts/setup.sh fetches it; run here when missing).
#
# Usage: scripts/test-meshlab2022.sh [--clean | --prepare-only]
#   --clean: rebuild the plugin from scratch; --prepare-only: make the root, install its packages
#   and fetch the sources, then stop
# Environment:
#   SLIM_TRIXIE_ROOT     the chroot (default /var/cache/support-slimming/trixie; ~1.6 GB)
#   SLIM_DEBIAN_MIRROR   default: the Debian mirror this machine's apt uses
set -euo pipefail

# Everything MeshLab 2022.02, the build and the tests need. The five libraries after dpkg-dev are
# system plugins' dependencies that Debian's meshlab only recommends: without them five plugins
# fail to load, the GUI shows a blocking error dialog and never loads extra plugins.
PACKAGES=(
  meshlab cmake g++ ninja-build qtbase5-dev libqt5opengl5-dev libglew-dev libeigen3-dev xvfb xauth dpkg-dev help2man
  lib3ds-1-3 libmuparser2v5 libopenctm1 libqhull-r8.0 libxerces-c3.2t64
  libsuitesparse-dev libopenblas0-pthread libtet1.5-dev lib3mf-dev libzip-dev
  libgtest-dev xdotool lintian ccache
)

source "$(dirname "${BASH_SOURCE[0]}")/lib/debian-chroot.sh"
meshlab_chroot_check meshlab2022 trixie SLIM_TRIXIE_ROOT /var/cache/support-slimming/trixie "$@"
