#!/usr/bin/env bash
# Checks a package made by scripts/package-deb.sh, on the Debian it was made for (run inside the
# chroot, or on the machine itself): the plugin in the installed meshlab's plugins folder,
# support-slim in /usr/bin with its man page, the README with its docs/ pages, copyright,
# changelog and .mlx examples in /usr/share/doc/meshlab-support-slimming; a dependency on exactly
# the installed meshlab and on CHOLMOD, TetGen and OpenBLAS; and no lintian errors (its warnings
# are shown, not fatal).
# Usage: check-deb.sh DEB
set -euo pipefail
deb="$1"
fail() { echo "check-deb: $deb: $*" >&2; exit 1; }
doc=./usr/share/doc/meshlab-support-slimming
files="$(dpkg-deb -c "$deb" | awk '{print $6}')"
for f in ./usr/lib/x86_64-linux-gnu/meshlab/plugins/libfilter_support_slimming.so ./usr/bin/support-slim \
         ./usr/share/man/man1/support-slim.1.gz \
         "$doc/README.md" "$doc/docs/usage.md" "$doc/copyright" "$doc/changelog.Debian.gz" "$doc/examples/support_slimming.mlx" \
         "$doc/examples/overhang_analysis.mlx" "$doc/examples/print_orientation.mlx"; do
  grep -qxF "$f" <<<"$files" || fail "$f is missing"
done
meshlab="$(dpkg-query -W -f='${Version}' meshlab)"
depends="$(dpkg-deb -f "$deb" Depends)"
echo "check-deb: Depends: $depends"
grep -qF "meshlab (= $meshlab)" <<<"$depends" || fail "it does not depend on the installed meshlab (= $meshlab)"
for lib in libcholmod libtet libopenblas0; do
  grep -q "$lib" <<<"$depends" || fail "it does not depend on $lib"
done
command -v lintian >/dev/null || fail "lintian is not installed"
lintian --fail-on error --tag-display-limit 0 "$deb" || fail "lintian reports errors (E: above)"
echo "check-deb: $(basename "$deb"): files, dependencies and lintian ok"
