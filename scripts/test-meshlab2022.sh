#!/usr/bin/env bash
# The MeshLab 2022.02 check (issue 9), in a Debian 13 (trixie) chroot:
#   1. a trixie root from debootstrap, cached in $SLIM_TRIXIE_ROOT (made once, reused after);
#   2. inside it, Debian's meshlab 2022.02 and the build tools, and MeshLab's upstream sources
#      (the orig tarball of Debian's source package) for its plugin headers and vcglib;
#   3. this checkout, bind-mounted read-only at /src, built for the 2022.02 plugin API;
#   4. ctest -L meshlab2022: the plugin harness (QPluginLoader, offscreen) on the sample bunny and
#      the GUI smoke check (meshlab on a private Xvfb with the plugin in its extra-plugins folder).
# Every stage prints how long it took. Needs root (debootstrap, chroot, mounts) and
# data/bunny.ply (scripts/setup.sh fetches it; run here when missing).
#
# Usage: scripts/test-meshlab2022.sh [--clean]     --clean: rebuild the plugin from scratch
# Environment:
#   SLIM_TRIXIE_ROOT     the chroot (default /var/cache/support-slimming/trixie; ~1.6 GB)
#   SLIM_DEBIAN_MIRROR   default: the Debian mirror this machine's apt uses
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
root="${SLIM_TRIXIE_ROOT:-/var/cache/support-slimming/trixie}"
build=/var/tmp/slim-build-meshlab2022  # inside the chroot: kept, so re-runs build incrementally
clean=0
[ "${1:-}" = "--clean" ] && clean=1

if [ "$(id -u)" -ne 0 ]; then exec sudo --preserve-env=SLIM_TRIXIE_ROOT,SLIM_DEBIAN_MIRROR "$0" "$@"; fi

# Everything MeshLab 2022.02 and the build need. The five libraries after dpkg-dev are system
# plugins' dependencies that Debian's meshlab only recommends: without them five plugins fail to
# load, the GUI shows a blocking error dialog and never loads extra plugins.
PACKAGES=(
  meshlab cmake g++ ninja-build qtbase5-dev libqt5opengl5-dev libglew-dev libeigen3-dev xvfb xauth dpkg-dev
  lib3ds-1-3 libmuparser2v5 libopenctm1 libqhull-r8.0 libxerces-c3.2t64
  libgtest-dev xdotool
)

stage_start=0
stage() { stage_start=$SECONDS; echo "=== [meshlab2022] $*"; }
stage_done() { echo "=== [meshlab2022] done in $((SECONDS - stage_start)) s"; }

