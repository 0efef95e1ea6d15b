//! The restricted-entry (complementary) simplex: Wolfe (1959), as used by
//! Conry & Seireg (1971) for the contact problem (their Fig. 2).
//!
//! On `A x = b` with complementary pairs `(x_i, x_j)`:
//!
//! 1. rows with `b_i < 0` are multiplied by -1;
//! 2. each row starts with a basic slack (a `+1` unit column of a
//!    non-negative unknown) when it has one, else with an artificial `Z_i`;
//! 3. free unknowns (the approach `alpha`) are pivoted into the basis first
//!    and never leave;
//! 4. phase 1 minimizes `sum Z_i`: the entering unknown is the one with the
//!    most negative reduced cost `d_s` SUBJECT TO the restricted-entry rule:
//!    `x_s` may not enter while its complement is basic, unless the ratio
//!    test makes that complement leave at this very pivot (it is preferred
//!    whenever it ties); inadmissible candidates are removed from the choice
//!    set and the next best is tried;
//! 5. phase 1 ends when `sum Z_i = 0`: a feasible complementary basic
//!    solution; or fails when no admissible candidate remains;
//! 6. with an objective `c^T x`, phase 2 lowers it by the same rule, the
//!    artificials left basic at level 0 held at 0 (the paper's design part);
//!    unknowns marked deferred (design parameters) stay at 0 through phase 1
//!    and may enter only here.
//!
//! The ratio test is lexicographic (no basis repeats); every
//! `refactor_interval` pivots the tableau is recomputed from the data.
//!
//! The contact form with a symmetric `M` and `q >= 0` runs the same rule on
//! the symmetric tableau first ([`crate::swept_simplex`]); what it cannot
//! finish comes here, its pivots counted. An explicit refactorization
//! interval (the retry's option) comes here directly.

use std::collections::HashSet;

use faer::{Col, Mat};

use crate::dense::norm_inf;
use crate::lemke::EQUILIBRATION_PASSES;
use crate::problem::{Bound, MixedLcpRef, Options, RawSolution, Statistics};
use crate::program::ComplementaryProgram;
use crate::system::{Column, System};
use crate::tableau::{Position, Ratio, RowRule, Tableau, UPDATE_BLOCK};
use crate::tolerance::Tolerances;
use crate::{LcpError, Method, swept_simplex};

/// What the restricted-entry simplex returns before certification.
pub(crate) struct Outcome {
    /// Every original unknown, in original units.
    pub x: Vec<f64>,
    /// Basic original unknowns.
    pub basis: Vec<usize>,
    pub statistics: Statistics,
}

/// Solves a mixed LCP: on the symmetric tableau when it applies, else (or
/// when that attempt breaks down) by [`solve_general`].
pub(crate) fn solve_mixed(p: &MixedLcpRef<'_>, opts: &Options) -> Result<RawSolution, LcpError> {
    // The contact form with a symmetric M: the same rule on the symmetric
    // tableau; what it cannot finish goes on below, its pivots counted.
    let before = match swept_simplex::applies(p, opts) {
        Some(load) => match swept_simplex::solve(p, opts, load) {
            Ok(raw) => return Ok(raw),
            Err(stats) => Some(stats),
        },
        None => None,
    };
    let mut result = solve_general(p, opts);
    if let (Ok(raw), Some(before)) = (&mut result, before) {
        raw.statistics.absorb(&before);
    }
    result
}

