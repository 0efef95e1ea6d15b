//! The restricted-entry (complementary) simplex on the general tableau:
//! Wolfe (1959), as used by Conry & Seireg (1971) for the contact problem
//! (their Fig. 2).
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
//! A mixed LCP `w = M z + B u + q`, `0 = C z + D u + r` is solved as the
//! program `-M z - B u + w = q`, `C z + D u = -r`, pairs `(z_i, w_i)`; any
//! border, non-negative extra unknowns included.

use std::cmp::Ordering;
use std::collections::{BinaryHeap, HashSet};

use faer::{Col, Mat};

use crate::LcpError;
use crate::linalg::norm_inf;
use crate::methods::{Answer, Attempted, Failure};
use crate::options::Options;
use crate::problem::{Bound, Problem};
use crate::program::{Column, ComplementaryProgram};
use crate::statistics::Work;
use crate::tableau::basic::basic_solution;
use crate::tableau::border::first_contact;
use crate::tableau::general::{GeneralTableau, Position, Ratio, RowRule, UPDATE_BLOCK};
use crate::tableau::system::{EQUILIBRATION_PASSES, System};

/// The answer of the restricted-entry simplex on a program, before
/// certification.
pub(crate) struct ProgramAnswer {
    /// Every original unknown, in original units.
    pub x: Vec<f64>,
    /// Basic original unknowns.
    pub basis: Vec<usize>,
    /// The attempt's counts.
    pub work: Work,
}

/// The restricted-entry simplex on the program of a mixed problem; with
/// `relaxed`, every extra unknown free (the strategy's answer to a stalled
/// phase 1 with non-negative extra unknowns: an answer whose extras come out
/// non-negative solves the problem as given, which its certificate checks).
pub(crate) fn attempt(problem: &Problem<'_>, opts: &Options, relaxed: bool) -> Attempted {
    let p = &problem.mixed;
    let (n, k, me) = (p.size(), p.extras(), p.equalities());
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
    if relaxed {
        bounds.extend(std::iter::repeat_n(Bound::Free, k));
    } else {
        bounds.extend_from_slice(p.bounds);
    }
    bounds.extend(std::iter::repeat_n(Bound::NonNegative, n));
    let mut complement: Vec<Option<usize>> = (0..n).map(|i| Some(n + k + i)).collect();
    complement.extend(std::iter::repeat_n(None, k));
    complement.extend((0..n).map(Some));
    let b = Col::from_fn(rows, |i| if i < n { p.q[i] } else { -p.r[i - n] });
    let mut program = ComplementaryProgram::from_parts(rows, dense, columns, bounds, complement, b);
    // The program is used once: its dense block moves into the engine
    // instead of being copied (one N x N matrix fewer).
    let dense = std::mem::replace(&mut program.dense, Mat::zeros(0, 0));
    // A border of several rows: the free unknowns enter at the rows of its
    // first contact (where the rigid bodies first rest), not at whichever
    // row limits each one alone.
    let entry = problem
        .border
        .filter(|b| b.columns.ncols() >= 2)
        .and_then(|b| {
            first_contact(b.columns, b.resultant, p.q, &opts.tolerances)
                .ok()
                .map(|f| f.basis)
        });
    let out = run_with(&program, dense, opts, entry.as_deref())?;
    let mut basic = vec![false; n];
    for &v in &out.basis {
        if v < n {
            basic[v] = true;
        }
    }
    Ok(Answer {
        z: Col::from_fn(n, |i| out.x[i]),
        u: Col::from_fn(k, |j| out.x[n + j]),
        basic,
        work: out.work,
    })
}

/// The restricted-entry simplex on a program (its dense block copied).
pub(crate) fn attempt_program(
    p: &ComplementaryProgram,
    opts: &Options,
) -> Result<ProgramAnswer, Failure> {
    run_with(p, p.dense.clone(), opts, None)
}

/// An entering candidate: its column, its direction (+1 up, -1 down for a
/// free unknown) and the improvement rate of its reduced cost.
struct Candidate {
    column: usize,
    sigma: f64,
    gain: f64,
}

/// The heap's order: the better candidate is the greater (larger gain,
/// then lower column; columns are distinct, so the order is total).
impl Ord for Candidate {
    fn cmp(&self, other: &Self) -> Ordering {
        self.gain
            .total_cmp(&other.gain)
            .then(other.column.cmp(&self.column))
    }
}

