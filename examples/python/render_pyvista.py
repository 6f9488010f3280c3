"""Render a real dataset read by PyVista with tetray and show it with
matplotlib.

    pip install ./crates/python pyvista matplotlib
    python examples/python/render_pyvista.py [MESH] [--scalars NAME] [--save out.png]

By default it reads data/real/disk_out_ref.ex2 (ParaView's disk_out_ref
sample, Exodus II) with PyVista's reader (VTK's), renders its temperature
with tetray from PyVista's mesh (no file written in between), then an orbit
of four views of the same Scene, and shows them; with --save it writes the
figure instead (no display needed).
"""

from __future__ import annotations

import argparse
import pathlib
import time

import matplotlib

REPO = pathlib.Path(__file__).resolve().parents[2]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mesh", nargs="?", default=REPO / "data" / "real" / "disk_out_ref.ex2")
    parser.add_argument("--scalars", default="Temp")
    parser.add_argument("--size", type=int, nargs=2, default=(400, 400), metavar=("W", "H"))
    parser.add_argument("--save", help="write the figure here instead of showing it")
    args = parser.parse_args()
    if args.save:
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pyvista as pv

    import tetray

    mesh = pv.read(args.mesh)
    print(mesh)

    start = time.perf_counter()
    scene = tetray.Scene(mesh, args.scalars, size=args.size, cmap="inferno", opacity="linear")
    print(f"scene ready in {time.perf_counter() - start:.2f} s on {scene.info['adapter']} "
          f"({scene.info['tets']} tetrahedra, {scene.info['field']} in {scene.info['range']})")
    start = time.perf_counter()
    views = scene.orbit(4)
    print(f"4 views in {time.perf_counter() - start:.2f} s")

    fig, axes = plt.subplots(1, 4, figsize=(16, 4.4), facecolor="black")
    for k, (ax, image) in enumerate(zip(axes, views)):
        # Premultiplied RGBA over black: what the CLI's PNG shows.
        ax.imshow(tetray.to_rgb8(image, background=(0.0, 0.0, 0.0)))
        ax.set_title(f"azimuth +{90 * k} deg", color="white")
        ax.axis("off")
    fig.suptitle(f"{pathlib.Path(args.mesh).name}: {scene.info['field']} (tetray, PyVista mesh)", color="white")
    fig.tight_layout()
    if args.save:
        fig.savefig(args.save, facecolor="black")
        print(f"wrote {args.save}")
    else:
        plt.show()


if __name__ == "__main__":
    main()