/// Solves a mixed LCP by writing it as a program:
/// `-M z - B u + w = q`, `C z + D u = -r`, pairs `(z_i, w_i)`.
///
/// The restricted-entry rule can stall in phase 1 when an extra unknown is
/// non-negative (its convergence theory is for free multipliers): the
/// problem is then solved with the extra unknowns free, and that answer
/// kept when they come out non-negative, which makes it a solution of this
/// problem too (`Statistics::retried`, the pivots of both attempts);
/// otherwise the first error stands.
fn solve_general(p: &MixedLcpRef<'_>, opts: &Options) -> Result<RawSolution, LcpError> {
    match solve_as_given(p, opts) {
        Err(first @ LcpError::Infeasible { pivot, .. })
            if p.bounds.contains(&Bound::NonNegative) =>
        {
            let free = vec![Bound::Free; p.bounds.len()];
            let relaxed = MixedLcpRef {
                bounds: &free,
                ..*p
            };
            match solve_as_given(&relaxed, opts) {
                Ok(mut raw) if extras_admissible(p.bounds, &raw.u, &opts.tolerances) => {
                    raw.statistics.pivots += pivot;
                    raw.statistics.retried = true;
                    Ok(raw)
                }
                _ => Err(first),
            }
        }
        other => other,
    }
}

/// Whether every non-negative extra unknown of `u` is, to the zero
/// tolerance of `u`'s scale.
fn extras_admissible(bounds: &[Bound], u: &Col<f64>, tol: &Tolerances) -> bool {
    let scale = norm_inf(u.as_ref()).max(f64::MIN_POSITIVE);
    bounds
        .iter()
        .zip(u.iter())
        .all(|(b, &v)| *b == Bound::Free || v >= -tol.zero * scale)
}

/// [`solve_mixed`] with the extra unknowns' bounds as given.
fn solve_as_given(p: &MixedLcpRef<'_>, opts: &Options) -> Result<RawSolution, LcpError> {
    let n = p.size();
    let k = p.extras();
    let me = p.equalities();
    let rows = n + me;
    let mut dense = Mat::<f64>::zeros(rows, n + k);
    for j in 0..n {
        for i in 0..n {
            dense[(i, j)] = -p.m[(i, j)];
        }
        for e in 0..me {
            dense[(n + e, j)] = p.c[(e, j)];
        }
    }
    for j in 0..k {
        for i in 0..n {
            dense[(i, n + j)] = -p.b[(i, j)];
        }
        for e in 0..me {
            dense[(n + e, n + j)] = p.d[(e, j)];
        }
    }
    let mut columns: Vec<Column> = (0..n + k).map(Column::Dense).collect();
    columns.extend((0..n).map(|i| Column::Unit { row: i, coef: 1.0 }));
    let mut bounds = vec![Bound::NonNegative; n];
    bounds.extend_from_slice(p.bounds);
    bounds.extend(std::iter::repeat_n(Bound::NonNegative, n));
    let mut complement: Vec<Option<usize>> = (0..n).map(|i| Some(n + k + i)).collect();
    complement.extend(std::iter::repeat_n(None, k));
    complement.extend((0..n).map(Some));
    let b = Col::from_fn(rows, |i| if i < n { p.q[i] } else { -p.r[i - n] });
    let mut program = ComplementaryProgram::from_parts(rows, dense, columns, bounds, complement, b);
    // The program is used once: its dense block moves into the engine
    // instead of being copied (one N x N matrix fewer).
    let dense = std::mem::replace(&mut program.dense, Mat::zeros(0, 0));
    let out = run_with(&program, dense, opts)?;
    let mut basic = vec![false; n];
    for &v in &out.basis {
        if v < n {
            basic[v] = true;
        }
    }
    Ok(RawSolution {
        z: Col::from_fn(n, |i| out.x[i]),
        u: Col::from_fn(k, |j| out.x[n + j]),
        basic,
        statistics: out.statistics,
    })
}

/// Which objective row a phase works on.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// Minimize the sum of artificials (objective row 0).
    Feasibility,
    /// Minimize `c^T x` (objective row 1).
    Objective,
}

struct Run<'a> {
    sys: System,
    tab: Tableau,
    bounds: Vec<Bound>,
    complement: &'a [Option<usize>],
    artificial: Vec<bool>,
    deferred: Vec<bool>,
    stats: Statistics,
    opts: &'a Options,
    zero_level: f64,
    limit: usize,
    refactor_every: usize,
    names: &'a ComplementaryProgram,
}

/// Runs the restricted-entry simplex on a program.
pub(crate) fn run(p: &ComplementaryProgram, opts: &Options) -> Result<Outcome, LcpError> {
    run_with(p, p.dense.clone(), opts)
}

