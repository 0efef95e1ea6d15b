#!/usr/bin/env python3
"""Writes the data files of two example scenes (standard library only):

- scenes/data/rough-surface.npy: a self-affine random surface (Hurst
  exponent H = 0.8, power spectrum C(q) ~ q^(-2 (1 + H)) between the
  wavelengths 0.32 mm and 0.02 mm, random phases, seed 29), 128 x 128
  heights at 0.005 mm, scaled to an RMS height of 0.2 um (mm), as a
  profilometer's map would come; for rough-sphere.toml.
- scenes/data/measured-crown.csv: a roller's crown as a measurement
  would give it, (y, drop) in mm at 0.25 mm over the 10 mm roller: a
  logarithmic crown d(y) = -k ln(1 - 0.95 u^2), u = (|y| - 3) / 2 beyond
  a 6 mm flat middle (k = 4 um), plus a 0.1 um grinding ripple of
  wavelength 0.8 mm; for measured-crown.toml.

Run from the repository's root: python3 examples/make_surface_data.py
"""

import cmath
import math
import os
import random
import struct

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "scenes", "data")


def rough_surface(n=128, spacing=0.005, hurst=0.8, rms=2e-4, seed=29):
    """Heights Z[j][i] of a random surface by spectral synthesis: the sum of
    the modes (kx, ky) with amplitude |q|^-(1 + H) and a random phase, done
    as two small matrix products (separable exponentials)."""
    rng = random.Random(seed)
    length = n * spacing
    kmin, kmax = 2, 32  # wavelengths length/2 = 0.32 mm to length/32 = 0.02 mm
    ks = range(-kmax, kmax + 1)
    amp = {}
    for kx in ks:
        for ky in range(0, kmax + 1):
            q = math.hypot(kx, ky)
            if kmin <= q <= kmax:
                amp[(kx, ky)] = q ** -(1.0 + hurst) * cmath.exp(2j * math.pi * rng.random())
    ex = [[cmath.exp(2j * math.pi * kx * i / n) for kx in ks] for i in range(n)]
    ey = [[cmath.exp(2j * math.pi * ky * j / n) for ky in range(kmax + 1)] for j in range(n)]
    # B[kx][j] = sum_ky A[kx, ky] ey[j][ky]; Z[j][i] = Re sum_kx ex[i][kx] B[kx][j].
    b = [[sum(amp.get((kx, ky), 0) * ey[j][ky] for ky in range(kmax + 1)) for j in range(n)]
         for kx in ks]
    z = [[sum(ex[i][a] * b[a][j] for a in range(len(ks))).real for i in range(n)]
         for j in range(n)]
    mean = sum(map(sum, z)) / n**2
    scale = rms / math.sqrt(sum((v - mean) ** 2 for row in z for v in row) / n**2)
    return [[(v - mean) * scale for v in row] for row in z]


def write_npy(path, rows):
    """A version-1 .npy file of float64, C order, shape (len(rows), len(rows[0]))."""
    header = "{'descr': '<f8', 'fortran_order': False, 'shape': (%d, %d), }" % (
        len(rows), len(rows[0]))
    header += " " * ((64 - (10 + len(header) + 1) % 64) % 64) + "\n"
    with open(path, "wb") as f:
        f.write(b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode())
        for row in rows:
            f.write(struct.pack("<%dd" % len(row), *row))


def measured_crown(half_length=5.0, flat=3.0, k=0.004, ripple=1e-4, step=0.25):
    """(y, drop) rows: -k ln(1 - 0.95 u^2), u = (|y| - flat) / (L - flat)
    beyond the flat, plus a ripple of amplitude `ripple`, wavelength 0.8 mm."""
    rows = []
    n = int(round(2 * half_length / step))
    for i in range(n + 1):
        y = -half_length + i * step
        u = max(0.0, abs(y) - flat) / (half_length - flat)
        drop = -k * math.log(max(1.0 - 0.95 * u * u, 1e-12))
        rows.append((y, drop + ripple * math.sin(2 * math.pi * y / 0.8)))
    return rows


def main():
    os.makedirs(HERE, exist_ok=True)
    write_npy(os.path.join(HERE, "rough-surface.npy"), rough_surface())
    with open(os.path.join(HERE, "measured-crown.csv"), "w") as f:
        f.write("# y (mm), drop (mm): written by examples/make_surface_data.py\n")
        for y, d in measured_crown():
            f.write("%.4f, %.9f\n" % (y, d))


if __name__ == "__main__":
    main()
