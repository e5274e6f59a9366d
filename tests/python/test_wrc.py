"""Tests of the wrc Python module against the runtime's C API (called through ctypes on the
shared library) and against values known in closed form.

    test_wrc.py MODULE_DIR LIBWRC_RUNTIME_SO TABLE_MAKER SCRATCH_DIR

TABLE_MAKER is tests/integration/make_table.cpp's executable. With WRC_BENCH=1 it also
measures the multilinear throughput of Table.eval on 10^6 random points (a benchmark, not a
test: it asserts nothing about time).
"""

import ctypes
import math
import os
import subprocess
import sys
import time
import unittest

import numpy as np

MODULE_DIR, LIBRARY, TABLE_MAKER, SCRATCH = sys.argv[1:5]
sys.path.insert(0, MODULE_DIR)
import wrc  # noqa: E402

RADIUS, V0 = 460.0, 20000.0
# Sign of fx fy fz mx my mz contact_y contact_angle t_gamma under the mirror image in the x-z
# plane.
OUTPUT_MIRROR = np.array([1, -1, 1, -1, 1, -1, -1, -1, 1], dtype=float)
N_OUTPUTS = len(OUTPUT_MIRROR)  # of the wheelset table tests/runtime/wheelset_table.h writes


def wheelset_function(k, y, roll, yaw, spin):
    """tests/runtime/wheelset_table.h: WheelsetFunction."""
    return (100.0 * (k + 1) + (10.0 + k) * y + 2000.0 * (k - 3) * roll
            + 5000.0 * (2 * k - 5) * yaw + 30000.0 * (k % 3 - 1) * spin)


class CApi:
    """The C functions the comparisons need, on the shared runtime."""

    class State(ctypes.Structure):
        _fields_ = [(name, ctypes.c_double) for name in
                    ("y", "z", "roll", "yaw", "vy", "vroll", "vyaw", "omega", "velocity")] + [
                        ("fz", ctypes.c_double * 2), ("mu", ctypes.c_double * 2)]

    class Contact(ctypes.Structure):
        _fields_ = [("force", ctypes.c_double * 3), ("moment", ctypes.c_double * 3),
                    ("contact_y", ctypes.c_double), ("contact_angle", ctypes.c_double),
                    ("t_gamma", ctypes.c_double),
                    ("flags", ctypes.c_int)]

    class Result(ctypes.Structure):
        pass

    Result._fields_ = [("wheel", Contact * 2), ("force", ctypes.c_double * 3),
                       ("moment", ctypes.c_double * 3)]

    def __init__(self, path):
        lib = ctypes.CDLL(path)
        lib.wrc_table_open.argtypes = [ctypes.c_char_p, ctypes.POINTER(ctypes.c_void_p)]
        lib.wrc_table_close.argtypes = [ctypes.c_void_p]
        lib.wrc_table_set_interpolation.argtypes = [ctypes.c_void_p, ctypes.c_int]
        lib.wrc_table_set_storage.argtypes = [ctypes.c_void_p, ctypes.c_int]
        for name in ("wrc_table_eval", "wrc_table_eval_deriv"):
            getattr(lib, name).restype = ctypes.c_int
        lib.wrc_table_eval.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p]
        lib.wrc_table_eval_deriv.argtypes = [ctypes.c_void_p] + [ctypes.c_void_p] * 3
        lib.wrc_wheelset_create.argtypes = [ctypes.c_void_p, ctypes.c_void_p,
                                            ctypes.POINTER(ctypes.c_void_p)]
        lib.wrc_wheelset_destroy.argtypes = [ctypes.c_void_p]
        lib.wrc_wheelset_state_init.argtypes = [ctypes.POINTER(CApi.State)]
        lib.wrc_wheelset_eval.argtypes = [ctypes.c_void_p, ctypes.POINTER(CApi.State),
                                          ctypes.POINTER(CApi.Result)]
        self.lib = lib

    def open(self, path, mode=0):
        handle = ctypes.c_void_p()
        assert self.lib.wrc_table_open(path.encode(), ctypes.byref(handle)) == 0
        assert self.lib.wrc_table_set_interpolation(handle, mode) == 0
        return handle

    def eval(self, handle, points, n_outputs, derivatives=False):
        """Point by point, as a C program would call it; failed points are NaN."""
        points = np.ascontiguousarray(points, dtype=float)
        n, n_axes = points.shape
        values = np.full((n, n_outputs), np.nan)
        d = np.full((n, n_outputs, n_axes), np.nan)
        flags = np.zeros(n, dtype=np.int32)
        p0, v0, d0 = points.ctypes.data, values.ctypes.data, d.ctypes.data
        eval_, eval_deriv = self.lib.wrc_table_eval, self.lib.wrc_table_eval_deriv
        for i in range(n):
            p, v = p0 + 8 * i * n_axes, v0 + 8 * i * n_outputs
            if derivatives:
                flags[i] = eval_deriv(handle, p, v, d0 + 8 * i * n_outputs * n_axes)
            else:
                flags[i] = eval_(handle, p, v)
            if flags[i] < 0:
                values[i] = np.nan
                d[i] = np.nan
        return values, d, flags


