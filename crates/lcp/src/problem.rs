//! The problem forms, as data.
//!
//! Standard LCP ([`Lcp`]): find `z`, `w` with
//!
//! ```text
//!     w = M z + q,   z >= 0,   w >= 0,   z^T w = 0
//! ```
//!
//! Bordered LCP ([`BorderedLcp`], [`BorderedLcpRef`]): `k` free unknowns
//! `λ` and as many equality rows, with a symmetric border `B` (n x k, full
//! column rank):
//!
//! ```text
//!     w = M z - B λ + q,   B^T z = b,   z >= 0, w >= 0, z^T w = 0,   λ free
//! ```
//!
//! the optimality conditions of `min 1/2 z^T M z + q^T z` subject to
//! `B^T z = b`, `z >= 0` (λ the multipliers). The contact problem of Conry &
//! Seireg is this form with `z = F`, `w = Y`, `M = S`, `q = ε`: one column
//! of ones (the approach α, its row the load P), and with tilts two more,
//! the points' coordinates (their rows the moments).
//!
//! Mixed LCP ([`MixedLcp`]): `n` complementary pairs, `m_e` equality rows
//! and `k` extra unknowns `u` that are free or non-negative:
//!
//! ```text
//!     w = M z + B u + q,   z >= 0, w >= 0, z^T w = 0
//!     0 = C z + D u + r
//! ```
//!
//! (a bordered LCP is the mixed form with `B -> -B`, `C = B^T`, `D = 0`,
//! `r = -b`, every `u` free). Which methods and tableaus apply to which form
//! is the strategy's business (the `strategy` module); this module only holds
//! and validates the data.

use std::cell::OnceCell;

use faer::{Col, ColRef, Mat, MatRef};

use crate::LcpError;
use crate::linalg::{asymmetry, first_non_finite};
use crate::tolerance::BORDER_RANK;

/// Sign restriction of an unknown that has no complementary partner.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bound {
    /// Any real value.
    Free,
    /// `>= 0`.
    NonNegative,
}

/// The standard LCP `w = M z + q, z >= 0, w >= 0, z^T w = 0`.
#[derive(Debug, Clone)]
pub struct Lcp {
    m: Mat<f64>,
    q: Col<f64>,
}

impl Lcp {
    /// A standard LCP; `m` must be square with the size of `q`, all finite.
    pub fn new(m: Mat<f64>, q: Col<f64>) -> Result<Self, LcpError> {
        check_square(m.as_ref(), q.as_ref())?;
        Ok(Self { m, q })
    }

    /// Number of complementary pairs.
    pub fn size(&self) -> usize {
        self.q.nrows()
    }

    /// The matrix `M`.
    pub fn matrix(&self) -> MatRef<'_, f64> {
        self.m.as_ref()
    }

    /// The vector `q`.
    pub fn q(&self) -> ColRef<'_, f64> {
        self.q.as_ref()
    }

    /// A borrowed view (no border).
    pub fn as_ref(&self) -> BorderedLcpRef<'_> {
        BorderedLcpRef::unchecked(self.m.as_ref(), self.q.as_ref())
    }
}

/// A borrowed bordered LCP (see the module documentation) whose `M` is
/// `A`: a dense matrix ([`BorderedLcpRef`]) or an operator known only by
/// its products ([`OperatorLcp`](crate::OperatorLcp)). Build it with the
/// form's `new` and, for `k > 0` rigid-body rows,
/// [`with_border`](Bordered::with_border): the border and its checks are
/// the same for both forms. Nothing large is copied.
#[derive(Clone, Copy)]
pub struct Bordered<'a, A> {
    pub(crate) m: A,
    pub(crate) q: ColRef<'a, f64>,
    pub(crate) border: MatRef<'a, f64>,
    pub(crate) resultant: ColRef<'a, f64>,
}

