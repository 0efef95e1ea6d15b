//! Stresses below the surface of an elastic half-space (z >= 0 into the
//! body; tension positive) under a unit normal pressure on a cell of the
//! surface: the influence coefficients of the stress, as the deflection's
//! are in `crate::kernels`. Only Poisson's ratio enters: the stresses of a
//! given pressure do not depend on E.
//!
//! With Boussinesq's potentials of a pressure p over a region A,
//! `psi = int_A p / rho` and `psi1 = int_A p ln(rho + z)`
//! (`rho^2 = (x - xi)^2 + (y - eta)^2 + z^2`), the stresses are (Johnson
//! 1985, eq. 3.18)
//!
//! ```text
//!     sigma_x  = (1 / 2 pi) [2 nu psi_z - z psi_xx - (1 - 2 nu) psi1_xx]
//!     sigma_y  = (1 / 2 pi) [2 nu psi_z - z psi_yy - (1 - 2 nu) psi1_yy]
//!     sigma_z  = (1 / 2 pi) [psi_z - z psi_zz]
//!     tau_xy   = -(1 / 2 pi) [(1 - 2 nu) psi1_xy + z psi_xy]
//!     tau_xz   = -(1 / 2 pi) z psi_xz
//!     tau_yz   = -(1 / 2 pi) z psi_yz
//! ```
//!
//! For a uniform pressure on the rectangle `[x0 - a, x0 + a] x [y0 - b,
//! y0 + b]` (Love 1929) every derivative is a sum over the four corners,
//! `Q = G(X1, Y1) - G(X1, Y2) - G(X2, Y1) + G(X2, Y2)` with
//! `X1 = x - x0 + a`, `X2 = x - x0 - a` (likewise Y) and `R = sqrt(X^2 + Y^2
//! + z^2)`, of the corner functions
//!
//! ```text
//!     psi_z:   -atan(X Y / (z R))                psi_zz:  X Y / R (1 / (X^2 + z^2) + 1 / (Y^2 + z^2))
//!     psi_xx:  X / (R (R + Y))                   psi_yy:  Y / (R (R + X))
//!     psi_xy:  1 / R                             psi_xz:  z / (R (R + Y))      psi_yz: z / (R (R + X))
//!     psi1_xx: atan(X Y (R - z) / (X^2 R + z Y^2))   psi1_yy: atan(X Y (R - z) / (Y^2 R + z X^2))
//!     psi1_xy: ln(R + z)
//! ```
//!
//! On a line (plane strain), a uniform pressure on the strip `[x0 - a,
//! x0 + a]` gives, from Flamant's line load, the edge sums of
//!
//! ```text
//!     sigma_x: -(1 / pi) [atan(X / z) - X z / (X^2 + z^2)]
//!     sigma_z: -(1 / pi) [atan(X / z) + X z / (X^2 + z^2)]
//!     tau_xz:   (1 / pi) z^2 / (X^2 + z^2)          sigma_y = nu (sigma_x + sigma_z)
//! ```
//!
//! over `X` from `x - x0 - a` to `x - x0 + a`. A point force's
//! (Boussinesq's) stresses, [`point_force`], are the rectangle's far field:
//! they are what the point-force model's forces give, and they are valid a
//! cell or more below the surface, where a cell looks like a point.

/// A stress tensor (stress; tension positive; z into the body).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Stress {
    /// sigma_x.
    pub xx: f64,
    /// sigma_y.
    pub yy: f64,
    /// sigma_z.
    pub zz: f64,
    /// tau_xy.
    pub xy: f64,
    /// tau_xz.
    pub xz: f64,
    /// tau_yz.
    pub yz: f64,
}

impl Stress {
    /// `self + w other`.
    pub fn add_scaled(&mut self, w: f64, other: &Stress) {
        self.xx += w * other.xx;
        self.yy += w * other.yy;
        self.zz += w * other.zz;
        self.xy += w * other.xy;
        self.xz += w * other.xz;
        self.yz += w * other.yz;
    }

