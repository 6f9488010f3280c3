#!/usr/bin/python3
"""Frame times of VTK's unstructured-grid ray caster against tetray's CPU
ray caster doing the same work, measured alternately in one run, as ratios
with the images' difference beside them.

Meshes: the Blunt Fin (density; VTK reads the PLOT3D files and splits them
with vtkDataSetTriangleFilter) and a thick torus shell, nonconvex, made by
`tetray generate solid` ("wave"; VTK reads the same .vtu). For each, one
ParaView preset file over the field's range is written and read by both
renderers (tetray: --tf FILE --no-rescale), with ParaView's unit distance
and opacity per unit distance as VTK applies it (--opacity-mode vtk).

VTK: vtkUnstructuredGridVolumeRayCastMapper with the homogeneous
integrator (VTK's default, beside tetray's PPI) and the linear one (beside
tetray's exact method); ResetCamera, azimuth 30, elevation 20, every pixel
cast (image sample distance 1), offscreen, the median of N frames after
one warm-up. tetray: `tetray bench --renderer cpu --orbit-step 0` with
VTK's camera, its median.

A round times each pair once, VTK first, then every --tetray binary; the
table gives each round's ratio VTK / tetray and the worst of them. The
image difference is the mean over every pixel and colour channel of
|VTK - tetray| (premultiplied colour over black, 0..1), from one more
frame of each renderer (both written as PNG to the work folder printed).

    target/python-venv/bin/python tools/vtk_compare.py \\
        --tetray target/release/tetray [--tetray OTHER_BUILD ...]

Needs VTK's Python wheel (pip install vtk, as PyVista brings it), which
renders offscreen without a display.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

from vtk_volume import (
    paraview_unit_distance,
    point_grid,
    preset,
    read_back,
    save_png,
    tetrahedra,
    view_of,
    volume_property,
    volume_window,
)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
XYZ = os.path.join(ROOT, "data", "plot3d", "bluntfinxyz.bin")
Q = os.path.join(ROOT, "data", "plot3d", "bluntfinq.bin")
PAIRS = [("homogeneous", "ppi"), ("linear", "exact")]


def blunt_fin():
    """The Blunt Fin's density as VTK reads it: (grid, cells as read)."""
    import vtk

    reader = vtk.vtkMultiBlockPLOT3DReader()
    reader.SetXYZFileName(XYZ)
    reader.SetQFileName(Q)
    reader.SetScalarFunctionNumber(100)  # density
    reader.Update()
    grid = reader.GetOutput().GetBlock(0)
    return grid, grid.GetNumberOfCells()


class Case:
    """One mesh: VTK's window on it and tetray's flags for the same view,
    preset and unit distance."""

    def __init__(self, name, grid, cells, tetray_args, size, work):
        import vtk

        self.name = name
        self.size = size
        lo, hi = grid.GetPointData().GetScalars().GetRange()
        unit = paraview_unit_distance(grid.GetBounds(), cells)
        tf = preset(lo, hi)
        tf_path = os.path.join(work, f"{name}-tf.json")
        with open(tf_path, "w") as f:
            json.dump(tf, f)
        ugrid = tetrahedra(grid)
        self.tets = ugrid.GetNumberOfCells()
        self.window, camera, self.mapper, self.volume = volume_window(
            ugrid, volume_property(tf, unit), size, 30, 20, offscreen=True
        )
        self.integrators = {
            "homogeneous": vtk.vtkUnstructuredGridHomogeneousRayIntegrator(),
            "linear": vtk.vtkUnstructuredGridLinearRayIntegrator(),
        }
        self.tetray_args = tetray_args + [
            "--tf", tf_path, "--no-rescale", "--unit-distance", repr(unit),
            "--opacity-mode", "vtk", *view_of(camera), "--size", f"{size}x{size}",
            "--renderer", "cpu",
        ]
        self.work = work

    def vtk_frames(self, integrator, frames):
        """Median ms of `frames` frames after a warm-up."""
        self.mapper.SetRayIntegrator(self.integrators[integrator])
        times = []
        for i in range(frames + 1):
            self.volume.Modified()
            self.mapper.Modified()
            start = time.perf_counter()
            self.window.Render()
            if i > 0:
                times.append((time.perf_counter() - start) * 1e3)
        return statistics.median(times)

    def vtk_image(self, integrator):
        self.mapper.SetRayIntegrator(self.integrators[integrator])
        self.volume.Modified()
        self.window.Render()
        return read_back(self.window, self.size)

    def tetray_frames(self, binary, method, frames, threads):
        """(median ms, segments/s) of `tetray bench`."""
        cmd = [binary, "bench", *self.tetray_args, "--integrator", method,
               "--orbit-step", "0", "--frames", str(frames)]
        if threads:
            cmd += ["--threads", str(threads)]
        report = json.loads(run(cmd))
        return report["ms_per_frame_median"], report["segments_per_s"]

    def tetray_image(self, binary, method):
        out = os.path.join(self.work, f"{self.name}-{method}.npy")
        run([binary, "render", *self.tetray_args, "--integrator", method, "-o", out])
        return np.load(out).astype(np.float64)


