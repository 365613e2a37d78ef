# The pictures of eval/studies/part.sh's report (sourced by it; uses its variables: out, parts,
# base, slicer_list, turns, eval_tool, and its helpers xrun, die, kv, fmt).
#
#   before_after.png  each part with its risky faces red, from above and from below
#   displacement.png  the result coloured by how far each vertex moved (mm), with a colour bar
#   support.png       the support each slicer will print: the support extrusions of the G-code
#                     (orange) beside the part's outer walls (grey), one row per slicer
# Every picture of a kind uses one camera, so the columns compare directly.

# caption PNG TEXT: a line of text above a picture (needs a font; the picture is fine without).
caption() {
  convert "$1" +repage -background white -gravity north -splice 0x32 -font DejaVu-Sans -pointsize 18 \
    -annotate +0+6 "$2" "$1" 2>/dev/null || true
}

# camera_for CX CY CZ REACH ELEVATION: f3d camera flags looking at (CX, CY, CZ) from direction
# (0.55, -0.8, ELEVATION), normalised, at distance REACH.
camera_for() {
  awk -v cx="$1" -v cy="$2" -v cz="$3" -v r="$4" -v ez="$5" 'BEGIN {
    n = sqrt(0.55 * 0.55 + 0.64 + ez * ez)
    printf "--camera-position=%g,%g,%g --camera-focal-point=%g,%g,%g --camera-view-up=0,0,1",
      cx + r * 0.55 / n, cy - r * 0.8 / n, cz + r * ez / n, cx, cy, cz }'
}

# centre_and_reach FILE: "cx cy cz reach" from the bbox_min/bbox_max lines of a slim-eval output.
centre_and_reach() {
  awk -F'[=,]' '/^bbox_min=/ { x0 = $2; y0 = $3; z0 = $4 } /^bbox_max=/ { x1 = $2; y1 = $3; z1 = $4 }
    END { dx = x1 - x0; dy = y1 - y0; dz = z1 - z0; print (x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2, 1.8 * sqrt(dx*dx + dy*dy + dz*dz) }' "$1"
}

# f3d_shot OUT.png INPUT CAMERA_ELEVATION [f3d flags...]: one rendering at the part's camera.
f3d_shot() {
  local png="$1" input="$2" elevation="$3"
  shift 3
  # shellcheck disable=SC2046  # the camera flags are meant to split
  xrun f3d "$input" --output="$png" --resolution=480,420 --bg-color=1,1,1 \
    $(camera_for "${view_centre[@]}" "$elevation") "$@" >"$out/render.log" 2>&1 && [ -s "$png" ] ||
    die "f3d could not render $(basename "$input") (see $out/render.log)"
}

render_risky() {
  local part views
  for part in "${parts[@]}"; do
    f3d_shot "$out/${part}_above.png" "$out/${part}_overhang.ply" 0.35 --scalars=RGBA --comp=-2 --cells
    f3d_shot "$out/${part}_below.png" "$out/${part}_overhang.ply" -0.6 --scalars=RGBA --comp=-2 --cells
    caption "$out/${part}_above.png" "$part"
    convert "$out/${part}_above.png" "$out/${part}_below.png" -append "$out/$part.png" ||
      die "ImageMagick could not stack the views of $part"
  done
  views=(); for part in "${parts[@]}"; do views+=("$out/$part.png"); done
  convert "${views[@]}" +append "$out/before_after.png" || die "ImageMagick could not join the pictures"
}

render_displacement() {
  local top range
  top="$(kv "$out/slimmed.txt" max_displacement)"
  range="0,$(awk -v t="$top" 'BEGIN { print (t > 0 ? t : 1e-6) }')"
  # Blue (not moved) through yellow to red (the largest displacement).
  local ramp=0,0.15,0.3,0.85,0.5,0.95,0.85,0.2,1,0.8,0.05,0.05
  f3d_shot "$out/displacement_above.png" "$out/displacement.vtk" 0.35 --scalars=displacement_mm --bar --range="$range" --colormap=$ramp
  f3d_shot "$out/displacement_below.png" "$out/displacement.vtk" -0.6 --scalars=displacement_mm --bar --range="$range" --colormap=$ramp
  convert "$out/displacement_above.png" "$out/displacement_below.png" +append "$out/displacement.png" ||
    die "ImageMagick could not join the displacement views"
  caption "$out/displacement.png" "how far each vertex moved, $base -> slimmed, in mm (largest $(fmt 2 "$top") mm)"
}

render_support() {
  local part slicer first="${turns%%,*}" row rows=()
  for part in "${parts[@]}"; do
    for slicer in "${slicer_list[@]}"; do
      "$eval_tool" toolpath "$out/slices/$part/${slicer}_turn$first.gcode" "$out/slices/$part/${slicer}_toolpath.vtk" \
        >"$out/slices/$part/${slicer}_toolpath.txt" 2>"$out/render.log" || die "$(tail -1 "$out/render.log")"
    done
  done
  # One camera for all: the input's PrusaSlicer tool path (both slicers centre the part on the bed).
  read -r -a view_centre < <(centre_and_reach "$out/slices/input/prusa_toolpath.txt")
  view_centre[3]="$(awk -v r="${view_centre[3]}" 'BEGIN { print 0.85 * r }')"
  for slicer in "${slicer_list[@]}"; do
    row=()
    for part in "${parts[@]}"; do
      local png="$out/slices/$part/${slicer}_support.png" label=PrusaSlicer
      [ "$slicer" = prusa ] || label=Cura
      f3d_shot "$png" "$out/slices/$part/${slicer}_toolpath.vtk" 0.2 --scalars=support --cells \
        --colormap=0,0.72,0.72,0.72,1,0.93,0.38,0.08
      caption "$png" "$part, $label: $(fmt 0 "$(kv "$out/slices/$part/${slicer}_turn$first.txt" support_mm3)") mm³ of support"
      row+=("$png")
    done
    convert "${row[@]}" +append "$out/support_$slicer.png" || die "ImageMagick could not join the support pictures"
    rows+=("$out/support_$slicer.png")
  done
  convert "${rows[@]}" -append "$out/support.png" || die "ImageMagick could not stack the support pictures"
}

render_pictures() {
  read -r -a view_centre < <(centre_and_reach "$out/input.txt")
  render_risky
  render_displacement
  render_support
}
