# Debian chroots for the checks against other Debian releases (scripts/test-meshlab2022.sh,
# scripts/test-meshlab2025.sh, scripts/test-deb.sh). Sourced, not run. Needs root.
#
#   chroot_setup TAG SUITE ROOT   names the chroot (TAG prefixes every message), takes its lock,
#                                 makes it with debootstrap when it is missing (cached after),
#                                 and mounts /proc, /sys, /dev and this checkout read-only at /src;
#                                 everything is unmounted again when the script exits
#   in_root 'CMD'                 runs CMD with bash -euo pipefail inside the root, clean environment
#   chroot_install PKG...         installs the packages that are not installed yet
#   chroot_meshlab_sources DIR    MeshLab's upstream sources (the orig tarball of the suite's meshlab
#                                 source package) in DIR inside the root, checked against the
#                                 installed meshlab's version
#   chroot_overlay                switches to a throwaway copy of the root (overlayfs): what is
#                                 installed from then on is gone when the script exits, and the
#                                 cached root stays as it was
#   deb_checks DEB                checks a .deb inside the root: its files and dependencies, lintian
#   stage TEXT / stage_done       a timed step: "=== [TAG] TEXT" ... "=== [TAG] done in N s"
#   meshlab_chroot_check ...      the whole MeshLab check of test-meshlab2022.sh and
#                                 test-meshlab2025.sh (below)
#
# The root is made in ROOT.partial and renamed when complete, so an interrupted run never leaves
# a root that looks usable. SLIM_DEBIAN_MIRROR overrides the mirror (default: the one this
# machine's apt uses for Debian itself; debian_mirror below, which fails when there is none).

chroot_tag=chroot
chroot_root=""
chroot_scratch=""  # the overlay's upper and work folders (chroot_overlay)
chroot_src="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"  # this checkout, mounted at /src

stage_start=0
stage() { stage_start=$SECONDS; echo "=== [$chroot_tag] $*"; }
stage_done() { echo "=== [$chroot_tag] done in $((SECONDS - stage_start)) s"; }

# The mirror this machine's apt uses for Debian itself (not -security, not third-party repos):
# the first http(s) URI ending in /debian of a binary source ("deb") in the apt sources, one-line
# (sources.list, *.list) or deb822 (*.sources, stanzas with Enabled: no skipped). Reads FILE...
# when given, else this machine's. With none, says so in one line on stderr and returns 1.
debian_mirror() {
  local files=("$@") f uri
  [ $# -gt 0 ] || files=(/etc/apt/sources.list /etc/apt/sources.list.d/*.list /etc/apt/sources.list.d/*.sources)
  uri="$(for f in "${files[@]}"; do
           [ -f "$f" ] && [ -r "$f" ] || continue
           case "$f" in
             *.sources) awk "$(debian_mirror_deb822_awk)" "$f" ;;
             *) awk '$1 == "deb" { sub(/#.*/, ""); gsub(/\[[^]]*\]/, ""); print $2 }' "$f" ;;
           esac
         done | grep -E '^https?://[^[:space:]]+/debian/?$' | head -1 || true)"
  if [ -z "$uri" ]; then
    echo "no Debian archive (a deb source at http(s)://.../debian) in the apt sources ${files[*]}; set SLIM_DEBIAN_MIRROR" >&2
    return 1
  fi
  echo "$uri"
}
# The awk program that prints the URIs of the enabled "deb" stanzas of a deb822 .sources file.
debian_mirror_deb822_awk() {
  cat <<'AWK'
function flush() {
  if (types ~ /(^| )deb( |$)/ && enabled != "no") { n = split(uris, u, " "); for (i = 1; i <= n; i++) print u[i] }
  types = ""; uris = ""; enabled = ""; field = ""
}
/^[ \t]*#/ { next }
/^[ \t]*$/ { flush(); next }
/^[ \t]/ { v = $0; gsub(/[ \t]+/, " ", v); if (field == "types") types = types v; else if (field == "uris") uris = uris v; next }
{
  field = tolower(substr($0, 1, index($0, ":") - 1)); value = substr($0, index($0, ":") + 1)
  gsub(/[ \t]+/, " ", value); sub(/^ /, "", value); sub(/ $/, "", value)
  if (field == "types") types = value; else if (field == "uris") uris = value; else if (field == "enabled") enabled = tolower(value)
}
END { flush() }
AWK
}

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
    [ "$(readlink "$p/root" 2>/dev/null)" = "$chroot_root" ] && kill -9 "${p#/proc/}" 2>/dev/null || true
  done
}