impl PartialOrd for Candidate {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl PartialEq for Candidate {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Candidate {}

/// Which objective row a phase works on.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// Minimize the sum of artificials (objective row 0).
    Feasibility,
    /// Minimize `c^T x` (objective row 1).
    Objective,
}

/// The state of one run of the simplex.
struct Run<'a> {
    sys: System,
    tab: GeneralTableau,
    bounds: Vec<Bound>,
    complement: &'a [Option<usize>],
    artificial: Vec<bool>,
    deferred: Vec<bool>,
    work: Work,
    opts: &'a Options,
    zero_level: f64,
    limit: usize,
    refactor_every: usize,
    names: &'a ComplementaryProgram,
    /// The rows the free unknowns enter at, in order, where they tie.
    entry: Option<&'a [usize]>,
}

/// The program's constraints scaled for pivoting: negative right-hand
/// sides negated, equilibrated, and the initial basis (a `+1` slack of a
/// non-negative unknown, else an artificial appended).
struct Setup {
    sys: System,
    basis: Vec<usize>,
    bounds: Vec<Bound>,
    artificial: Vec<bool>,
}

fn setup(p: &ComplementaryProgram, dense: Mat<f64>, opts: &Options) -> Setup {
    let m = p.rows;
    let nv = p.columns.len();
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
    Setup {
        sys,
        basis,
        bounds,
        artificial,
    }
}

/// Runs the restricted-entry simplex on the program's constraints with
/// `dense` as its dense block (a copy of `p.dense`, or the block itself
/// moved out of a one-use program).
fn run_with(
    p: &ComplementaryProgram,
    dense: Mat<f64>,
    opts: &Options,
    entry: Option<&[usize]>,
) -> Result<ProgramAnswer, Failure> {
    let m = p.rows;
    let nv = p.columns.len();
    let Setup {
        sys,
        basis,
        bounds,
        artificial,
    } = setup(p, dense, opts);
    let total = sys.columns.len();
    let mut deferred = p.deferred.clone();
    deferred.resize(total, false);
    let par = opts.par(m, total - m + 1);
    let work = Work {
        tableau_rows: m,
        tableau_columns: total - m + 1,
        ..Work::default()
    };
    let tab = match GeneralTableau::from_identity(&sys, basis, par, UPDATE_BLOCK) {
        Ok(tab) => tab,
        Err(e) => return Err(Failure::error(e, work)),
    };
    let zero_level = opts.tolerances.zero * norm_inf(sys.b.as_ref()).max(f64::MIN_POSITIVE);
    let mut run = Run {
        sys,
        tab,
        bounds,
        complement: &p.complement,
        artificial,
        deferred,
        work,
        opts,
        zero_level,
        limit: opts.pivot_limit(m, nv),
        refactor_every: opts.refactor_every(m),
        names: p,
        entry,
    };
    match run.phases(p.cost.is_some()) {
        Ok(()) => {}
        Err(e) => return Err(Failure::error(e, run.work)),
    }
    // Final basic solution from the data, refined.
    let basis = run.tab.basic.clone();
    let (xb, steps) = match basic_solution(
        &run.sys,
        &basis,
        Some(&mut run.tab),
        par,
        opts.refinement_steps,
    ) {
        Ok(v) => v,
        Err(singular) => {
            let e = singular.at(m, run.work.pivots);
            return Err(Failure::error(e, run.work));
        }
    };
    run.work.refinement_steps = steps;
    let mut x = vec![0.0; nv];
    let mut basis = Vec::new();
    for (row, &var) in run.tab.basic.iter().enumerate() {
        if var < nv {
            x[var] = run.sys.col_scale[var] * xb[row];
            basis.push(var);
        }
    }
    Ok(ProgramAnswer {
        x,
        basis,
        work: run.work,
    })
}

