//! The paper's design method: the min-max problem of a linear family over
//! every load case as one linear program with complementarity constraints
//! (Conry & Seireg 1971, eq. 16), solved on the engine's restricted-entry
//! simplex.
//!
//! For load cases l = 1..L (points k of case l, influence matrix S_l,
//! separations eps_l, load P_l, measures A_k) and a profile
//! `y(s) = sum_i theta_i phi_i(s)` linear in its parameters:
//!
//! ```text
//!     minimize    t                                   (t = the worst p_max_l / r_l over the cases)
//!     subject to  -S_l F_l + Y_l + alpha_l e - Phi_l theta = eps_l     compatibility, per case
//!                 F_l - r_l A_l t + s_l = 0                             F_k / A_k <= r_l t
//!                 e^T F_l = P_l                                        equilibrium
//!                 Phi theta >= 0 at every axial station                the correction is a separation
//!                 theta_0 <= c_max                                     the constant (polynomial families)
//!                 F_l, Y_l, s_l >= 0,  F_lk Y_lk = 0                   the contact criterion
//! ```
//!
//! Part 1 finds the contact solution with the design parameters held at 0
//! (deferred columns), part 2 lowers t with theta as extra columns, keeping
//! `F_lk Y_lk = 0` by the restricted-entry rule. It ends at a complementary
//! basic solution that no admissible pivot improves: a local minimum.
//! Every case is a block of one tableau, so its memory and time grow with
//! the square of all the cases' points together.

use elcon_lcp::{Bound, ProgramBuilder};
use faer::{Col, Mat};

use crate::DesignError;
use crate::basis::Basis;
use crate::found::Found;
use crate::prepared::{Case, Solver};

/// Variables of the design program.
struct Layout {
    forces: Vec<std::ops::Range<usize>>,
    theta: std::ops::Range<usize>,
    t: usize,
}

/// The program's rows: each case's block (compatibility, intensity and
/// resultant rows) from `starts[l]`, then one row per axial station from
/// `profile`, then the constant's bound row where the family has one.
struct Rows {
    starts: Vec<usize>,
    profile: usize,
    stations: usize,
    bound: Option<usize>,
    count: usize,
}