/// A borrowed bordered LCP with a dense `M` (see [`Bordered`]): build it
/// with [`BorderedLcpRef::new`] and, for `k > 0` rigid-body rows,
/// [`Bordered::with_border`].
pub type BorderedLcpRef<'a> = Bordered<'a, MatRef<'a, f64>>;

impl<'a, A: Copy> Bordered<'a, A> {
    /// The LCP `w = M z + q` with no border, its data already checked.
    pub(crate) fn unchecked(m: A, q: ColRef<'a, f64>) -> Self {
        let n = q.nrows();
        Self {
            m,
            q,
            border: MatRef::from_column_major_slice(&[], n, 0),
            resultant: ColRef::from_slice(&[]),
        }
    }

    /// Adds the border: `border` is `B` (n x k, full column rank), its
    /// columns the unknowns `λ`; `resultant` is `b` (k), the right-hand side
    /// of `B^T z = b`.
    pub fn with_border(
        self,
        border: MatRef<'a, f64>,
        resultant: ColRef<'a, f64>,
    ) -> Result<Self, LcpError> {
        check_border(self.q.nrows(), border, resultant)?;
        Ok(Self {
            border,
            resultant,
            ..self
        })
    }

    /// Number of complementary pairs `n`.
    pub fn size(&self) -> usize {
        self.q.nrows()
    }

    /// Number of border columns (free unknowns) `k`.
    pub fn border_size(&self) -> usize {
        self.border.ncols()
    }

    /// The matrix `M` (a dense matrix, or the operator of its products).
    pub fn matrix(&self) -> A {
        self.m
    }

    /// The vector `q`.
    pub fn q(&self) -> ColRef<'a, f64> {
        self.q
    }

    /// The border `B` (n x k).
    pub fn border(&self) -> MatRef<'a, f64> {
        self.border
    }

    /// The resultants `b` (k).
    pub fn resultant(&self) -> ColRef<'a, f64> {
        self.resultant
    }
}

impl<'a> BorderedLcpRef<'a> {
    /// The LCP `w = M z + q` with no border yet; `m` square with the size of
    /// `q`, all finite.
    pub fn new(m: MatRef<'a, f64>, q: ColRef<'a, f64>) -> Result<Self, LcpError> {
        check_square(m, q)?;
        Ok(Self::unchecked(m, q))
    }
}

impl std::fmt::Debug for BorderedLcpRef<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BorderedLcpRef")
            .field("m", &self.m)
            .field("q", &self.q)
            .field("border", &self.border)
            .field("resultant", &self.resultant)
            .finish()
    }
}

/// Checks a border `B` (n x k) and its resultants `b` (k): sizes, finite
/// entries, full column rank.
fn check_border(
    n: usize,
    border: MatRef<'_, f64>,
    resultant: ColRef<'_, f64>,
) -> Result<(), LcpError> {
    check_dims(
        "border",
        border.nrows(),
        border.ncols(),
        n,
        resultant.nrows(),
    )?;
    check_finite_mat("border", border)?;
    check_finite_col("resultant", resultant)?;
    if let Some(column) = dependent_column(border) {
        return Err(LcpError::RankDeficient {
            field: "border",
            column,
        });
    }
    Ok(())
}

/// An owned bordered LCP (see [`BorderedLcpRef`]).
#[derive(Debug, Clone)]
pub struct BorderedLcp {
    m: Mat<f64>,
    q: Col<f64>,
    border: Mat<f64>,
    resultant: Col<f64>,
}

impl BorderedLcp {
    /// The LCP `w = M z + q` with no border yet (see [`BorderedLcpRef::new`]).
    pub fn new(m: Mat<f64>, q: Col<f64>) -> Result<Self, LcpError> {
        check_square(m.as_ref(), q.as_ref())?;
        let n = q.nrows();
        Ok(Self {
            m,
            q,
            border: Mat::zeros(n, 0),
            resultant: Col::zeros(0),
        })
    }

