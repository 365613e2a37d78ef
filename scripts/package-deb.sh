#!/usr/bin/env bash
# Makes the Debian package of the plugin and support-slim for the meshlab installed here, and
# prints the .deb's path as its last line.
#
# The package (packaging/debian.cmake, made by CPack) installs the plugin into MeshLab's plugins
# folder, support-slim into /usr/bin with its man page, and the README and the .mlx examples into
# /usr/share/doc/meshlab-support-slimming. It depends on exactly the installed meshlab version and
# on the libraries the binaries link (CHOLMOD, TetGen, Qt), and on OpenBLAS.
#
#   scripts/package-deb.sh [BUILD_DIR]
#
# BUILD_DIR (default build/) is reused as it is configured; when it is not configured yet, this
# is Debian 12 with MeshLab 2020.09: scripts/setup.sh installs what the build needs and the build
# is configured as scripts/build.sh does. In a Debian 13 or forky chroot (scripts/test-meshlab2022.sh,
# scripts/test-meshlab2025.sh) BUILD_DIR is their build, configured for MeshLab 2022.02 or 2025.07.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"

if [ ! -f "$build/CMakeCache.txt" ]; then
  "$here/scripts/setup.sh" >&2
  generator=()
  command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
  cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=Release "${generator[@]}" >&2
fi
command -v dpkg-shlibdeps >/dev/null || { echo "package-deb: dpkg-shlibdeps is missing (apt-get install dpkg-dev)" >&2; exit 1; }
# Only what goes into the package, its changelog and support-slim's man page (help2man).
cmake --build "$build" -j 2 --target filter_support_slimming support-slim slim_deb_changelog slim_deb_man >&2
rm -rf "$build/packages"
(cd "$build" && cpack -G DEB --config CPackConfig.cmake >&2)
deb="$(ls "$build"/packages/*.deb)"
[ "$(echo "$deb" | wc -l)" -eq 1 ] || { echo "package-deb: expected one .deb in $build/packages, got: $deb" >&2; exit 1; }
dpkg-deb --info "$deb" | sed -n '/Package:/,$p' >&2
echo "$deb"
