#!/usr/bin/env python3
"""Slims the supports of a part with PyMeshLab and our plugin: the pipeline a user writes.

    python3 examples/support_slimming.py [--plugin PATH] [--orient] IN OUT

Loads IN (any format PyMeshLab reads: PLY, STL, OBJ, OFF, 3MF, ...), optionally turns it into the
print pose that needs the least support (Print Orientation), runs Support Slimming with its
defaults, saves the slimmed layer to OUT (face quality and colour show what still overhangs,
vertex quality how far each vertex moved), and prints the figures the filters return.

The plugin is the double-precision build for PyMeshLab (scripts/pymeshlab-plugin.sh). Without
--plugin it is taken from $SLIM_PYMESHLAB_PLUGIN, or else from where that script builds it
(build-pymeshlab/ in this checkout).
"""
import argparse
import os
import sys

import pymeshlab

DEFAULT_PLUGIN = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "build-pymeshlab",
                              "filter_support_slimming", "libfilter_support_slimming.so")


def find_plugin(given):
    path = given or os.environ.get("SLIM_PYMESHLAB_PLUGIN") or os.path.normpath(DEFAULT_PLUGIN)
    if not os.path.isfile(path):
        sys.exit(f"support_slimming.py: no plugin at {path}; build it with scripts/pymeshlab-plugin.sh "
                 "or pass --plugin PATH")
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--plugin", help="the plugin built by scripts/pymeshlab-plugin.sh")
    parser.add_argument("--orient", action="store_true", help="turn the part into its best print pose first")
    parser.add_argument("input", metavar="IN")
    parser.add_argument("output", metavar="OUT")
    args = parser.parse_args()

    pymeshlab.load_plugin(find_plugin(args.plugin))
    ms = pymeshlab.MeshSet()
    try:
        ms.load_new_mesh(args.input)
        if args.orient:
            # A new layer in the print pose: +Z up, resting on z = 0.
            posed = ms.apply_filter("generate_print_oriented_mesh")
            print(f"oriented: risky area {posed['risky_area_before']:.6g} -> {posed['risky_area_after']:.6g} mm^2, "
                  f"support proxy {posed['shadow_volume_before']:.6g} -> {posed['shadow_volume_after']:.6g} mm^3")
            if posed.get("support_estimate_before_mm3", -1.0) >= 0.0:
                print(f"oriented: support (estimated) {posed['support_estimate_before_mm3']:.6g} -> "
                      f"{posed['support_estimate_after_mm3']:.6g} mm^3")
        # Slims the current layer (the posed one after --orient) into a new layer, printing along +Z.
        slim = ms.apply_filter("generate_support_slimmed_mesh")
        ms.save_current_mesh(args.output)
    except pymeshlab.PyMeshLabException as e:
        sys.exit(f"support_slimming.py: {e}")
    before, after = slim["risky_area_before"], slim["risky_area_after"]
    cut = 100.0 * (1.0 - after / before) if before > 0 else 0.0
    print(f"slimmed: risky area {before:.6g} -> {after:.6g} mm^2 ({cut:.1f}% less) in {slim['iterations']} "
          f"iterations; the farthest vertex moved {slim['max_displacement']:.4g} mm")
    if slim.get("support_estimate_before_mm3", 0.0) > 0.0:
        print(f"support (estimated): {slim['support_estimate_before_mm3']:.6g} -> "
              f"{slim['support_estimate_after_mm3']:.6g} mm^3 ({slim['support_change_pct']:+.1f}%)")
    print(f"shape: Hausdorff {slim['hausdorff_mm']:.4g} mm ({slim['hausdorff_pct']:.2f}% of the diagonal), "
          f"volume {slim['volume_change_pct']:+.2f}%, creases {slim['crease_share_pct']:.2f}% of the edge length; "
          f"budget {slim['budget_mm']:.4g} mm")
    print(f"saved {args.output}")


if __name__ == "__main__":
    main()
