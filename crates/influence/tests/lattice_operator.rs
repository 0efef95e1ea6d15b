//! Reference values for the matrix-free lattice operator: closed forms of
//! loads spread over many cells, on grids too large for a quick dense S.
//!
//! A uniform pressure over every cell of a grid is, by superposition, the
//! same pressure over the grid's whole rectangle (or strip): the operator's
//! product must equal the single-patch closed form at every point. A Hertz
//! pressure must give Hertz's parabolic deflection, to the discretization
//! error.

use std::f64::consts::PI;

use elcon_influence::{
    Body, LatticeOperator, Material, PointSet, combined_modulus, love_rectangle, plane_strain_strip,
};

fn steel() -> Material {
    Material::new(210e9, 0.3).unwrap()
}

fn aluminium() -> Material {
    Material::new(70e9, 0.33).unwrap()
}

#[test]
fn uniform_pressure_on_a_rectangle_is_loves_rectangle() {
    // 151 x 101 cells of 20 x 30 um (N = 15,251); Love's deflection of the
    // whole 3.02 x 3.03 mm rectangle, p a b love_rectangle(x, y, a, b) / (pi E*),
    // at every cell centre. Superposition is exact, so the difference is the
    // rounding of the kernel (~1e-15 relative) and of the FFT (~1e-15 of the
    // largest value); 1e-12 leaves a margin and catches any missing cell
    // (each is ~1e-4 of the total).
    let (nx, ny, a, b) = (151, 101, 3.02e-3, 3.03e-3);
    let points = PointSet::grid_rectangle(a / 2.0, b / 2.0, nx, ny).unwrap();
    let bodies = [
        &Body::uniform_patch(steel()),
        &Body::uniform_patch(aluminium()),
    ];
    let mut op = LatticeOperator::new(&points, &bodies).unwrap();
    let p = 2.0e8; // Pa
    let forces: Vec<f64> = (0..points.len()).map(|k| p * points.measure(k)).collect();
    let mut w = vec![0.0; points.len()];
    op.apply(&forces, &mut w);
    let e_star = combined_modulus(&steel(), &aluminium());
    let mut largest_error = 0.0f64;
    for k in 0..points.len() {
        let expected = p * a * b * love_rectangle(points.x(k), points.y(k), a, b) / (PI * e_star);
        largest_error = largest_error.max((w[k] / expected - 1.0).abs());
    }
    assert!(largest_error < 1e-12, "{largest_error:e}");
    // The centre: 2 p / (pi E*) (a asinh(b/a) + b asinh(a/b)) (Love 1929).
    let centre = (0..points.len())
        .position(|k| points.radius(k) < 1e-12)
        .unwrap();
    let closed = 2.0 * p / (PI * e_star) * (a * (b / a).asinh() + b * (a / b).asinh());
    assert!((w[centre] / closed - 1.0).abs() < 1e-12);
}

#[test]
fn uniform_pressure_on_a_strip_is_the_whole_strip() {
    // 2000 strips of a 4 mm band, datum 12 mm: the plane-strain deflection of
    // the band under p, 2 p L plane_strain_strip(x, L, d0) / (pi E*), by
    // superposition of the strips' logarithmic kernels. Tolerance as above.
    let (n, length, d0) = (2000, 4e-3, 12e-3);
    let line = PointSet::line(-length / 2.0, length / 2.0, n).unwrap();
    let bodies = [
        &Body::plane_strain(steel(), d0),
        &Body::plane_strain(steel(), d0),
    ];
    let mut op = LatticeOperator::new(&line, &bodies).unwrap();
    let p = 5.0e7; // Pa; forces per unit width, N/m
    let forces: Vec<f64> = (0..n).map(|k| p * line.measure(k)).collect();
    let mut w = vec![0.0; n];
    op.apply(&forces, &mut w);
    let e_star = combined_modulus(&steel(), &steel());
    for k in 0..n {
        let expected = 2.0 * p * length * plane_strain_strip(line.x(k), length, d0) / (PI * e_star);
        assert!((w[k] / expected - 1.0).abs() < 1e-12, "x = {}", line.x(k));
    }
}

#[test]
fn hertz_pressure_gives_hertz_deflection() {
    // p = p0 sqrt(1 - r^2/a^2) on a disk of radius a deflects the two
    // surfaces by pi p0 (2 a^2 - r^2) / (4 a E*) inside the contact
    // (Johnson 1985, eq. 3.41a). Forces p(r_k) h^2 at the cell centres: the
    // discretization error is largest at the edge, where p has an infinite
    // slope; inside r < 0.9 a it decreases with h. At a/h = 80 (N = 20,081)
    // the dense S would take 3.2 GB; the operator about 1 MB.
    let e_star = combined_modulus(&steel(), &steel());
    let (a, p0) = (1.0e-3, 1.0e9);
    let mut errors = Vec::new();
    for cells in [40.0, 80.0] {
        let h = a / cells;
        let points = PointSet::grid_disk(h, a).unwrap();
        let bodies = [&Body::uniform_patch(steel()), &Body::uniform_patch(steel())];
        let mut op = LatticeOperator::new(&points, &bodies).unwrap();
        let forces: Vec<f64> = (0..points.len())
            .map(|k| p0 * (1.0 - (points.radius(k) / a).powi(2)).max(0.0).sqrt() * h * h)
            .collect();
        let mut w = vec![0.0; points.len()];
        op.apply(&forces, &mut w);
        let error = (0..points.len())
            .filter(|&k| points.radius(k) < 0.9 * a)
            .map(|k| {
                let r = points.radius(k);
                let hertz = PI * p0 * (2.0 * a * a - r * r) / (4.0 * a * e_star);
                (w[k] / hertz - 1.0).abs()
            })
            .fold(0.0f64, f64::max);
        errors.push(error);
    }
    // Measured 5.5e-4 at a/h = 40 and 2.0e-4 at a/h = 80 (about h^1.4): the
    // bounds leave ~40 % and require the error to fall with h.
    assert!(errors[0] < 8e-4, "{errors:?}");
    assert!(errors[1] < 3e-4, "{errors:?}");
    assert!(errors[1] < 0.5 * errors[0], "{errors:?}");
}
