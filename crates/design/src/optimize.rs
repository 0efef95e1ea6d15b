//! The paper's design problem: the profile correction of a family that
//! minimizes the maximum load intensity (Conry & Seireg 1971, eq. 16),
//! extended to several load cases at once.
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
//! Linear but for the complementarity, solved as the paper does on the
//! engine's restricted-entry simplex ([`elcon_lcp::ComplementaryProgram`]):
//! part 1 finds the contact solution with the design parameters held at 0
//! (deferred columns), part 2 lowers t with theta as extra columns, keeping
//! `F_lk Y_lk = 0` by the restricted-entry rule.
//!
//! What is guaranteed: part 2 ends at a complementary basic solution that no
//! admissible pivot improves, a local minimum of a non-convex problem;
//! global optimality is not (the paper says so too). The local minima are
//! real: on a flexible beam over a stiff foundation the uncorrected start
//! ends with the load on the few points under it (p_max more than 5 P/L
//! with a free profile, the bound the test checks) because bringing the
//! next point into contact needs a move that first raises p_max. elcon
//! therefore runs part 2 from more than one start (the uncorrected
//! geometry, as in the paper; for line contacts the
//! least-squares fit of the uniform-pressure separation to the family, the
//! paper's own comparison; and any profiles the caller gives) and keeps the
//! best. Part 2 never ends worse than its start.
//! Every design is re-analysed with elcon-analysis; its p_max and the
//! re-analysis' agree to [`DesignOptions::agreement`] or the design is an
//! error. The constant c has an upper bound (the paper's c_max): a uniform
//! separation only shifts the approach, and without a bound the program
//! would have a ray along which c and alpha grow together.
//!
//! Several load cases share theta and t; the program has one block per case,
//! so the correction found is a local minimum of the worst p_max over the
//! cases, with the same guarantee as for one case. `r_l` are reference
//! intensities ([`DesignOptions::reference_intensities`], default 1): with
//! `r_l` = each load's Hertz or mean pressure the design evens the pressure
//! relative to each load, so that a light load counts as much as a heavy one.

use elcon_analysis::{ContactProblem, Method, Options};
use elcon_influence::{Dimension, PointSet};
use elcon_lcp::{Bound, Certificate, ProgramBuilder, Statistics};
use faer::linalg::solvers::SolveLstsq;
use faer::{Col, Mat, MatRef};

use crate::evaluate::{Evaluation, evaluate, load_of};
use crate::target::uniform_target;
use crate::{Axis, DesignError, Profile};

/// A profile family linear in its parameters, for the design program.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// The paper's `a s^2 + b s + c`.
    Quadratic,
    /// `sum_{i <= degree} c_i s^i`.
    Polynomial {
        /// The degree d (at least 0).
        degree: usize,
    },
    /// One drop per axial station.
    Free,
}

/// Options of a design.
#[derive(Debug, Clone)]
pub struct DesignOptions {
    /// The bound c_max on the constant of a polynomial family (length).
    /// Default: ten times the largest elastic deflection under a uniform
    /// pressure plus the largest initial separation, over the cases (and at
    /// least twice the constant of the fitted start).
    pub max_constant: Option<f64>,
    /// Options of the engine for the design program.
    pub engine: Options,
    /// The method of the re-analysis (default: block principal pivoting).
    pub reanalysis: Method,
    /// Options of the re-analysis.
    pub reanalysis_options: Options,
    /// Also start part 2 from the least-squares fit of the uniform-pressure
    /// separation (line contacts only; default true).
    pub fitted_start: bool,
    /// More starting profiles (any family: each is sampled at the stations
    /// and fitted to the design's family by least squares, shifted to be
    /// non-negative). A design from a start is never worse than the start
    /// itself, so a known good crown given here bounds the result. Default
    /// none.
    pub starts: Vec<Profile>,
    /// Largest accepted relative difference between the design's objective
    /// and its re-analysis' (default 1e-9).
    pub agreement: f64,
    /// Reference intensities r_l, one per load case (force per length or per
    /// area, > 0): the objective is the worst `p_max_l / r_l`. Default: all 1
    /// (the worst p_max itself).
    pub reference_intensities: Option<Vec<f64>>,
}

