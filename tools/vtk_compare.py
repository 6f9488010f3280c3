#!/usr/bin/python3
"""Frame times of VTK 9's unstructured-grid ray caster against tetray's CPU
ray caster on the Blunt Fin, measured alternately in one run, as ratios.

VTK: vtkUnstructuredGridVolumeRayCastMapper on the PLOT3D grid split into
tetrahedra (vtkDataSetTriangleFilter), with the homogeneous integrator
(VTK's default, compared with tetray's PPI) and the linear one (compared
with tetray's exact method); ResetCamera, azimuth 30, elevation 20,
512 x 512, every pixel cast (image sample distance 1), the median of N
frames after one warm-up. tetray: `tetray bench --renderer cpu
--integrator ppi|exact --orbit-step 0`, same view and size, its median.

Needs python3-vtk9 and an X display for VTK's render window (xvfb-run):

    apt-get install -y python3-vtk9 xvfb
    xvfb-run -a /usr/bin/python3 tools/vtk_compare.py \\
        --tetray target/release/tetray [--tetray OTHER_BUILD ...]

Several --tetray binaries (a baseline and a new build) are run in turn with
VTK in the same rounds, so their ratios are measured under the same load.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

from vtk_volume import paraview_unit_distance, volume_window

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
XYZ = os.path.join(ROOT, "data", "plot3d", "bluntfinxyz.bin")
Q = os.path.join(ROOT, "data", "plot3d", "bluntfinq.bin")


def vtk_setup(size):
    import vtk

    reader = vtk.vtkMultiBlockPLOT3DReader()
    reader.SetXYZFileName(XYZ)
    reader.SetQFileName(Q)
    reader.SetScalarFunctionNumber(100)  # density
    reader.SetVectorFunctionNumber(202)
    reader.Update()
    grid = reader.GetOutput().GetBlock(0)
    tets = vtk.vtkDataSetTriangleFilter()
    tets.SetInputData(grid)
    tets.Update()
    ugrid = tets.GetOutput()
    lo, hi = ugrid.GetPointData().GetScalars().GetRange()

    # A cool-to-warm ramp with rising opacity over the range, as tetray's
    # default transfer function; opacity per ParaView's unit distance.
    color = vtk.vtkColorTransferFunction()
    color.SetColorSpaceToDiverging()
    color.AddRGBPoint(lo, 0.231, 0.298, 0.753)
    color.AddRGBPoint(hi, 0.706, 0.016, 0.150)
    opacity = vtk.vtkPiecewiseFunction()
    opacity.AddPoint(lo, 0.0)
    opacity.AddPoint(hi, 1.0)
    prop = vtk.vtkVolumeProperty()
    prop.SetColor(color)
    prop.SetScalarOpacity(opacity)
    prop.SetScalarOpacityUnitDistance(
        paraview_unit_distance(ugrid.GetBounds(), grid.GetNumberOfCells())
    )
    prop.SetInterpolationTypeToLinear()
    window, _, mapper, volume = volume_window(ugrid, prop, size, 30, 20)
    integrators = {
        "homogeneous": vtk.vtkUnstructuredGridHomogeneousRayIntegrator(),
        "linear": vtk.vtkUnstructuredGridLinearRayIntegrator(),
    }
    return window, mapper, volume, integrators, ugrid.GetNumberOfCells()


def vtk_frames(setup, integrator, frames):
    window, mapper, volume, integrators, _ = setup
    mapper.SetRayIntegrator(integrators[integrator])
    times = []
    for i in range(frames + 1):
        volume.Modified()
        mapper.Modified()
        start = time.perf_counter()
        window.Render()
        elapsed = time.perf_counter() - start
        if i > 0:
            times.append(elapsed * 1e3)
    return statistics.median(times)


def tetray_frames(binary, integrator, size, frames, threads):
    cmd = [
        binary,
        "bench",
        "--renderer",
        "cpu",
        "--integrator",
        integrator,
        "--orbit-step",
        "0",
        "--azimuth",
        "30",
        "--elevation",
        "20",
        "--size",
        f"{size}x{size}",
        "--frames",
        str(frames),
    ]
    if threads:
        cmd += ["--threads", str(threads)]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    report = json.loads(out)
    return report["ms_per_frame_median"], report["segments_per_s"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tetray", action="append", help="tetray binary (repeatable)")
    ap.add_argument("--size", type=int, default=512)
    ap.add_argument("--frames", type=int, default=5)
    ap.add_argument("--rounds", type=int, default=2, help="alternations")
    ap.add_argument("--threads", type=int, default=None, help="tetray --threads")
    args = ap.parse_args()
    binaries = args.tetray or [os.path.join(ROOT, "target", "release", "tetray")]

    setup = vtk_setup(args.size)
    print(f"VTK: {setup[4]} tetrahedra, {args.size}x{args.size}, median of "
          f"{args.frames} frames, {args.rounds} rounds", file=sys.stderr)
    pairs = [("homogeneous", "ppi"), ("linear", "exact")]
    results = {}
    for r in range(args.rounds):
        for vtk_int, ours in pairs:
            v = vtk_frames(setup, vtk_int, args.frames)
            results.setdefault(("vtk", vtk_int), []).append(v)
            print(f"round {r}: vtk {vtk_int}: {v:.1f} ms", file=sys.stderr)
            for b in binaries:
                ms, seg = tetray_frames(b, ours, args.size, args.frames, args.threads)
                results.setdefault((b, ours), []).append(ms)
                print(f"round {r}: {b} {ours}: {ms:.1f} ms ({seg / 1e6:.1f} M segments/s)",
                      file=sys.stderr)

    print("| VTK integrator | VTK ms | tetray | method | tetray ms | VTK / tetray |")
    print("|---|---:|---|---|---:|---:|")
    for vtk_int, ours in pairs:
        v = statistics.median(results[("vtk", vtk_int)])
        for b in binaries:
            t = statistics.median(results[(b, ours)])
            print(f"| {vtk_int} | {v:.1f} | {b} | {ours} | {t:.1f} | {v / t:.2f} |")


if __name__ == "__main__":
    main()
