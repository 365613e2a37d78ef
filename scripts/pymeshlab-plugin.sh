#!/usr/bin/env bash
# Builds the plugin for PyMeshLab and prints its path as the last line.
#
# PyMeshLab loads only a plugin built for its own MeshLab release and precision, linked to what
# its wheel bundles. So, for the first python3 on PATH that has pymeshlab installed:
#   1. the MeshLab release it pins (pymeshlab 2025.7.post1 -> MeshLab 2025.07), whose sources
#      (plugin headers, vcglib) come from Debian's meshlab source package of that release, cached
#      in $SLIM_SOURCE_CACHE (override with MESHLAB_SOURCE_DIR=...);
#   2. the wheel's lib/: libmeshlab-common.so must be there and built in double precision, its
#      C++ ABI (the new std::string or the old one) is matched, and its Qt must be the same
#      minor release as the Qt headers this machine compiles with;
#   3. a build with MESHLAB_SCALAR=double in BUILD_DIR, linked to the wheel's libmeshlab-common.so
#      and Qt (-Wl,--no-undefined checks every symbol against them). Its ctest label pymeshlab
#      is the test (scripts/test-pymeshlab.sh runs it).
#
# Usage: scripts/pymeshlab-plugin.sh [BUILD_DIR]      (default: build-pymeshlab/ in this checkout)
# Environment: SLIM_SOURCE_CACHE (default /var/cache/support-slimming/src), MESHLAB_SOURCE_DIR,
#              SLIM_CCACHE_DIR (default /var/cache/support-slimming/ccache-pymeshlab),
#              SLIM_DEBIAN_MIRROR (default: the Debian mirror this machine's apt uses)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build-pymeshlab}"
say() { echo "[pymeshlab-plugin] $*" >&2; }
fail() { echo "[pymeshlab-plugin] $*" >&2; exit 1; }

# ---- the python and its pymeshlab --------------------------------------------------------------
# Without importing it: importing pymeshlab loads all of its plugins, which takes a while.
probe='import importlib.metadata as m, importlib.util as u, os, sys
s = u.find_spec("pymeshlab")
if s is None: sys.exit(1)
print(m.version("pymeshlab"), os.path.dirname(s.origin), sys.executable)'
python="" info=""
IFS=: read -ra path_dirs <<<"$PATH"
for d in "${path_dirs[@]}"; do
  [ -x "$d/python3" ] || continue
  if info="$("$d/python3" -c "$probe" 2>/dev/null)"; then python="$d/python3"; break; fi
done
[ -n "$python" ] || fail "no python3 on PATH has pymeshlab; e.g. python3 -m venv venv && venv/bin/pip install pymeshlab==2025.7.post1, then PATH=\$PWD/venv/bin:\$PATH $0"
read -r pymeshlab_version package_dir python_exe <<<"$info"
wheel_lib="$package_dir/lib"
# pymeshlab YYYY.M[.postN] pins MeshLab YYYY.MM.
meshlab_version="$(echo "$pymeshlab_version" | sed -E 's/^([0-9]{4})\.([0-9]{1,2}).*/\1.\2/' | awk -F. '{printf "%s.%02d", $1, $2}')"
say "python $python_exe: pymeshlab $pymeshlab_version (MeshLab $meshlab_version) in $package_dir"

"$here/scripts/setup.sh" >&2  # build tools, Qt and GLEW headers, Eigen, CHOLMOD, TetGen; the bunny

# ---- what the wheel bundles ----------------------------------------------------------------------
common="$wheel_lib/libmeshlab-common.so"
[ -f "$common" ] || fail "$common is missing: this pymeshlab bundles no libmeshlab-common.so to link against"
symbols="$(nm -DC --defined-only "$common")"
grep -q 'Point3Value::Point3Value(vcg::Point3<double> const&)' <<<"$symbols" ||
  fail "$common is not a double-precision MeshLab (no Point3Value(vcg::Point3<double>)); MESHLAB_SCALAR=double would not fit"
abi_flags=""
# (A here-string, not a pipe: grep -q stopping early would fail the pipe under pipefail.)
if grep -q 'std::__cxx11::' <<<"$symbols"; then
  say "C++ ABI: the new (C++11) std::string ABI, g++'s default"
else
  abi_flags="-D_GLIBCXX_USE_CXX11_ABI=0"
  say "C++ ABI: the old (pre-C++11) std::string ABI: building with $abi_flags"
fi
[ -f "$wheel_lib/libQt5Core.so.5" ] || fail "$wheel_lib/libQt5Core.so.5 is missing: the wheel bundles no Qt 5"
wheel_qt="$(strings "$wheel_lib/libQt5Core.so.5" | grep -m1 -oE '^5\.[0-9]+\.[0-9]+$' || true)"
host_qt="$(pkg-config --modversion Qt5Core)"
[ "${wheel_qt%.*}" = "${host_qt%.*}" ] ||
  fail "the wheel's Qt is ${wheel_qt:-unknown}, the Qt headers here are $host_qt: the minor releases must match"
