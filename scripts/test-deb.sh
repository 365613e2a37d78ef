#!/usr/bin/env bash
# The Debian 12 package, tested as a user gets it:
#   1. scripts/package-deb.sh makes the .deb from build/ (for MeshLab 2020.09);
#   2. a bookworm root from debootstrap with Debian's meshlab, xvfb and lintian, cached in
#      $SLIM_BOOKWORM_ROOT; each run works on a throwaway overlay of it, so the root stays clean;
#   3. there: lintian (no errors; scripts/lib/check-deb.sh checks the files and dependencies too),
#      apt-get install of the .deb (with support-slim's man page), the real meshlabserver running the three installed
#      examples/*.mlx on the bunny with the plugin from the system plugins folder, support-slim
#      from /usr/bin, and dpkg -r, after which none of the package's files may be left.
# Every stage prints how long it took; any failure exits non-zero. Needs root.
#
# Usage: scripts/test-deb.sh [DEB]        (default: make it with scripts/package-deb.sh)
#        scripts/test-deb.sh --prepare-only    make the root and install its packages, then stop
# Environment:
#   SLIM_BOOKWORM_ROOT   the chroot (default /var/cache/support-slimming/bookworm; ~0.9 GB)
#   SLIM_DEBIAN_MIRROR   default: the Debian mirror this machine's apt uses
set -euo pipefail
if [ "$(id -u)" -ne 0 ]; then exec sudo --preserve-env=SLIM_BOOKWORM_ROOT,SLIM_DEBIAN_MIRROR "$0" "$@"; fi
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$here/scripts/lib/debian-chroot.sh"
chroot_tag=deb
root="${SLIM_BOOKWORM_ROOT:-/var/cache/support-slimming/bookworm}"
if [ "${1:-}" = "--prepare-only" ]; then
  chroot_setup deb bookworm "$root"
  chroot_install meshlab xvfb xauth lintian
  exit 0
fi

stage "making the package (scripts/package-deb.sh)"
deb="${1:-$("$here/scripts/package-deb.sh" | tail -n 1)}"
echo "[deb] $deb"
stage_done

chroot_setup deb bookworm "$root"
chroot_install meshlab xvfb xauth lintian
chroot_overlay
cp "$deb" "$chroot_root/tmp/"
pkg="/tmp/$(basename "$deb")"

stage "lintian and the package's files and dependencies"
deb_checks "$pkg"
stage_done

stage "apt-get install $(basename "$deb")"
in_root "apt-get update -qq && apt-get install -y -qq --no-install-recommends $pkg >/dev/null
         dpkg -L meshlab-support-slimming >/tmp/installed-files
         [ -f /usr/lib/x86_64-linux-gnu/meshlab/plugins/libfilter_support_slimming.so ] || { echo 'no plugin in the system plugins folder' >&2; exit 1; }
         man=/usr/share/man/man1/support-slim.1.gz
         [ -f \$man ] || { echo \"no man page: \$man\" >&2; exit 1; }
         # help2man writes each option in roff, its hyphens escaped: \\-\\-max\\-deviation.
         zcat \$man | sed 's/\\\\-/-/g' | grep -q -- '--max-deviation' ||
           { zcat \$man >&2; echo \"the man page does not list support-slim's options\" >&2; exit 1; }
         echo \"[deb] man page: \$man, \$(zcat \$man | grep -c '^\\.TP') options\""
stage_done

stage "meshlabserver runs the installed examples with the system plugin; support-slim runs"
# The real /usr/bin/meshlabserver reads only /usr/lib/x86_64-linux-gnu/meshlab/plugins. Each
# example must succeed and its filter's result line must be in the log.
in_root "export HOME=/tmp/home && mkdir -p \$HOME && cd /tmp
         examples=/usr/share/doc/meshlab-support-slimming/examples
         run() {  # SCRIPT FILTER
           /src/scripts/with-xvfb.sh meshlabserver -i /src/data/bunny.ply -o /tmp/\$1.ply -m fq fc vq -l /tmp/\$1.log \\
             -s \$examples/\$1.mlx >/tmp/\$1.out 2>&1 || { cat /tmp/\$1.out /tmp/\$1.log >&2; echo \"meshlabserver failed on \$1.mlx\" >&2; exit 1; }
           grep -q \"\$2: .*risky\" /tmp/\$1.log || { cat /tmp/\$1.log >&2; echo \"\$1.mlx: no '\$2' result in the log\" >&2; exit 1; }
           [ -s /tmp/\$1.ply ] || { echo \"\$1.mlx wrote no mesh\" >&2; exit 1; }
           echo \"[deb] \$1.mlx: \$(grep -m1 \"\$2: .*risky\" /tmp/\$1.log | cut -c1-150)\"
         }
         run overhang_analysis 'Overhang Analysis'
         run support_slimming 'Support Slimming'
         run print_orientation 'Print Orientation'
         OPENBLAS_NUM_THREADS=1 support-slim /src/data/bunny.ply -o /tmp/cli.ply --iterations 2 >/tmp/cli.out 2>&1 ||
           { cat /tmp/cli.out >&2; echo 'support-slim failed' >&2; exit 1; }
         echo \"[deb] support-slim: ok\""
stage_done

stage "dpkg -r meshlab-support-slimming removes every file"
in_root "dpkg -r meshlab-support-slimming >/dev/null
         status=\$(dpkg-query -W -f='\${Status}' meshlab-support-slimming 2>/dev/null || true)
         case \"\$status\" in ''|*not-installed*) ;; *) echo \"still registered after dpkg -r: \$status\" >&2; exit 1 ;; esac
         left=0
         while read -r f; do
           # Files must be gone; so must folders, unless another package owns them (/usr/bin).
           if [ -L \"\$f\" ] || [ -f \"\$f\" ]; then echo \"left behind: \$f\" >&2; left=1
           elif [ -d \"\$f\" ] && ! dpkg -S \"\$f\" >/dev/null 2>&1; then echo \"left behind: \$f/\" >&2; left=1
           fi
         done </tmp/installed-files
         [ \"\$left\" = 0 ]
         echo \"[deb] \$(grep -c . /tmp/installed-files) paths installed, none of its own left\""
stage_done
echo "PASS: $(basename "$deb") installs, runs and removes cleanly on Debian 12"