# The mirror this machine's apt uses for Debian itself (not -security, not third-party repos).
debian_mirror() {
  local uri
  uri="$( { grep -hs '^URIs:' /etc/apt/sources.list.d/*.sources | awk '{for (i = 2; i <= NF; i++) print $i}'
            grep -hs '^deb ' /etc/apt/sources.list /etc/apt/sources.list.d/*.list | sed 's/\[[^]]*\]//' | awk '{print $2}'
          } | grep -E '/debian/?$' | head -1)"
  echo "${uri:-http://deb.debian.org/debian}"
}
mirror="${SLIM_DEBIAN_MIRROR:-$(debian_mirror)}"

# Unmounts everything at or below a directory, deepest first.
unmount_below() {
  local dir="$1" m
  awk -v d="$dir" '$2 == d || index($2, d "/") == 1 {print $2}' /proc/self/mounts | sort -r |
    while read -r m; do umount -l "$m" 2>/dev/null || true; done
}
# Stops what is still running inside the root (a stray Xvfb would keep /dev busy).
stop_chroot_processes() {
  local p
  for p in /proc/[0-9]*; do
    [ "$(readlink "$p/root" 2>/dev/null)" = "$root" ] && kill -9 "${p#/proc/}" 2>/dev/null || true
  done
}
cleanup() {
  stop_chroot_processes
  unmount_below "$root"
}

mkdir -p "$(dirname "$root")"
exec 9>"$root.lock"
flock -n 9 || { echo "another $0 uses $root" >&2; exit 1; }

# ---- 1. the trixie root ----------------------------------------------------------------------
# Made in a .partial folder and renamed when complete, so an interrupted run never leaves a root
# that looks usable.
if [ ! -e "$root/.slim-bootstrapped" ]; then
  [ -e "$root" ] && { echo "$root exists but was not made by this script; remove it or set SLIM_TRIXIE_ROOT" >&2; exit 1; }
  stage "debootstrap trixie from $mirror into $root"
  command -v debootstrap >/dev/null || apt-get install -y -qq debootstrap >/dev/null
  unmount_below "$root.partial"
  rm -rf --one-file-system "$root.partial"
  debootstrap --variant=minbase trixie "$root.partial" "$mirror" >"$(dirname "$root")/debootstrap.log" 2>&1 ||
    { tail -20 "$(dirname "$root")/debootstrap.log" >&2; exit 1; }
  printf 'deb %s trixie main\ndeb-src %s trixie main\n' "$mirror" "$mirror" >"$root.partial/etc/apt/sources.list"
  # No daemons start inside the chroot.
  printf '#!/bin/sh\nexit 101\n' >"$root.partial/usr/sbin/policy-rc.d"
  chmod +x "$root.partial/usr/sbin/policy-rc.d"
  touch "$root.partial/.slim-bootstrapped"
  mv "$root.partial" "$root"
  stage_done
fi

trap cleanup EXIT INT TERM
mount -t proc proc "$root/proc"
mount -t sysfs sysfs "$root/sys"
mount --rbind /dev "$root/dev"
mount --make-rslave "$root/dev"  # unmounting our copy must never reach the host's /dev
mkdir -p "$root/src"
mount --bind "$here" "$root/src"
mount -o remount,bind,ro "$root/src"
cp -L /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null || true

in_root() {
  chroot "$root" env -i HOME=/root PATH=/usr/local/bin:/usr/bin:/bin:/usr/local/sbin:/usr/sbin:/sbin \
    LANG=C.UTF-8 DEBIAN_FRONTEND=noninteractive OPENBLAS_NUM_THREADS=1 bash -euo pipefail -c "$1"
}

# ---- 2. packages and MeshLab's sources -------------------------------------------------------
installed="$(in_root "dpkg-query -W -f='\${Package} \${Status}\n' ${PACKAGES[*]} 2>/dev/null | grep -c 'install ok installed' || true")"
if [ "$installed" -ne "${#PACKAGES[@]}" ]; then
  stage "installing ${PACKAGES[*]}"
  in_root "apt-get update -qq && apt-get install -y -qq --no-install-recommends ${PACKAGES[*]} >/dev/null"
  stage_done
fi

meshlab_src=/opt/meshlab-2022.02
if [ ! -e "$root$meshlab_src/ML_VERSION" ]; then
  stage "MeshLab sources (orig tarball of Debian's meshlab source package) -> $meshlab_src"
  # apt-get source may fail on the .dsc while the orig tarball, all we need, downloads.
  in_root "mkdir -p /var/cache/slim-src && cd /var/cache/slim-src && rm -f meshlab_*
           apt-get update -qq && (apt-get source --download-only -qq meshlab >/dev/null 2>&1 || true)
           tarball=\$(ls meshlab_*.orig.tar.* | head -1)
           [ -n \"\$tarball\" ] || { echo 'the meshlab orig tarball did not download' >&2; exit 1; }
           rm -rf $meshlab_src.partial && mkdir -p $meshlab_src.partial
           tar -xf \"\$tarball\" -C $meshlab_src.partial --strip-components=1
           mv $meshlab_src.partial $meshlab_src"
  stage_done
fi
# The headers must be those of the installed meshlab: MeshLab refuses a plugin of another version.
in_root "installed=\$(dpkg-query -W -f='\${Version}' meshlab); source=\$(cat $meshlab_src/ML_VERSION)
         [ \"\${installed%%+*}\" = \"\$source\" ] || { echo \"meshlab \$installed installed, sources are \$source\" >&2; exit 1; }
         echo \"[meshlab2022] meshlab \$installed, sources $meshlab_src (\$source)\""

# ---- 3. build --------------------------------------------------------------------------------
[ -f "$here/data/bunny.ply" ] || "$here/scripts/setup.sh"
stage "building the plugin and its tests for MeshLab 2022.02"
[ "$clean" = 1 ] && rm -rf --one-file-system "$root$build"
in_root "cmake -S /src -B $build -G Ninja -DCMAKE_BUILD_TYPE=Release -DSLIM_MESHLAB_API=2022.02 \
           -DMESHLAB_SOURCE_DIR=$meshlab_src -DSLIM_DATA_DIR=/src/data -DSLIM_BUILD_BENCH=OFF >/dev/null
         cmake --build $build -j 2 --target slim_meshlab2022_tests"
stage_done

# ---- 4. tests --------------------------------------------------------------------------------
stage "ctest -L meshlab2022"
in_root "cd $build && ctest -L meshlab2022 --output-on-failure"
stage_done
