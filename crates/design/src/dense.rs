//! The design's small dense solves and products on the calling thread
//! (`Par::Seq`): faer's own solvers and operators take its global
//! parallelism, whose splitting of the work changes with the threads of
//! the rayon pool they run in, and with it the rounding of the results;
//! a design's numbers must be the same to the bit on any thread count.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::linalg::matmul::matmul;
use faer::perm::Perm;
use faer::{Accum, Conj, Mat, MatRef, Par};

/// `a b`, on the calling thread.
pub(crate) fn product(a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> Mat<f64> {
    let mut out = Mat::zeros(a.nrows(), b.ncols());
    matmul(out.as_mut(), Accum::Replace, a, b, 1.0, Par::Seq);
    out
}

/// `a^-1 rhs` by an LU factorization with partial pivoting of the square
/// `a`, on the calling thread (a singular `a` gives values that are not
/// finite, as faer's own solver does).
pub(crate) fn lu_solve(a: MatRef<'_, f64>, rhs: MatRef<'_, f64>) -> Mat<f64> {
    let n = a.nrows();
    let mut lu = a.to_owned();
    let (mut fwd, mut bwd) = (vec![0usize; n], vec![0usize; n]);
    let mut mem = MemBuffer::new(factor::lu_in_place_scratch::<usize, f64>(
        n,
        n,
        Par::Seq,
        Default::default(),
    ));
    factor::lu_in_place(
        lu.as_mut(),
        &mut fwd,
        &mut bwd,
        Par::Seq,
        MemStack::new(&mut mem),
        Default::default(),
    );
    let perm = Perm::new_checked(fwd.into_boxed_slice(), bwd.into_boxed_slice(), n);
    let mut x = rhs.to_owned();
    let mut mem = MemBuffer::new(solve::solve_in_place_scratch::<usize, f64>(
        n,
        x.ncols(),
        Par::Seq,
    ));
    solve::solve_in_place_with_conj(
        lu.as_ref(),
        lu.as_ref(),
        perm.as_ref(),
        Conj::No,
        x.as_mut(),
        Par::Seq,
        MemStack::new(&mut mem),
    );
    x
}

/// The least-squares solution of `a x = rhs` (`a` with at least as many
/// rows as columns) by a QR factorization, on the calling thread.
pub(crate) fn lstsq(a: MatRef<'_, f64>, rhs: MatRef<'_, f64>) -> Mat<f64> {
    use faer::linalg::qr::no_pivoting::{factor as qr, solve as qr_solve};
    let (m, n) = a.shape();
    let block = qr::recommended_block_size::<f64>(m, n);
    let mut packed = a.to_owned();
    let mut coeff = Mat::zeros(block, m.min(n));
    let mut mem = MemBuffer::new(qr::qr_in_place_scratch::<f64>(
        m,
        n,
        block,
        Par::Seq,
        Default::default(),
    ));
    qr::qr_in_place(
        packed.as_mut(),
        coeff.as_mut(),
        Par::Seq,
        MemStack::new(&mut mem),
        Default::default(),
    );
    // The Householder basis (unit lower trapezoid) and R (upper triangle),
    // apart, as faer's own solver holds them.
    let basis = Mat::from_fn(m, n, |i, j| match i.cmp(&j) {
        std::cmp::Ordering::Greater => packed[(i, j)],
        std::cmp::Ordering::Equal => 1.0,
        std::cmp::Ordering::Less => 0.0,
    });
    let r = Mat::from_fn(n, n, |i, j| if i <= j { packed[(i, j)] } else { 0.0 });
    let mut x = rhs.to_owned();
    let mut mem = MemBuffer::new(qr_solve::solve_lstsq_in_place_scratch::<f64>(
        m,
        n,
        block,
        x.ncols(),
        Par::Seq,
    ));
    qr_solve::solve_lstsq_in_place_with_conj(
        basis.as_ref(),
        coeff.as_ref(),
        r.as_ref(),
        Conj::No,
        x.as_mut(),
        Par::Seq,
        MemStack::new(&mut mem),
    );
    x.subrows(0, n).to_owned()
}
