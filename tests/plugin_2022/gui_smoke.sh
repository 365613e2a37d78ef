#!/usr/bin/env bash
# GUI smoke check for MeshLab 2022.02 and later (2025.07 too): the real meshlab, on a private
# Xvfb, with our plugin in the per-user extra-plugins folder
# $XDG_DATA_HOME/VCG/MeshLab_64bit_fp/MeshLabExtraPlugins/VERSION/,
# opening the sample bunny. It passes when, SLIM_GUI_SECONDS (default 10) seconds after its first
# window appears:
#   - meshlab is still running,
#   - its main window is up and no dialog is: MeshLab reports a plugin it refuses (another
#     version or precision, a missing library, a bad filter class) in a blocking dialog, "Error
#     while loading plugins.", and then loads no extra plugin at all,
#   - our plugin is mapped into the process,
#   - Overhang Analysis, Support Slimming and Print Orientation, found through MeshLab's filter search (Ctrl+F) and
#     applied with their dialogs' defaults, write their results to the log.
# A control run with a broken plugin next to ours must show that dialog, so a check that can no
# longer see dialogs fails instead of passing. Logs go to OUT_DIR.
# Usage: gui_smoke.sh PLUGIN.so MESHLAB_VERSION OUT_DIR MESH
set -euo pipefail

if [ "${1:-}" = "--inside-xvfb" ]; then
  # ---- runs on the private Xvfb: start meshlab, wait, look, and (with --run-filters) use it -------
  plugin="$2" out="$3" mesh="$4" name="$5" run_filters="${6:-}"
  log="$out/$name.meshlab.log"  # MeshLab 2022.02 and later echo the log window to stderr: "LOG: n ..."
  report="$out/$name.report"
  : >"$report"
  meshlab "$mesh" >"$log" 2>&1 &
  pid=$!
  trap 'kill "$pid" 2>/dev/null || true; wait "$pid" 2>/dev/null || true' EXIT
  # visible_window TITLE: the id of meshlab's visible window with exactly that title.
  visible_window() {
    local w
    for w in $(xdotool search --onlyvisible --pid "$pid" 2>/dev/null); do
      [ "$(xdotool getwindowname "$w" 2>/dev/null)" = "$1" ] && { echo "$w"; return 0; }
    done
    return 1
  }
  wait_log() {  # REGEX SECONDS
    local tries=$((2 * $2))
    while [ "$tries" -gt 0 ] && kill -0 "$pid" 2>/dev/null; do
      grep -qE "$1" "$log" && return 0
      sleep 0.5; tries=$((tries - 1))
    done
    return 1
  }
  # The first window (the main one, or a dialog that blocks before it) appears within seconds.
  for _ in $(seq 60); do
    [ -n "$(xdotool search --onlyvisible --pid "$pid" 2>/dev/null)" ] && break
    sleep 1
  done
  sleep "${SLIM_GUI_SECONDS:-10}"
  if kill -0 "$pid" 2>/dev/null; then echo "alive yes" >>"$report"; else echo "alive no" >>"$report"; fi
  for w in $(xdotool search --onlyvisible --pid "$pid" 2>/dev/null); do
    echo "window $(xdotool getwindowname "$w")" >>"$report"
  done
  if grep -qF "$(basename "$plugin")" "/proc/$pid/maps" 2>/dev/null; then echo "mapped yes" >>"$report"; else echo "mapped no" >>"$report"; fi
  [ -n "$run_filters" ] || exit 0

  # Each filter as a user finds it: Ctrl+F (MeshLab's filter search), its name, Return; then
  # Apply in its dialog with the defaults, and its result line in the log.
  for filter in "Overhang Analysis" "Support Slimming" "Print Orientation"; do
    for w in $(xdotool search --onlyvisible --pid "$pid" 2>/dev/null); do
      case "$(xdotool getwindowname "$w" 2>/dev/null)" in "MeshLab "[0-9]*) xdotool windowfocus --sync "$w" || true ;; esac
    done
    xdotool key ctrl+f || true
    sleep 1
    xdotool type --delay 30 "$filter" || true
    sleep 1
    xdotool key Down Return || true
    dialog=""
    for _ in $(seq 20); do dialog="$(visible_window "$filter")" && break; sleep 0.5; done
    if [ -z "$dialog" ]; then echo "filter $filter: no dialog" >>"$report"; continue; fi
    eval "$(xdotool getwindowgeometry --shell "$dialog")"  # sets WIDTH and HEIGHT
    # The dialog's last row is Close (left half) and Apply (right half).
    xdotool mousemove --window "$dialog" $((WIDTH * 3 / 4)) $((HEIGHT - 20)) click 1 || true
    if wait_log "Applied filter:? $filter" 120 && grep -qE "^LOG: [0-9]+ $filter: .*risky" "$log"; then
      echo "filter $filter: applied" >>"$report"
    else
      echo "filter $filter: no result in the log" >>"$report"
    fi
    xdotool mousemove --window "$dialog" $((WIDTH / 4)) $((HEIGHT - 20)) click 1 || true
    sleep 1
  done
  exit 0
