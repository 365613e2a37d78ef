#!/usr/bin/env bash
# The evaluation corpus: real models from Debian and npm packages or made by Debian tools, and
# the synthetic creatures made in code, each in its print pose (+Z up, resting on the plate) and
# scaled as the judge scales it (longest side 60 mm, slim-eval prepare). Idempotent: what is
# there already is kept. Nothing here is committed: it all goes into data/corpus/ (ignored).
#
#   eval/run.sh corpus [--build DIR] [--size MM] [--out DIR]     (DIR default: data/corpus)
#
#  1. Tools: openscad (the CAD parts are its examples, exported to STL) and assimp-utils (3DS,
#     OBJ, PLY, Collada -> STL); installed with apt-get when missing.
#  2. Each source package is fetched with `apt-get download` into data/corpus/debs/ and unpacked
#     with dpkg-deb -x into data/corpus/pkgs/<package>/ (not installed: nothing on the machine
#     changes). The npm bunny is the one scripts/setup.sh fetched (data/bunny.ply).
#  3. Each model -> data/corpus/raw/<name>.stl -> data/corpus/<name>.ply in its print pose.
#  4. data/corpus/manifest.tsv: name, kind (organic, cad, creature), faces, vertices, source
#     package and version, licence, the file in the package, the print direction used, and the
#     faces turned to agree with their neighbours (only where a model needs it).
#
# Needs a build with eval/slim-eval and tests/eval/write_shape (--build, default build/).
# Debian's libcgal-demo meshes are kept for an independent evaluation and are never used here.
set -euo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="$repo/build" size=60 corpus="$repo/data/corpus"
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build="$(cd "$2" && pwd)"; shift 2 ;;
    --out) mkdir -p "$2"; corpus="$(cd "$2" && pwd)"; shift 2 ;;
    --size) size="$2"; shift 2 ;;
    -h|--help) sed -n 2,20p "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "corpus: unknown argument $1" >&2; exit 1 ;;
  esac
done
die() { echo "corpus: $*" >&2; exit 1; }
eval_tool="$build/eval/slim-eval"; write_shape="$build/tests/eval/write_shape"
[ -x "$eval_tool" ] && [ -x "$write_shape" ] || die "build the targets slim-eval and write_shape first (scripts/build.sh)"
mkdir -p "$corpus"/{debs,pkgs,raw}

SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
need=()
command -v openscad >/dev/null 2>&1 || need+=(openscad)
command -v assimp >/dev/null 2>&1 || need+=(assimp-utils)
if [ "${#need[@]}" -gt 0 ]; then
  echo "[corpus] installing ${need[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
fi

# name | kind | package | file in the package | print direction in the file's frame | licence
# [| mend: "orient-faces" turns the few faces that disagree with their neighbours and leaves out
#   faces that name one vertex twice (slim-eval prepare --orient-faces yes); the judge, like the
#   CLI, refuses such a mesh]
MODELS=(
  "bunny|organic|npm:bunny|(data/bunny.ply, turned +Z up by setup)|0,0,1|public domain (Stanford 3D Scanning Repository)"
  "bunny_70k|organic|glmark2-data|usr/share/glmark2/models/bunny.obj|0,1,0|GPL-3+"
  "horse|organic|glmark2-data|usr/share/glmark2/models/horse.3ds|0,0,-1|GPL-3+|orient-faces"
  "knight|organic|brutalchess|usr/share/games/brutalchess/models/knight.obj|0,1,0|GPL-2+"
  "suzanne|organic|python-kivy-examples|usr/share/kivy-examples/3Drendering/monkey.obj|0,1,0|Expat"
  "wuson|organic|assimp-testmodels|usr/share/assimp/models/PLY/Wuson.ply|0,1,0|BSD-3-clause"
  "duck|organic|assimp-testmodels|usr/share/assimp/models/Collada/duck.dae|0,1,0|BSD-3-clause"
  "spider|organic|assimp-testmodels|usr/share/assimp/models/OBJ/spider.obj|0,1,0|BSD-3-clause|orient-faces"
  "scad_example001|cad|openscad|usr/share/openscad/examples/Old/example001.scad|0,0,1|GPL-2+ (OpenSCAD examples)"
  "scad_example004|cad|openscad|usr/share/openscad/examples/Old/example004.scad|0,0,1|GPL-2+ (OpenSCAD examples)"
  "scad_example017|cad|openscad|usr/share/openscad/examples/Old/example017.scad|0,0,1|GPL-2+ (OpenSCAD examples)"
  "netgen_hinge|cad|netgen-doc|usr/share/doc/netgen/examples/hinge.stl|0,0,1|LGPL-2+"
)