/// [`run`] on the program's constraints with `dense` as its dense block
/// (a copy of `p.dense`, or the block itself moved out of a one-use program).
fn run_with(
    p: &ComplementaryProgram,
    dense: Mat<f64>,
    opts: &Options,
) -> Result<Outcome, LcpError> {
    let m = p.rows;
    let nv = p.columns.len();
    let mut stats = Statistics::new(Method::RestrictedSimplex);
    let mut sys = System {
        rows: m,
        dense,
        columns: p.columns.clone(),
        b: p.b.clone(),
        costs: Vec::new(),
        col_scale: vec![1.0; nv],
        row_scale: vec![1.0; m],
    };
    // 1. Rows with a negative right-hand side are negated.
    for i in 0..m {
        if sys.b[i] < 0.0 {
            sys.b[i] = -sys.b[i];
            sys.row_scale[i] = -1.0;
            let mut row = sys.dense.as_mut().row_mut(i);
            row *= -1.0;
        }
    }
    for col in sys.columns.iter_mut() {
        if let Column::Unit { row, coef } = col {
            *coef *= sys.row_scale[*row];
        }
    }
    if opts.equilibrate {
        sys.equilibrate(EQUILIBRATION_PASSES, opts.par(sys.rows, sys.dense.ncols()));
    }
    // 2. Initial basis: a +1 slack of a non-negative unknown, else an artificial.
    let mut basis = vec![usize::MAX; m];
    let mut in_basis = vec![false; nv];
    for (var, col) in sys.columns.iter().enumerate() {
        if let Column::Unit { row, coef } = *col
            && coef == 1.0
            && p.bounds[var] == Bound::NonNegative
            && basis[row] == usize::MAX
            && !p.complement[var].is_some_and(|c| in_basis[c])
        {
            basis[row] = var;
            in_basis[var] = true;
        }
    }
    let mut bounds = p.bounds.clone();
    let mut artificial = vec![false; nv];
    for (row, slot) in basis.iter_mut().enumerate() {
        if *slot == usize::MAX {
            *slot = sys.columns.len();
            sys.columns.push(Column::Unit { row, coef: 1.0 });
            sys.col_scale.push(1.0);
            bounds.push(Bound::NonNegative);
            artificial.push(true);
        }
    }
    let total = sys.columns.len();
    let mut deferred = p.deferred.clone();
    deferred.resize(total, false);
    let phase1: Vec<f64> = artificial
        .iter()
        .map(|&a| if a { 1.0 } else { 0.0 })
        .collect();
    sys.costs.push(phase1);
    if let Some(c) = &p.cost {
        let mut c2 = vec![0.0; total];
        for j in 0..nv {
            c2[j] = c[j] * sys.col_scale[j];
        }
        sys.costs.push(c2);
    }
    let par = opts.par(m, total - m + 1);
    let tab = Tableau::from_identity(&sys, basis, par, UPDATE_BLOCK);
    stats.tableau_rows = m;
    stats.tableau_columns = total - m + 1;
    let zero_level = opts.tolerances.zero * norm_inf(sys.b.as_ref()).max(f64::MIN_POSITIVE);
    let mut run = Run {
        sys,
        tab,
        bounds,
        complement: &p.complement,
        artificial,
        deferred,
        stats,
        opts,
        zero_level,
        limit: opts.pivot_limit(m, nv),
        refactor_every: opts.refactor_every(m),
        names: p,
    };
    // 3. Free unknowns enter first.
    run.enter_free()?;
    // 4-5. Phase 1.
    let artificials = run.artificial.iter().filter(|a| **a).count();
    let stop = run.zero_level * artificials.max(1) as f64;
    run.iterate(Phase::Feasibility, stop)?;
    let residual = run.tab.objective_value(0);
    if residual > stop {
        // One refactorization to rule out drift before declaring failure.
        run.refactor()?;
        run.iterate(Phase::Feasibility, stop)?;
        let residual = run.tab.objective_value(0);
        if residual > stop {
            return Err(LcpError::Infeasible {
                size: m,
                pivot: run.stats.pivots,
                residual: residual / norm_inf(run.sys.b.as_ref()).max(f64::MIN_POSITIVE),
            });
        }
    }
    // 6. Phase 2.
    if p.cost.is_some() {
        run.iterate(Phase::Objective, f64::NEG_INFINITY)?;
    }
    // Final basic solution from the data, refined.
    let (xb, steps) = run
        .sys
        .basic_solution(
            &run.tab.basic.clone(),
            Some(&mut run.tab),
            par,
            opts.refinement_steps,
        )
        .map_err(|ratio| LcpError::SingularBasis {
            size: m,
            pivot: run.stats.pivots,
            ratio,
        })?;
    run.stats.refinement_steps = steps;
    let mut x = vec![0.0; nv];
    let mut basis = Vec::new();
    for (row, &var) in run.tab.basic.iter().enumerate() {
        if var < nv {
            x[var] = run.sys.col_scale[var] * xb[row];
            basis.push(var);
        }
    }
    Ok(Outcome {
        x,
        basis,
        statistics: run.stats,
    })
}

