#!/usr/bin/env bash
# Idempotent setup for a fresh Debian bookworm machine (root or sudo).
#  1. Debian packages for building, testing and running the plugin (and for the corpus's
#     conversions, eval/run.sh corpus, which a test builds: OpenSCAD and assimp).
#  2. MeshLab 2020.09 sources (headers + vcglib) from Debian's source package -> third_party/ (ignored).
#  3. The sample bunny from the npm package `bunny`, turned +Z up -> data/bunny.ply (ignored).
#  4. CuraEngine's printer definitions (fdmprinter/fdmextruder.def.json) from Debian's `cura`
#     package, unpacked (not installed) -> /var/cache/support-slimming/cura/definitions.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive

PACKAGES=(
  build-essential cmake pkg-config ninja-build dpkg-dev ccache python3 help2man
  qtbase5-dev libqt5opengl5-dev libglew-dev libeigen3-dev
  libgtest-dev libgmock-dev googletest libbenchmark-dev
  libsuitesparse-dev libopenblas0-pthread
  libtet1.5-dev lib3mf-dev libzip-dev
  meshlab xvfb xauth
  prusa-slicer cura-engine f3d imagemagick xdotool
  openscad assimp-utils
  clang libclang-rt-14-dev libomp-14-dev
)
# Node.js only for fetching the npm sample data; keep whatever node the machine already has.
command -v npm >/dev/null 2>&1 || PACKAGES+=(nodejs npm)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
  echo "[setup] installing: ${missing[*]}"
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# --- MeshLab sources (headers and vcglib are not packaged as -dev) ---------------------------
ML_DIR="$here/third_party/meshlab"
if [ ! -f "$ML_DIR/src/common/interfaces.h" ]; then
  if ! grep -rqs "deb-src" /etc/apt/sources.list /etc/apt/sources.list.d/ ; then
    echo "[setup] adding a deb-src entry"
    src_list=/etc/apt/sources.list.d/support-slimming-src.sources
    if [ -f /etc/apt/sources.list.d/debian.sources ]; then
      # deb822: copy the deb stanzas, turning them into deb-src
      sed 's/^Types: deb$/Types: deb-src/' /etc/apt/sources.list.d/debian.sources | $SUDO tee "$src_list" >/dev/null
    else
      grep -E '^deb ' /etc/apt/sources.list | sed 's/^deb /deb-src /' | $SUDO tee /etc/apt/sources.list.d/support-slimming-src.list >/dev/null
    fi
  fi
  $SUDO apt-get update -qq
  tmp="$(mktemp -d)"
  (cd "$tmp" && apt-get source -qq meshlab >/dev/null 2>&1)
  srcdir="$(find "$tmp" -maxdepth 1 -type d -name 'meshlab-*' | head -1)"
  [ -n "$srcdir" ] || { echo "[setup] apt-get source meshlab failed" >&2; exit 1; }
  mkdir -p "$here/third_party"
  rm -rf "$ML_DIR"
  mv "$srcdir" "$ML_DIR"
  rm -rf "$tmp"
  echo "[setup] MeshLab sources in $ML_DIR"
fi

# --- Sample data: the Stanford bunny from npm, +Y up -> +Z up --------------------------------
DATA="$here/data"
mkdir -p "$DATA"
if [ ! -f "$DATA/bunny.ply" ]; then
  if [ ! -f "$DATA/npm/node_modules/bunny/index.js" ]; then
    mkdir -p "$DATA/npm"
    (cd "$DATA/npm" && npm install --silent --no-audit --no-fund --prefix . bunny@1 >/dev/null)
  fi
  node "$here/scripts/bunny_to_ply.js" "$DATA/npm/node_modules/bunny" "$DATA/bunny.ply"
  echo "[setup] sample mesh: $DATA/bunny.ply"
fi
# --- CuraEngine's definitions: only in the `cura` front end's package, which is not installed --
CURA_DEFS=/var/cache/support-slimming/cura/definitions
if [ ! -f "$CURA_DEFS/fdmprinter.def.json" ] || [ ! -f "$CURA_DEFS/fdmextruder.def.json" ]; then
  tmp="$(mktemp -d)"
  chmod 755 "$tmp"  # apt's download user must be able to write there
  (cd "$tmp" && apt-get download -qq cura >/dev/null 2>&1) || { $SUDO apt-get update -qq; (cd "$tmp" && apt-get download -qq cura >/dev/null); }
  dpkg-deb -x "$tmp"/cura_*.deb "$tmp/x"
  $SUDO mkdir -p "$CURA_DEFS"
  $SUDO cp "$tmp/x/usr/share/cura/resources/definitions/fdmprinter.def.json" \
           "$tmp/x/usr/share/cura/resources/definitions/fdmextruder.def.json" "$CURA_DEFS/"
  rm -rf "$tmp"
  echo "[setup] Cura definitions in $CURA_DEFS"
fi
echo "[setup] ok"