# package_dir PACKAGE: the unpacked package (fetched and unpacked once).
package_dir() {
  local p="$1" dir="$corpus/pkgs/$1"
  if [ ! -f "$dir/.unpacked" ]; then
    if ! ls "$corpus/debs/${p}"_*.deb >/dev/null 2>&1; then
      echo "[corpus] apt-get download $p" >&2
      chmod 755 "$corpus/debs"
      (cd "$corpus/debs" && apt-get download -qq "$p" >/dev/null 2>&1) ||
        { $SUDO apt-get update -qq; (cd "$corpus/debs" && apt-get download -qq "$p" >/dev/null) || die "apt-get download $p failed"; }
    fi
    rm -rf "$dir"; mkdir -p "$dir"
    dpkg-deb -x "$(ls "$corpus/debs/${p}"_*.deb | head -1)" "$dir"
    touch "$dir/.unpacked"
  fi
  echo "$dir"
}
package_version() {
  case "$1" in
    npm:bunny) echo "1.0.1" ;;
    openscad) dpkg-query -W -f='${Version}' openscad ;;
    *) basename "$(ls "$corpus/debs/$1"_*.deb | head -1)" | cut -d_ -f2 ;;
  esac
}

# to_stl NAME PACKAGE FILE: the model as it comes, as STL in data/corpus/raw/.
to_stl() {
  local name="$1" pkg="$2" file="$3" raw="$corpus/raw/$1.stl"
  [ -s "$raw" ] && return 0
  case "$pkg" in
    npm:bunny) [ -f "$repo/data/bunny.ply" ] || die "data/bunny.ply is missing: run scripts/setup.sh"
               cp "$repo/data/bunny.ply" "$corpus/raw/$name.ply"; raw="$corpus/raw/$name.ply" ;;
    openscad) echo "[corpus] openscad -o $name.stl $(basename "$file")" >&2
              openscad -o "$raw.tmp.stl" "/$file" >/dev/null 2>"$corpus/raw/$name.log" || die "openscad failed on $file"
              mv "$raw.tmp.stl" "$raw" ;;
    *) local src; src="$(package_dir "$pkg")/$file"
       [ -f "$src" ] || die "$pkg has no $file"
       case "$src" in
         *.stl) cp "$src" "$raw" ;;
         *) assimp export "$src" "$raw.tmp.stl" >"$corpus/raw/$name.log" 2>&1 || die "assimp could not convert $file"
            mv "$raw.tmp.stl" "$raw" ;;
       esac ;;
  esac
}
raw_file() { if [ -f "$corpus/raw/$1.ply" ]; then echo "$corpus/raw/$1.ply"; else echo "$corpus/raw/$1.stl"; fi; }

manifest="$corpus/manifest.tsv"
printf 'name\tkind\tfaces\tvertices\tsource\tversion\tlicence\tfile\tprint_direction\tflipped_faces\n' >"$manifest.tmp"
for entry in "${MODELS[@]}"; do
  IFS='|' read -r name kind pkg file dir licence mend <<<"$entry"
  to_stl "$name" "$pkg" "$file"
  if [ ! -s "$corpus/$name.ply" ] || [ ! -s "$corpus/$name.prepare.txt" ]; then
    orient=no; [ "$mend" != orient-faces ] || orient=yes
    "$eval_tool" prepare "$(raw_file "$name")" "$corpus/$name" --size "$size" --dir "$dir" --orient-faces "$orient" \
      >"$corpus/$name.prepare.txt" ||
      die "slim-eval prepare failed on $name"
  fi
  faces="$(awk -F= '$1 == "faces" { print $2 }' "$corpus/$name.prepare.txt")"
  verts="$(awk -F= '$1 == "vertices" { print $2 }' "$corpus/$name.prepare.txt")"
  flipped="$(awk -F= '$1 == "flipped_faces" { print $2 }' "$corpus/$name.prepare.txt")"
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$kind" "$faces" "$verts" "$pkg" "$(package_version "$pkg")" \
    "$licence" "$file" "$dir" "${flipped:-0}" >>"$manifest.tmp"
done
for name in quadruped long_neck upright; do
  if [ ! -s "$corpus/creature_$name.ply" ]; then
    "$write_shape" "$name" "$corpus/raw/creature_$name.ply" || die "write_shape $name failed"
    "$eval_tool" prepare "$corpus/raw/creature_$name.ply" "$corpus/creature_$name" --size "$size" \
      >"$corpus/creature_$name.prepare.txt" || die "slim-eval prepare failed on creature_$name"
  fi
  faces="$(awk -F= '$1 == "faces" { print $2 }' "$corpus/creature_$name.prepare.txt")"
  verts="$(awk -F= '$1 == "vertices" { print $2 }' "$corpus/creature_$name.prepare.txt")"
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "creature_$name" creature "$faces" "$verts" "support-slimming" "-" \
    "GPL-3.0-or-later" "tests/support/creatures.cpp" "0,0,1" 0 >>"$manifest.tmp"
done
mv "$manifest.tmp" "$manifest"
echo "[corpus] $(($(wc -l <"$manifest") - 1)) models in $corpus (manifest.tsv)"