impl Default for DesignOptions {
    fn default() -> Self {
        Self {
            max_constant: None,
            engine: Options::default(),
            reanalysis: Method::BlockPivoting,
            reanalysis_options: Options::default(),
            fitted_start: true,
            starts: Vec::new(),
            agreement: 1e-9,
            reference_intensities: None,
        }
    }
}

/// How one start of part 2 ended.
#[derive(Debug, Clone)]
pub struct StartOutcome {
    /// "uncorrected", "fitted uniform-pressure separation", or "given start i".
    pub label: String,
    /// The objective it reached (the worst p_max_l / r_l), or why it failed.
    pub result: Result<f64, String>,
    /// Pivots of its solve.
    pub pivots: usize,
}

/// A certified design.
#[derive(Debug, Clone)]
pub struct Design {
    /// The correction, shifted so that its smallest drop over the stations is 0.
    pub profile: Profile,
    /// The axial stations (distinct axial positions of the points; length).
    pub stations: Vec<f64>,
    /// The design program's objective t: the worst `p_max_l / r_l` over the
    /// cases (the worst p_max when every r_l = 1).
    pub objective: f64,
    /// The design program's worst load intensity over the cases, max_k F_k / A_k.
    pub max_intensity: f64,
    /// The re-analysis with elcon-analysis: each case's certified solution.
    pub evaluation: Evaluation,
    /// Every start of part 2 and where it ended.
    pub starts: Vec<StartOutcome>,
    /// The certificate of the chosen design program's solution.
    pub certificate: Certificate,
    /// The engine's statistics for the chosen start.
    pub statistics: Statistics,
    /// The bound c_max used (polynomial families).
    pub max_constant: Option<f64>,
    /// Whether the normalized constant (smallest drop 0) needs the whole of
    /// c_max: the bound then limits the design; raise it.
    pub constant_at_bound: bool,
}

/// The basis of a family at the stations: `Phi[st, i] = phi_i(s_st)`, in the
/// normalized coordinate `s / scale` for polynomials.
struct Basis {
    phi: Mat<f64>,
    /// Index of the constant parameter (polynomials).
    constant: Option<usize>,
    /// The length that normalizes s.
    scale: f64,
}

impl Basis {
    fn new(family: Family, stations: &[f64]) -> Result<Self, DesignError> {
        let n = stations.len();
        let scale = stations.iter().fold(0.0f64, |a, s| a.max(s.abs()));
        let scale = if scale > 0.0 { scale } else { 1.0 };
        match family {
            Family::Quadratic | Family::Polynomial { .. } => {
                let degree = match family {
                    Family::Polynomial { degree } => degree,
                    _ => 2,
                };
                if degree + 1 > n {
                    return Err(DesignError::Incompatible {
                        field: "family.degree",
                        reason: format!(
                            "degree {degree} needs at least {} axial stations, the cases have {n}",
                            degree + 1
                        ),
                    });
                }
                Ok(Self::polynomial(degree, stations, scale))
            }
            Family::Free => Ok(Self {
                phi: Mat::identity(n, n),
                constant: None,
                scale,
            }),
        }
    }

    fn polynomial(degree: usize, stations: &[f64], scale: f64) -> Self {
        Self {
            phi: Mat::from_fn(stations.len(), degree + 1, |st, i| {
                (stations[st] / scale).powi(i as i32)
            }),
            constant: Some(0),
            scale,
        }
    }

    fn params(&self) -> usize {
        self.phi.ncols()
    }

    /// The drops at the stations for parameters theta.
    fn drops(&self, theta: &[f64]) -> Vec<f64> {
        (0..self.phi.nrows())
            .map(|st| (0..theta.len()).map(|i| self.phi[(st, i)] * theta[i]).sum())
            .collect()
    }

