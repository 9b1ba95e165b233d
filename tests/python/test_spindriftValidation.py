"""Tests of etc/python/spindriftValidation.py (the validation cases' and the utilities' shared
readers and plotting helpers) and of how the scripts find it, on small files made here.

    SPINDRIFT_DIR=<source tree> python3 -m unittest test_spindriftValidation
"""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import numpy as np

SOURCE = os.environ.get("SPINDRIFT_DIR") or os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(SOURCE, "etc", "python"))
import spindriftValidation as sv  # noqa: E402

FLUID_PROPERTIES = """/*---*\\
  fluid properties
\\*---*/
FoamFile
{
    version     2.0;
    object      fluidProperties;
}

rho0            1000;           // kg/m^3
gravity         (0 -9.81 0);
particleSpacing 5e-05;          // L/20
"""

GEOMETRY = """FoamFile { object geometry; }
// the walls come first here: the fluid's box must still be the fluid's
walls { tank { type container; min (-1 -1 0); max (9 9 0); } }
fluid
{
    column { type box; min (0 0 0); max (0.05715 0.1143 0); }   // (a 2a 0)
}
periodic { x (0 1); y (0 2); }
"""


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as fh:
        fh.write(text)


class Readers(unittest.TestCase):
    def setUp(self):
        self.case = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, self.case)

    def test_read_dat_joins_the_start_time_folders_in_time_order(self):
        for start, rows in (("10", "10 4\n11 5\n"), ("2", "2 2\n3 3\n"), ("0", "0 0\n1 1\n")):
            write(os.path.join(self.case, "postProcessing", "stats", start, "stats.dat"), "# Time\tmaxSpeed\n" + rows)
        stats = sv.read_dat("stats", self.case)
        self.assertEqual(stats.columns, ["Time", "maxSpeed"])
        np.testing.assert_array_equal(stats.time, [0, 1, 2, 3, 10, 11])
        np.testing.assert_array_equal(stats["maxSpeed"], [0, 1, 2, 3, 4, 5])
        with self.assertRaises(KeyError):
            stats["kineticEnergy"]

    def test_read_dat_reads_the_units_line(self):
        write(os.path.join(self.case, "postProcessing", "stats", "0", "stats.dat"),
              "# Time\tmaxSpeed\trhoErrMax\n# [s]\t[m/s]\t[%]\n0 0 0.1\n1 2 0.3\n")
        stats = sv.read_dat("stats", self.case)
        self.assertEqual(stats.units, ["s", "m/s", "%"])
        self.assertEqual(stats.unit("rhoErrMax"), "%")
        np.testing.assert_array_equal(stats["rhoErrMax"], [0.1, 0.3])

    def test_read_dat_of_a_missing_function_object_says_which(self):
        with self.assertRaises(SystemExit) as e:
            sv.read_dat("front", self.case)
        self.assertIn("'front' function object", str(e.exception))

    def test_read_table_is_none_when_missing_or_empty(self):
        self.assertIsNone(sv.read_table(os.path.join(self.case, "none.dat")))
        write(os.path.join(self.case, "empty.dat"), "# Time x\n")
        self.assertIsNone(sv.read_table(os.path.join(self.case, "empty.dat")))

    def test_fluid_properties_parse_numbers_and_vectors_without_header_or_comments(self):
        write(os.path.join(self.case, "constant", "fluidProperties"), FLUID_PROPERTIES)
        props = sv.fluid_properties(self.case)
        self.assertEqual(set(props), {"rho0", "gravity", "particleSpacing"})
        self.assertEqual(props["rho0"], 1000)
        self.assertEqual(props["particleSpacing"], 5e-05)
        np.testing.assert_array_equal(props["gravity"], [0, -9.81, 0])

    def test_geometry_box_and_periodic_extent_read_their_own_section(self):
        write(os.path.join(self.case, "constant", "geometry"), GEOMETRY)
        lo, hi = sv.geometry_box("fluid", self.case)
        np.testing.assert_array_equal(lo, [0, 0, 0])
        np.testing.assert_array_equal(hi, [0.05715, 0.1143, 0])
        np.testing.assert_array_equal(sv.geometry_box("walls", self.case)[1], [9, 9, 0])
        self.assertEqual(sv.periodic_extent("y", self.case), (0, 2))

    def test_written_times_are_the_time_directories_holding_the_file_in_time_order(self):
        for d in ("0", "0.5", "10", "2"):
            write(os.path.join(self.case, d, "fluid.vtp"), "")
        os.makedirs(os.path.join(self.case, "3"))  # no fluid.vtp
        os.makedirs(os.path.join(self.case, "system"))
        self.assertEqual(sv.written_times(self.case), [(0, "0"), (0.5, "0.5"), (2, "2"), (10, "10")])

    def test_read_csv_skips_comment_lines(self):
        write(os.path.join(self.case, "data.csv"), "# Martin & Moyce\nseries,T,Z\nn2=2,0.41,1.11\n")
        self.assertEqual(sv.read_csv(os.path.join(self.case, "data.csv")), [{"series": "n2=2", "T": "0.41", "Z": "1.11"}])
        self.assertEqual(sv.read_csv(os.path.join(self.case, "missing.csv")), [])

    def test_read_vtp_gives_positions_and_the_named_array(self):
        try:
            from vtkmodules.util.numpy_support import numpy_to_vtk
            from vtkmodules.vtkCommonCore import vtkPoints
            from vtkmodules.vtkCommonDataModel import vtkPolyData
            from vtkmodules.vtkIOXML import vtkXMLPolyDataWriter
        except ImportError:
            self.skipTest("no VTK in this python")
        x = np.array([[0, 0, 0], [1, 2, 0]], dtype=float)
        points = vtkPoints()
        points.SetData(numpy_to_vtk(x, deep=1))
        data = vtkPolyData()
        data.SetPoints(points)
        velocity = numpy_to_vtk(np.array([[1, 0, 0], [0, 3, 0]], dtype=float), deep=1)
        velocity.SetName("velocity")
        data.GetPointData().AddArray(velocity)
        writer = vtkXMLPolyDataWriter()
        writer.SetFileName(os.path.join(self.case, "fluid.vtp"))
        writer.SetInputData(data)
        writer.Write()
        positions, u = sv.read_vtp(os.path.join(self.case, "fluid.vtp"))
        np.testing.assert_array_equal(positions, x)
        np.testing.assert_array_equal(u[:, 1], [0, 3])
        with self.assertRaises(SystemExit):
            sv.read_vtp(os.path.join(self.case, "fluid.vtp"), "pressure")


