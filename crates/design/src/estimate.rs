//! What a design will cost, known before anything of its size is
//! allocated: the memory its stage holds at its peak and rough seconds,
//! from each design load's contact problem as elcon-analysis estimates it
//! (`elcon_analysis::Estimate`: its S or operator held for repeated solves,
//! one solve's working matrices, one restricted solve's block):
//!
//! ```text
//!     linear, the program    own + sum_l held_l + work_max + 4.25 x 8 R C
//!     linear, the descent    own + sum_l held_l + work_max + block_max + its rows
//!     crowns                 own + sum_l held_l + work_max
//! ```
//!
//! with `own` the caller's own problem (kept alive beside the cases), the
//! design program's `R = sum_l (2 n_l + 1) + stations (+ 1)` rows and
//! `C = sum_l n_l + L + parameters + 1` dense columns (its builder's
//! growing buffer, the program, the engine's copy and the tableau, each
//! about R x C, overlap). Seconds: each case analysed before and after,
//! plus the program's `c R C^2`, the descent's iterations of an analysis
//! of every case, or the crown search's evaluations. A stress objective's
//! descent iteration also sweeps each case's field below the surface
//! ([`sweep_seconds`]): twice an analysis and a sweep of every case (the
//! trial's, and the model's sensitivities and stress rows at an accepted
//! step).

use elcon_analysis::Estimate;
use elcon_influence::{Dimension, PointSet};

use crate::objective::Objective;
use crate::request::{DesignFamily, DesignRequest};
use crate::subsurface::DEPTHS;
use crate::{DesignMethod, Family, axial_stations};

/// Bytes of one matrix entry (f64).
const ENTRY: f64 = 8.0;

/// Seconds per `R C^2` of the design program (about 0.8 C pivots of R x C
/// each, memory bound): 133 s at R = 14,460, C = 7261.
const PROGRAM_SECONDS: f64 = 2.5e-10;

/// The design program's peak in matrices of R x C: 3.7 to 4.1 measured.
const PROGRAM_MATRICES: f64 = 4.25;

/// The descent's iterations per start, rounded up (2 to 7 on Example 2
/// and the roller, docs/design.md §2 and §6).
const DESCENT_ITERATIONS: f64 = 20.0;

/// A stress objective's descent iterations per start: 8 to 70 on the
/// crowned roller's grids (von Mises 12 and 31 on 9 x 40 and 18 x 80
/// cells; the largest shear 8, 70 and 16 on 9 x 40 to 27 x 120), fitted to
/// the two designs' seconds (docs/reliability.md).
const STRESS_ITERATIONS: f64 = 15.0;

/// Doubles per point of every case the design stage holds per iterate
/// of the descent (the iterate's and the trial's problems with their point
/// sets and separations, their solutions, the evaluations before and after
/// the design), besides a step-program row of `parameters + 2` per point:
/// fitted to the crowned roller over 50 and 400 loads (docs/reliability.md),
/// rounded up.
const DESCENT_VECTORS: f64 = 64.0;

/// Seconds per point and depth of a stress sweep on a lattice (the depth
/// layers by FFT, each stress component): 0.8 to 1.2 microseconds measured
/// on the crowned roller's 9 x 40 to 27 x 120 cells (the 2-core AMD EPYC
/// VM under a load average of 5), rounded up.
const LAYER_SECONDS: f64 = 1.2e-6;

/// Seconds per point, loaded point and depth of a stress sweep by direct
/// sums (points off a lattice): a rectangle's stress influence, rounded up.
const DIRECT_SECONDS: f64 = 1e-7;

/// Evaluations of a circular crown's search: its samples and refinement.
const SEARCH_EVALUATIONS: f64 = 30.0;

/// What a design will cost (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct DesignEstimate {
    /// Load cases.
    pub cases: usize,
    /// Points of every case together.
    pub points: usize,
    /// How a linear family is solved ("auto" resolved; `None` for a crown).
    pub method: Option<DesignMethod>,
    /// Rows and dense columns of the design program (a linear family solved
    /// by the program).
    pub program: Option<(usize, usize)>,
    /// Bytes the stage holds at its peak (the caller's own problem included).
    pub bytes: u64,
    /// Rough seconds (an order of magnitude).
    pub seconds: f64,
}

/// Bytes as a whole number, saturating.
fn to_bytes(b: f64) -> u64 {
    if b >= u64::MAX as f64 {
        u64::MAX
    } else {
        b.ceil() as u64
    }
}

/// Seconds of one sweep of a stress objective's measure over `points`:
/// each field's [`DEPTHS`] layers below every point, by FFT on a lattice
/// (1.2e-6 s a point and depth), by direct sums over every
/// loaded point elsewhere (1e-7 s a pair: every point taken loaded).
pub fn sweep_seconds(points: &PointSet, fields: usize) -> f64 {
    let n = points.len() as f64;
    let per_depth = if points.lattice().is_some() {
        LAYER_SECONDS * n
    } else {
        DIRECT_SECONDS * n * n
    };
    fields as f64 * DEPTHS as f64 * per_depth
}