impl Rows {
    fn of(cases: &[Case<'_>], basis: &Basis) -> Self {
        let mut count = 0;
        let mut starts = Vec::new();
        for c in cases {
            starts.push(count);
            count += 2 * c.station.len() + c.resultants.len();
        }
        let (profile, stations) = (count, basis.phi.nrows());
        count += stations;
        let bound = basis.constant.map(|_| count);
        if bound.is_some() {
            count += 1;
        }
        Self {
            starts,
            profile,
            stations,
            bound,
            count,
        }
    }
}

/// Builds the design program around the start `theta0` (the program's
/// parameters are `delta = theta - theta0`).
fn program(
    cases: &[Case<'_>],
    basis: &Basis,
    c_max: Option<f64>,
    theta0: &[f64],
) -> Result<(elcon_lcp::ComplementaryProgram, Layout), DesignError> {
    let rows = Rows::of(cases, basis);
    let drops0 = basis.drops(theta0);
    let mut b = ProgramBuilder::new(rows.count);
    let mut rhs = Col::<f64>::zeros(rows.count);
    let forces = contact_columns(&mut b, &mut rhs, cases, &rows, &drops0)?;
    motion_columns(&mut b, cases, &rows)?;
    // theta: -Phi in the compatibility rows and the station rows, +1 in the bound row.
    let (n_st, m) = (rows.stations, basis.params());
    let mut theta_block = Mat::<f64>::zeros(rows.count, m);
    for (l, c) in cases.iter().enumerate() {
        for (k, &st) in c.station.iter().enumerate() {
            for i in 0..m {
                theta_block[(rows.starts[l] + k, i)] = -basis.phi[(st, i)];
            }
        }
    }
    for st in 0..n_st {
        for i in 0..m {
            theta_block[(rows.profile + st, i)] = -basis.phi[(st, i)];
        }
        rhs[rows.profile + st] = drops0[st];
    }
    if let (Some(row), Some(ci), Some(c_max)) = (rows.bound, basis.constant, c_max) {
        theta_block[(row, ci)] = 1.0;
        rhs[row] = c_max - theta0[ci];
    }
    let theta = b.dense_columns("theta", theta_block.as_ref(), Bound::Free)?;
    b.defer(theta.clone())?;
    let t = objective_and_slacks(&mut b, cases, &rows)?;
    b.rhs(rhs.as_ref())?;
    Ok((b.build()?, Layout { forces, theta, t }))
}

/// Each case's forces F and gaps Y, complementary, with their rows'
/// right-hand sides in `rhs`: compatibility rows `-S F + Y (+ sum
/// lambda_j m_j) = eps + drops`, intensity rows `F / A`, resultant rows
/// `sum m_j F = b_j`. Returns the forces' columns.
fn contact_columns(
    b: &mut ProgramBuilder,
    rhs: &mut Col<f64>,
    cases: &[Case<'_>],
    rows: &Rows,
    drops0: &[f64],
) -> Result<Vec<std::ops::Range<usize>>, DesignError> {
    let mut forces = Vec::new();
    for (l, c) in cases.iter().enumerate() {
        let n = c.station.len();
        let start = rows.starts[l];
        let (rc, ri, re) = (start, start + n, start + 2 * n);
        let s = c
            .problem
            .entries("the design program (use the descent: DesignMethod::Descent or Auto)")
            .map_err(DesignError::analysis(format!("load case {l}")))?;
        let block = Mat::from_fn(rows.count, n, |r, j| {
            if (rc..rc + n).contains(&r) {
                -s[(r - rc, j)]
            } else if r == ri + j {
                1.0
            } else if (re..re + c.resultants.len()).contains(&r) {
                c.levers[(j, r - re)]
            } else {
                0.0
            }
        });
        let f = b.dense_columns(&format!("F{l}"), block.as_ref(), Bound::NonNegative)?;
        let y = b.unit_columns(&format!("Y{l}"), rc..rc + n, 1.0, Bound::NonNegative)?;
        for j in 0..n {
            b.complementary(f.start + j, y.start + j)?;
        }
        forces.push(f);
        for k in 0..n {
            rhs[rc + k] = c.separation[k] + drops0[c.station[k]];
        }
        for (j, &resultant) in c.resultants.iter().enumerate() {
            rhs[re + j] = resultant;
        }
    }
    Ok(forces)
}

/// The free rigid motions: every case's approach, then every case's free
/// rotations (levers in the compatibility rows).
fn motion_columns(
    b: &mut ProgramBuilder,
    cases: &[Case<'_>],
    rows: &Rows,
) -> Result<(), DesignError> {
    let motions = cases.iter().map(|c| c.resultants.len()).max().unwrap_or(0);
    for j in 0..motions {
        let with: Vec<usize> = (0..cases.len())
            .filter(|&l| j < cases[l].resultants.len())
            .collect();
        let block = Mat::from_fn(rows.count, with.len(), |r, col| {
            let l = with[col];
            let start = rows.starts[l];
            if (start..start + cases[l].station.len()).contains(&r) {
                cases[l].levers[(r - start, j)]
            } else {
                0.0
            }
        });
        let name = if j == 0 {
            "alpha".to_string()
        } else {
            format!("rotation{j}")
        };
        b.dense_columns(&name, block.as_ref(), Bound::Free)?;
    }
    Ok(())
}

/// The worst intensity `t` (the cost), `-r_l A_k / w_k` in each case's
/// intensity rows, and the slacks: of the intensity rows, of the station
/// rows and of the bound row. Returns `t`'s column.
fn objective_and_slacks(
    b: &mut ProgramBuilder,
    cases: &[Case<'_>],
    rows: &Rows,
) -> Result<usize, DesignError> {
    let t_col = Mat::from_fn(rows.count, 1, |r, _| {
        for (l, c) in cases.iter().enumerate() {
            let n = c.station.len();
            let ri = rows.starts[l] + n;
            if (ri..ri + n).contains(&r) {
                return -c.reference * c.measures[r - ri] / c.weights[r - ri];
            }
        }
        0.0
    });
    let t = b.dense_column("p_max", t_col.col(0), Bound::Free)?;
    b.cost(t, 1.0)?;
    for (l, c) in cases.iter().enumerate() {
        let n = c.station.len();
        let ri = rows.starts[l] + n;
        b.unit_columns(&format!("s{l}"), ri..ri + n, 1.0, Bound::NonNegative)?;
    }
    let stations = rows.profile..rows.profile + rows.stations;
    b.unit_columns("u", stations, 1.0, Bound::NonNegative)?;
    if let Some(row) = rows.bound {
        b.unit_columns("v", row..row + 1, 1.0, Bound::NonNegative)?;
    }
    Ok(t)
}

/// Part 1 and part 2 from the start `theta0`.
pub(crate) fn solve(
    prepared: &[Case<'_>],
    basis: &Basis,
    c_max: Option<f64>,
    theta0: &[f64],
    engine: &elcon_lcp::Options,
) -> Result<Found, DesignError> {
    let (program, layout) = program(prepared, basis, c_max, theta0)?;
    let solution = program.solve(engine)?;
    let theta: Vec<f64> = layout
        .theta
        .clone()
        .map(|v| theta0[v - layout.theta.start] + solution.x[v])
        .collect();
    // The objective from the program's forces (t itself may sit above it at
    // a degenerate vertex; the forces are what the re-analysis reproduces).
    let (mut max_intensity, mut objective) = (0.0f64, 0.0f64);
    for (l, range) in layout.forces.iter().enumerate() {
        for (k, v) in range.clone().enumerate() {
            let p = solution.x[v] / prepared[l].measures[k];
            max_intensity = max_intensity.max(p);
            objective = objective.max(prepared[l].weights[k] * p / prepared[l].reference);
        }
    }
    debug_assert!(solution.x[layout.t] >= objective * (1.0 - 1e-9));
    Ok(Found {
        theta,
        objective,
        max_intensity,
        solutions: None,
        solver: Solver::Program {
            certificate: solution.certificate,
            statistics: solution.statistics,
        },
        criterion: crate::subsurface::Criterion::Pressure,
    })
}