    /// The profile of parameters theta, shifted so its smallest drop is 0.
    fn profile(&self, family: Family, stations: &[f64], theta: &[f64]) -> Profile {
        let lowest = self.drops(theta).into_iter().fold(f64::INFINITY, f64::min);
        let mut theta = theta.to_vec();
        match family {
            Family::Free => {
                return Profile::Free {
                    positions: stations.to_vec(),
                    drops: theta.iter().map(|t| t - lowest).collect(),
                };
            }
            _ => theta[0] -= lowest,
        }
        let coefficients: Vec<f64> = theta
            .iter()
            .enumerate()
            .map(|(i, t)| t / self.scale.powi(i as i32))
            .collect();
        match family {
            Family::Quadratic => Profile::Quadratic {
                a: coefficients[2],
                b: coefficients[1],
                c: coefficients[0],
            },
            _ => Profile::Polynomial { coefficients },
        }
    }

    /// Least-squares parameters of drops `y` at the stations, shifted up so
    /// every drop is >= 0.
    fn fit(&self, y: &[f64]) -> Vec<f64> {
        match self.constant {
            None => y.iter().map(|v| v.max(0.0)).collect(),
            Some(c) => {
                let rhs = Col::from_fn(y.len(), |st| y[st]);
                let sol = self.phi.qr().solve_lstsq(&rhs);
                let mut theta: Vec<f64> = sol.iter().copied().collect();
                let lowest = self.drops(&theta).into_iter().fold(f64::INFINITY, f64::min);
                theta[c] -= lowest.min(0.0);
                theta
            }
        }
    }
}

/// The least-squares fit of `drops` at `positions` (one per station, length)
/// by a profile of `family`, shifted up so that every drop is >= 0 and the
/// smallest is 0: the paper's curve-fitting approximation ("assume a
/// uniform load distribution, compute the necessary initial separations and
/// then fit these data to a curve"), which ignores the resulting loads.
///
/// # Errors
/// [`DesignError::Incompatible`] for mismatched lengths, fewer than two
/// positions, repeated positions or a degree the positions cannot carry;
/// [`DesignError::InvalidInput`] for a non-finite value.
pub fn fit_profile(
    family: Family,
    positions: &[f64],
    drops: &[f64],
) -> Result<Profile, DesignError> {
    if positions.len() != drops.len() || positions.len() < 2 {
        return Err(DesignError::Incompatible {
            field: "drops",
            reason: format!(
                "needs one drop per position and at least two positions ({} positions, {} drops)",
                positions.len(),
                drops.len()
            ),
        });
    }
    if let Some(&v) = positions.iter().chain(drops).find(|v| !v.is_finite()) {
        return Err(DesignError::InvalidInput {
            field: "drops",
            value: v,
            reason: "positions and drops must be finite",
        });
    }
    let mut order: Vec<usize> = (0..positions.len()).collect();
    order.sort_by(|&a, &b| positions[a].total_cmp(&positions[b]));
    let stations: Vec<f64> = order.iter().map(|&i| positions[i]).collect();
    if stations.windows(2).any(|w| w[1] <= w[0]) {
        return Err(DesignError::Incompatible {
            field: "positions",
            reason: "positions must be distinct".into(),
        });
    }
    let y: Vec<f64> = order.iter().map(|&i| drops[i]).collect();
    let basis = Basis::new(family, &stations)?;
    Ok(basis.profile(family, &stations, &basis.fit(&y)))
}

/// One load case, prepared: its points' stations, measures and load, and
/// its free rigid motions (the approach first, then the free rotations that
/// its symmetry does not make zero) with the separations shifted by the
/// prescribed ones. (A correction that breaks a case's symmetry makes its
/// re-analysis free a rotation the program held: the re-analysis then
/// disagrees, and the design says so.)
struct Case<'a> {
    problem: &'a ContactProblem,
    /// The problem's dense S (the program is built from its entries).
    influence: MatRef<'a, f64>,
    station: Vec<usize>,
    measures: Vec<f64>,
    load: f64,
    /// The free motions' levers at every point (n x k) and resultants.
    levers: Mat<f64>,
    resultants: Vec<f64>,
    /// `eps` shifted by the prescribed motions.
    separation: Vec<f64>,
    /// Reference intensity r_l.
    reference: f64,
}

