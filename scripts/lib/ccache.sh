# Sourced by the scripts that build on this machine (build.sh, sanitize.sh, fuzz.sh): compiles
# through ccache when it is installed (scripts/setup.sh installs it). Sets `ccache_launcher` to
# the CMake arguments that use it, or to nothing without ccache.
# The cache sits next to the chroots and the venv in /var/cache/support-slimming (or in
# ~/.cache/ccache when that is not writable). Paths are taken relative to the checkout and the
# working directory is left out of the hash, so a fresh clone anywhere (CI's) compiles only the
# files whose contents changed; the tests keep the checkout's paths out of their objects for this
# (tests/support/source_paths.h).
ccache_launcher=()
if command -v ccache >/dev/null 2>&1; then
  export CCACHE_DIR="${CCACHE_DIR:-/var/cache/support-slimming/ccache}"
  mkdir -p "$CCACHE_DIR" 2>/dev/null && [ -w "$CCACHE_DIR" ] || export CCACHE_DIR="${HOME:-/tmp}/.cache/ccache"
  export CCACHE_BASEDIR="$here" CCACHE_NOHASHDIR=true CCACHE_MAXSIZE="${CCACHE_MAXSIZE:-8G}"
  ccache_launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
