//! The reduction of a contact problem to the engine's bordered LCP and its
//! solve. Load control (P given) is `w = S z - B λ + q`, `B^T z = b` with
//! `z = F`, `w = Y`, `λ` the free rigid motions (the approach alpha first,
//! then the free tilts), `B` their levers (`e` for the approach), `q` the
//! separations eps shifted by the prescribed motions and `b` the
//! resultants (P, the moments). Displacement control (alpha given, P =
//! e^T F follows) is the plain LCP `Y = S F + (eps - alpha e)`. A folded
//! problem has one unknown per orbit, its rows scaled by 1 / s_a.

use std::time::Instant;

use elcon_lcp::{Method, Options};
use faer::{Col, ColRef, Mat};

use super::layout::shifted;
use super::problem::ContactProblem;
use super::solution::{ContactSolution, Engine};
use crate::AnalysisError;
use crate::rigid::point;

impl ContactProblem {
    /// Solves starting from the contact set of `previous` (a solution of a
    /// similar problem: the previous load step, a neighbouring design), as
    /// `options.warm_start`. Block principal pivoting then starts from that
    /// set (on Hertz spheres, a load step from 90 to 100 lb is tested to take
    /// at most three iterations and fewer than a cold start); the tableau
    /// methods start from their usual basis (the option does not apply to
    /// them).
    /// The answer does not depend on the start.
    ///
    /// # Errors
    /// As [`ContactProblem::solve`]; a `previous` with another number of
    /// points is [`AnalysisError::SizeMismatch`].
    pub fn solve_from(
        &self,
        previous: &ContactSolution,
        method: Method,
        options: &Options,
    ) -> Result<ContactSolution, AnalysisError> {
        let n = self.points.len();
        if previous.forces.len() != n {
            return Err(AnalysisError::SizeMismatch {
                field: "previous.forces",
                expected: n,
                found: previous.forces.len(),
            });
        }
        let start: Vec<bool> = match &self.folding {
            Some(f) => (0..f.len())
                .map(|a| previous.forces[f.rep(a)] > 0.0)
                .collect(),
            None => previous.forces.iter().map(|&f| f > 0.0).collect(),
        };
        let mut options = options.clone();
        options.warm_start = Some(start);
        self.solve(method, &options)
    }

    /// Solves with the engine's `method`; the solution carries the
    /// certificate computed from the original S, eps and P.
    pub fn solve(
        &self,
        method: Method,
        options: &Options,
    ) -> Result<ContactSolution, AnalysisError> {
        let start = Instant::now();
        // The unknowns: every point, or one representative per orbit of a
        // folded problem, whose rows are scaled by 1 / s_a (docs of
        // `elcon_influence::Folding`): w_a = Y_a / s_a, and the equilibrium
        // row by 1 / |G|, which keeps [B; D] and [C D] a skew pair.
        let n = self.influence.len();
        let scale = |a: usize| self.folding.as_ref().map_or(1.0, |f| f.stabilizer(a));
        let order = self.folding.as_ref().map_or(1.0, |f| f.order() as f64);
        // The bordered form: q the separations shifted by the prescribed
        // rigid motions, a column per free motion (its lever; 1 for the
        // approach), each scaled by 1 / s_a when folded, and the resultants
        // (load, moments) over |G|.
        let rigid = &self.rigid;
        // Unfolded with no prescribed motion, q is eps itself: borrowed.
        let shifted = shifted(&self.points, &self.separation, rigid);
        let q = self
            .folding
            .as_ref()
            .map(|f| Col::from_fn(n, |a| shifted[f.rep(a)] / f.stabilizer(a)));
        let q = q.as_ref().map_or(ColRef::from_slice(&shifted), Col::as_ref);
        let border = self.border();
        let resultant = Col::from_fn(rigid.free.len(), |j| rigid.free[j].1 / order);
        let sol = self.influence.solve_bordered(
            q,
            border.as_ref(),
            resultant.as_ref(),
            method,
            options,
        )?;
        // The engine's border is not needed any more: at a million points
        // every column is 8 MB.
        drop(border);
        let elcon_lcp::LcpSolution {
            z,
            w,
            u,
            certificate,
            statistics,
            ..
        } = sol;
        let lambda: Vec<f64> = u.iter().copied().collect();
        // The gaps are the engine's w = M z - B λ + q, computed from the data
        // above: Y = S F + eps - (rigid motion); folded, row a is scaled by
        // 1 / s_a, so w_a = Y_a / s_a (the same sums regrouped) and
        // Y_a = s_a w_a, exactly (s_a is a power of two).
        let z = into_vec(z);
        let w = into_vec(w);
        let (forces, gaps, slack) = match &self.folding {
            Some(f) => {
                let folded_gaps: Vec<f64> = (0..n).map(|a| scale(a) * w[a]).collect();
                (f.unfold(&z), f.unfold(&folded_gaps), Some(f.unfold(&w)))
            }
            None => (z, w, None),
        };
        let engine = Engine {
            forces,
            gaps,
            slack,
            lambda,
            certificate,
            statistics,
            solve_seconds: start.elapsed().as_secs_f64(),
        };
        Ok(self.finish(engine))
    }
}

impl ContactProblem {
    /// The engine's border `B`: a column per free motion, its lever at
    /// every unknown's point (a uniform lever, the approach's 1, needs no
    /// point), row a divided by `s_a` when folded. Unfolded, the points are walked
    /// in order ([`PointSet::positions`](elcon_influence::PointSet::positions))
    /// instead of looked up one by one.
    fn border(&self) -> Mat<f64> {
        let (rigid, n) = (&self.rigid, self.influence.len());
        let mut border = Mat::<f64>::zeros(n, rigid.free.len());
        for (j, &(mode, _)) in rigid.free.iter().enumerate() {
            let mut column = border.col_mut(j);
            let column = column
                .as_mut()
                .try_as_col_major_mut()
                .expect("a new matrix's columns are contiguous")
                .as_slice_mut();
            let lever = |at| mode.lever(at, rigid.load_point);
            // A uniform lever's value, the same at any point.
            let uniform = mode.is_uniform().then(|| lever((0.0, 0.0)));
            match (&self.folding, uniform) {
                (Some(f), _) => {
                    for (a, v) in column.iter_mut().enumerate() {
                        let at = || point(&self.points, f.rep(a));
                        *v = uniform.unwrap_or_else(|| lever(at())) / f.stabilizer(a);
                    }
                }
                (None, Some(value)) => column.fill(value),
                (None, None) => {
                    let mut values = column.iter_mut();
                    self.points.positions().for_each(|at| {
                        *values.next().expect("a value per point") = lever(at);
                    });
                }
            }
        }
        border
    }
}

/// A column's values as a vector (the column is freed).
fn into_vec(col: Col<f64>) -> Vec<f64> {
    col.iter().copied().collect()
}