    /// The von Mises equivalent stress
    /// `sqrt(((sx - sy)^2 + (sy - sz)^2 + (sz - sx)^2) / 2 + 3 (txy^2 + txz^2 + tyz^2))`.
    pub fn von_mises(&self) -> f64 {
        let d =
            (self.xx - self.yy).powi(2) + (self.yy - self.zz).powi(2) + (self.zz - self.xx).powi(2);
        (0.5 * d + 3.0 * (self.xy * self.xy + self.xz * self.xz + self.yz * self.yz)).sqrt()
    }

    /// The principal stresses, largest first: the symmetric 3 x 3
    /// tensor's eigenvalues by cyclic Jacobi rotations, to rounding. (faer's
    /// self-adjoint eigensolver gives the same, but allocates on every call:
    /// a depth layer asks this at every one of up to 10^6 points.)
    pub fn principal(&self) -> [f64; 3] {
        let mut a = [
            [self.xx, self.xy, self.xz],
            [self.xy, self.yy, self.yz],
            [self.xz, self.yz, self.zz],
        ];
        let scale = a.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        for _ in 0..JACOBI_SWEEPS {
            let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
            if off <= f64::EPSILON * f64::EPSILON * scale || scale == 0.0 {
                break;
            }
            for (p, q) in [(0, 1), (0, 2), (1, 2)] {
                rotate(&mut a, p, q);
            }
        }
        let mut e = [a[0][0], a[1][1], a[2][2]];
        e.sort_by(|x, y| y.total_cmp(x));
        e
    }

    /// The largest shear stress (Tresca): half the spread of the principal
    /// stresses.
    pub fn tresca(&self) -> f64 {
        let [s1, _, s3] = self.principal();
        0.5 * (s1 - s3)
    }
}

/// Jacobi sweeps at most: each squares the off-diagonal's size, so a few
/// reach rounding from any start.
const JACOBI_SWEEPS: usize = 12;

/// The Jacobi rotation of the symmetric `a` in the plane (p, q) that zeroes
/// `a[p][q]` (Golub & Van Loan, Algorithm 8.5.1).
fn rotate(a: &mut [[f64; 3]; 3], p: usize, q: usize) {
    if a[p][q] == 0.0 {
        return;
    }
    let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
    let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
    let t = if theta == 0.0 { 1.0 } else { t };
    let c = 1.0 / (t * t + 1.0).sqrt();
    let s = t * c;
    for k in 0..3 {
        let (akp, akq) = (a[k][p], a[k][q]);
        a[k][p] = c * akp - s * akq;
        a[k][q] = s * akp + c * akq;
    }
    for k in 0..3 {
        let (apk, aqk) = (a[p][k], a[q][k]);
        a[p][k] = c * apk - s * aqk;
        a[q][k] = s * apk + c * aqk;
    }
}

/// The stresses at `(x, y, z)`, z > 0, of a unit uniform pressure on the
/// rectangle `[-dx/2, dx/2] x [-dy/2, dy/2]` of the surface of a
/// half-space of Poisson's ratio `nu` (Love 1929; see the [module
/// documentation](self)).
pub fn love_rectangle_stress(x: f64, y: f64, z: f64, dx: f64, dy: f64, nu: f64) -> Stress {
    let (a, b) = (0.5 * dx, 0.5 * dy);
    let (x1, x2) = (x + a, x - a);
    let (y1, y2) = (y + b, y - b);
    let at = |x, y| corner_functions(x, y, z);
    rectangle_from_corners([at(x1, y1), at(x1, y2), at(x2, y1), at(x2, y2)], z, nu)
}