class Plotting(unittest.TestCase):
    def test_plot_requested_unless_no_plot_is_asked_for(self):
        environment = dict(os.environ)
        self.addCleanup(lambda: (os.environ.clear(), os.environ.update(environment)))
        os.environ.pop("SPINDRIFT_NO_PLOT", None)
        self.assertTrue(sv.plot_requested(["evaluate.py"]))
        self.assertFalse(sv.plot_requested(["evaluate.py", "--no-plot"]))
        os.environ["SPINDRIFT_NO_PLOT"] = "1"
        self.assertFalse(sv.plot_requested(["evaluate.py"]))

    def test_point_labels_overlap_neither_each_other_nor_the_points(self):
        plt = sv.pyplot()
        fig, ax = plt.subplots()
        xs = [1.0, 1.02, 1.04, 1.0, 1.02, 2.0]
        ys = [1.0, 1.0, 1.0, 1.02, 1.02, 2.0]
        ax.scatter(xs, ys)
        sv.label_points(ax, xs, ys, ["combination %d" % k for k in range(len(xs))])
        renderer = fig.canvas.get_renderer()
        boxes = [t.get_window_extent(renderer) for t in ax.texts]
        self.assertEqual(len(boxes), len(xs))
        overlaps = [(i, j) for i in range(len(boxes)) for j in range(i) if boxes[i].overlaps(boxes[j])]
        self.assertEqual(overlaps, [])
        plt.close(fig)

    def test_legend_below_stays_under_the_axes_and_their_labels(self):
        plt = sv.pyplot()
        fig, axes = plt.subplots(1, 2)
        for k in range(6):
            axes[0].plot([0, 1], [k, k], label="combination %d" % k)
            axes[1].plot([0, 1], [k, -k])
        axes[0].set_xlabel("t [s]")
        fig.tight_layout()
        legend = sv.legend_below(fig, axes)
        renderer = fig.canvas.get_renderer()
        self.assertEqual(len(legend.get_texts()), 6)
        top = legend.get_window_extent(renderer).y1
        self.assertTrue(all(top <= ax.get_tightbbox(renderer).y0 for ax in axes))
        plt.close(fig)

    def test_figure_definitions_name_their_units(self):
        label, definition = sv.figure_definition("frontRMS")
        self.assertIn("[-]", label)
        self.assertIn("Martin & Moyce", definition)
        self.assertEqual(sv.figure_definition("myFigure"), ("myFigure", ""))