impl DesignRequest {
    /// The finer grids a design is estimated to be made on before one
    /// verifies it (see [`crate::sequence`]): none for a crown (its closed
    /// form is not fitted to the grid's stations: the crowned roller's
    /// logarithmic and circular crowns held on the first finer grid, 18 x
    /// 80 cells); one for a linear family under the pressure or the von
    /// Mises objective; two under the largest shear (Tresca), whose
    /// measure has a kink wherever two principal stresses change order:
    /// the crowned roller designed for it on 18 x 80 cells moved by more
    /// than the grid tolerance on 27 x 120 and held only from there, where
    /// its von Mises design held on 18 x 80 (docs/reliability.md).
    pub fn finer_designs(&self) -> usize {
        if !matches!(self.family, DesignFamily::Linear(_)) {
            return 0;
        }
        match self.objective {
            Objective::MaxShear => 2,
            Objective::Pressure | Objective::VonMises => 1,
        }
    }

    /// Whether a design made on a finer grid, started from the coarser
    /// grid's profile, is a full descent (a stress objective, whose
    /// maximum moves below the surface as the grid resolves it), not the
    /// few analyses of a pressure design's polish.
    pub fn refines_by_descent(&self) -> bool {
        self.objective.is_stress()
    }

    /// The distinct stress fields a stress objective sweeps (twin bodies
    /// count once); 0 for the pressure objective.
    fn stress_fields(&self) -> usize {
        let mut fields = Vec::new();
        if self.objective.is_stress() {
            for body in &self.bodies {
                if let Ok(f) = elcon_influence::StressKernel::of(body)
                    && !fields.contains(&f)
                {
                    fields.push(f);
                }
            }
        }
        fields.len()
    }

    /// The cost of the design over `loads` (each design load's points and
    /// its problem's estimate under that load), every load a case at each
    /// of `angles` misalignments (1 for the loads alone), beside the
    /// caller's own problem of `own` bytes.
    pub fn estimate(
        &self,
        loads: &[(&PointSet, Estimate)],
        angles: usize,
        own: f64,
    ) -> DesignEstimate {
        let total: usize = angles * loads.iter().map(|(p, _)| p.len()).sum::<usize>();
        let cases = angles * loads.len();
        let Some(largest) = loads.iter().map(|(_, e)| *e).max_by_key(|e| e.points) else {
            return DesignEstimate {
                cases,
                points: total,
                method: None,
                program: None,
                bytes: to_bytes(own),
                seconds: 0.0,
            };
        };
        let analysis = largest.seconds;
        let held: f64 = loads.iter().map(|(_, e)| e.held_bytes).sum();
        let mut bytes = own + held + largest.work_bytes;
        // Each case analysed before and after.
        let mut seconds = 2.0 * cases as f64 * analysis;
        let line = loads.iter().all(|(p, _)| p.dimension() == Dimension::Line);
        let starts = if line { 2.0 } else { 1.0 };
        let mut method = None;
        let program = match &self.family {
            DesignFamily::Linear(family) => {
                let (stations, _) = axial_stations(loads.iter().map(|(p, _)| *p), self.axis);
                let params = match family {
                    Family::Quadratic => 3,
                    Family::Polynomial { degree } => degree + 1,
                    Family::Free => stations.len(),
                };
                let entries = loads.iter().all(|(_, e)| e.storage.holds_entries());
                let resolved = self.method.resolve(total, entries);
                method = Some(resolved);
                if resolved == DesignMethod::Descent {
                    // One contact block and its solves at a time, every
                    // case's solutions twice (the iterate and the trial),
                    // the step's program of m + 1 rows and a column per
                    // point in contact.
                    let columns = (total + 2 * params + 1) as f64;
                    bytes += largest.restricted_bytes
                        + ENTRY * (largest.points * (params + 4)) as f64
                        + ENTRY * (2.0 * DESCENT_VECTORS + (params + 2) as f64) * total as f64
                        + PROGRAM_MATRICES * ENTRY * (params + 1) as f64 * columns;
                    let iterations = if self.objective.is_stress() {
                        STRESS_ITERATIONS
                    } else {
                        DESCENT_ITERATIONS
                    };
                    seconds += starts * iterations * self.iteration_seconds(loads, angles);
                    None
                } else {
                    let constant = usize::from(!matches!(family, Family::Free));
                    let rows = 2 * total + cases + stations.len() + constant;
                    let columns = total + cases + params + 1;
                    bytes += PROGRAM_MATRICES * ENTRY * rows as f64 * columns as f64;
                    seconds += starts
                        * (PROGRAM_SECONDS * rows as f64 * (columns as f64).powi(2)
                            + cases as f64 * analysis);
                    Some((rows, columns))
                }
            }
            DesignFamily::CircularCrown { .. } => {
                seconds += SEARCH_EVALUATIONS * cases as f64 * analysis;
                None
            }
            DesignFamily::LogarithmicCrown { .. } => None,
        };
        DesignEstimate {
            cases,
            points: total,
            method,
            program,
            bytes: to_bytes(bytes),
            seconds,
        }
    }

    /// Seconds of one descent iteration over `loads` at `angles`
    /// misalignments: twice an analysis of every case (the trial's, and
    /// the sensitivities' restricted solves at an accepted step), the
    /// largest load's analysis standing for each; under a stress objective
    /// every case's own analysis and two sweeps of its field
    /// ([`sweep_seconds`]: the trial's measure and the model's rows).
    fn iteration_seconds(&self, loads: &[(&PointSet, Estimate)], angles: usize) -> f64 {
        let fields = self.stress_fields();
        let angles = angles as f64;
        if fields == 0 {
            let analysis = loads.iter().map(|(_, e)| e.seconds).fold(0.0, f64::max);
            return 2.0 * angles * loads.len() as f64 * analysis;
        }
        2.0 * angles
            * loads
                .iter()
                .map(|(p, e)| e.seconds + sweep_seconds(p, fields))
                .sum::<f64>()
    }
}