impl Run<'_> {
    fn rule(&self, phase: Phase) -> impl Fn(usize) -> RowRule + '_ {
        move |i| {
            let v = self.tab.basic[i];
            if self.bounds[v] == Bound::Free {
                RowRule::Skip
            } else if self.artificial[v] && phase == Phase::Objective {
                RowRule::Fixed
            } else {
                RowRule::Bounded
            }
        }
    }

    fn pivot(&mut self, ratio: Ratio, col: usize) -> Result<(), LcpError> {
        // At most `limit` pivots: refuse the one after (not the last one,
        // which may finish the solve; Lemke's method counts the same way).
        if self.stats.pivots >= self.limit {
            return Err(LcpError::PivotLimit {
                size: self.tab.m,
                limit: self.limit,
            });
        }
        if ratio.theta == 0.0 {
            self.stats.degenerate_pivots += 1;
        }
        self.tab.pivot(ratio.row, col, ratio.column);
        self.stats.pivots += 1;
        if self.refactor_every > 0 && self.stats.pivots.is_multiple_of(self.refactor_every) {
            self.refactor()?;
        }
        Ok(())
    }

    fn refactor(&mut self) -> Result<(), LcpError> {
        self.tab
            .refactor(&self.sys)
            .map_err(|ratio| LcpError::SingularBasis {
                size: self.tab.m,
                pivot: self.stats.pivots,
                ratio,
            })?;
        self.stats.refactorizations += 1;
        Ok(())
    }

    /// Pivots every non-basic free unknown (but the deferred ones) into the basis, in the direction
    /// in which a row limits it (preferring the one that lowers the phase-1
    /// objective). A free unknown no row limits stays non-basic at 0.
    fn enter_free(&mut self) -> Result<(), LcpError> {
        let free: Vec<usize> = (0..self.bounds.len())
            .filter(|&v| self.bounds[v] == Bound::Free && !self.deferred[v])
            .collect();
        for var in free {
            let Position::Nonbasic(s) = self.tab.position[var] else {
                continue;
            };
            let d = self.tab.reduced_cost(0, s);
            let first = if d > 0.0 { -1.0 } else { 1.0 };
            let mut chosen = None;
            for sigma in [first, -first] {
                if let Some(r) = self.tab.ratio_test(
                    s,
                    sigma,
                    self.rule(Phase::Feasibility),
                    None,
                    &self.opts.tolerances,
                    self.zero_level,
                ) {
                    chosen = Some(r);
                    break;
                }
            }
            if let Some(r) = chosen {
                self.pivot(r, s)?;
            }
        }
        Ok(())
    }

    /// Pivots on objective row `phase` until no admissible candidate
    /// improves it or its value falls to `stop`.
    ///
    /// In phase 1, when no admissible candidate has a negative reduced cost
    /// but the artificial sum is still positive, admissible candidates with
    /// a zero reduced cost (within the cost tolerance) may enter: such a
    /// move leaves the objective unchanged but can unlock the restricted
    /// entry of another unknown (a non-negative extra unknown that no row
    /// of the objective involves). A set of visited bases rules out cycling
    /// among these moves.
    fn iterate(&mut self, phase: Phase, stop: f64) -> Result<(), LcpError> {
        let k = match phase {
            Phase::Feasibility => 0,
            Phase::Objective => 1,
        };
        let tol = self.opts.tolerances;
        let mut cost_scale = 0.0f64;
        for j in 0..self.tab.n() {
            cost_scale = cost_scale.max(self.tab.reduced_cost(k, j).abs());
        }
        let cost_tol = tol.cost * cost_scale.max(f64::MIN_POSITIVE);
        let mut visited: HashSet<Vec<usize>> = HashSet::new();
        loop {
            if self.tab.objective_value(k) <= stop {
                return Ok(());
            }
            let chosen = match self.choose(k, phase, |d| d < -cost_tol, |d| d.abs() > cost_tol)? {
                Some(c) => Some(c),
                None if phase == Phase::Feasibility => {
                    let mut key = self.tab.basic.clone();
                    key.sort_unstable();
                    if visited.insert(key) {
                        self.choose(k, phase, |d| d.abs() <= cost_tol, |d| d.abs() <= cost_tol)?
                    } else {
                        None
                    }
                }
                None => None,
            };
            match chosen {
                Some((r, j)) => self.pivot(r, j)?,
                None => return Ok(()),
            }
        }
    }

    /// The admissible entering candidate of best reduced cost among those
    /// whose reduced cost `d` passes `nonneg_ok(d)` (non-negative unknowns,
    /// entering upwards) or `free_ok(d)` (free unknowns, entering against the
    /// sign of `d`); with the row its ratio test picks.
    fn choose(
        &self,
        k: usize,
        phase: Phase,
        nonneg_ok: impl Fn(f64) -> bool,
        free_ok: impl Fn(f64) -> bool,
    ) -> Result<Option<(Ratio, usize)>, LcpError> {
        let tol = self.opts.tolerances;
        let mut cands: Vec<(usize, f64, f64)> = Vec::new();
        for j in 0..self.tab.n() {
            let var = self.tab.nonbasic[j];
            if self.artificial[var] || (self.deferred[var] && phase == Phase::Feasibility) {
                continue;
            }
            let d = self.tab.reduced_cost(k, j);
            match self.bounds[var] {
                Bound::NonNegative if nonneg_ok(d) => cands.push((j, 1.0, -d)),
                Bound::Free if free_ok(d) => {
                    cands.push((j, if d > 0.0 { -1.0 } else { 1.0 }, d.abs()))
                }
                _ => {}
            }
        }
        // Best first (largest improvement, then lowest column): usually the
        // first or second candidate is admissible, so candidates are taken
        // out one by one rather than sorted (a sort per pivot cost more than
        // the pivot's own bookkeeping).
        let better =
            |a: &(usize, f64, f64), b: &(usize, f64, f64)| b.2.total_cmp(&a.2).then(a.0.cmp(&b.0));
        while let Some(best) = (0..cands.len()).min_by(|&x, &y| better(&cands[x], &cands[y])) {
            let (j, sigma, _) = cands.swap_remove(best);
            let var = self.tab.nonbasic[j];
            let prefer = self.complement[var].and_then(|c| match self.tab.position[c] {
                Position::Basic(r) => Some(r),
                Position::Nonbasic(_) => None,
            });
            match self
                .tab
                .ratio_test(j, sigma, self.rule(phase), prefer, &tol, self.zero_level)
            {
                Some(r) if prefer.is_none_or(|rc| rc == r.row) => return Ok(Some((r, j))),
                Some(_) => continue,
                None if prefer.is_some() => continue,
                None if phase == Phase::Objective => {
                    return Err(LcpError::Unbounded {
                        size: self.tab.m,
                        pivot: self.stats.pivots,
                        entering: self.names.name(var),
                    });
                }
                None => continue,
            }
        }
        Ok(None)
    }
}