    /// Adds the border `B` and the resultants `b` (see [`BorderedLcpRef::with_border`]).
    pub fn with_border(self, border: Mat<f64>, resultant: Col<f64>) -> Result<Self, LcpError> {
        BorderedLcpRef::unchecked(self.m.as_ref(), self.q.as_ref())
            .with_border(border.as_ref(), resultant.as_ref())?;
        Ok(Self {
            border,
            resultant,
            ..self
        })
    }

    /// A borrowed view of the problem's data.
    pub fn as_ref(&self) -> BorderedLcpRef<'_> {
        BorderedLcpRef {
            m: self.m.as_ref(),
            q: self.q.as_ref(),
            border: self.border.as_ref(),
            resultant: self.resultant.as_ref(),
        }
    }

    /// Number of complementary pairs `n`.
    pub fn size(&self) -> usize {
        self.q.nrows()
    }
}

/// The data of a mixed LCP, by name (see the module documentation). Sizes:
/// `m` n x n, `b` n x k, `q` n, `c` m_e x n, `d` m_e x k, `r` m_e, `bounds`
/// k; all entries finite.
#[derive(Debug, Clone)]
pub struct MixedLcpParts {
    /// `M` (n x n).
    pub m: Mat<f64>,
    /// `B` (n x k), the extra unknowns' columns in the complementary rows.
    pub b: Mat<f64>,
    /// `q` (n).
    pub q: Col<f64>,
    /// `C` (m_e x n), the equality rows on `z`.
    pub c: Mat<f64>,
    /// `D` (m_e x k), the equality rows on `u`.
    pub d: Mat<f64>,
    /// `r` (m_e).
    pub r: Col<f64>,
    /// The sign restriction of each extra unknown (k).
    pub bounds: Vec<Bound>,
}

/// A validated mixed LCP (see the module documentation).
#[derive(Debug, Clone)]
pub struct MixedLcp {
    parts: MixedLcpParts,
}

impl MixedLcp {
    /// Validates the parts: sizes consistent, every entry finite.
    pub fn new(parts: MixedLcpParts) -> Result<Self, LcpError> {
        let p = &parts;
        check_square(p.m.as_ref(), p.q.as_ref())?;
        let (n, k, me) = (p.q.nrows(), p.bounds.len(), p.r.nrows());
        check_dims("b", p.b.nrows(), p.b.ncols(), n, k)?;
        check_dims("c", p.c.nrows(), p.c.ncols(), me, n)?;
        check_dims("d", p.d.nrows(), p.d.ncols(), me, k)?;
        check_finite_mat("b", p.b.as_ref())?;
        check_finite_mat("c", p.c.as_ref())?;
        check_finite_mat("d", p.d.as_ref())?;
        check_finite_col("r", p.r.as_ref())?;
        Ok(Self { parts })
    }

    /// Number of complementary pairs `n`.
    pub fn size(&self) -> usize {
        self.parts.q.nrows()
    }

    /// The problem's data.
    pub fn parts(&self) -> &MixedLcpParts {
        &self.parts
    }

    pub(crate) fn view(&self) -> MixedRef<'_> {
        self.parts.view()
    }
}

impl MixedLcpParts {
    /// A borrowed view of the parts.
    fn view(&self) -> MixedRef<'_> {
        MixedRef {
            m: self.m.as_ref(),
            b: self.b.as_ref(),
            q: self.q.as_ref(),
            c: self.c.as_ref(),
            d: self.d.as_ref(),
            r: self.r.as_ref(),
            bounds: &self.bounds,
        }
    }
}

/// The mixed form every method reads (see the module documentation); for
/// a bordered problem `b = -B`, `c = B^T`, `d = 0`, `r = -b`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct MixedRef<'a> {
    pub m: MatRef<'a, f64>,
    pub b: MatRef<'a, f64>,
    pub q: ColRef<'a, f64>,
    pub c: MatRef<'a, f64>,
    pub d: MatRef<'a, f64>,
    pub r: ColRef<'a, f64>,
    pub bounds: &'a [Bound],
}