class Locating(unittest.TestCase):
    """The scripts find the module through SPINDRIFT_DIR, their source tree or beside them when
    installed, and say what to do when they cannot."""

    def setUp(self):
        self.work = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, self.work)
        self.environment = {k: v for k, v in os.environ.items() if k != "SPINDRIFT_DIR"}

    def test_an_evaluate_py_copied_out_of_the_tree_needs_spindrift_dir(self):
        case = os.path.join(self.work, "damBreak2D")
        shutil.copytree(os.path.join(SOURCE, "tutorials", "validation", "damBreak2D"), case)
        run = subprocess.run([sys.executable, "evaluate.py", "--no-plot"], cwd=case, env=self.environment,
                             capture_output=True, text=True)
        self.assertNotEqual(run.returncode, 0)
        self.assertIn("set SPINDRIFT_DIR", run.stderr)
        # with SPINDRIFT_DIR it gets as far as the missing results
        run = subprocess.run([sys.executable, "evaluate.py", "--no-plot"], cwd=case,
                             env=dict(self.environment, SPINDRIFT_DIR=SOURCE), capture_output=True, text=True)
        self.assertIn("'front' function object", run.stderr)

    def test_the_installed_bench_plot_finds_the_module_beside_it(self):
        share = os.path.join(self.work, "share", "spindrift")
        os.makedirs(os.path.join(share, "etc", "python"))
        shutil.copy(os.path.join(SOURCE, "applications", "utilities", "spindriftBench", "spindriftBenchPlot.py"), share)
        shutil.copy(os.path.join(SOURCE, "etc", "python", "spindriftValidation.py"), os.path.join(share, "etc", "python"))
        write(os.path.join(self.work, "bench.csv"),
              "combination,kernel.type,status,wallTime_s,steps,fluidParticles,endTime,avgIterations,"
              "maxDensityError_pct,figureName,figure,pareto,note\n"
              "a,cubicSpline,ok,1.5,100,800,0.2,,2.0,frontRMS,0.1,yes,\n"
              "b,sinc2,ok,2.5,100,800,0.2,,2.0,frontRMS,0.12,,\n"
              "c,noSuchKernel,unavailable,,,,,,,,,,kernel 'noSuchKernel' is not built\n")
        png = os.path.join(self.work, "bench.png")
        run = subprocess.run([sys.executable, os.path.join(share, "spindriftBenchPlot.py"),
                              os.path.join(self.work, "bench.csv"), png, "test"],
                             env=self.environment, capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stderr)
        with open(png, "rb") as fh:
            self.assertEqual(fh.read(4), b"\x89PNG")


if __name__ == "__main__":
    unittest.main()


class PlotScriptUsage(unittest.TestCase):
    """The utilities' plotting scripts give usage (argparse), not an IndexError traceback."""

    SCRIPTS = [os.path.join(SOURCE, "applications", "utilities", "spindriftBench", "spindriftBenchPlot.py"),
               os.path.join(SOURCE, "applications", "utilities", "spindriftStress", "spindriftStressPlot.py")]

    def run_script(self, script, *args):
        return subprocess.run([sys.executable, script, *args], capture_output=True, text=True, timeout=60)

    def test_without_arguments_usage_and_exit_2(self):
        for script in self.SCRIPTS:
            r = self.run_script(script)
            self.assertEqual(r.returncode, 2, r.stderr)
            self.assertIn("usage: " + os.path.basename(script), r.stderr)
            self.assertNotIn("Traceback", r.stderr)

    def test_help_describes_the_arguments(self):
        for script in self.SCRIPTS:
            r = self.run_script(script, "-h")
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertIn("positional arguments", r.stdout)

    def test_a_missing_input_is_named(self):
        r = self.run_script(self.SCRIPTS[0], "/nonexistent/bench.csv", "/tmp/x.png")
        self.assertEqual(r.returncode, 2)
        self.assertIn("no file /nonexistent/bench.csv", r.stderr)
        r = self.run_script(self.SCRIPTS[1], "/nonexistent")
        self.assertEqual(r.returncode, 2)
        self.assertIn("no directory /nonexistent", r.stderr)