/// The axial stations of point sets (the load cases' points, say): the
/// distinct axial positions of all their points, increasing, positions
/// within 1e-9 of the whole range merged into the first of them; and, per
/// set, each point's station (an index into the stations). These are the
/// stations a design's free profile has one drop at ([`Design::stations`])
/// and its table is written at.
pub fn axial_stations<'a>(
    sets: impl IntoIterator<Item = &'a PointSet>,
    axis: Axis,
) -> (Vec<f64>, Vec<Vec<usize>>) {
    let all: Vec<Vec<f64>> = sets.into_iter().map(|p| axis.positions(p)).collect();
    let mut sorted: Vec<f64> = all.iter().flatten().copied().collect();
    sorted.sort_by(f64::total_cmp);
    let range = sorted.last().copied().unwrap_or(0.0) - sorted.first().copied().unwrap_or(0.0);
    let merge = 1e-9 * range.max(f64::MIN_POSITIVE);
    let mut stations: Vec<f64> = Vec::new();
    for s in sorted {
        if stations.last().is_none_or(|&last| s - last > merge) {
            stations.push(s);
        }
    }
    let index = all
        .iter()
        .map(|positions| {
            positions
                .iter()
                .map(|&s| {
                    let i = stations.partition_point(|&st| st < s - merge);
                    i.min(stations.len() - 1)
                })
                .collect()
        })
        .collect();
    (stations, index)
}

/// Variables of the design program.
struct Layout {
    forces: Vec<std::ops::Range<usize>>,
    theta: std::ops::Range<usize>,
    t: usize,
}