chroot_cleanup() {
  [ -n "$chroot_root" ] || return 0
  stop_chroot_processes
  unmount_below "$chroot_root"
  if [ -n "$chroot_scratch" ]; then rm -rf --one-file-system "$chroot_scratch"; fi
}

# debootstrap SUITE into ROOT.partial, then rename it to ROOT.
chroot_bootstrap() {
  local suite="$1" root="$2" mirror script=""
  mirror="${SLIM_DEBIAN_MIRROR:-$(debian_mirror)}" || return 1
  stage "debootstrap $suite from $mirror into $root"
  command -v debootstrap >/dev/null || apt-get install -y -qq debootstrap >/dev/null
  # An older debootstrap has no script for a newer testing release; sid's fits every one of them.
  [ -e "/usr/share/debootstrap/scripts/$suite" ] || script=/usr/share/debootstrap/scripts/sid
  unmount_below "$root.partial"
  rm -rf --one-file-system "$root.partial"
  debootstrap --variant=minbase "$suite" "$root.partial" "$mirror" $script >"$root.debootstrap.log" 2>&1 ||
    { tail -20 "$root.debootstrap.log" >&2; return 1; }
  printf 'deb %s %s main\ndeb-src %s %s main\n' "$mirror" "$suite" "$mirror" "$suite" >"$root.partial/etc/apt/sources.list"
  # No daemons start inside the chroot.
  printf '#!/bin/sh\nexit 101\n' >"$root.partial/usr/sbin/policy-rc.d"
  chmod +x "$root.partial/usr/sbin/policy-rc.d"
  touch "$root.partial/.slim-bootstrapped"
  mv "$root.partial" "$root"
  stage_done
}

# Mounts what a build and an X server need, and the checkout read-only at /src.
chroot_mount() {
  local root="$1"
  mount -t proc proc "$root/proc"
  mount -t sysfs sysfs "$root/sys"
  mount --rbind /dev "$root/dev"
  mount --make-rslave "$root/dev"  # unmounting our copy must never reach the host's /dev
  mkdir -p "$root/src"
  mount --bind "$chroot_src" "$root/src"
  mount -o remount,bind,ro "$root/src"
  # A checkout whose data/ or third_party/ is a symlink (a git worktree sharing them) gets the
  # target mounted at the same path, so the link resolves inside the root too.
  local link target
  for link in data third_party; do
    [ -L "$chroot_src/$link" ] || continue
    target="$(readlink -f "$chroot_src/$link")"
    [ -d "$target" ] || continue
    mkdir -p "$root$target"
    mount --bind "$target" "$root$target"
    mount -o remount,bind,ro "$root$target"
  done
  cp -L /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null || true
}