say "Qt: the wheel bundles $wheel_qt, compiling with the headers of $host_qt"

# ---- MeshLab's sources for that release ------------------------------------------------------------
source_dir="${MESHLAB_SOURCE_DIR:-${SLIM_SOURCE_CACHE:-/var/cache/support-slimming/src}/meshlab-$meshlab_version}"
if [ ! -f "$source_dir/ML_VERSION" ]; then
  [ -z "${MESHLAB_SOURCE_DIR:-}" ] || fail "MESHLAB_SOURCE_DIR=$MESHLAB_SOURCE_DIR holds no MeshLab sources (no ML_VERSION)"
  # Debian testing (forky) ships 2025.07; a private apt state reads its source index without
  # touching this machine's apt sources.
  source "$here/scripts/lib/debian-chroot.sh"  # debian_mirror
  mirror="${SLIM_DEBIAN_MIRROR:-$(debian_mirror)}" || exit 1
  say "fetching the meshlab $meshlab_version sources (Debian's source package) into $source_dir"
  apt_dir="$(mktemp -d)"
  trap 'rm -rf "$apt_dir"' EXIT
  mkdir -p "$apt_dir/lists/partial" "$apt_dir/cache/archives/partial"
  printf 'deb-src %s forky main\ndeb-src %s sid main\n' "$mirror" "$mirror" >"$apt_dir/sources.list"
  apt_opts=(-o "Dir::Etc::SourceList=$apt_dir/sources.list" -o Dir::Etc::SourceParts=/dev/null
            -o "Dir::State::Lists=$apt_dir/lists" -o "Dir::Cache=$apt_dir/cache" -o Acquire::Check-Valid-Until=false)
  apt-get "${apt_opts[@]}" update -qq >&2
  # apt-get source may fail on the .dsc while the orig tarball, all that is needed, downloads.
  (cd "$apt_dir" && apt-get "${apt_opts[@]}" source --download-only -qq "meshlab" >/dev/null 2>&1 || true)
  tarball="$(ls "$apt_dir"/meshlab_"$meshlab_version"*.orig.tar.* 2>/dev/null | head -1)"
  [ -n "$tarball" ] || fail "Debian's archive has no meshlab $meshlab_version source package; set MESHLAB_SOURCE_DIR"
  rm -rf "$source_dir.partial" && mkdir -p "$source_dir.partial"
  tar -xf "$tarball" -C "$source_dir.partial" --strip-components=1
  mv "$source_dir.partial" "$source_dir"
fi
[ "$(cat "$source_dir/ML_VERSION")" = "$meshlab_version" ] ||
  fail "$source_dir holds MeshLab $(cat "$source_dir/ML_VERSION"), pymeshlab needs $meshlab_version"

# ---- the build ----------------------------------------------------------------------------------------
# ccache, with paths taken relative to this checkout, lets a fresh checkout elsewhere (CI's)
# reuse the objects of files whose contents did not change.
if ! command -v ccache >/dev/null; then
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO=sudo
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq ccache >/dev/null
fi
export CCACHE_DIR="${SLIM_CCACHE_DIR:-$(dirname "${SLIM_SOURCE_CACHE:-/var/cache/support-slimming/src}")/ccache-pymeshlab}"
mkdir -p "$CCACHE_DIR" 2>/dev/null && [ -w "$CCACHE_DIR" ] || export CCACHE_DIR="$HOME/.cache/ccache"
export CCACHE_BASEDIR="$here"
generator=()
command -v ninja >/dev/null 2>&1 && [ ! -f "$build/Makefile" ] && generator=(-G Ninja)
cmake -S "$here" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DSLIM_BUILD_BENCH=OFF \
  -DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache \
  -DSLIM_MESHLAB_API=2022.02 -DMESHLAB_SOURCE_DIR="$source_dir" -DMESHLAB_LIBRARY_DIR="$wheel_lib" \
  -DMESHLAB_SCALAR=double -DSLIM_PYMESHLAB_PYTHON="$python_exe" -DCMAKE_CXX_FLAGS="$abi_flags" >&2
cmake --build "$build" -j 2 --target filter_support_slimming >&2
plugin="$build/filter_support_slimming/libfilter_support_slimming.so"
# Every library it needs resolves (the wheel's through its RUNPATH, the system's from /usr/lib).
if ldd "$plugin" | grep -q 'not found'; then ldd "$plugin" >&2; fail "$plugin misses libraries"; fi
echo "$plugin"