/// Love's stresses at depth `z` of a unit pressure on the cell at every
/// lattice offset `(di dx, dj dy)`, `di < ni`, `dj < nj`, in `out` (row
/// `di` at `di nj`): [`love_rectangle_stress`] at each offset to rounding
/// (its corners at `(k - 1/2) dx` instead of `k dx ± dx/2`), each corner's
/// functions computed once for the four cells that share it, a row of
/// corners at a time.
pub(crate) fn love_rectangle_table(
    (ni, nj): (usize, usize),
    z: f64,
    (dx, dy): (f64, f64),
    nu: f64,
    out: &mut Vec<Stress>,
) {
    let corner_row = |k: usize| -> Vec<[f64; 10]> {
        let x = (k as f64 - 0.5) * dx;
        (0..=nj)
            .map(|l| corner_functions(x, (l as f64 - 0.5) * dy, z))
            .collect()
    };
    let mut low = corner_row(0);
    for di in 0..ni {
        let high = corner_row(di + 1);
        for dj in 0..nj {
            let c = [high[dj + 1], high[dj], low[dj + 1], low[dj]];
            out.push(rectangle_from_corners(c, z, nu));
        }
        low = high;
    }
}

/// The ten corner functions of Love's rectangle at corner `(x, y)`, depth
/// `z`: the potentials' derivatives `psi_z, psi_zz, psi_xx, psi_yy,
/// psi_xy, psi_xz, psi_yz, psi1_xx, psi1_yy, psi1_xy` before the sum over
/// the corners.
fn corner_functions(x: f64, y: f64, z: f64) -> [f64; 10] {
    let r = |x: f64, y: f64| (x * x + y * y + z * z).sqrt();
    // The `yy` and `yz` functions are the `xx` and `xz` ones with x and y
    // swapped (r is symmetric in them, to the last bit).
    let over = |x: f64, y: f64, top: f64| {
        let rr = r(x, y);
        top / (rr * (rr + y))
    };
    let angle = |x: f64, y: f64| {
        let rr = r(x, y);
        (x * y * (rr - z)).atan2(x * x * rr + z * y * y)
    };
    [
        -(x * y / (z * r(x, y))).atan(),
        x * y / r(x, y) * (1.0 / (x * x + z * z) + 1.0 / (y * y + z * z)),
        over(x, y, x),
        over(y, x, y),
        1.0 / r(x, y),
        over(x, y, z),
        over(y, x, z),
        angle(x, y),
        angle(y, x),
        (r(x, y) + z).ln(),
    ]
}

/// The rectangle's stresses from its corners' functions, in the order
/// `(x + a, y + b), (x + a, y - b), (x - a, y + b), (x - a, y - b)`.
fn rectangle_from_corners(c: [[f64; 10]; 4], z: f64, nu: f64) -> Stress {
    let psi = |f: usize| c[0][f] - c[1][f] - c[2][f] + c[3][f];
    from_potentials(
        z,
        nu,
        [psi(0), psi(1), psi(2), psi(3), psi(4), psi(5), psi(6)],
        [psi(7), psi(8), psi(9)],
    )
}

/// The stresses from the potentials' derivatives `[psi_z, psi_zz, psi_xx,
/// psi_yy, psi_xy, psi_xz, psi_yz]` and `[psi1_xx, psi1_yy, psi1_xy]`.
fn from_potentials(z: f64, nu: f64, psi: [f64; 7], psi1: [f64; 3]) -> Stress {
    let [psi_z, psi_zz, psi_xx, psi_yy, psi_xy, psi_xz, psi_yz] = psi;
    let [psi1_xx, psi1_yy, psi1_xy] = psi1;
    let k = 0.5 / std::f64::consts::PI;
    Stress {
        xx: k * (2.0 * nu * psi_z - z * psi_xx - (1.0 - 2.0 * nu) * psi1_xx),
        yy: k * (2.0 * nu * psi_z - z * psi_yy - (1.0 - 2.0 * nu) * psi1_yy),
        zz: k * (psi_z - z * psi_zz),
        xy: -k * ((1.0 - 2.0 * nu) * psi1_xy + z * psi_xy),
        xz: -k * z * psi_xz,
        yz: -k * z * psi_yz,
    }
}