chroot_setup() {
  chroot_tag="$1"
  local suite="$2" root="$3"
  mkdir -p "$(dirname "$root")"
  exec 9>"$root.lock"
  # One user of a root at a time; another run (a second checkout's CI) is waited for.
  if ! flock -n 9; then
    echo "[$chroot_tag] waiting for the other script that uses $root (at most 15 min)" >&2
    flock -w 900 9 || { echo "another script still uses $root" >&2; return 1; }
  fi
  if [ ! -e "$root/.slim-bootstrapped" ]; then
    [ -e "$root" ] && { echo "$root exists but was not made by these scripts; remove it or choose another root" >&2; return 1; }
    chroot_bootstrap "$suite" "$root" || return 1
  fi
  # Testing's Release files carry a Valid-Until date that a mirror snapshot outlives; its
  # signatures are still checked.
  printf 'Acquire::Check-Valid-Until "false";\n' >"$root/etc/apt/apt.conf.d/99slim-snapshot"
  chroot_root="$root"
  trap chroot_cleanup EXIT
  trap 'exit 143' INT TERM
  chroot_mount "$root"
}

chroot_overlay() {
  local base="$chroot_root"
  stop_chroot_processes
  unmount_below "$base"
  chroot_scratch="$(mktemp -d /var/tmp/slim-overlay.XXXXXX)"
  mkdir -p "$chroot_scratch/upper" "$chroot_scratch/work" "$chroot_scratch/root"
  mount -t overlay overlay -o "lowerdir=$base,upperdir=$chroot_scratch/upper,workdir=$chroot_scratch/work" \
    "$chroot_scratch/root"
  chroot_root="$chroot_scratch/root"
  chroot_mount "$chroot_root"
}

in_root() {
  chroot "$chroot_root" env -i HOME=/root PATH=/usr/local/bin:/usr/bin:/bin:/usr/local/sbin:/usr/sbin:/sbin \
    LANG=C.UTF-8 DEBIAN_FRONTEND=noninteractive OPENBLAS_NUM_THREADS=1 bash -euo pipefail -c "$1"
}

chroot_install() {
  local installed
  installed="$(in_root "dpkg-query -W -f='\${Package} \${Status}\n' $* 2>/dev/null | grep -c 'install ok installed' || true")"
  [ "$installed" -eq "$#" ] && return 0
  stage "installing $*"
  in_root "apt-get update -qq && apt-get install -y -qq --no-install-recommends $* >/dev/null && apt-get clean"
  stage_done
}