impl MixedRef<'_> {
    /// Number of complementary pairs `n`.
    pub fn size(&self) -> usize {
        self.q.nrows()
    }

    /// Number of extra unknowns `k`.
    pub fn extras(&self) -> usize {
        self.bounds.len()
    }

    /// Number of equality rows `m_e`.
    pub fn equalities(&self) -> usize {
        self.r.nrows()
    }
}

/// The mixed parts of a bordered problem: `-B`, `B^T`, `D = 0`, `r = -b`,
/// every extra unknown free (n x k data, small beside `M`); `M` and `q`
/// are left empty, the bordered problem's own.
pub(crate) struct MixedBorder(MixedLcpParts);

impl MixedBorder {
    pub fn of(p: &BorderedLcpRef<'_>) -> Self {
        let k = p.border_size();
        Self(MixedLcpParts {
            m: Mat::zeros(0, 0),
            b: -p.border,
            q: Col::zeros(0),
            c: p.border.transpose().to_owned(),
            d: Mat::zeros(k, k),
            r: -p.resultant,
            bounds: vec![Bound::Free; k],
        })
    }

    pub fn view<'a>(&'a self, p: &BorderedLcpRef<'a>) -> MixedRef<'a> {
        MixedRef {
            m: p.m,
            q: p.q,
            ..self.0.view()
        }
    }
}

/// The border of a bordered problem, in its own sign: `w = M z - B λ + q`,
/// `B^T z = b`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Border<'a> {
    /// `B` (n x k).
    pub columns: MatRef<'a, f64>,
    /// `b` (k).
    pub resultant: ColRef<'a, f64>,
}

/// A problem as the strategy hands it to the methods: its mixed form, the
/// border when it is a bordered problem (`None` for a general mixed LCP),
/// and facts about `M` computed once, when first asked for.
pub(crate) struct Problem<'a> {
    /// The mixed form (every problem has one).
    pub mixed: MixedRef<'a>,
    /// The bordered form, for a standard (`k = 0`) or bordered LCP.
    pub border: Option<Border<'a>>,
    symmetric: OnceCell<bool>,
}

impl<'a> Problem<'a> {
    /// A bordered (or standard, `k = 0`) problem; `parts` its mixed parts.
    pub fn bordered(p: &BorderedLcpRef<'a>, parts: &'a MixedBorder) -> Self {
        Self {
            mixed: parts.view(p),
            border: Some(Border {
                columns: p.border,
                resultant: p.resultant,
            }),
            symmetric: OnceCell::new(),
        }
    }

    /// A general mixed problem.
    pub fn mixed(p: MixedRef<'a>) -> Self {
        Self {
            mixed: p,
            border: None,
            symmetric: OnceCell::new(),
        }
    }

    /// Number of complementary pairs `n`.
    pub fn size(&self) -> usize {
        self.mixed.size()
    }

    /// Whether `M` is symmetric (to `SYMMETRY` of its largest diagonal entry).
    pub fn symmetric(&self) -> bool {
        *self
            .symmetric
            .get_or_init(|| asymmetry(self.mixed.m).is_none())
    }

    /// Whether every diagonal entry of `M` is positive.
    pub fn positive_diagonal(&self) -> bool {
        let m = self.mixed.m;
        (0..self.size()).all(|i| m[(i, i)] > 0.0)
    }

    /// Whether every extra unknown is free and there are as many equality
    /// rows (an LCP once the free unknowns are split; what Lemke's method
    /// and block pivoting solve).
    pub fn free_square(&self) -> bool {
        self.mixed.extras() == self.mixed.equalities()
            && self.mixed.bounds.iter().all(|b| *b == Bound::Free)
    }
}