/// Builds the design program around the start `theta0` (the program's
/// parameters are `delta = theta - theta0`).
fn program(
    cases: &[Case<'_>],
    basis: &Basis,
    c_max: Option<f64>,
    theta0: &[f64],
) -> Result<(elcon_lcp::ComplementaryProgram, Layout), DesignError> {
    let n_st = basis.phi.nrows();
    let m = basis.params();
    let mut rows = 0;
    let mut starts = Vec::new();
    for c in cases {
        starts.push(rows);
        rows += 2 * c.station.len() + c.resultants.len();
    }
    let profile_rows = rows;
    rows += n_st;
    let bound_row = basis.constant.map(|_| rows);
    if bound_row.is_some() {
        rows += 1;
    }
    let drops0 = basis.drops(theta0);
    let mut b = ProgramBuilder::new(rows);
    let mut rhs = Col::<f64>::zeros(rows);
    let mut forces = Vec::new();
    for (l, c) in cases.iter().enumerate() {
        let n = c.station.len();
        let (rc, ri, re) = (starts[l], starts[l] + n, starts[l] + 2 * n);
        let s = c.influence;
        // Compatibility rows -S F + Y + sum lambda_j m_j = eps (+ drops),
        // intensity rows F / A, resultant rows sum m_j F = b_j.
        let block = Mat::from_fn(rows, n, |r, j| {
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
    // The free rigid motions: every case's approach, then every case's free
    // rotations (levers in the compatibility rows).
    let motions = cases.iter().map(|c| c.resultants.len()).max().unwrap_or(0);
    for j in 0..motions {
        let with: Vec<usize> = (0..cases.len())
            .filter(|&l| j < cases[l].resultants.len())
            .collect();
        let block = Mat::from_fn(rows, with.len(), |r, col| {
            let l = with[col];
            let start = starts[l];
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
    // theta: -Phi in the compatibility rows and the station rows, +1 in the bound row.
    let mut theta_block = Mat::<f64>::zeros(rows, m);
    for (l, c) in cases.iter().enumerate() {
        for (k, &st) in c.station.iter().enumerate() {
            for i in 0..m {
                theta_block[(starts[l] + k, i)] = -basis.phi[(st, i)];
            }
        }
    }
    for st in 0..n_st {
        for i in 0..m {
            theta_block[(profile_rows + st, i)] = -basis.phi[(st, i)];
        }
        rhs[profile_rows + st] = drops0[st];
    }
    if let (Some(row), Some(ci), Some(c_max)) = (bound_row, basis.constant, c_max) {
        theta_block[(row, ci)] = 1.0;
        rhs[row] = c_max - theta0[ci];
    }
    let theta = b.dense_columns("theta", theta_block.as_ref(), Bound::Free)?;
    b.defer(theta.clone())?;
    let t_col = Mat::from_fn(rows, 1, |r, _| {
        for (l, c) in cases.iter().enumerate() {
            let n = c.station.len();
            let ri = starts[l] + n;
            if (ri..ri + n).contains(&r) {
                return -c.reference * c.measures[r - ri];
            }
        }
        0.0
    });
    let t = b.dense_column("p_max", t_col.col(0), Bound::Free)?;
    b.cost(t, 1.0)?;
    for (l, c) in cases.iter().enumerate() {
        let n = c.station.len();
        let ri = starts[l] + n;
        b.unit_columns(&format!("s{l}"), ri..ri + n, 1.0, Bound::NonNegative)?;
    }
    b.unit_columns(
        "u",
        profile_rows..profile_rows + n_st,
        1.0,
        Bound::NonNegative,
    )?;
    if let Some(row) = bound_row {
        b.unit_columns("v", row..row + 1, 1.0, Bound::NonNegative)?;
    }
    b.rhs(rhs.as_ref())?;
    Ok((b.build()?, Layout { forces, theta, t }))
}

/// Designs the correction of `family` that minimizes the worst load
/// intensity over `cases` (each under load control, [`elcon_analysis::Normal::Load`]);
/// see the [module documentation](self) for the method and what it guarantees.
///
/// # Errors
/// [`DesignError::Incompatible`] for no case, a displacement-controlled case
/// or a degree the stations cannot carry; [`DesignError::InvalidInput`] for
/// a bad `max_constant` or `agreement`; [`DesignError::Engine`] or
/// [`DesignError::Analysis`] when every start failed (the first start's
/// error); [`DesignError::Disagreement`] when the best design's re-analysis
/// does not reproduce its p_max.
pub fn design(
    cases: &[ContactProblem],
    axis: Axis,
    family: Family,
    options: &DesignOptions,
) -> Result<Design, DesignError> {
    if cases.is_empty() {
        return Err(DesignError::Incompatible {
            field: "cases",
            reason: "no load case given".into(),
        });
    }
    if !(options.agreement.is_finite() && options.agreement > 0.0 && options.agreement < 1.0) {
        return Err(DesignError::InvalidInput {
            field: "agreement",
            value: options.agreement,
            reason: "must be in (0, 1)",
        });
    }
    if let Some(c) = options.max_constant
        && !(c.is_finite() && c > 0.0)
    {
        return Err(DesignError::InvalidInput {
            field: "max_constant",
            value: c,
            reason: "must be finite and > 0",
        });
    }
    let references = reference_intensities(options.reference_intensities.as_deref(), cases.len())?;
    let (stations, index) = axial_stations(cases.iter().map(ContactProblem::points), axis);
    let basis = Basis::new(family, &stations)?;
    let prepared: Vec<Case<'_>> =
        cases
            .iter()
            .zip(index)
            .enumerate()
            .map(|(l, (problem, station))| {
                let rigid = problem.rigid().clone();
                let points = problem.points();
                let at = |k: usize| (points.x(k), points.y(k));
                let levers = Mat::from_fn(points.len(), rigid.free.len(), |k, j| {
                    rigid.free[j].0.lever(at(k), rigid.load_point)
                });
                let shift = |k: usize| -> f64 {
                    -rigid
                        .prescribed
                        .iter()
                        .map(|&(mode, value)| value * mode.lever(at(k), rigid.load_point))
                        .sum::<f64>()
                };
                let eps = problem.separation();
                let influence = problem.influence().ok_or_else(|| DesignError::Incompatible {
                field: "cases",
                reason: format!(
                    "load case {l} holds S matrix-free (ContactProblem::lattice); the design \
                     program is built from S's entries: build it with ContactProblem::new or \
                     ::symmetric"
                ),
            })?;
                Ok(Case {
                    problem,
                    influence,
                    measures: points.measures(),
                    station,
                    load: load_of(problem, l)?,
                    levers,
                    resultants: rigid.free.iter().map(|&(_, v)| v).collect(),
                    separation: (0..points.len()).map(|k| eps[k] + shift(k)).collect(),
                    reference: references[l],
                })
            })
            .collect::<Result<_, DesignError>>()?;

    // Starts: the uncorrected geometry; for line contacts, the fit of the
    // uniform-pressure separation of the heaviest case.
    let mut starts: Vec<(String, Vec<f64>)> =
        vec![("uncorrected".into(), vec![0.0; basis.params()])];
    let heaviest = (0..prepared.len())
        .max_by(|&a, &b| prepared[a].load.total_cmp(&prepared[b].load))
        .unwrap_or(0);
    let line = cases
        .iter()
        .all(|c| c.points().dimension() == Dimension::Line);
    if options.fitted_start && line {
        let target = uniform_target(&cases[heaviest])?;
        let mut y = vec![0.0; stations.len()];
        for (k, &st) in prepared[heaviest].station.iter().enumerate() {
            y[st] = target.correction[k];
        }
        starts.push(("fitted uniform-pressure separation".into(), basis.fit(&y)));
    }
    for (i, profile) in options.starts.iter().enumerate() {
        let y = profile.separations(&stations)?;
        starts.push((
            format!("given start {i} ({})", profile.family()),
            basis.fit(&y),
        ));
    }
    let c_max = basis.constant.map(|ci| {
        options.max_constant.unwrap_or_else(|| {
            let elastic = prepared
                .iter()
                .map(|c| deflection_scale(c))
                .fold(0.0f64, f64::max);
            let fitted = starts.iter().map(|(_, th)| th[ci]).fold(0.0f64, f64::max);
            (10.0 * elastic).max(2.0 * fitted)
        })
    });

    let mut outcomes = Vec::new();
    let mut best: Option<Design> = None;
    let mut first_error = None;
    for (label, theta0) in &starts {
        let run = run_start(
            cases, &prepared, &basis, family, axis, &stations, c_max, theta0, options,
        );
        match run {
            Ok(d) => {
                outcomes.push(StartOutcome {
                    label: label.clone(),
                    result: Ok(d.objective),
                    pivots: d.statistics.pivots(),
                });
                if best.as_ref().is_none_or(|b| d.objective < b.objective) {
                    best = Some(d);
                }
            }
            Err(e) => {
                outcomes.push(StartOutcome {
                    label: label.clone(),
                    result: Err(e.to_string()),
                    pivots: 0,
                });
                first_error.get_or_insert(e);
            }
        }
    }
    match best {
        Some(mut d) => {
            d.starts = outcomes;
            Ok(d)
        }
        None => Err(first_error.expect("at least one start ran")),
    }
}

/// The reference intensities r_l: given (one per case, finite, > 0) or all
/// 1 (the design program's and the crown search's).
pub(crate) fn reference_intensities(
    given: Option<&[f64]>,
    cases: usize,
) -> Result<Vec<f64>, DesignError> {
    match given {
        None => Ok(vec![1.0; cases]),
        Some(r) if r.len() != cases => Err(DesignError::Incompatible {
            field: "reference_intensities",
            reason: format!(
                "has {} entries, expected {cases} (one per load case)",
                r.len()
            ),
        }),
        Some(r) => match r.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
            Some(&v) => Err(DesignError::InvalidInput {
                field: "reference_intensities",
                value: v,
                reason: "every reference intensity must be finite and > 0",
            }),
            None => Ok(r.to_vec()),
        },
    }
}

/// Largest elastic deflection under a uniform pressure plus the largest
/// initial separation: the scale of the default c_max.
fn deflection_scale(c: &Case<'_>) -> f64 {
    let s = c.influence;
    let n = c.station.len();
    let total: f64 = c.measures.iter().sum();
    let deflection = (0..n)
        .map(|k| {
            (0..n)
                .map(|j| s[(k, j)] * c.load * c.measures[j] / total)
                .sum::<f64>()
        })
        .fold(0.0f64, f64::max);
    let eps = c
        .problem
        .separation()
        .iter()
        .fold(0.0f64, |a, e| a.max(e.abs()));
    deflection + eps
}

/// The design's objective and its re-analysis' must agree to `tolerance`
/// (relative), or the design is refused.
fn agree(design: f64, reanalysis: f64, tolerance: f64) -> Result<(), DesignError> {
    let relative = (reanalysis - design).abs() / design;
    if relative <= tolerance {
        Ok(())
    } else {
        Err(DesignError::Disagreement {
            design,
            reanalysis,
            relative,
            tolerance,
        })
    }
}

/// Part 1 and part 2 from one start, then the re-analysis.
#[allow(clippy::too_many_arguments)]
fn run_start(
    cases: &[ContactProblem],
    prepared: &[Case<'_>],
    basis: &Basis,
    family: Family,
    axis: Axis,
    stations: &[f64],
    c_max: Option<f64>,
    theta0: &[f64],
    options: &DesignOptions,
) -> Result<Design, DesignError> {
    let (program, layout) = program(prepared, basis, c_max, theta0)?;
    let solution = program.solve(&options.engine)?;
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
            objective = objective.max(p / prepared[l].reference);
        }
    }
    debug_assert!(solution.x[layout.t] >= objective * (1.0 - 1e-9));
    let profile = basis.profile(family, stations, &theta);
    let evaluation = evaluate(
        cases,
        axis,
        &profile,
        options.reanalysis,
        &options.reanalysis_options,
    )?;
    let references: Vec<f64> = prepared.iter().map(|c| c.reference).collect();
    agree(
        objective,
        evaluation.relative_worst(&references),
        options.agreement,
    )?;
    // A uniform shift of the profile only moves the approach, so the bound
    // constrains the design only if the normalized profile (smallest drop 0)
    // still needs the whole of it.
    let constant_at_bound = match (&profile, c_max) {
        (Profile::Quadratic { c, .. }, Some(c_max)) => *c >= (1.0 - 1e-9) * c_max,
        (Profile::Polynomial { coefficients }, Some(c_max)) => {
            coefficients[0] >= (1.0 - 1e-9) * c_max
        }
        _ => false,
    };
    Ok(Design {
        profile,
        stations: stations.to_vec(),
        objective,
        max_intensity,
        evaluation,
        starts: Vec::new(),
        certificate: solution.certificate,
        statistics: solution.statistics,
        max_constant: c_max,
        constant_at_bound,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_reanalysis_that_disagrees_refuses_the_design() {
        assert!(agree(100.0, 100.0 * (1.0 + 1e-12), 1e-9).is_ok());
        let e = agree(100.0, 101.0, 1e-9).unwrap_err();
        assert!(matches!(e, DesignError::Disagreement { .. }));
        assert_eq!(
            e.to_string(),
            "the design's objective 1.000000e2 and its re-analysis' 1.010000e2 differ by 1.00e-2 relative (tolerance 1.0e-9)"
        );
        // NaN never agrees.
        assert!(agree(100.0, f64::NAN, 1e-9).is_err());
    }
}