def run(cmd):
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{' '.join(cmd)}: {done.stderr}")
    return done.stdout


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tetray", action="append", help="tetray binary (repeatable)")
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--frames", type=int, default=5)
    ap.add_argument("--rounds", type=int, default=3, help="alternations")
    ap.add_argument("--threads", type=int, default=None, help="tetray --threads")
    ap.add_argument("--shell-tets", default="200k",
                    help="tetrahedra of the generated torus shell (tetray generate solid --tets)")
    ap.add_argument("--mesh", action="append", choices=["bluntfin", "shell"],
                    help="meshes to measure (default: both)")
    args = ap.parse_args()
    binaries = args.tetray or [os.path.join(ROOT, "target", "release", "tetray")]
    meshes = args.mesh or ["bluntfin", "shell"]
    work = tempfile.mkdtemp(prefix="vtk-compare-")

    cases = []
    for name in meshes:
        if name == "bluntfin":
            grid, cells = blunt_fin()
            cases.append(Case(name, grid, cells, [XYZ, "--scalar", "density"], args.size, work))
        else:
            path = os.path.join(work, "shell.vtu")
            run([binaries[0], "generate", "solid", "--tets", args.shell_tets, "-o", path])
            grid = point_grid(path, "wave")
            cells = grid.GetNumberOfCells()
            cases.append(Case(name, grid, cells, [path, "--scalar", "wave"], args.size, work))

    times = {}
    for r in range(args.rounds):
        for case in cases:
            for vtk_int, ours in PAIRS:
                v = case.vtk_frames(vtk_int, args.frames)
                print(f"round {r}: {case.name} vtk {vtk_int}: {v:.1f} ms", file=sys.stderr)
                for b in binaries:
                    ms, seg = case.tetray_frames(b, ours, args.frames, args.threads)
                    times.setdefault((case.name, vtk_int, b), []).append((v, ms))
                    print(f"round {r}: {case.name} {b} {ours}: {ms:.1f} ms "
                          f"({seg / 1e6:.1f} M segments/s)", file=sys.stderr)

    import vtk

    print(f"VTK {vtk.vtkVersion.GetVTKVersion()}, "
          f"{args.size} x {args.size}, median of {args.frames} frames, {args.rounds} rounds; "
          f"images in {work}")
    print("| mesh | VTK tets | VTK integrator | tetray | method | VTK / tetray per round "
          "| worst | mean abs RGB difference |")
    print("| --- | ---: | --- | --- | --- | --- | ---: | ---: |")
    for case in cases:
        for vtk_int, ours in PAIRS:
            reference = case.vtk_image(vtk_int)[..., :3]
            for b in binaries:
                image = np.clip(case.tetray_image(b, ours)[..., :3], 0.0, 1.0)
                diff = float(np.abs(image - reference).mean())
                save_png(reference, os.path.join(work, f"{case.name}-vtk-{vtk_int}.png"))
                save_png(image, os.path.join(work, f"{case.name}-tetray-{ours}.png"))
                ratios = [v / t for v, t in times[(case.name, vtk_int, b)]]
                rounds = ", ".join(f"{v:.0f}/{t:.0f} ms = {v / t:.2f}x"
                                   for v, t in times[(case.name, vtk_int, b)])
                print(f"| {case.name} | {case.tets} | {vtk_int} | {b} | {ours} | {rounds} "
                      f"| {min(ratios):.2f}x | {diff:.4f} |")


if __name__ == "__main__":
    main()
