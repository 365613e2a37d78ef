#!/usr/bin/env bash
# Drives the real MeshLab GUI under Xvfb the way a user would:
#   open MESH, Filters -> Smoothing, Fairing and Deformation -> Support Slimming, Apply, Close,
#   then File -> Export Mesh As (Ctrl+Shift+E) on the current layer.
# Checks on the way: the filter's dialog is titled "Support Slimming"; its last parameter, the
# "Optimize the orientation first" checkbox, is on screen whole (see check_last_parameter), also
# with every parameter's help shown (the Help button), and the dialog then still fits the screen;
# the least saving, the crease limit and the deviation budget's percentage field are edited with
# the keyboard (see edit_field) and the filter logs the values typed, the budget typed in % coming
# back in mm (MeshLab's absolute-or-percentage widget); the filter logs its result; the export
# dialog is titled 'Save "<name>_slimmed" Layer', i.e. the current layer is the new one; the new
# layer is drawn in its displacement colours right after Apply (see ramp_blue).
# Keeps OUT/dialog.png, OUT/dialog_help.png (help shown, values edited), OUT/meshlab_gui.png (both
# layers listed, the new one in its displacement colours), OUT/layer.ply (the exported new layer)
# and OUT/meshlab.log; OUT/failure.png when a step fails. Every wait has a timeout.
#
#   gui_check.sh PREFIX MESH OUT SMOOTHING_INDEX
# PREFIX: a private MeshLab prefix (scripts/make_prefix.sh) whose plugins include ours.
# SMOOTHING_INDEX: the filter's place (0-based) in the Smoothing submenu; MeshLab lists a
# submenu's filters in the order of their names over all plugins (gui_test.cpp works it out).
set -euo pipefail
if [ -z "${SLIM_GUI_UNDER_XVFB:-}" ]; then  # run ourselves again inside a fresh X server
  export SLIM_GUI_UNDER_XVFB=1
  exec "$(dirname "$0")/../../scripts/with-xvfb.sh" "$0" "$@"
