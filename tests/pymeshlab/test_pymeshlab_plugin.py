"""The double-precision plugin in the real PyMeshLab (scripts/test-pymeshlab.sh; ctest -L pymeshlab).

pymeshlab.load_plugin() loads our plugin into PyMeshLab's own MeshLab, and each filter runs on
the sample bunny through ms.apply_filter() with parameters other than the defaults. The checks:
a new layer where the filter makes one, the input layer untouched, the figures the filter hands
back equal to an independent numpy computation on the meshes PyMeshLab returns (risky faces:
n.d + sin(alpha) < 0, faces on the build plate excepted), and bad input refused with our reason
in a PyMeshLabException.

Environment: SLIM_PLUGIN (the plugin), SLIM_BUNNY (data/bunny.ply), SLIM_VERSION (the project's
version, from CMake).
"""
import math
import os
import unittest

import numpy as np
import pymeshlab

PLUGIN = os.environ["SLIM_PLUGIN"]
BUNNY = os.environ["SLIM_BUNNY"]
VERSION = [int(part) for part in os.environ["SLIM_VERSION"].split(".")]
NAMES = {
    "Overhang Analysis": "compute_scalar_by_overhang_per_face",
    "Support Slimming": "generate_support_slimmed_mesh",
    "Print Orientation": "generate_print_oriented_mesh",
}
METHODS_AT_IMPORT = set(dir(pymeshlab.MeshSet))
pymeshlab.load_plugin(PLUGIN)
# PyMeshLab 2025.7 keeps a pointer to the log of the MeshSet whose filter raised, and its next
# mesh load writes there (a PyMeshLab bug): a MeshSet that saw a refusal must outlive the
# test run, or a later load_new_mesh writes into freed memory (std::bad_alloc, or worse).
REFUSING_MESH_SETS = []


def overhang(vertices, faces, alpha_deg, direction=(0.0, 0.0, 1.0), plate_tolerance=None):
    """Quality n.d + sin(alpha) per face (plate faces +1), the risky mask and the areas."""
    d = np.asarray(direction, dtype=float)
    d /= np.linalg.norm(d)
    tri = vertices[faces]
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    area = 0.5 * np.linalg.norm(cross, axis=1)
    normal = cross / np.maximum(2.0 * area, 1e-300)[:, None]
    quality = normal @ d + math.sin(math.radians(alpha_deg))
    height = vertices @ d
    if plate_tolerance is None:  # the filter's default: 0.1% of the bounding box diagonal
        plate_tolerance = 1e-3 * np.linalg.norm(vertices.max(axis=0) - vertices.min(axis=0))
    on_plate = (height[faces] <= height.min() + plate_tolerance).all(axis=1) & (normal @ d < 0)
    quality[on_plate] = 1.0
    risky = quality < 0
    return quality, risky, area


