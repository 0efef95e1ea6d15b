//! Tests of the lattice operator: its products against the dense S of
//! [`assemble`](crate::assemble) on every grid and model, its workspaces,
//! its memory against the estimate, and what it refuses.

use faer::{Col, Mat};

use super::grid::padded_length;
use super::{LatticeKernel, LatticeOperator, LatticeWorkspace};
use crate::assembly::assemble;
use crate::error::InfluenceError;
use crate::error::try_vec;
use crate::fixtures::{BEAM, disk_and_reversed, pool, scattered, sparse_pair, surface};
use crate::material::Material;
use crate::models::Body;
use crate::points::{Cell, Dimension, PointSet};

/// `max |S x - op x| / max |S x|` is at most this. The FFT's rounding is
/// a few eps log2(P1 P2) of the sum of |K| |x| entering a value, about
/// 1e-15 on these grids (measured at most 1.2e-15 over every case here,
/// signed x included); a wrong offset, padding or scale gives 1e-2 to 1.
const TOLERANCE: f64 = 1e-12;

fn steel() -> Material {
    Material::new(30e6, 0.3).unwrap()
}

fn aluminium() -> Material {
    Material::new(10e6, 0.33).unwrap()
}

/// A reproducible x in [lo, 1) (xorshift; no dev-dependency needed).
fn random_vector(n: usize, seed: u64, lo: f64) -> Vec<f64> {
    let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    (0..n)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            lo + (1.0 - lo) * (state >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect()
}

/// The relative error of the operator against the dense S on x.
fn relative_error(s: &Mat<f64>, op: &mut LatticeOperator, x: &[f64]) -> f64 {
    let dense = s * Col::<f64>::from_fn(x.len(), |k| x[k]);
    let mut y = vec![0.0; x.len()];
    op.apply(x, &mut y);
    let scale = dense.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let error = (0..x.len()).fold(0.0f64, |m, k| m.max((dense[k] - y[k]).abs()));
    error / scale
}

/// The grids: disks (odd extents), rectangles odd and even, square and
/// oblong cells, a single row and a single point.
fn grids() -> Vec<(&'static str, PointSet)> {
    vec![
        ("disk r = 3.2 h", PointSet::grid_disk(0.1, 0.32).unwrap()),
        ("disk r = 5 h", PointSet::grid_disk(0.2, 1.0).unwrap()),
        (
            "rectangle 7 x 5, oblong cells",
            PointSet::grid_rectangle(0.7, 2.0, 7, 5).unwrap(),
        ),
        (
            "rectangle 8 x 6, square cells",
            PointSet::grid_rectangle(0.4, 0.3, 8, 6).unwrap(),
        ),
        (
            "rectangle 4 x 9",
            PointSet::grid_rectangle(1.0, 3.0, 4, 9).unwrap(),
        ),
        (
            "row 12 x 1",
            PointSet::grid_rectangle(1.0, 0.05, 12, 1).unwrap(),
        ),
        (
            "one point",
            PointSet::grid_rectangle(1.0, 1.0, 1, 1).unwrap(),
        ),
    ]
}

fn surface_bodies() -> Vec<(&'static str, Vec<Body>)> {
    vec![
        (
            "patch + patch",
            vec![Body::uniform_patch(steel()), Body::uniform_patch(steel())],
        ),
        (
            "point + point, two materials",
            vec![Body::point_force(steel()), Body::point_force(aluminium())],
        ),
        (
            "patch + point",
            vec![Body::uniform_patch(aluminium()), Body::point_force(steel())],
        ),
        (
            "rigid + patch",
            vec![Body::rigid(), Body::uniform_patch(aluminium())],
        ),
        (
            "patch on a foundation",
            vec![Body::uniform_patch(steel()), Body::winkler(3e8)],
        ),
        ("foundation alone", vec![Body::winkler(3e8), Body::rigid()]),
    ]
}

fn check(name: &str, points: &PointSet, bodies: &[Body]) {
    let refs: Vec<&Body> = bodies.iter().collect();
    let s = assemble(points, &refs).unwrap();
    let mut op = LatticeOperator::new(points, &refs).unwrap();
    assert_eq!(op.len(), points.len());
    for (seed, lo) in [(1, 0.0), (2, -1.0)] {
        let x = random_vector(points.len(), seed, lo);
        let e = relative_error(&s, &mut op, &x);
        assert!(e <= TOLERANCE, "{name}, x in [{lo}, 1): {e:e}");
    }
    for k in 0..points.len() {
        assert_eq!(op.diagonal(), s[(k, k)], "{name}: S_{k}{k}");
    }
    check_columns(name, &s, &op);
}

/// `add_columns` adds the dense S's columns: `y0 + S d` for a `d` on a
/// few points (the first, one in the middle, the last, repeated), to
/// rounding relative to the largest `|S d|`, and the same as the FFT
/// product of `d`.
fn check_columns(name: &str, s: &Mat<f64>, op: &LatticeOperator) {
    let n = op.len();
    let columns = [(n / 2, 0.7), (0, -1.3), (n - 1, 2.1), (n / 2, 0.4)];
    let mut d = vec![0.0; n];
    columns.iter().for_each(|&(p, v)| d[p] += v);
    let y0 = random_vector(n, 11, -1.0);
    let mut y = y0.clone();
    op.add_columns(&columns, &mut y);
    let dense = s * Col::<f64>::from_fn(n, |k| d[k]);
    let mut product = vec![0.0; n];
    let mut workspace = op.workspace().unwrap();
    op.apply_with(&d, &mut product, &mut workspace);
    let scale = dense.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for k in 0..n {
        let (added, expected) = (y[k] - y0[k], dense[k]);
        assert!(
            (added - expected).abs() <= 1e-14 * scale + 4.0 * f64::EPSILON * y0[k].abs(),
            "{name}: column sum at {k}: {added:e} vs {expected:e}"
        );
        assert!(
            (added - product[k]).abs() <= TOLERANCE * scale + 4.0 * f64::EPSILON * y0[k].abs(),
            "{name}: against the product at {k}"
        );
    }
}

#[test]
fn columns_are_the_same_to_the_bit_on_any_number_of_threads() {
    let points = PointSet::grid_disk(0.1, 3.0).unwrap();
    let bodies = [&Body::uniform_patch(steel()), &Body::point_force(steel())];
    let op = LatticeOperator::new(&points, &bodies).unwrap();
    let n = op.len();
    let columns: Vec<(usize, f64)> = (0..40).map(|t| ((t * 97) % n, t as f64 - 19.5)).collect();
    let run = |threads| {
        pool(threads).install(|| {
            let mut y = random_vector(n, 3, -1.0);
            op.add_columns(&columns, &mut y);
            y.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
        })
    };
    assert_eq!(run(1), run(2));
    assert_eq!(run(1), run(3));
    assert!(op.columns_per_product() >= 1);
}

#[test]
fn equals_the_dense_s_on_every_surface_grid_and_model() {
    for (grid, points) in grids() {
        for (models, bodies) in surface_bodies() {
            check(&format!("{grid}, {models}"), &points, &bodies);
        }
    }
}

#[test]
fn equals_the_dense_s_on_a_line() {
    // The plane-strain strip is a translation-invariant kernel too.
    for n in [1, 2, 9, 16] {
        let line = PointSet::line(-1.0, 1.0, n).unwrap();
        check(
            &format!("line of {n}, strips"),
            &line,
            &[
                Body::plane_strain(steel(), 3.0),
                Body::plane_strain(aluminium(), 3.0),
            ],
        );
        check(
            &format!("line of {n}, strip on a foundation"),
            &line,
            &[Body::plane_strain(steel(), 10.0), Body::winkler(5e6)],
        );
    }
}

#[test]
fn follows_the_order_of_a_shuffled_irregular_lattice() {
    // An L-shaped set on a lattice, in a scrambled order, from
    // PointSet::from_points: the gather order is not the lattice order.
    let (mut xs, mut ys) = (Vec::new(), Vec::new());
    for t in 0..60usize {
        let k = (t * 37) % 60;
        let (i, j) = (k / 6, k % 6);
        if i < 4 || j < 2 {
            xs.push(0.5 + i as f64 * 0.25);
            ys.push(-1.0 + j as f64 * 0.4);
        }
    }
    let points =
        PointSet::from_points(Dimension::Surface, xs, ys, Cell { dx: 0.25, dy: 0.4 }).unwrap();
    assert!(points.lattice().is_some());
    for (models, bodies) in surface_bodies() {
        check(&format!("L-shape, {models}"), &points, &bodies);
    }
}

#[test]
fn a_shared_workspace_gives_the_same_product() {
    let points = PointSet::grid_disk(0.1, 0.55).unwrap();
    let bodies = [&Body::uniform_patch(steel()), &Body::point_force(steel())];
    let mut op = LatticeOperator::new(&points, &bodies).unwrap();
    let x = random_vector(points.len(), 7, -1.0);
    let (mut a, mut b, mut c) = (vec![0.0; x.len()], vec![0.0; x.len()], vec![0.0; x.len()]);
    op.apply(&x, &mut a);
    op.apply(&x, &mut b); // the workspace holds the last product's values
    let mut ws = op.workspace().unwrap();
    op.apply_with(&x, &mut c, &mut ws);
    assert_eq!(a, b);
    assert_eq!(a, c);
    // A kernel alone: the same product, the workspace's bytes fewer.
    let kernel = LatticeKernel::new(&points, &bodies).unwrap();
    assert_eq!(kernel.memory_bytes() + ws.memory_bytes(), op.memory_bytes());
    assert_eq!(kernel.memory_bytes(), op.kernel().memory_bytes());
    let mut d = vec![0.0; x.len()];
    kernel.apply_with(&x, &mut d, &mut ws);
    assert_eq!(a, d);
    // Shared between threads, one workspace each.
    let shared = &op;
    std::thread::scope(|scope| {
        for seed in [1, 2] {
            scope.spawn(move || {
                let mut ws = shared.workspace().unwrap();
                let x = random_vector(shared.len(), seed, 0.0);
                let mut y = vec![0.0; x.len()];
                shared.apply_with(&x, &mut y, &mut ws);
                assert!(y.iter().all(|v| *v > 0.0));
            });
        }
    });
}

#[test]
fn a_scratch_stack_gives_the_workspaces_bits() {
    use faer::dyn_stack::{PodBuffer, PodStack};
    let points = PointSet::grid_disk(0.1, 0.55).unwrap();
    let bodies = [&Body::uniform_patch(steel()), &Body::winkler(3e10)];
    let kernel = LatticeKernel::new(&points, &bodies).unwrap();
    let x = random_vector(points.len(), 3, -1.0);
    let mut ws = kernel.workspace().unwrap();
    // The stack's bytes are the workspace's, aligned.
    let request = kernel.apply_scratch();
    assert!(request.size_bytes() >= ws.memory_bytes() - std::mem::size_of_val(&ws));
    let mut buffer = PodBuffer::new(request);
    let (mut a, mut b) = (vec![0.0; x.len()], vec![0.0; x.len()]);
    kernel.apply_with(&x, &mut a, &mut ws);
    // Twice in the same memory: what a product leaves there means nothing.
    for _ in 0..2 {
        kernel.apply_in(&x, &mut b, PodStack::new(&mut buffer));
        assert_eq!(a, b);
    }
    let pc = kernel.preconditioner().unwrap().unwrap();
    kernel.precondition_with(&x, &mut a, &pc, &mut ws);
    kernel.precondition_in(&x, &mut b, &pc, PodStack::new(&mut buffer));
    assert_eq!(a, b);
    // Foundations alone: no convolution, no scratch.
    let winkler = LatticeKernel::new(&points, &[&Body::winkler(3e10), &Body::rigid()]).unwrap();
    assert_eq!(winkler.apply_scratch().size_bytes(), 0);
    winkler.apply_in(
        &x,
        &mut b,
        PodStack::new(&mut PodBuffer::new(winkler.apply_scratch())),
    );
    let mut ws = winkler.workspace().unwrap();
    winkler.apply_with(&x, &mut a, &mut ws);
    assert_eq!(a, b);
}

#[test]
fn memory_is_linear_in_the_points_and_estimated_before() {
    // Held bytes, made on one thread: 16 per cell of the padded box's
    // quarter (the spectrum 8, one band of the row spectra 8), 8 per cell
    // of the box (the kernel table, for the columns), 12 per
    // segment of the gather order (one a lattice row on these grids), and
    // O(sqrt N) for the plans and a column batch. A rectangle's box is its
    // points, a disk's 4/pi of them; padding to 5-smooth lengths adds up
    // to ~10 %. The bounds leave a few percent over the figures measured.
    // Each further thread adds a batch of columns (the workspace's wave).
    pool(1).install(memory_on_one_thread);
    let points = PointSet::grid_disk(1.0, 64.0).unwrap();
    let bodies = [&Body::uniform_patch(steel()), &Body::uniform_patch(steel())];
    let held = |threads| {
        pool(threads).install(|| {
            let op = LatticeOperator::new(&points, &bodies).unwrap();
            (op.memory_bytes(), op.fft_shape().unwrap().0)
        })
    };
    let ((one, p1), (three, _)) = (held(1), held(3));
    assert_eq!(three - one, 2 * 16 * 16 * p1);
}

fn memory_on_one_thread() {
    let bodies = [&Body::uniform_patch(steel()), &Body::uniform_patch(steel())];
    for (name, small, large, bound) in [
        (
            "square 128 x 128 and 256 x 256",
            PointSet::grid_rectangle(1.0, 1.0, 128, 128).unwrap(),
            PointSet::grid_rectangle(1.0, 1.0, 256, 256).unwrap(),
            32.0,
        ),
        (
            "disks of radius 64 h and 128 h",
            PointSet::grid_disk(1.0, 64.0).unwrap(),
            PointSet::grid_disk(1.0, 128.0).unwrap(),
            44.0,
        ),
    ] {
        let mut per_point = Vec::new();
        for points in [&small, &large] {
            let estimate = LatticeOperator::estimate_bytes(points, &bodies).unwrap();
            let op = LatticeOperator::new(points, &bodies).unwrap();
            let held = op.memory_bytes();
            // The estimate bounds the FFT scratch from above by at most
            // the bound itself, P1 + P2 complex values.
            let (p1, p2) = op.fft_shape().unwrap();
            assert!(held <= estimate, "{name}: {held} > {estimate}");
            assert!(
                estimate <= held + 16 * (p1 + p2),
                "{name}: {estimate} vs {held}"
            );
            per_point.push(held as f64 / points.len() as f64);
        }
        // Four times the points: the bytes per point do not grow (a
        // term in N^2 would multiply them by 4) and stay under the bound.
        assert!(per_point[1] <= per_point[0], "{name}: {per_point:?}");
        assert!(
            per_point.iter().all(|&b| b < bound),
            "{name}: {per_point:?}"
        );
    }
}

#[test]
fn padded_lengths_avoid_wrap_around_and_are_fast() {
    for (n, expected) in [
        (1, 2),
        (2, 4),
        (3, 6),
        (5, 10),
        (6, 12),
        (65, 144),
        (512, 1024),
    ] {
        assert_eq!(padded_length(n), expected, "n = {n}");
    }
    for n in 1..300 {
        let p = padded_length(n);
        assert!(p + 1 >= 2 * n && p.is_multiple_of(2), "n = {n}: {p}");
    }
    let points = PointSet::grid_rectangle(1.0, 1.0, 20, 3).unwrap();
    let op = LatticeOperator::new(&points, &[&Body::uniform_patch(steel())]).unwrap();
    assert_eq!(op.fft_shape(), Some((40, 6)));
    let foundation = LatticeOperator::new(&points, &[&Body::winkler(1.0)]).unwrap();
    assert_eq!(foundation.fft_shape(), None);
}

#[test]
fn refuses_points_off_a_lattice() {
    let patch = Body::uniform_patch(steel());
    let scattered = scattered();
    assert!(scattered.lattice().is_none());
    let e = LatticeOperator::new(&scattered, &[&patch]).unwrap_err();
    assert!(matches!(e, InfluenceError::LatticeRequired { .. }), "{e}");
    assert!(
        e.to_string()
            .starts_with("the lattice operator needs the points on a compact lattice: the points lie on no lattice"),
        "{e}"
    );
    assert_eq!(
        LatticeOperator::estimate_bytes(&scattered, &[&patch]),
        Err(e)
    );
    // A lattice far sparser than its box: 2 points 1000 cells apart.
    let sparse = sparse_pair();
    let e = LatticeOperator::new(&sparse, &[&patch]).unwrap_err();
    assert!(
        e.to_string()
            .contains("bounding box of 1001 x 1 cells is more than 72 cells for 2 points"),
        "{e}"
    );
    // Two points within the lattice tolerance of one cell.
    let twins = surface(vec![0.0, 1e-14, 1.0], vec![0.0, 0.0, 0.0], 1.0);
    assert_eq!(twins.lattice().unwrap().to_vec(), [(0, 0), (0, 0), (1, 0)]);
    let e = LatticeOperator::new(&twins, &[&patch]).unwrap_err();
    assert!(
        e.to_string()
            .contains("points 0 and 1 fall on one lattice cell (i, j) = (0, 0)"),
        "{e}"
    );
}

#[test]
fn refuses_beams_and_what_assemble_refuses() {
    let line = PointSet::line(-1.0, 1.0, 8).unwrap();
    let e = LatticeOperator::new(&line, &[&Body::beam(BEAM).unwrap(), &Body::winkler(1e3)])
        .unwrap_err();
    assert_eq!(
        e,
        InfluenceError::NotTranslationInvariant {
            model: "Euler-Bernoulli beam"
        }
    );
    assert!(
        e.to_string()
            .starts_with("the Euler-Bernoulli beam model is not translation invariant"),
        "{e}"
    );
    let rigid = Body::rigid();
    assert_eq!(
        LatticeOperator::new(&line, &[&rigid, &rigid]).unwrap_err(),
        InfluenceError::AllRigid { bodies: 2 }
    );
    let e = LatticeOperator::new(&line, &[&Body::uniform_patch(steel())]).unwrap_err();
    assert!(matches!(e, InfluenceError::DimensionMismatch { .. }), "{e}");
    let e = LatticeOperator::new(&line, &[&Body::plane_strain(steel(), 0.5)]).unwrap_err();
    assert!(matches!(e, InfluenceError::InvalidModel { .. }), "{e}");
}

#[test]
fn a_failed_allocation_is_an_error() {
    let e = try_vec(usize::MAX / 4, 0.0f64, "kernel spectrum").unwrap_err();
    assert_eq!(
        e,
        InfluenceError::AllocationFailed {
            what: "kernel spectrum",
            bytes: usize::MAX
        }
    );
    assert!(
        e.to_string().starts_with(&format!(
            "could not allocate {} bytes for the kernel spectrum",
            usize::MAX
        )),
        "{e}"
    );
}

#[test]
#[should_panic(expected = "x has 3 entries for 4 points")]
fn a_wrong_length_panics_with_the_lengths() {
    let points = PointSet::grid_rectangle(1.0, 1.0, 2, 2).unwrap();
    let mut op = LatticeOperator::new(&points, &[&Body::uniform_patch(steel())]).unwrap();
    op.apply(&[1.0; 3], &mut [0.0; 4]);
}

#[test]
fn is_send_and_sync() {
    fn shared<T: Send + Sync>() {}
    shared::<LatticeKernel>();
    shared::<LatticeOperator>();
    shared::<LatticeWorkspace>();
}

#[test]
fn a_product_is_the_same_to_the_bit_on_any_number_of_threads() {
    // A disk (points in lattice-row order: the rows write their own slices
    // of y) and the same disk's points in reverse (the rows' values
    // gathered on the caller's thread), each with a workspace made on one
    // thread and on three (waves of one and of three column batches).
    let bodies = [&Body::uniform_patch(steel()), &Body::point_force(steel())];
    for (name, points) in disk_and_reversed() {
        let x = random_vector(points.len(), 11, -1.0);
        let product = |made_on: usize, applied_on: usize| {
            let mut op = pool(made_on).install(|| LatticeOperator::new(&points, &bodies).unwrap());
            let mut y = vec![0.0; x.len()];
            pool(applied_on).install(|| op.apply(&x, &mut y));
            y.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
        };
        let one = product(1, 1);
        for (made_on, applied_on) in [(1, 3), (3, 1), (3, 3), (2, 2)] {
            assert!(
                one == product(made_on, applied_on),
                "{name}: made on {made_on}, applied on {applied_on} threads"
            );
        }
    }
}