fi

plugin="$1" version="$2" out="$3" mesh="$4"
rm -rf "$out"
mkdir -p "$out"

# run_meshlab NAME [--run-filters] FILE...: one meshlab run with a fresh HOME, so no earlier
# settings or plugins count, with FILE... in its extra-plugins folder. Leaves OUT_DIR/NAME.report.
run_meshlab() {
  local name="$1" home="$out/$1-home" run_filters=""
  shift
  [ "$1" = "--run-filters" ] && { run_filters=yes; shift; }
  local extra="$home/share/VCG/MeshLab_64bit_fp/MeshLabExtraPlugins/$version"
  mkdir -p "$extra" "$home/runtime"
  chmod 700 "$home/runtime"
  cp "$@" "$extra/"
  HOME="$home" XDG_DATA_HOME="$home/share" XDG_CONFIG_HOME="$home/config" XDG_RUNTIME_DIR="$home/runtime" \
    "$(dirname "$0")/../../scripts/with-xvfb.sh" "$0" --inside-xvfb "$plugin" "$out" "$mesh" "$name" $run_filters
  echo "--- $name:"
  cat "$out/$name.report"
}

# The check itself.
run_meshlab with-plugin --run-filters "$plugin"
report="$out/with-plugin.report"
status=0
grep -qx "alive yes" "$report" || { echo "FAIL: meshlab did not stay up"; status=1; }
grep -qx "mapped yes" "$report" || { echo "FAIL: meshlab did not load $(basename "$plugin")"; status=1; }
# The main window is titled "MeshLab VERSION - [Project_1]"; Qt's untitled helper windows carry
# the application's name. Anything else (a QMessageBox has a title) is a dialog.
grep -q "^window MeshLab $version - " "$report" || { echo "FAIL: no MeshLab main window"; status=1; }
if grep '^window ' "$report" | grep -v "^window MeshLab $version - \|^window MeshLab_64bit_fp$"; then
  echo "FAIL: meshlab shows a dialog (above)"
  status=1
fi
if grep -qi "unable to load\|does not seem to be\|has different" "$out/with-plugin.meshlab.log"; then
  echo "FAIL: meshlab's output reports a plugin problem:"
  grep -i "unable to load\|does not seem to be\|has different" "$out/with-plugin.meshlab.log"
  status=1
fi

for filter in "Overhang Analysis" "Support Slimming" "Print Orientation"; do
  grep -qx "filter $filter: applied" "$report" || { echo "FAIL: $filter did not run from the GUI"; status=1; }
done

# The control: a file that is no plugin at all must raise the error dialog.
printf 'not a plugin\n' >"$out/libbroken_plugin.so"
run_meshlab control-broken-plugin "$plugin" "$out/libbroken_plugin.so"
grep -q "^window Error while loading plugins" "$out/control-broken-plugin.report" ||
  { echo "FAIL: the control run showed no error dialog, so this check cannot see one"; status=1; }

[ "$status" -eq 0 ] && echo "PASS: meshlab $version loads $(basename "$plugin") without error dialogs"
exit "$status"
