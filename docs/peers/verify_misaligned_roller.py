"""The misaligned roller's designed crown checked by an independent solver.

`cargo run --release --example misaligned_roller` designs a free crown (a
natural cubic spline through 40 knots) for 33 cases -- a steel roller,
D = 10 mm, l = 10 mm, on a flat steel raceway, at 1, 5 and 10 kN, each
misaligned by 0 to 1 mrad about x -- and writes it to
out/misaligned_roller/designed_profile.csv with the worst p_max / p0 it
reports on its own design grid. This script takes that profile and solves
the same 33 cases with ContactMechanics (FreeFFTElasticHalfSpace, Love's
uniform-pressure cells by DC-FFT, and its Polonsky-Keer constrained
conjugate gradient, load-controlled) on a grid `--factor` times finer than
the design's (default 3: the design's 18 x 80 cells become 54 x 240), and
prints each load's worst p_max / p0 and the worst over all cases beside
elcon's.

The gap of each case is the cylinder's `x^2 / (2 R)`, plus the crown's drop
at y (the spline, its end slopes carried on beyond its end knots), less the
prescribed misalignment's `theta y`; the rotation about y is free and zero
by the mirror about x = 0, as in elcon.

Kept out of CI. Usage (numpy, scipy, contactmechanics from PyPI):

    python verify_misaligned_roller.py [--profile out/misaligned_roller/designed_profile.csv]
                                       [--design-cells 18 80] [--factor 3]
"""
import argparse
import json
import time

import numpy as np
from ContactMechanics import FreeFFTElasticHalfSpace
from ContactMechanics.Optimization import constrained_conjugate_gradients
from scipy.interpolate import CubicSpline

RADIUS, LENGTH = 5.0, 10.0                     # mm
E, NU = 210e3, 0.3                             # MPa
E_STAR = E / (2.0 * (1.0 - NU**2))             # both bodies steel
LOADS = [1e3, 5e3, 10e3]                       # N
ANGLES = [i / 1e4 for i in range(11)]          # rad


def read_profile(path):
    """The knots, drops and elcon's reported objective."""
    with open(path) as f:
        comment = f.readline()
    objective = float(comment.split("p_max/p0 ")[1].split()[0])
    table = np.loadtxt(path, delimiter=",", skiprows=2)
    return table[:, 0], table[:, 1], objective


def crown(knots, drops):
    """The natural cubic spline, carried on along its end slopes."""
    spline = CubicSpline(knots, drops, bc_type="natural")
    slope = spline.derivative()
    lo, hi = knots[0], knots[-1]

    def drop(y):
        inside = spline(np.clip(y, lo, hi))
        below = drops[0] + slope(lo) * (y - lo)
        above = drops[-1] + slope(hi) * (y - hi)
        return np.where(y < lo, below, np.where(y > hi, above, inside))

    return drop


def solve(load, angle, drop, cells):
    """p_max / p0 of one case on nx x ny cells."""
    per_length = load / LENGTH
    b = np.sqrt(4.0 * per_length * RADIUS / (np.pi * E_STAR))
    p0 = 2.0 * per_length / (np.pi * b)
    nx, ny = cells
    width = 2.0 * 1.6 * b
    x = (np.arange(nx) + 0.5) * width / nx - 0.5 * width
    y = (np.arange(ny) + 0.5) * LENGTH / ny - 0.5 * LENGTH
    xx, yy = np.meshgrid(x, y, indexing="ij")
    separation = xx**2 / (2.0 * RADIUS) + drop(yy) - angle * yy
    substrate = FreeFFTElasticHalfSpace((nx, ny), E_STAR, (width, LENGTH))
    result = constrained_conjugate_gradients(
        substrate, -separation, external_force=load, pentol=1e-10 * separation.max(),
        forcetol=1e-10 * load / (nx * ny), thermotol=1e-12, maxiter=100000)
    if not result.success:
        raise RuntimeError(f"{load} N at {angle} rad: not converged ({result.message})")
    pressure = result.jac / ((width / nx) * (LENGTH / ny))
    return pressure.max() / p0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--profile", default="out/misaligned_roller/designed_profile.csv")
    parser.add_argument("--design-cells", nargs=2, type=int, default=[18, 80])
    parser.add_argument("--factor", type=int, default=3)
    args = parser.parse_args()
    knots, drops, reported = read_profile(args.profile)
    drop = crown(knots, drops)
    cells = (args.design_cells[0] * args.factor, args.design_cells[1] * args.factor)
    start = time.perf_counter()
    worst = 0.0
    for load in LOADS:
        values = [solve(load, angle, drop, cells) for angle in ANGLES]
        worst = max(worst, max(values))
        print(json.dumps({"load_N": load, "worst_pmax_over_p0": max(values),
                          "by_angle": [round(v, 5) for v in values]}), flush=True)
    relative = worst / reported - 1.0
    print(f"ContactMechanics on {cells[0]} x {cells[1]} cells: worst p_max/p0 {worst:.4f}; "
          f"elcon reported {reported:.4f} on its design grid; difference {relative:+.2%} "
          f"({time.perf_counter() - start:.0f} s)")


if __name__ == "__main__":
    main()
