#!/usr/bin/python3
"""The image of a VTK XML unstructured grid rendered by VTK's
unstructured-grid ray caster beside tetray's, with one transfer-function
file read by both, and how far apart they are.

VTK: vtkUnstructuredGridVolumeRayCastMapper on the grid split into
tetrahedra (vtkDataSetTriangleFilter), its linear integrator (exact for
linear scalars, as tetray's exact method), opacity per unit distance as
VTK applies it (tetray's --opacity-mode vtk), ResetCamera, azimuth,
elevation, every pixel cast, over black. tetray: `tetray render
--renderer cpu --integrator exact` with VTK's camera (position, focal
point, view up, view angle) and the same preset, unit distance and range.

Printed per tetray binary: lit pixels (either image's alpha above 2/255),
the share of them whose colour differs by more than 2/255 in some channel,
the 99th percentile and the maximum of that difference; the images are
written as PNG beside each other (--out).

    target/python-venv/bin/python tools/vtk_image_diff.py data/real/can.vtu \\
        --field EQPS --tetray target/release/tetray --out /tmp/can
"""

import argparse
import json
import os
import subprocess
import sys

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


def vtk_render(grid, tf, unit, size, azimuth, elevation):
    import vtk

    prop = volume_property(tf, unit)
    window, camera, mapper, _ = volume_window(
        tetrahedra(grid), prop, size, azimuth, elevation, offscreen=True
    )
    mapper.SetRayIntegrator(vtk.vtkUnstructuredGridLinearRayIntegrator())
    window.Render()
    return read_back(window, size), view_of(camera)


def tetray_render(binary, path, field, tf_path, unit, size, view, out):
    args = [
        binary, "render", path, "--scalar", field, "--renderer", "cpu",
        "--integrator", "exact", "--tf", tf_path, "--no-rescale",
        "--unit-distance", repr(unit), "--opacity-mode", "vtk", *view,
        "--size", f"{size}x{size}", "-o", out,
    ]
    run = subprocess.run(args, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"{binary}: {run.stderr}")
    return np.load(out).astype(np.float64)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mesh")
    parser.add_argument("--field", required=True)
    parser.add_argument("--tetray", action="append", required=True)
    parser.add_argument("--size", type=int, default=400)
    parser.add_argument("--azimuth", type=float, default=30.0)
    parser.add_argument("--elevation", type=float, default=20.0)
    parser.add_argument("--out", default="vtk-image-diff")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)

    grid = point_grid(args.mesh, args.field)
    lo, hi = grid.GetPointData().GetArray(args.field).GetRange()
    unit = paraview_unit_distance(grid.GetBounds(), grid.GetNumberOfCells())
    tf = preset(lo, hi, "eqps-study")
    tf_path = os.path.join(args.out, "tf.json")
    with open(tf_path, "w") as f:
        json.dump(tf, f)

    reference, view = vtk_render(grid, tf, unit, args.size, args.azimuth, args.elevation)
    save_png(reference, os.path.join(args.out, "vtk.png"))
    print(f"{args.mesh} {args.field} range [{lo:.4g}, {hi:.4g}], unit distance {unit:.4g}, "
          f"{args.size} x {args.size}, azimuth {args.azimuth}, elevation {args.elevation}")
    print("| tetray | lit pixels | share > 2/255 | p99 | max |")
    print("| --- | ---: | ---: | ---: | ---: |")
    for k, binary in enumerate(args.tetray):
        image = tetray_render(binary, args.mesh, args.field, tf_path, unit, args.size, view,
                              os.path.join(args.out, f"tetray{k}.npy"))
        # Premultiplied colour over black is what VTK's window shows.
        rgb = np.clip(image[..., :3], 0.0, 1.0)
        save_png(rgb, os.path.join(args.out, f"tetray{k}.png"))
        lit = (reference[..., 3] > 2 / 255) | (image[..., 3] > 2 / 255)
        diff = np.abs(rgb - reference[..., :3]).max(axis=2)[lit]
        share = float((diff > 2 / 255).mean())
        print(f"| {binary} | {int(lit.sum())} | {100 * share:.2f}% | "
              f"{np.percentile(diff, 99):.3f} | {diff.max():.3f} |")


if __name__ == "__main__":
    main()