/// The first column of `border` that depends linearly on the ones before
/// it, if any: a Cholesky of the Gram matrix of the columns scaled to unit
/// length (each column in its own units), whose pivot `j` is the squared
/// distance of column `j` from the span of the ones before it; a pivot at
/// most `BORDER_RANK` is a dependent column.
fn dependent_column(border: MatRef<'_, f64>) -> Option<usize> {
    use faer::linalg::cholesky::llt::factor::LltError;
    let k = border.ncols();
    let norms: Vec<f64> = (0..k).map(|j| border.col(j).norm_l2()).collect();
    if let Some(j) = norms.iter().position(|&norm| !(norm > 0.0)) {
        return Some(j);
    }
    // The columns scaled as they are read: no copy of the border (n x k).
    let gram = Mat::<f64>::from_fn(k, k, |a, b| {
        let (ca, cb) = (border.col(a), border.col(b));
        (0..border.nrows())
            .map(|i| (ca[i] / norms[a]) * (cb[i] / norms[b]))
            .sum()
    });
    match gram.llt(faer::Side::Lower) {
        Ok(llt) => {
            let l = llt.L();
            (0..k).find(|&j| !(l[(j, j)] * l[(j, j)] > BORDER_RANK))
        }
        Err(LltError::NonPositivePivot { index }) => Some(index),
    }
}

fn check_square(m: MatRef<'_, f64>, q: ColRef<'_, f64>) -> Result<(), LcpError> {
    let n = q.nrows();
    if n == 0 {
        return Err(LcpError::Empty { field: "q" });
    }
    check_dims("m", m.nrows(), m.ncols(), n, n)?;
    check_finite_mat("m", m)?;
    check_finite_col("q", q)
}

/// Checks that a matrix named `field` is `er` x `ec`.
pub(crate) fn check_dims(
    field: &'static str,
    rows: usize,
    cols: usize,
    er: usize,
    ec: usize,
) -> Result<(), LcpError> {
    check_size(field, rows, er, "rows")?;
    check_size(field, cols, ec, "columns")
}

/// Checks that `field` has `expected` of `unit` (its rows, columns or
/// entries), `found` given.
pub(crate) fn check_size(
    field: &'static str,
    found: usize,
    expected: usize,
    unit: &'static str,
) -> Result<(), LcpError> {
    if found != expected {
        return Err(LcpError::DimensionMismatch {
            field,
            expected,
            found,
            unit,
        });
    }
    Ok(())
}

/// Checks a matrix for NaN/inf, naming the field.
pub(crate) fn check_finite_mat(field: &'static str, a: MatRef<'_, f64>) -> Result<(), LcpError> {
    match first_non_finite(a) {
        Some((index, value)) => Err(LcpError::NonFinite {
            field,
            index,
            value,
        }),
        None => Ok(()),
    }
}

/// Checks a vector for NaN/inf, naming the field.
pub(crate) fn check_finite_col(field: &'static str, a: ColRef<'_, f64>) -> Result<(), LcpError> {
    match a.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(LcpError::NonFinite {
            field,
            index,
            value: a[index],
        }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::{col, mat};

    #[test]
    fn a_border_with_dependent_columns_is_refused() {
        let m = Mat::<f64>::identity(3, 3);
        let q = col![1.0, 2.0, 3.0];
        let p = BorderedLcpRef::new(m.as_ref(), q.as_ref()).unwrap();
        let b = col![1.0, 1.0];
        let dependent = mat![[1.0, 2.0], [1.0, 2.0], [1.0, 2.0]];
        let e = p.with_border(dependent.as_ref(), b.as_ref()).unwrap_err();
        assert!(matches!(
            e,
            LcpError::RankDeficient {
                field: "border",
                column: 1
            }
        ));
        let independent = mat![[1.0, -1.0], [1.0, 0.0], [1.0, 1.0]];
        let p = p.with_border(independent.as_ref(), b.as_ref()).unwrap();
        assert_eq!(p.border_size(), 2);
    }
}