class PyMeshLabPluginTest(unittest.TestCase):
    def setUp(self):
        self.ms = pymeshlab.MeshSet()
        self.ms.load_new_mesh(BUNNY)
        self.input_id = self.ms.current_mesh_id()
        self.V = self.ms.current_mesh().vertex_matrix().copy()
        self.F = self.ms.current_mesh().face_matrix().copy()

    def assert_input_untouched(self):
        m = self.ms.mesh(self.input_id)
        np.testing.assert_array_equal(m.vertex_matrix(), self.V)
        np.testing.assert_array_equal(m.face_matrix(), self.F)

    def test_filters_have_their_python_names(self):
        listed = set(pymeshlab.filter_list())
        for name in NAMES.values():
            self.assertIn(name, listed)
        # Methods are bound at import time only: a plugin loaded later is reached through
        # apply_filter, or bound the way pymeshlab binds its own (docs/pymeshlab.md).
        for name in NAMES.values():
            self.assertNotIn(name, METHODS_AT_IMPORT)
            self.assertFalse(hasattr(self.ms, name))
        setattr(pymeshlab.MeshSet, NAMES["Overhang Analysis"], pymeshlab.bind_function(NAMES["Overhang Analysis"]))
        out = self.ms.compute_scalar_by_overhang_per_face(alphamax=50.0)
        self.assertGreater(out["risky_area"], 0.0)
        # which build made the result: PyMeshLab hands back numbers only, so the version's parts
        self.assertEqual([out["version_major"], out["version_minor"], out["version_patch"]], VERSION)

    def test_overhang_analysis_matches_numpy(self):
        alpha, tolerance = 35.0, 0.05
        out = self.ms.apply_filter(NAMES["Overhang Analysis"], alphamax=alpha, selectrisky=True, colorize=False,
                                   platetolerance=pymeshlab.PureValue(tolerance))
        quality, risky, area = overhang(self.V, self.F, alpha, plate_tolerance=tolerance)
        self.assertEqual(self.ms.mesh_number(), 1)  # no new layer: it only analyses
        self.assert_input_untouched()
        self.assertEqual(out["risky_faces"], int(risky.sum()))
        self.assertAlmostEqual(out["risky_area"], area[risky].sum(), places=9)
        self.assertAlmostEqual(out["total_area"], area.sum(), places=9)
        self.assertGreater(out["risky_area"], 0.0)
        m = self.ms.current_mesh()
        np.testing.assert_allclose(m.face_scalar_array(), quality, atol=1e-9)
        np.testing.assert_array_equal(m.face_selection_array(), risky)

    def test_support_slimming_makes_a_layer_with_less_risky_area(self):
        alpha, budget = 50.0, 4.0
        out = self.ms.apply_filter(NAMES["Support Slimming"], alphamax=alpha, resolution=12, maxiterations=30,
                                   maxdeviation=pymeshlab.PercentageValue(budget), method=0)
        self.assertEqual(self.ms.mesh_number(), 2)
        self.assertNotEqual(self.ms.current_mesh_id(), self.input_id)
        self.assert_input_untouched()
        result = self.ms.current_mesh()
        W = result.vertex_matrix()
        np.testing.assert_array_equal(result.face_matrix(), self.F)  # same vertices, same faces
        _, risky_before, area_before = overhang(self.V, self.F, alpha)
        _, risky_after, area_after = overhang(W, self.F, alpha)
        self.assertAlmostEqual(out["risky_area_before"], area_before[risky_before].sum(), places=9)
        self.assertAlmostEqual(out["risky_area_after"], area_after[risky_after].sum(), delta=1e-6)
        self.assertLess(out["risky_area_after"], out["risky_area_before"])
        # What the default method chooses by: less support, as its support model estimates it.
        self.assertGreater(out["support_estimate_before_mm3"], 0.0)
        self.assertLess(out["support_estimate_after_mm3"], 0.98 * out["support_estimate_before_mm3"])
        self.assertGreaterEqual(out["iterations"], 1)
        self.assertLessEqual(out["iterations"], 30)
        moved = np.linalg.norm(W - self.V, axis=1)
        self.assertAlmostEqual(out["max_displacement"], moved.max(), delta=1e-5)
        # The budget given as a percentage is of the bbox diagonal (MeshLab's absolute-or-percentage value).
        diagonal = np.linalg.norm(self.V.max(axis=0) - self.V.min(axis=0))
        self.assertAlmostEqual(out["budget_mm"], budget / 100.0 * diagonal, delta=1e-6 * diagonal)
        self.assertLessEqual(moved.max(), out["budget_mm"] * (1.0 + 1e-6))
        np.testing.assert_allclose(result.vertex_scalar_array(), moved, atol=1e-5)  # vertex quality
        diagonal = np.linalg.norm(self.V.max(axis=0) - self.V.min(axis=0))
        self.assertLessEqual(moved.max(), budget / 100.0 * diagonal * (1 + 1e-6))
        # The shape's cost, next to the budget: the same figures support-slim --report writes.
        self.assertAlmostEqual(out["budget_mm"], budget / 100.0 * diagonal, delta=1e-6 * diagonal)
        self.assertAlmostEqual(out["max_displacement_mm"], moved.max(), delta=1e-5)
        self.assertLessEqual(out["hausdorff_mm"], out["budget_mm"] * (1 + 1e-6))
        self.assertGreater(out["hausdorff_mm"], 0.0)
        self.assertLess(abs(out["volume_change_pct"]), 2.0)
        self.assertGreaterEqual(out["crease_share_pct"], 0.0)
        self.assertLessEqual(out["crease_share_pct"], 100.0)
        # The proportions, computed here with numpy: extents, height (+Z), mean move, folds, and the
        # best-fit affine map (with its translation, by least squares) against a rigid motion.
        box_in, box_out = self.V.max(axis=0) - self.V.min(axis=0), W.max(axis=0) - W.min(axis=0)
        for axis, key in enumerate(("extent_change_x_pct", "extent_change_y_pct", "extent_change_z_pct")):
            self.assertAlmostEqual(out[key], 100.0 * (box_out[axis] / box_in[axis] - 1.0), delta=1e-3)
        self.assertAlmostEqual(out["height_change_pct"], out["extent_change_z_pct"], delta=1e-9)
        self.assertAlmostEqual(out["mean_displacement_pct"], 100.0 * moved.mean() / diagonal, delta=1e-4)

        def crosses(P):
            a, b, c = P[self.F[:, 0]], P[self.F[:, 1]], P[self.F[:, 2]]
            return np.cross(b - a, c - a)
        self.assertEqual(out["folded_faces"], int(np.sum(np.einsum("ij,ij->i", crosses(self.V), crosses(W)) < 0)))
        X = np.hstack([self.V, np.ones((len(self.V), 1))])
        fit = np.linalg.lstsq(X, W, rcond=None)[0]  # 4 by 3: the linear part's transpose, then the shift
        sigma = np.linalg.svd(fit[:3, :], compute_uv=False)
        self.assertAlmostEqual(out["affine_departure_pct"], 100.0 * np.abs(sigma - 1.0).max(), delta=1e-3)
        self.assertGreaterEqual(W[:, 2].min(), self.V[:, 2].min() - 1e-9)  # nothing below the plate
        # By default the part keeps its proportions and moves little on average.
        self.assertLessEqual(out["affine_departure_pct"], 1.0)
        self.assertLessEqual(out["mean_displacement_pct"], 1.5)
        self.assertEqual(out["folded_faces"], 0)

    def test_allow_stretch_lets_the_whole_part_move(self):
        held = self.ms.apply_filter(NAMES["Support Slimming"], resolution=12, maxdeviation=pymeshlab.PercentageValue(5.0))
        self.ms.set_current_mesh(self.input_id)
        free = self.ms.apply_filter(NAMES["Support Slimming"], resolution=12, maxdeviation=pymeshlab.PercentageValue(5.0),
                                  allowstretch=True)
        self.assertEqual(self.ms.mesh_number(), 3)
        self.assert_input_untouched()
        self.assertLessEqual(held["affine_departure_pct"], 1.0)
        self.assertGreater(free["affine_departure_pct"], held["affine_departure_pct"] + 0.5)

    def test_print_orientation_turns_the_part_rigidly(self):
        alpha = 40.0
        out = self.ms.apply_filter(NAMES["Print Orientation"], alphamax=alpha, searcheffort=0, applyresult=True)
        self.assertEqual(self.ms.mesh_number(), 2)
        self.assert_input_untouched()
        W = self.ms.current_mesh().vertex_matrix()
        # One plate tolerance in every pose: 0.1% of the bbox diagonal of the part as given.
        tolerance = 1e-3 * np.linalg.norm(self.V.max(axis=0) - self.V.min(axis=0))
        _, risky_before, area_before = overhang(self.V, self.F, alpha, plate_tolerance=tolerance)
        _, risky_after, area_after = overhang(W, self.F, alpha, plate_tolerance=tolerance)
        self.assertAlmostEqual(out["risky_area_before"], area_before[risky_before].sum(), places=6)
        self.assertAlmostEqual(out["risky_area_after"], area_after[risky_after].sum(), delta=1e-6)
        # The pose is the support model's choice: never more support by its estimate than the pose
        # as given, beyond what a pose that stands by itself may cost (the proxies may rise).
        self.assertGreater(out["support_estimate_before_mm3"], 0.0)
        self.assertLessEqual(out["support_estimate_after_mm3"], out["support_estimate_before_mm3"] * 1.05 + 1.0)
        self.assertAlmostEqual(W[:, 2].min(), 0.0, places=9)  # resting on z = 0
        # A rigid turn: every edge keeps its length.
        for a, b in ((0, 1), (1, 2), (2, 0)):
            before = np.linalg.norm(self.V[self.F[:, a]] - self.V[self.F[:, b]], axis=1)
            after = np.linalg.norm(W[self.F[:, a]] - W[self.F[:, b]], axis=1)
            np.testing.assert_allclose(after, before, rtol=1e-9, atol=1e-9)

    def assert_refused(self, name, message, **params):
        REFUSING_MESH_SETS.append(self.ms)
        with self.assertRaises(pymeshlab.PyMeshLabException) as caught:
            self.ms.apply_filter(name, **params)
        self.assertIn(message, str(caught.exception))
        return caught.exception

    def test_bad_parameters_are_refused_with_our_reason(self):
        for filter_name in NAMES:
            name = NAMES[filter_name]
            error = self.assert_refused(name, "the self-supporting angle must be in [0, 90) degrees", alphamax=95.0)
            self.assertIn(filter_name, str(error))
            self.assertEqual(self.ms.mesh_number(), 1)
            self.assert_input_untouched()
        self.assert_refused(NAMES["Support Slimming"], "the print direction must be a non-zero vector",
                            printdirection=np.zeros(3))
        self.assert_refused(NAMES["Support Slimming"], "the voxel resolution must be at least 1 cell", resolution=0)
        self.assertEqual(self.ms.mesh_number(), 1)
        self.assert_input_untouched()

    def test_a_point_cloud_is_refused_with_our_reason(self):
        self.ms.add_mesh(pymeshlab.Mesh(vertex_matrix=self.V), "points")
        for name in NAMES.values():
            self.assert_refused(name, "not a point cloud")
            self.assertEqual(self.ms.mesh_number(), 2)


if __name__ == "__main__":
    unittest.main()