/// The stresses at `(x, y, z)`, z > 0, of a unit normal point force at the
/// origin of the surface (Boussinesq; from the potentials `1 / rho` and
/// `ln(rho + z)`).
pub fn point_force(x: f64, y: f64, z: f64, nu: f64) -> Stress {
    let rho2 = x * x + y * y + z * z;
    let rho = rho2.sqrt();
    let (rho3, rho5) = (rho2 * rho, rho2 * rho2 * rho);
    let s = rho + z;
    // d2/dx2 ln(rho + z) = 1/(rho s) - x^2 (2 rho + z) / (rho^3 s^2), likewise y.
    let ln_xx = 1.0 / (rho * s) - x * x * (2.0 * rho + z) / (rho3 * s * s);
    let ln_yy = 1.0 / (rho * s) - y * y * (2.0 * rho + z) / (rho3 * s * s);
    let ln_xy = -x * y * (2.0 * rho + z) / (rho3 * s * s);
    from_potentials(
        z,
        nu,
        [
            -z / rho3,
            3.0 * z * z / rho5 - 1.0 / rho3,
            3.0 * x * x / rho5 - 1.0 / rho3,
            3.0 * y * y / rho5 - 1.0 / rho3,
            3.0 * x * y / rho5,
            3.0 * x * z / rho5,
            3.0 * y * z / rho5,
        ],
        [ln_xx, ln_yy, ln_xy],
    )
}