impl Run<'_> {
    /// Steps 3 to 6: the free unknowns enter, phase 1, and phase 2 when
    /// the program has an objective.
    fn phases(&mut self, objective: bool) -> Result<(), LcpError> {
        self.enter_free()?;
        let artificials = self.artificial.iter().filter(|a| **a).count();
        let stop = self.zero_level * artificials.max(1) as f64;
        self.iterate(Phase::Feasibility, stop)?;
        if self.tab.objective_value(0) > stop {
            // One refactorization to rule out drift before declaring failure.
            self.refactor()?;
            self.iterate(Phase::Feasibility, stop)?;
            let residual = self.tab.objective_value(0);
            if residual > stop {
                return Err(LcpError::Infeasible {
                    size: self.tab.m,
                    pivot: self.work.pivots,
                    residual: residual / norm_inf(self.sys.b.as_ref()).max(f64::MIN_POSITIVE),
                });
            }
        }
        if objective {
            self.iterate(Phase::Objective, f64::NEG_INFINITY)?;
        }
        Ok(())
    }

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
        if self.work.pivots >= self.limit {
            return Err(LcpError::PivotLimit {
                size: self.tab.m,
                limit: self.limit,
            });
        }
        if ratio.theta == 0.0 {
            self.work.degenerate_pivots += 1;
        }
        self.tab.pivot(ratio.row, col, ratio.column);
        self.work.pivots += 1;
        if self.refactor_every > 0 && self.work.pivots.is_multiple_of(self.refactor_every) {
            self.refactor()?;
        }
        Ok(())
    }

    fn refactor(&mut self) -> Result<(), LcpError> {
        self.tab
            .refactor(&self.sys)
            .map_err(|singular| singular.at(self.tab.m, self.work.pivots))?;
        self.work.refactorizations += 1;
        Ok(())
    }

    /// Pivots every non-basic free unknown (but the deferred ones) into the basis, in the direction
    /// in which a row limits it (preferring the one that lowers the phase-1
    /// objective). A free unknown no row limits stays non-basic at 0.
    fn enter_free(&mut self) -> Result<(), LcpError> {
        let free: Vec<usize> = (0..self.bounds.len())
            .filter(|&v| self.bounds[v] == Bound::Free && !self.deferred[v])
            .collect();
        for (index, var) in free.into_iter().enumerate() {
            let Position::Nonbasic(s) = self.tab.position[var] else {
                continue;
            };
            let prefer = self.entry.and_then(|rows| rows.get(index).copied());
            let d = self.tab.reduced_cost(0, s);
            let first = if d > 0.0 { -1.0 } else { 1.0 };
            let mut chosen = None;
            for sigma in [first, -first] {
                if let Some(r) = self.tab.ratio_test(
                    s,
                    sigma,
                    self.rule(Phase::Feasibility),
                    prefer,
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
            crate::cancel::check()?;
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
        let mut cands: Vec<Candidate> = Vec::new();
        for column in 0..self.tab.n() {
            let var = self.tab.nonbasic[column];
            if self.artificial[var] || (self.deferred[var] && phase == Phase::Feasibility) {
                continue;
            }
            let d = self.tab.reduced_cost(k, column);
            match self.bounds[var] {
                Bound::NonNegative if nonneg_ok(d) => cands.push(Candidate {
                    column,
                    sigma: 1.0,
                    gain: -d,
                }),
                Bound::Free if free_ok(d) => cands.push(Candidate {
                    column,
                    sigma: if d > 0.0 { -1.0 } else { 1.0 },
                    gain: d.abs(),
                }),
                _ => {}
            }
        }
        // Best first (largest improvement, then lowest column), taken out of
        // a heap: built in one pass (a full sort per pivot cost more than the
        // pivot's own bookkeeping), and a run of rejected candidates (465 a
        // pivot on the spheres under an approach at N = 3801) costs a log each.
        let mut cands = BinaryHeap::from(cands);
        let rule = self.rule(phase);
        while let Some(Candidate {
            column: j, sigma, ..
        }) = cands.pop()
        {
            let var = self.tab.nonbasic[j];
            let prefer = self.complement[var].and_then(|c| match self.tab.position[c] {
                Position::Basic(r) => Some(r),
                Position::Nonbasic(_) => None,
            });
            // A restricted entry whose complement cannot leave is rejected
            // from one entry, without reading the column.
            if let Some(rc) = prefer
                && !self.tab.may_leave(rc, j, sigma, rule(rc))
            {
                continue;
            }
            match self
                .tab
                .ratio_test(j, sigma, &rule, prefer, &tol, self.zero_level)
            {
                Some(r) if prefer.is_none_or(|rc| rc == r.row) => return Ok(Some((r, j))),
                Some(_) => continue,
                None if prefer.is_some() => continue,
                None if phase == Phase::Objective => {
                    return Err(LcpError::Unbounded {
                        size: self.tab.m,
                        pivot: self.work.pivots,
                        entering: self.names.name(var),
                    });
                }
                None => continue,
            }
        }
        Ok(None)
    }
}