fi
[ $# -eq 4 ] || { echo "usage: gui_check.sh PREFIX MESH OUT SMOOTHING_INDEX" >&2; exit 2; }
prefix="$1" mesh="$2" out="$3" index="$4"
for tool in xdotool import convert compare; do
  command -v "$tool" >/dev/null 2>&1 || { echo "gui_check: $tool is not installed (scripts/setup.sh)" >&2; exit 1; }
done
[ -x "$prefix/bin/meshlab" ] || { echo "gui_check: no meshlab in $prefix/bin" >&2; exit 1; }
mkdir -p "$out"
rm -f "$out"/*.png "$out/layer.ply" "$out/meshlab.log"
log="$out/meshlab.log"
home="$(mktemp -d)"
export HOME="$home" XDG_CONFIG_HOME="$home/.config"  # MeshLab's settings: never the user's
unset QT_QPA_PLATFORM  # a real window on the Xvfb display (offscreen hangs on any error dialog)

fail() {
  echo "gui_check: $*" >&2
  import -window root "$out/failure.png" 2>/dev/null || true
  exit 1
}
# wait_window REGEX SECONDS: prints the id of the first visible window whose name matches.
wait_window() {
  local id tries=$((2 * $2))
  while [ "$tries" -gt 0 ]; do
    id="$(xdotool search --onlyvisible --name "$1" 2>/dev/null | head -1 || true)"
    if [ -n "$id" ]; then echo "$id"; return 0; fi
    sleep 0.5; tries=$((tries - 1))
  done
  return 1
}
# wait_log REGEX SECONDS: until MeshLab's log (its stderr) has a matching line.
wait_log() {
  local tries=$((2 * $2))
  while [ "$tries" -gt 0 ]; do
    grep -qE "$1" "$log" && return 0
    kill -0 "$meshlab" 2>/dev/null || return 1  # MeshLab is gone
    sleep 0.5; tries=$((tries - 1))
  done
  return 1
}
# press_button WINDOW COLUMN: clicks the bottom row of a filter dialog, which holds two buttons:
# COLUMN 0 is Close, 1 is Apply (the left and right halves).
press_button() {
  # shellcheck disable=SC2034  # getwindowgeometry --shell sets all six
  local WIDTH HEIGHT X Y SCREEN WINDOW
  eval "$(xdotool getwindowgeometry --shell "$1")"
  xdotool mousemove --window "$1" $((WIDTH * (1 + 2 * $2) / 4)) $((HEIGHT - 24)) click 1
}
keys() {  # KEY COUNT: press KEY COUNT times
  local i
  for ((i = 0; i < $2; i++)); do xdotool key "$1"; sleep 0.05; done
}

# changed_box A.png B.png: the bounding box (WxH+X+Y) of the pixels that differ; empty if none.
changed_box() {
  local box
  box="$(convert "$1" "$2" -compose difference -composite -colorspace gray -threshold 0 -format '%@' info: 2>/dev/null)"
  case "$box" in 0x0* | "") echo "" ;; *) echo "$box" ;; esac
}
# tick_box WINDOW BACKTABS NAME: BACKTABS times Shift+Tab from the widget with the focus (at first
# Apply, the dialog's default) focuses a checkbox; Space ticks it; prints the box of the pixels
# that changed (its check mark), then Space unticks it again.
tick_box() {
  xdotool windowfocus --sync "$1"
  keys shift+Tab "$2"
  sleep 0.3
  import -window root "$out/$3-off.png"
  xdotool key space
  sleep 0.3
  import -window root "$out/$3-on.png"
  xdotool key space
  sleep 0.3
  changed_box "$out/$3-off.png" "$out/$3-on.png"
  rm -f "$out/$3-off.png" "$out/$3-on.png"
}
# The last parameter is on screen whole. Qt draws the dialog's widgets into one X window, so the
# checkbox has no geometry of its own to ask X for. It is found by ticking it with the keyboard (in
# the dialog's tab order it comes just before the Help, Close and Apply buttons) and seeing which
# pixels change: its check mark, which must lie inside the dialog's window. The checkbox above it
# is found the same way; the distance between the two marks is the height of a row. Then, both
# unticked, the last row's band (a row's height about its mark, as wide as the box and a margin)
# must look exactly like the row above's: a row cut off by the dialog's edge or covered by its
# buttons does not (and when the last checkbox is out of sight, ticking it changes nothing).
check_last_parameter() {
  # shellcheck disable=SC2034  # getwindowgeometry --shell sets all six
  local WIDTH HEIGHT X Y SCREEN WINDOW last above w h x y aw ah ax ay pitch differing
  eval "$(xdotool getwindowgeometry --shell "$1")"
  echo "dialog geometry: ${WIDTH}x${HEIGHT}+${X}+${Y}"
  last="$(tick_box "$1" 3 last)"    # Apply -> Close -> Help -> the last parameter
  above="$(tick_box "$1" 1 above)"  # -> the parameter above it
  echo "last parameter's check mark: ${last:-none}; the one above: ${above:-none}"
  [ -n "$last" ] || fail "the last parameter (Optimize the orientation first) is not on screen: ticking it changed nothing"
  [ -n "$above" ] || fail "ticking 'Preserve selection as rigid features' changed nothing: the keyboard did not reach it"
  IFS='x+' read -r w h x y <<<"$last"
  IFS='x+' read -r aw ah ax ay <<<"$above"
  [ "$x" -ge "$X" ] && [ "$y" -ge "$Y" ] && [ $((x + w)) -le $((X + WIDTH)) ] && [ $((y + h)) -le $((Y + HEIGHT)) ] ||
    fail "the last parameter's check mark ($last) lies outside the dialog (${WIDTH}x${HEIGHT}+${X}+${Y})"
  pitch=$((y - ay))
  [ "$pitch" -gt "$h" ] && [ "$x" -eq "$ax" ] || fail "the check marks found ($last, $above) are not one row apart"
  keys Tab 4  # -> the last parameter, Help, Close, Apply: the focus where it was
  sleep 0.3
  import -window root "$out/rows.png"
  convert "$out/rows.png" -crop "$((w + 12))x${pitch}+$((x - 6))+$((y + h / 2 - pitch / 2))" +repage "$out/row-last.png"
  convert "$out/rows.png" -crop "$((w + 12))x${pitch}+$((x - 6))+$((ay + h / 2 - pitch / 2))" +repage "$out/row-above.png"
  differing="$(compare -metric AE "$out/row-last.png" "$out/row-above.png" null: 2>&1 || true)"
  rm -f "$out/rows.png" "$out/row-last.png" "$out/row-above.png"
  echo "last row against the row above: ${differing} pixels differ (band ${pitch} px high)"
  [ "$differing" = 0 ] || fail "the last parameter's row is cut off: it differs from the row above in $differing pixels"
  echo "last parameter visible: yes"
}

# ramp_blue PNG: how many of its pixels are the blue end of the displacement colour ramp (a vertex
# that did not move, lit); MeshLab's background and default grey have none of them.
ramp_blue() {
  convert "$1" -fx "(r<0.2&&g<0.2&&b>0.7)?1:0" -format "%[fx:round(mean*w*h)]" info:
}
# edit_field WINDOW BACKTABS TEXT: from Apply (the focus), BACKTABS times Shift+Tab reaches a
# field; its text is replaced by TEXT and the focus goes back to Apply. Backwards from Apply the
# dialog's tab order is: Close, Help, Optimize the orientation first, Preserve selection, Max
# proxies, Allow stretch, Least saving, Crease limit, then the budget's percentage and mm fields.
edit_field() {
  xdotool windowfocus --sync "$1"
  keys shift+Tab "$2"
  xdotool key ctrl+a
  xdotool type --delay 20 "$3"
  keys Tab "$2"
  sleep 0.3
}
# The help shown: the Help button (two Shift+Tabs from Apply) shows every parameter's help line
# below the dialog's text; the dialog must still fit the 1280x1024 screen with its last parameter
# whole (check_last_parameter again, now with the help lines in every row).
show_help() {
  # shellcheck disable=SC2034  # getwindowgeometry --shell sets all six
  local WIDTH HEIGHT X Y SCREEN WINDOW before
  eval "$(xdotool getwindowgeometry --shell "$1")"
  before="${WIDTH}x${HEIGHT}"
  xdotool windowfocus --sync "$1"
  keys shift+Tab 2
  xdotool key space
  keys Tab 2
  sleep 1
  eval "$(xdotool getwindowgeometry --shell "$1")"
  echo "dialog with help: ${WIDTH}x${HEIGHT}+${X}+${Y} (without: $before)"
  [ "${WIDTH}x${HEIGHT}" != "$before" ] || fail "the Help button changed nothing: no help lines shown"
  [ "$X" -ge 0 ] && [ "$Y" -ge 0 ] && [ $((X + WIDTH)) -le 1280 ] && [ $((Y + HEIGHT)) -le 1024 ] ||
    fail "with its help shown the dialog (${WIDTH}x${HEIGHT}+${X}+${Y}) does not fit the 1280x1024 screen"
  import -window root "$out/dialog_help.png"
  check_last_parameter "$1"
  echo "help fits: yes"
}

"$prefix/bin/meshlab" "$mesh" >"$log" 2>&1 &
meshlab=$!
trap 'kill "$meshlab" 2>/dev/null || true; wait "$meshlab" 2>/dev/null || true; rm -rf "$home"' EXIT

main="$(wait_window '^MeshLab [0-9.]+ ' 60)" || fail "no MeshLab window within 60 s"
wait_log 'All files opened' 60 || fail "MeshLab did not open $mesh (see $log)"
sleep 1
import -window root "$out/opened.png"

# Filters (Alt+L) -> the 7th submenu below "Show current filter script" (MeshLab 2020.09's fixed
# layout: Selection, Cleaning, Create, Remeshing, Polygonal, Color, Smoothing) -> the filter.
xdotool windowfocus --sync "$main"
xdotool key alt+l
sleep 0.5
keys Down 7
xdotool key Right
sleep 0.5
keys Down "$index"
xdotool key Return
dialog="$(wait_window '^Support Slimming$' 20)" || fail "Filters -> Smoothing, Fairing and Deformation -> item $index did not open the Support Slimming dialog"
sleep 0.5
import -window root "$out/dialog.png"
check_last_parameter "$dialog"
edit_field "$dialog" 7 0    # Least saving (%): any saving
edit_field "$dialog" 8 2.5  # Crease limit (%)
edit_field "$dialog" 9 4    # Deviation budget, its percentage field: 4% of the bbox diagonal
show_help "$dialog"

press_button "$dialog" 1  # Apply, with the defaults but for the three values edited
wait_log 'LOG: [0-9]+ Support Slimming: risky area' 120 || fail "the filter logged no result within 120 s (see $log)"
wait_log 'Applied filter Support Slimming' 30 || fail "MeshLab did not finish the filter (see $log)"
press_button "$dialog" 0  # Close
sleep 1
# The new layer is drawn in its vertex colours at once: far more ramp-blue pixels than before.
import -window root "$out/applied.png"
blue_before="$(ramp_blue "$out/opened.png")" blue_after="$(ramp_blue "$out/applied.png")"
rm -f "$out/opened.png" "$out/applied.png"
echo "ramp-blue pixels: $blue_before before, $blue_after after Apply"
[ "$blue_after" -gt $((blue_before + 2000)) ] || fail "the new layer is not drawn in its displacement colours"
echo "displacement colours shown: yes"

# Export the current layer: its dialog names the layer, which must be the filter's new one.
xdotool windowfocus --sync "$main"
xdotool key ctrl+shift+e
save="$(wait_window '^Save ".*_slimmed" Layer$' 20)" || fail "Export Mesh As did not offer a '<name>_slimmed' layer: no new current layer"
echo "export dialog: $(xdotool getwindowname "$save")"
xdotool windowfocus --sync "$save"
xdotool type --delay 10 "$out/layer.ply"
xdotool key Return
options="$(wait_window '^Choose Saving Options' 20)" || fail "no saving options dialog"
xdotool windowfocus --sync "$options"
xdotool key Return
wait_log "Saved Mesh .*layer\.ply" 30 || fail "MeshLab did not save the layer (see $log)"
sleep 1
import -window root "$out/meshlab_gui.png"
grep -E 'LOG: [0-9]+ Support Slimming' "$log"
echo "gui_check: ok"