chroot_meshlab_sources() {
  local dir="$1"
  if [ ! -e "$chroot_root$dir/ML_VERSION" ]; then
    stage "MeshLab sources (orig tarball of Debian's meshlab source package) -> $dir"
    # apt-get source may fail on the .dsc while the orig tarball, all that is needed, downloads.
    in_root "mkdir -p /var/cache/slim-src && cd /var/cache/slim-src && rm -f meshlab_*
             apt-get update -qq && (apt-get source --download-only -qq meshlab >/dev/null 2>&1 || true)
             tarball=\$(ls meshlab_*.orig.tar.* | head -1)
             [ -n \"\$tarball\" ] || { echo 'the meshlab orig tarball did not download' >&2; exit 1; }
             rm -rf $dir.partial && mkdir -p $dir.partial
             tar -xf \"\$tarball\" -C $dir.partial --strip-components=1
             mv $dir.partial $dir"
    stage_done
  fi
  # The headers must be those of the installed meshlab: MeshLab refuses a plugin of another version.
  # Debian's version is upstream's plus +dfsg1 (2022.02) or ~dfsg (2025.07) and the revision.
  in_root "installed=\$(dpkg-query -W -f='\${Version}' meshlab); source=\$(cat $dir/ML_VERSION)
           upstream=\${installed%%[+~]*}
           [ \"\$upstream\" = \"\$source\" ] || { echo \"meshlab \$installed installed, sources are \$source\" >&2; exit 1; }
           echo \"[$chroot_tag] meshlab \$installed, sources $dir (\$source)\""
}

# A package made by scripts/package-deb.sh, at DEB inside the root: the plugin in the installed
# meshlab's plugins folder, support-slim in /usr/bin, the docs, a dependency on exactly the
# installed meshlab, and no lintian errors (warnings are shown, not fatal).
deb_checks() { in_root "/src/scripts/lib/check-deb.sh '$1'"; }

# The check of a MeshLab of the FilterPlugin API in its Debian release, shared by
# scripts/test-meshlab2022.sh and scripts/test-meshlab2025.sh:
#   meshlab_chroot_check TAG SUITE ROOT_VARIABLE DEFAULT_ROOT [--clean | --prepare-only]
# installs the global array PACKAGES (meshlab among them) in the SUITE root (${!ROOT_VARIABLE},
# else DEFAULT_ROOT), fetches the installed meshlab's sources into /opt/meshlab-VERSION, builds
# this checkout (read-only at /src) for the 2022.02 API in /var/tmp/slim-build-TAG (kept, so
# re-runs build incrementally; --clean starts afresh), runs ctest -L meshlabYYYY there (the
# plugin harness and the GUI smoke check), and makes and checks that release's .deb. With
# --prepare-only it stops once the root, its packages and the sources are ready (.ci/run does that
# in the background while the main suite runs). Re-runs itself through sudo when not root.
meshlab_chroot_check() {
  local tag="$1" suite="$2" root_variable="$3" default_root="$4" clean=0 prepare_only=0
  shift 4
  if [ "$(id -u)" -ne 0 ]; then exec sudo --preserve-env="$root_variable,SLIM_DEBIAN_MIRROR" "$0" "$@"; fi
  case "${1:-}" in
    --clean) clean=1 ;;
    --prepare-only) prepare_only=1 ;;
    "") ;;
    *) echo "unknown option: $1 (expected --clean or --prepare-only)" >&2; return 2 ;;
  esac
  local root="${!root_variable:-$default_root}"
  local build="/var/tmp/slim-build-$tag" version label
  chroot_setup "$tag" "$suite" "$root"
  chroot_install "${PACKAGES[@]}"
  version="$(in_root "dpkg-query -W -f='\${Version}' meshlab")"
  version="${version%%[+~]*}"
  label="meshlab${version:0:4}"
  chroot_meshlab_sources "/opt/meshlab-$version"
  [ "$prepare_only" = 0 ] || return 0

  [ -f "$chroot_src/data/bunny.ply" ] || "$chroot_src/scripts/setup.sh"
  stage "building the plugin and its tests for MeshLab $version"
  # The build is kept for re-runs of the same checkout only: ninja goes by file times, and another
  # checkout mounted at the same /src (an older commit cloned earlier) would look up to date.
  local stamp want
  stamp="$root$build/.slim-source" want="$(cd "$chroot_src" && { pwd; git rev-parse HEAD 2>/dev/null; git diff HEAD 2>/dev/null; } | sha1sum)"
  if [ "$clean" = 1 ] || [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then rm -rf --one-file-system "$root$build"; fi
  # ccache (its cache in the root's /root/.cache) makes the rebuild of a fresh checkout, all of
  # whose files are new to ninja, cost only the files whose contents changed.
  in_root "cmake -S /src -B $build -G Ninja -DCMAKE_BUILD_TYPE=Release -DSLIM_MESHLAB_API=2022.02 \
             -DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache \
             -DMESHLAB_SOURCE_DIR=/opt/meshlab-$version -DSLIM_DATA_DIR=/src/data -DSLIM_BUILD_BENCH=OFF \
             -DSLIM_CHECK_STRUCTURE=OFF >/dev/null
           cmake --build $build -j 2 --target slim_filterplugin_tests"
  echo "$want" >"$stamp"
  stage_done

  stage "ctest -L $label"
  in_root "cd $build && ctest -L $label --output-on-failure"
  stage_done

  # The same package command as on Debian 12, for this release's meshlab.
  stage "the Debian package for MeshLab $version (scripts/package-deb.sh)"
  local deb
  deb="$(in_root "/src/scripts/package-deb.sh $build" | tail -n 1)"
  deb_checks "$deb"
  echo "[$tag] package: $root$deb"
  stage_done
}
