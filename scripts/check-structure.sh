#!/usr/bin/env bash
# The house rules, checked on the tree (scripts/lib/check_structure.py says each one and why):
# includes run downwards only (the core's folders are ranked, lowest first: utilities, platform,
# geometry, print, rotation, domain, solver, support_model, optimizer, orientation; the core
# includes no Qt, VCG or MeshLab header and nothing outside itself; vcg_adapters/ includes only the
# core, mesh_io/ the core and vcg_adapters/, the CLI the core and mesh_io/, the plugin the core and
# vcg_adapters/, eval/ the core, mesh_io/ and vcg_adapters/); no function over 80 lines and no file
# over 400 in the core, the adapters, the CLI, the plugin and eval/. Prints each breach as
# path:line and exits 1 when there is one.
#
#   scripts/check-structure.sh [ROOT]      (ROOT: a checkout; default this one)
#
# The test suite runs it (ctest -R structure).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
command -v python3 >/dev/null 2>&1 || { echo "check-structure: python3 is missing (apt-get install python3)" >&2; exit 2; }
exec python3 "$here/lib/check_structure.py" "${1:-$here/..}"