def random_points(rng, n, low, high):
    return low + (high - low) * rng.random((n, len(low)))


class PythonModuleTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        os.makedirs(SCRATCH, exist_ok=True)
        cls.wheelset_path = os.path.join(SCRATCH, "wheelset.h5")
        cls.small_path = os.path.join(SCRATCH, "small.h5")
        subprocess.run([TABLE_MAKER, "--wheelset", cls.wheelset_path], check=True)
        subprocess.run([TABLE_MAKER, cls.small_path], check=True)
        cls.c = CApi(LIBRARY)
        cls.table = wrc.Table(cls.wheelset_path)
        cls.low = np.array([-10.0, -0.002, -0.01, -0.01])
        cls.high = -cls.low

    def test_axes_outputs_and_grid(self):
        t = self.table
        self.assertEqual(t.axis_names, ["y", "roll", "yaw", "spin"])
        self.assertEqual(t.output_names[:3], ["fx", "fy", "fz"])
        axes = t.axes
        np.testing.assert_array_equal(axes["y"], np.linspace(-10.0, 10.0, 41))
        self.assertEqual(axes["spin"].shape, (9,))
        grid = t.outputs["mz"]
        self.assertEqual(grid.shape, (41, 5, 5, 9))
        y, roll, yaw, spin = np.meshgrid(*axes.values(), indexing="ij")
        np.testing.assert_allclose(grid, wheelset_function(5, y, roll, yaw, spin), rtol=1e-12)
        self.assertEqual(t.status.dtype, np.int8)
        self.assertFalse(t.status.any())
        self.assertIn("velocity = 20000.0", t.attribute("scene"))

    def test_an_unsealed_table_loads_with_a_warning_naming_the_upgrade(self):
        # The test tables are written without a seal, as tables were before seals.
        self.assertIn("wrc upgrade", wrc.Table(self.small_path).warning)

    def test_what_is_not_a_real_number_or_path_is_refused(self):
        # None would become NaN and 1j lose its imaginary part under a silent cast
        for bad in ([None, 0.0, 0.0, 0.0], [1j, 0.0, 0.0, 0.0], ["a", "b", "c", "d"]):
            with self.assertRaises(TypeError):
                self.table.eval(bad)
        ws = wrc.Wheelset(left=self.table, right=self.table)
        with self.assertRaises(TypeError):
            ws.eval(y=None, omega=-V0 / RADIUS, velocity=V0)
        # a NUL would end the C path early and open another file
        with self.assertRaises(ValueError):
            wrc.Table(self.wheelset_path + "\0ignored")
        # the grids handed out are copies: writing to them must fail, not seem to work
        for grid in (self.table.outputs["fy"], self.table.axes["y"], self.table.status):
            with self.assertRaises(ValueError):
                grid.flat[0] = 1

    def test_an_object_made_without_its_constructor_is_refused(self):
        # __new__ alone leaves no C++ object behind: every use must raise, never read the memory.
        # In a child process under MALLOC_PERTURB_, so that a read of freed or uninitialised
        # memory crashes (and fails this test) instead of passing by luck.
        script = "\n".join([
            "import wrc",
            "t = wrc.Table.__new__(wrc.Table)",
            "w = wrc.Wheelset.__new__(wrc.Wheelset)",
            "uses = [lambda: t.eval([0.0, 0.0]), lambda: t.eval_flags([0.0, 0.0]),",
            "        lambda: t.eval_deriv([0.0, 0.0]), lambda: t.outputs, lambda: t.axes,",
            "        lambda: t.status, lambda: t.axis_names, lambda: t.output_names,",
            "        lambda: t.axis_unit(0), lambda: t.output_unit(0), lambda: t.attribute('x'),",
            "        lambda: t.interpolation, lambda: setattr(t, 'interpolation', 'cubic'),",
            "        lambda: wrc.Wheelset(left=t), lambda: w.eval(omega=-1.0, velocity=1.0),",
            "        lambda: w.set_rail_origin(0, 0.0, 0.0)]",
            "for use in uses:",
            "    try:",
            "        use()",
            "    except TypeError as e:",
            "        assert 'not initialised' in str(e), e",
            "    else:",
            "        raise SystemExit('accepted')",
            "print('refused', len(uses))",
        ])
        env = dict(os.environ, MALLOC_PERTURB_="165", PYTHONPATH=os.pathsep.join(sys.path))
        run = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True,
                             text=True, timeout=60)
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertEqual(run.stdout.strip(), "refused 16")
        with self.assertRaises(ValueError):
            self.table.attribute("scene\0junk")

    def test_closed_form_value(self):
        small = wrc.Table(self.small_path)
        values = small.eval([0.5, 0.005])
        self.assertAlmostEqual(values[0, 0], 1.0 + 1.0 + 1.5 + 0.125, delta=1e-12)

    def test_million_points_multilinear_equal_c_api_bit_for_bit(self):
        rng = np.random.default_rng(19)
        points = random_points(rng, 10**6, self.low * 1.05, self.high * 1.05)  # some clamped
        points[12345, 2] = np.nan
        values, flags = self.table.eval_flags(points)
        handle = self.c.open(self.wheelset_path)
        expected, _, expected_flags = self.c.eval(handle, points, N_OUTPUTS)
        self.c.lib.wrc_table_close(handle)
        np.testing.assert_array_equal(flags, expected_flags)
        self.assertEqual(flags[12345], -2)  # WRC_ERR_NAN_INPUT
        self.assertTrue((flags == wrc.FLAG_CLAMPED).any())
        self.assertEqual(values.tobytes(), expected.tobytes())
        with self.assertRaises(ValueError):
            self.table.eval(points[12340:12350])

    def test_cubic_with_derivatives_equal_c_api_bit_for_bit(self):
        t = wrc.Table(self.wheelset_path)
        t.interpolation = "cubic"
        self.assertEqual(t.interpolation, "cubic")
        rng = np.random.default_rng(20)
        points = random_points(rng, 20000, self.low * 1.05, self.high * 1.05)
        values, d, flags = t.eval_deriv(points)
        handle = self.c.open(self.wheelset_path, mode=1)
        expected, expected_d, expected_flags = self.c.eval(handle, points, N_OUTPUTS, derivatives=True)
        self.c.lib.wrc_table_close(handle)
        np.testing.assert_array_equal(flags, expected_flags)
        self.assertEqual(values.tobytes(), expected.tobytes())
        self.assertEqual(d.tobytes(), expected_d.tobytes())
        self.assertEqual(d.shape, (20000, N_OUTPUTS, 4))
        with self.assertRaises(ValueError):
            t.interpolation = "quadratic"

    def test_float32_storage_is_the_c_apis_and_within_float_rounding(self):
        t = wrc.Table(self.wheelset_path)
        self.assertEqual(t.storage, "float64")
        rng = np.random.default_rng(21)
        points = random_points(rng, 20000, self.low, self.high)
        exact = t.eval(points)
        t.storage = "float32"
        self.assertEqual(t.storage, "float32")
        values = t.eval(points)
        handle = self.c.open(self.wheelset_path)
        self.assertEqual(self.c.lib.wrc_table_set_storage(handle, 1), 0)
        expected, _, _ = self.c.eval(handle, points, N_OUTPUTS)
        self.c.lib.wrc_table_close(handle)
        self.assertEqual(values.tobytes(), expected.tobytes())
        # float rounding of the node values (|values| up to ~1e5 here): 2^-24 relative, a few
        # corners' worth
        scale = np.abs(exact).max()
        self.assertLess(np.abs(values - exact).max(), 1e-6 * scale)
        self.assertGreater(np.abs(values - exact).max(), 0.0)
        with self.assertRaises(ValueError):
            t.storage = "float16"

    @unittest.skipUnless(os.environ.get("WRC_BENCH"), "a benchmark: set WRC_BENCH=1")
    def test_throughput_multilinear(self):
        rng = np.random.default_rng(21)
        points = random_points(rng, 10**6, self.low, self.high)
        self.table.eval(points[:1000])  # warm up
        best = math.inf
        for _ in range(3):
            start = time.perf_counter()
            self.table.eval(points)
            best = min(best, time.perf_counter() - start)
        rate = len(points) / best
        print(f"\nTable.eval multilinear, 10^6 random points, 4 axes, {N_OUTPUTS} outputs: "
              f"{rate / 1e6:.1f} M points/s ({1e9 / rate:.0f} ns per point)")

    def test_wheelset_mirror_and_c_api(self):
        ws = wrc.Wheelset(right=self.table)
        rng = np.random.default_rng(22)
        n = 200
        y, roll = rng.uniform(-9, 9, n), rng.uniform(-0.0019, 0.0019, n)
        yaw, spin = rng.uniform(-0.009, 0.009, n), rng.uniform(-0.009, 0.009, n)
        velocity = rng.uniform(5000.0, 60000.0, n)
        omega = -(velocity / RADIUS) * (1.0 + spin)
        r = ws.eval(y=y, roll=roll, yaw=yaw, omega=omega, velocity=velocity)
        self.assertEqual(r["force"].shape, (n, 2, 3))
        np.testing.assert_array_equal(r["code"], 0)
        for k in range(3):
            right = wheelset_function(k, y, roll, yaw, spin)
            left = OUTPUT_MIRROR[k] * wheelset_function(k, -y, -roll, -yaw, spin)
            np.testing.assert_allclose(r["force"][:, wrc.RIGHT, k], right, rtol=1e-9)
            np.testing.assert_allclose(r["force"][:, wrc.LEFT, k], left, rtol=1e-9)
        # Tγ, a dissipated power, is the same for a wheel and its mirror image.
        np.testing.assert_allclose(r["t_gamma"][:, wrc.RIGHT],
                                   wheelset_function(8, y, roll, yaw, spin), rtol=1e-9)
        np.testing.assert_allclose(r["t_gamma"][:, wrc.LEFT],
                                   wheelset_function(8, -y, -roll, -yaw, spin), rtol=1e-9)
        np.testing.assert_array_equal(r["total_force"], -(r["force"][:, 0] + r["force"][:, 1]))
        # The same states through the C API, to the bit.
        handle = self.c.open(self.wheelset_path)
        wheelset = ctypes.c_void_p()
        self.assertEqual(self.c.lib.wrc_wheelset_create(None, handle, ctypes.byref(wheelset)), 0)
        state, result = CApi.State(), CApi.Result()
        for i in range(n):
            self.c.lib.wrc_wheelset_state_init(ctypes.byref(state))
            state.y, state.roll, state.yaw = y[i], roll[i], yaw[i]
            state.omega, state.velocity = omega[i], velocity[i]
            self.assertEqual(
                self.c.lib.wrc_wheelset_eval(wheelset, ctypes.byref(state), ctypes.byref(result)),
                0)
            for side in (0, 1):
                self.assertEqual(list(result.wheel[side].force), list(r["force"][i, side]))
                self.assertEqual(list(result.wheel[side].moment), list(r["moment"][i, side]))
                self.assertEqual(result.wheel[side].contact_y, r["contact_y"][i, side])
                self.assertEqual(result.wheel[side].t_gamma, r["t_gamma"][i, side])
        self.c.lib.wrc_wheelset_destroy(wheelset)
        self.c.lib.wrc_table_close(handle)

    def test_wheelset_flags_and_arguments(self):
        ws = wrc.Wheelset(left=self.table, right=self.table)
        r = ws.eval(y=[0.0, 20.0], vy=[0.0, 0.0], omega=-V0 / RADIUS, velocity=V0)
        np.testing.assert_array_equal(r["flags"], [[0, 0], [wrc.FLAG_CLAMPED, wrc.FLAG_CLAMPED]])
        # vroll enters through the yaw axis (the pose of equal creepage): nothing is fixed
        r = ws.eval(vroll=0.01, omega=-V0 / RADIUS, velocity=V0)
        np.testing.assert_array_equal(r["flags"], [[0, 0]])
        # a load other than the table's 10 kN is
        r = ws.eval(omega=-V0 / RADIUS, velocity=V0, fz_left=12000.0, fz_right=12000.0)
        np.testing.assert_array_equal(r["flags"], [[wrc.FLAG_FIXED, wrc.FLAG_FIXED]])
        self.assertTrue(np.isnan(r["total_moment"]).all())  # rail origins not set
        r = ws.eval(omega=-V0 / RADIUS, velocity=0.0)
        self.assertLess(r["code"][0], 0)
        with self.assertRaises(TypeError):
            ws.eval(omega=1.0)  # no velocity
        with self.assertRaises(TypeError):
            ws.eval(omega=1.0, velocity=1.0, speed=3.0)
        with self.assertRaises(ValueError):
            ws.eval(y=[1.0, 2.0], yaw=[1.0, 2.0, 3.0], omega=1.0, velocity=1.0)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