/// The plane-strain stresses at `(x, z)`, z > 0, of a unit uniform
/// pressure on the strip `[-h/2, h/2]` of a half-space of Poisson's ratio
/// `nu` (see the [module documentation](self)); `yy` is the out-of-plane
/// `nu (sigma_x + sigma_z)`, `xy` and `yz` zero.
pub fn strip_stress(x: f64, z: f64, h: f64, nu: f64) -> Stress {
    let edges = |g: &dyn Fn(f64) -> f64| g(x + 0.5 * h) - g(x - 0.5 * h);
    let atan = |t: f64| (t / z).atan();
    let frac = |t: f64| t * z / (t * t + z * z);
    let pi = std::f64::consts::PI;
    let xx = -edges(&|t| atan(t) - frac(t)) / pi;
    let zz = -edges(&|t| atan(t) + frac(t)) / pi;
    let xz = edges(&|t| z * z / (t * t + z * z)) / pi;
    Stress {
        xx,
        yy: nu * (xx + zz),
        zz,
        xy: 0.0,
        xz,
        yz: 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table of a layer's offsets, from shared corners, is Love's
    /// rectangle at each offset to rounding (relative to the largest
    /// component of the offset's stress and of the cell's own).
    #[test]
    fn the_layer_table_is_the_rectangle_at_each_offset() {
        let (dx, dy, nu) = (0.3, 0.2, 0.28);
        for z in [0.05, 0.4, 2.0] {
            let mut table = Vec::new();
            love_rectangle_table((7, 5), z, (dx, dy), nu, &mut table);
            assert_eq!(table.len(), 35);
            let own = love_rectangle_stress(0.0, 0.0, z, dx, dy, nu);
            let scale = [own.xx, own.yy, own.zz]
                .iter()
                .fold(0.0f64, |m, v| m.max(v.abs()));
            for di in 0..7 {
                for dj in 0..5 {
                    let (x, y) = (di as f64 * dx, dj as f64 * dy);
                    let e = love_rectangle_stress(x, y, z, dx, dy, nu);
                    let t = table[di * 5 + dj];
                    for (a, b) in [
                        (t.xx, e.xx),
                        (t.yy, e.yy),
                        (t.zz, e.zz),
                        (t.xy, e.xy),
                        (t.xz, e.xz),
                        (t.yz, e.yz),
                    ] {
                        assert!(
                            (a - b).abs() <= 1e-13 * scale,
                            "z {z} ({di}, {dj}): {a} vs {b}"
                        );
                    }
                }
            }
        }
    }

    /// Gauss-Legendre nodes and weights on [-1, 1] (16 points).
    fn gauss16() -> Vec<(f64, f64)> {
        // Newton iteration on the Legendre polynomial's roots.
        let n = 16;
        (0..n)
            .map(|i| {
                let mut t = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
                let mut dp = 0.0;
                for _ in 0..100 {
                    let (mut p0, mut p1) = (1.0, t);
                    for k in 2..=n {
                        let p2 = ((2 * k - 1) as f64 * t * p1 - (k - 1) as f64 * p0) / k as f64;
                        (p0, p1) = (p1, p2);
                    }
                    dp = n as f64 * (t * p1 - p0) / (t * t - 1.0);
                    t -= p1 / dp;
                }
                (t, 2.0 / ((1.0 - t * t) * dp * dp))
            })
            .collect()
    }

    /// The rectangle's stresses by quadrature of Boussinesq's point force
    /// over it, composite (m x m panels of 16 x 16 Gauss points).
    fn quadrature(x: f64, y: f64, z: f64, dx: f64, dy: f64, nu: f64, m: usize) -> Stress {
        let g = gauss16();
        let mut total = Stress::default();
        let (hx, hy) = (dx / m as f64, dy / m as f64);
        for i in 0..m {
            for j in 0..m {
                let (cx, cy) = (
                    -0.5 * dx + (i as f64 + 0.5) * hx,
                    -0.5 * dy + (j as f64 + 0.5) * hy,
                );
                for &(u, wu) in &g {
                    for &(v, wv) in &g {
                        let (xi, eta) = (cx + 0.5 * hx * u, cy + 0.5 * hy * v);
                        let w = wu * wv * 0.25 * hx * hy;
                        total.add_scaled(w, &point_force(x - xi, y - eta, z, nu));
                    }
                }
            }
        }
        total
    }

    fn close(a: &Stress, b: &Stress, tolerance: f64) {
        let scale = [a.xx, a.yy, a.zz, a.xy, a.xz, a.yz]
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        for (p, q) in [
            (a.xx, b.xx),
            (a.yy, b.yy),
            (a.zz, b.zz),
            (a.xy, b.xy),
            (a.xz, b.xz),
            (a.yz, b.yz),
        ] {
            assert!((p - q).abs() <= tolerance * scale, "{a:?} against {b:?}");
        }
    }

    #[test]
    fn the_rectangles_corner_formulas_are_the_point_force_integrated_over_it() {
        for &(x, y, z) in &[
            (0.0, 0.0, 0.5),
            (0.3, -0.2, 0.7),
            (1.7, 0.4, 0.6),
            (-0.45, 0.55, 0.3),
            (2.5, -3.0, 1.5),
            (0.5, 0.0, 0.9),
        ] {
            let (dx, dy, nu) = (1.0, 1.4, 0.3);
            let closed = love_rectangle_stress(x, y, z, dx, dy, nu);
            let numeric = quadrature(x, y, z, dx, dy, nu, 8);
            close(&closed, &numeric, 1e-9);
        }
    }

    #[test]
    fn far_from_its_cell_a_pressure_acts_as_its_resultant() {
        let (dx, dy, nu) = (0.1, 0.1, 0.25);
        let at = (0.3, -0.4, 2.0);
        let cell = love_rectangle_stress(at.0, at.1, at.2, dx, dy, nu);
        let mut point = point_force(at.0, at.1, at.2, nu);
        point = Stress {
            xx: point.xx * dx * dy,
            yy: point.yy * dx * dy,
            zz: point.zz * dx * dy,
            xy: point.xy * dx * dy,
            xz: point.xz * dx * dy,
            yz: point.yz * dx * dy,
        };
        // The difference is of the order (cell / distance)^2.
        close(&cell, &point, 1e-3);
    }

    #[test]
    fn at_the_surface_under_a_wide_pressure_sigma_z_is_the_pressure() {
        // Just below the middle of a large loaded square: sigma_z = -p and,
        // by the square's symmetry, sigma_x = sigma_y = -(1 + 2 nu) p / 2
        // (their sum is -(1 + 2 nu) p under any pressure at the surface).
        let s = love_rectangle_stress(0.0, 0.0, 1e-6, 100.0, 100.0, 0.3);
        assert!((s.zz + 1.0).abs() < 1e-6, "{s:?}");
        assert!(
            (s.xx + 0.8).abs() < 1e-6 && (s.yy + 0.8).abs() < 1e-6,
            "{s:?}"
        );
        // Under a wide strip (plane strain) sigma_x = sigma_z = -p.
        let t = strip_stress(0.0, 1e-6, 100.0, 0.3);
        assert!(
            (t.zz + 1.0).abs() < 1e-6 && (t.xx + 1.0).abs() < 1e-4,
            "{t:?}"
        );
        assert!((t.yy - 0.3 * (t.xx + t.zz)).abs() < 1e-15);
    }

    #[test]
    fn the_strips_formulas_are_flamants_line_load_integrated_over_it() {
        let flamant = |x: f64, z: f64| {
            let d = (x * x + z * z).powi(2);
            let k = -2.0 / std::f64::consts::PI;
            (k * x * x * z / d, k * z * z * z / d, k * x * z * z / d)
        };
        let g = gauss16();
        for &(x, z) in &[(0.0, 0.3), (0.8, 0.5), (-1.3, 0.2), (2.0, 1.5)] {
            let h = 1.0;
            let m = 16;
            let (mut sx, mut sz, mut txz) = (0.0, 0.0, 0.0);
            for i in 0..m {
                let c = -0.5 * h + (i as f64 + 0.5) * h / m as f64;
                for &(u, w) in &g {
                    let xi = c + 0.5 * h / m as f64 * u;
                    let (a, b, t) = flamant(x - xi, z);
                    let w = w * 0.5 * h / m as f64;
                    (sx, sz, txz) = (sx + w * a, sz + w * b, txz + w * t);
                }
            }
            let s = strip_stress(x, z, h, 0.3);
            assert!((s.xx - sx).abs() < 1e-10, "{x} {z}: {} {sx}", s.xx);
            assert!((s.zz - sz).abs() < 1e-10, "{x} {z}: {} {sz}", s.zz);
            assert!((s.xz - txz).abs() < 1e-10, "{x} {z}: {} {txz}", s.xz);
        }
    }

    #[test]
    fn invariants_of_a_known_tensor() {
        // Uniaxial tension 2: von Mises 2, Tresca 1, principal (2, 0, 0).
        let s = Stress {
            xx: 2.0,
            ..Stress::default()
        };
        assert!((s.von_mises() - 2.0).abs() < 1e-15);
        assert!((s.tresca() - 1.0).abs() < 1e-14);
        // Pure shear tau: principal (tau, 0, -tau), von Mises sqrt(3) tau.
        let t = Stress {
            xz: 1.5,
            ..Stress::default()
        };
        let [a, b, c] = t.principal();
        assert!((a - 1.5).abs() < 1e-12 && b.abs() < 1e-12 && (c + 1.5).abs() < 1e-12);
        assert!((t.von_mises() - 1.5 * 3f64.sqrt()).abs() < 1e-12);
        // A general tensor: the principal stresses keep the trace and
        // the von Mises invariant.
        let g = Stress {
            xx: -3.0,
            yy: 1.0,
            zz: 0.5,
            xy: 0.7,
            xz: -1.1,
            yz: 0.4,
        };
        let p = g.principal();
        assert!((p.iter().sum::<f64>() - (g.xx + g.yy + g.zz)).abs() < 1e-12);
        let from_principal =
            (0.5 * ((p[0] - p[1]).powi(2) + (p[1] - p[2]).powi(2) + (p[2] - p[0]).powi(2))).sqrt();
        assert!((from_principal - g.von_mises()).abs() < 1e-12);
        assert!(p[0] >= p[1] && p[1] >= p[2]);
    }
}
