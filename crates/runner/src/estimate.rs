//! What a scene will cost, known before anything of size N x N is
//! allocated: its peak memory and a rough class of its run time.
//!
//! The contact solve's part is elcon-analysis's estimate of the scene's
//! problem (`elcon_analysis::Estimate`, from its [`Plan`](elcon_analysis::Plan): the storage, the
//! method and the unknowns; dense, `m` matrices of n x n, 8 bytes an entry;
//! matrix-free, the lattice operator and a few vectors of N). The design
//! stage holds each design load's problem as elcon-analysis counts it for
//! repeated solves, plus its own:
//!
//! ```text
//!     design, linear     S + sum_l held_l + 4.25 R C + work_max   (the program)
//!                        S + sum_l held_l + block_max + rows      (the descent)
//!     design, crowns     S + sum_l held_l + work_max
//! ```
//!
//! with S the scene's own problem, `held_l` design load l's problem (its S,
//! or its operator and vectors), `work_max` the largest solve's working
//! matrices, the design program's `R = sum_l (2 n_l + 1) + stations (+ 1)`
//! rows and `C = sum_l n_l + L + parameters + 1` dense columns (its
//! builder's growing buffer, the program, the engine's copy and the
//! tableau, each about R x C, overlap). The discretization error estimate
//! (on by default) solves the coarser grids one at a time while the
//! scene's S is held: `S + coarse_max`, a coarse grid's solve, at most a
//! sixteenth of the scene's on a surface and a quarter on a line. The
//! stresses below the surface (`outputs.subsurface`) take a layer at a
//! time on each thread while S is held: `S + 340 N threads` bytes. The peak
//! is the largest of the stages plus [`BASELINE`].
//!
//! The time comes from the pivots' cost: about `c n^3` for a dense solve
//! (a path of a pivot of about `c n^2` per point in contact, every point
//! assumed in contact: an upper-ish bound, above a Hertz contact's),
//! linear in N matrix-free, and `c R C^2` for the design program, with c
//! measured through `elcon run` on the reference machine
//! (docs/reliability.md), rounded up. `check` prints it rounded to two
//! digits in seconds, minutes or hours, with its class ([`TimeFigure`],
//! [`TimeClass`]).

use elcon_analysis::discretization::{finer_allowance, refine_seconds_allowance};
use elcon_analysis::{GridFamily, Relief};
pub use elcon_design::DesignEstimate;
use elcon_influence::PointSet;

use elcon_process::{Ceiling, Limit, gemm_reserve, human};
use elcon_scene::{DesignSpec, Plot, Scene};

use crate::design_load::design_load;
use crate::error::RunError;

mod time;

pub use time::{TimeClass, TimeFigure};

/// Bytes a point of the pressure plot, built whole before it is written:
/// one mark or cell of SVG a point and its data, rounded up (measured at
/// 347,949 and 262,144 points: 137 for the spheres' pressure against the
/// radius, 90 for the roller's pressure map; docs/reliability.md).
const PLOT_BYTES_PER_POINT: f64 = 160.0;

/// Bytes a candidate point of the stresses below the surface for each
/// thread of the pool, while the scene's problem is held: each thread holds
/// one depth layer at a time (the pressure's and the six kernels' spectra
/// on the zero-padded lattice, the layer's stresses); rounded up from 318
/// on one thread and 529 on two measured at 106,353 points (Hertz spheres
/// on a disk, docs/performance.md §7).
const SUBSURFACE_BYTES_PER_POINT: f64 = 340.0;

/// Bytes held per byte of a data file (height map, profile, separation
/// file) at its peak: the file's bytes as read and the table parsed from
/// them, both alive while it is parsed (a 5792 x 5792 float64 map of 268
/// MB peaks near 530 MB).
const DATA_BYTES_PER_FILE_BYTE: f64 = 2.0;

/// What the process holds besides the matrices (code, threads, buffers),
/// bytes: about what a run of a scene with a handful of points peaks at.
pub const BASELINE: u64 = 32 << 20;

/// A scene's estimated peak memory and run time.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    /// Candidate points N.
    pub points: usize,
    /// Unknowns of the solve: N, or one per orbit when the problem folds.
    pub unknowns: usize,
    /// The method's N x N matrices ([`elcon_analysis::estimate::matrices`]).
    pub matrices: f64,
    /// Bytes the contact solve holds at its peak.
    pub solve_bytes: u64,
    /// Bytes the scene's data files take, read and parsed (held through
    /// the run: the tables the surfaces are read from).
    pub data_bytes: u64,
    /// Bytes the discretization error estimate's stage holds: the scene's
    /// S and the largest of its other grids' solves (finer grids
    /// included; 0 when the estimate is off).
    pub error_estimate_bytes: u64,
    /// The design stage, if the scene has one.
    pub design: Option<DesignEstimate>,
    /// The whole run's peak, bytes: the larger stage plus [`BASELINE`].
    pub peak_bytes: u64,
    /// Rough seconds (an order of magnitude).
    pub seconds: f64,
    /// Its class.
    pub time: TimeClass,
}

/// Bytes as a whole number, rounded up: a float-to-integer cast saturates
/// (at `u64::MAX` above it, 0 for NaN).
fn to_bytes(b: f64) -> u64 {
    b.ceil() as u64
}

impl Estimate {
    /// The estimate of a validated scene.
    ///
    /// # Errors
    /// [`RunError::Run`] when a design load's points cannot be laid out
    /// (as the run would fail).
    pub fn of(scene: &Scene) -> Result<Self, RunError> {
        let solve = &scene.plan().estimate;
        let n = scene.points().len();
        let (coarse_bytes, coarse_seconds) = discretization(scene);
        let mut seconds = solve.seconds + coarse_seconds;
        let design = match scene.design() {
            Some(spec) => {
                let d = design(scene, spec, solve.influence_bytes)?;
                seconds += d.seconds;
                Some(d)
            }
            None => None,
        };
        let plot = if scene.outputs().plots().contains(&Plot::Pressure) {
            PLOT_BYTES_PER_POINT * n as f64
        } else {
            0.0
        };
        let subsurface = if scene.outputs().subsurface().is_some() {
            SUBSURFACE_BYTES_PER_POINT * rayon::current_num_threads() as f64 * n as f64
        } else {
            0.0
        };
        let data: u64 = scene.inputs().iter().map(|i| i.bytes).sum();
        let data_bytes = to_bytes(DATA_BYTES_PER_FILE_BYTE * data as f64);
        let error_estimate_bytes = if coarse_bytes > 0.0 {
            to_bytes(solve.influence_bytes + coarse_bytes)
        } else {
            0
        };
        let stage = design
            .as_ref()
            .map_or(0, |d| d.bytes)
            .max(to_bytes(solve.solve_bytes))
            .max(error_estimate_bytes)
            .max(to_bytes(solve.influence_bytes + subsurface))
            .saturating_add(to_bytes(plot))
            .saturating_add(data_bytes);
        Ok(Self {
            points: n,
            unknowns: solve.unknowns,
            matrices: solve.matrices,
            solve_bytes: to_bytes(solve.solve_bytes),
            error_estimate_bytes,
            data_bytes,
            design,
            peak_bytes: stage.saturating_add(BASELINE),
            seconds,
            time: TimeClass::of(seconds),
        })
    }

    /// One line for `elcon check`: "1653 points (222 unknowns, folded);
    /// peak memory about 3.2 MiB; time: about 0.02 s (under a second)".
    pub fn summary(&self) -> String {
        let mut s = format!("{} points", self.points);
        if self.unknowns != self.points {
            let _ = std::fmt::Write::write_fmt(
                &mut s,
                format_args!(" ({} unknowns, folded)", self.unknowns),
            );
        }
        if let Some(d) = &self.design {
            let _ = std::fmt::Write::write_fmt(
                &mut s,
                format_args!(
                    ", design over {} load case{} ({} points)",
                    d.cases,
                    if d.cases == 1 { "" } else { "s" },
                    d.points
                ),
            );
        }
        format!(
            "{s}; peak memory about {}; time: {} ({})",
            human(self.peak_bytes),
            TimeFigure::of(self.seconds),
            self.time
        )
    }

    /// Why a scene over `ceiling` is refused, and what would help.
    pub fn refusal(&self, scene: &Scene, ceiling: &Ceiling) -> RunError {
        let folded = if self.unknowns != self.points {
            format!(" ({} unknowns, folded)", self.unknowns)
        } else {
            String::new()
        };
        let solve = &scene.plan().estimate;
        let mut what = format!(
            "N = {} points{folded} needs about {} ({}",
            self.points,
            human(self.peak_bytes),
            solve.holding()
        );
        let design_dominates = self
            .design
            .as_ref()
            .is_some_and(|d| d.bytes > self.solve_bytes);
        if let Some(d) = self.design.as_ref().filter(|_| design_dominates) {
            let _ = std::fmt::Write::write_fmt(
                &mut what,
                format_args!(
                    "; the design stage over {} load cases and {} points holds {}",
                    d.cases,
                    d.points,
                    human(d.bytes)
                ),
            );
        }
        let estimate_dominates = !design_dominates && self.error_estimate_bytes > self.solve_bytes;
        if estimate_dominates {
            let _ = std::fmt::Write::write_fmt(
                &mut what,
                format_args!(
                    "; the discretization error estimate's other grids (coarser, or finer where \
                     the coarser would not resolve a quantity) hold up to {} beside S",
                    human(self.error_estimate_bytes)
                ),
            );
        }
        what.push(')');
        let mut hints = Vec::new();
        if estimate_dominates {
            hints.push("solver.error_estimate = false (no discretization error estimate)");
        }
        if design_dominates {
            hints.push("fewer design cases (design.loads, design.misalignments)");
            hints.push("a coarser grid");
        } else {
            if self.unknowns == self.points {
                hints.push(
                    "folding by symmetry (solver.symmetry = \"auto\" with a grid, bodies and \
                     surfaces symmetric about x = 0 and y = 0)",
                );
            }
            hints.push("a coarser grid (fewer points across, a smaller zone)");
            for relief in solve.reliefs() {
                hints.push(match relief {
                    Relief::MatrixFree => {
                        "solver.method = \"auto\" or \"conjugate-gradient\" (matrix-free on a \
                         lattice: O(N) memory, docs/performance.md section 6)"
                    }
                    Relief::FewerMatrices => "solver.method = \"block-pivoting\" (fewer matrices)",
                    _ => continue,
                });
            }
        }
        let address;
        if matches!(ceiling.limit, Some((Limit::AddressSpace, _))) {
            address = format!(
                "a higher address-space limit (ulimit -v): faer's matrix products alone reserve {} \
                 of address space here",
                human(gemm_reserve())
            );
            hints.push(&address);
        }
        hints.push("a machine with more memory");
        RunError::TooBig {
            scene: scene.name().to_string(),
            needed: what,
            ceiling: ceiling.to_string(),
            hints: hints.join(", or "),
        }
    }
}

/// The discretization error estimate's peak and time: the other grids'
/// problems, planned as the run builds them (`elcon_analysis::GridFamily`:
/// `coarser`, 2h then 4h, and `finer`, h/2 then h/4, with the grids
/// between each pair, `intermediate`, that the least-squares fit solves
/// where the nested grids do not resolve a quantity, while within
/// `elcon_analysis::discretization::finer_allowance` of the scene's own
/// solve), are solved one at a time while the scene's own S is held, so
/// the stage's peak is the scene's S plus the largest of their solves'
/// bytes, finer grids included (the run solves them where the grid at 4h
/// would not resolve the contact, which only the solve tells). The
/// seconds are the coarser grids' (the run's usual path), or the finer
/// ones' where the layout has no coarser grid at all. Nothing when the
/// estimate is off or the layout has no family.
fn discretization(scene: &Scene) -> (f64, f64) {
    let Some(family) = scene
        .error_estimate()
        .then(|| scene.grid_family().ok())
        .flatten()
    else {
        return (0.0, 0.0);
    };
    let plan = |grid: &GridFamily| {
        let points = grid.points().ok()?;
        let plan = scene.builder(points, scene.loading()).plan().ok()?;
        Some(plan.estimate)
    };
    let allowance = finer_allowance(scene.plan().estimate.solve_bytes);
    let mut paths = [(0.0f64, 0.0f64, 0usize); 2];
    for (path, step) in paths
        .iter_mut()
        .zip([GridFamily::coarser, |g: &GridFamily| Some(g.finer())])
    {
        let mut current = family;
        for _ in 0..2 {
            let Some((grid, e)) = step(&current).and_then(|g| Some((g, plan(&g)?))) else {
                break;
            };
            if grid.spacing() < current.spacing() && !(e.solve_bytes <= allowance) {
                break;
            }
            *path = (path.0.max(e.solve_bytes), path.1 + e.seconds, path.2 + 1);
            // The grid between this pair (about sqrt 2 coarser than the
            // finer of the two), solved where the nested grids do not
            // resolve a quantity (which only the solve tells).
            let finer = if grid.spacing() < current.spacing() {
                grid
            } else {
                current
            };
            if let Some(e) = finer.intermediate().and_then(|g| plan(&g))
                && e.solve_bytes <= allowance
            {
                *path = (path.0.max(e.solve_bytes), path.1 + e.seconds, path.2);
            }
            current = grid;
        }
    }
    let [
        (coarse_bytes, coarse_seconds, coarse),
        (finer_bytes, finer_seconds, _),
    ] = paths;
    let seconds = if coarse > 0 {
        coarse_seconds + refine_seconds(scene, &family, plan, allowance)
    } else {
        finer_seconds
    };
    (coarse_bytes.max(finer_bytes), seconds)
}

/// The seconds of the finer grid h/2 and the grid between it and h that
/// the run adds where its coarser grids leave a quantity not resolved
/// (which only the solve tells: counted whenever they would be solved),
/// each within the memory `allowance` and
/// `elcon_analysis::discretization::refine_seconds_allowance` of the
/// scene's own solve; 0 when h/2 is not.
fn refine_seconds(
    scene: &Scene,
    family: &GridFamily,
    plan: impl Fn(&GridFamily) -> Option<elcon_analysis::Estimate>,
    allowance: f64,
) -> f64 {
    let time = refine_seconds_allowance(scene.plan().estimate.seconds);
    let within = |e: &elcon_analysis::Estimate| e.solve_bytes <= allowance && e.seconds <= time;
    let finer = family.finer();
    let Some(half) = plan(&finer).filter(within) else {
        return 0.0;
    };
    let between = (finer.intermediate().and_then(|g| plan(&g)))
        .filter(within)
        .map_or(0.0, |e| e.seconds);
    half.seconds + between
}

/// Each design load's problem on the grid of `fineness` (1: the scene's
/// own), planned as the run builds it (unfolded; held as the scene's on
/// its own grid, as elcon-analysis decides on a finer one) under its load
/// alone.
fn design_loads(
    scene: &Scene,
    spec: &DesignSpec,
    fineness: f64,
) -> Result<Vec<(PointSet, elcon_analysis::Estimate)>, RunError> {
    let failed = |reason: String| RunError::Run {
        scene: scene.name().to_string(),
        reason,
    };
    spec.loads()
        .iter()
        .map(|&load| {
            // The scene's own grid fails as the scene; a finer one as the run.
            let builder = design_load(scene, load, fineness).map_err(|e| {
                if fineness == 1.0 {
                    RunError::from(e)
                } else {
                    failed(e.to_string())
                }
            })?;
            let plan = builder.plan().map_err(|e| failed(e.to_string()))?;
            Ok((builder.points().clone(), plan.estimate))
        })
        .collect()
}

/// The least a design grid of the sequence costs (s): the stage's set-up
/// and bookkeeping on a handful of points (Example 2: 0.017 s and 0.009 s
/// of a run's 0.027 s on its 80 and 160 cells, on the reference machine
/// under a load of 7 on its 2 cores), rounded down.
const GRID_SECONDS: f64 = 0.005;

/// Analyses of each case a design on a finer grid of the sequence makes:
/// it starts from the coarser grid's profile, so about one descent
/// iteration (each case analysed before, at the iterate, at the trial and
/// after).
const REFINED_ANALYSES: f64 = 4.0;

/// The design stage's estimate; `own` the bytes of the scene's own S,
/// alive through the stage. Its memory is the largest the grids of its
/// path hold at once: the design on the scene's grid; the design on each
/// finer grid beside the coarser grid's cases (kept until the finer
/// grid's design replaces them); the verifying grid's cases beside the
/// last design grid's, with one analysis's work. Its seconds those of the
/// shortest path over the grid sequence (`design.refine`, the default):
/// the design on the scene's grid, the design on each finer grid the
/// request is estimated to design on within `design.max_points` a case
/// (`DesignRequest::finer_designs`: the second grid; the third too for
/// the largest shear; none for a crown) and each case
/// analysed once on the next, where a
/// design holds at the earliest (Example 2: designed on 80 and 160 cells,
/// verified on 240; the crowned roller on 9 x 40 and 18 x 80, verified on
/// 27 x 120); at least [`GRID_SECONDS`] a grid. A finer grid's design
/// starts from the coarser grid's profile: a pressure design's is its full
/// estimate or [`REFINED_ANALYSES`] of each case, whichever is less, the
/// analyses times the square root of a misaligned roller's end lift over
/// its lightest load's approach (`Scene::end_lift`, at least 1): the
/// first grid resolves the tilted contact, about `sqrt(approach / lift)`
/// of the length, on that many times fewer stations, and the finer grid's
/// design moves further from it (the crowned roller took 3.9, 12 and 15 s
/// at lifts of 1.7, 8.4 and 17 approaches); a stress design's a full
/// descent (`DesignRequest::refines_by_descent`).
/// A dense solve grows as the cube of its points, so the finer grids
/// dominate: the scene's grid alone was 10 times short of the crowned
/// roller's measured seconds.
fn design(scene: &Scene, spec: &DesignSpec, own: f64) -> Result<DesignEstimate, RunError> {
    let angles = spec.misalignments().len().max(1) as f64;
    let request = spec.request(None, Some(scene.method()), scene.options());
    let at = |loads: &[(PointSet, elcon_analysis::Estimate)]| {
        let loads: Vec<(&PointSet, elcon_analysis::Estimate)> =
            loads.iter().map(|(p, e)| (p, *e)).collect();
        request.estimate(&loads, angles as usize, own)
    };
    // Every case's analysis on a grid.
    let analyses = |loads: &[(PointSet, elcon_analysis::Estimate)]| {
        angles * loads.iter().map(|(_, e)| e.seconds).sum::<f64>()
    };
    // Each grid's cases' held problems, and one analysis's work among them.
    let held = |loads: &[(PointSet, elcon_analysis::Estimate)]| {
        loads.iter().map(|(_, e)| e.held_bytes).sum::<f64>()
    };
    let work = |loads: &[(PointSet, elcon_analysis::Estimate)]| {
        loads
            .iter()
            .map(|(_, e)| e.work_bytes)
            .fold(0.0f64, f64::max)
    };
    let first = design_loads(scene, spec, 1.0)?;
    let mut estimate = at(&first);
    estimate.seconds = estimate.seconds.max(GRID_SECONDS);
    let Some(sequence) = spec.sequence() else {
        return Ok(estimate);
    };
    let within = |fineness: f64| {
        design_loads(scene, spec, fineness).ok().filter(|loads| {
            loads
                .iter()
                .all(|(points, _)| points.len() <= sequence.max_points)
        })
    };
    let mut levels = sequence.fineness.iter().copied().filter(|&f| f != 1.0);
    let polish = REFINED_ANALYSES * scene.end_lift().map_or(1.0, |l| l.ratio().max(1.0).sqrt());
    let mut coarser = first;
    for _ in 0..request.finer_designs() {
        let Some(loads) = levels.next().and_then(within) else {
            return Ok(estimate);
        };
        let designed = at(&loads);
        estimate.bytes = estimate
            .bytes
            .max(designed.bytes.saturating_add(to_bytes(held(&coarser))));
        let seconds = if request.refines_by_descent() {
            designed.seconds
        } else {
            designed.seconds.min(polish * analyses(&loads))
        };
        estimate.seconds += seconds.max(GRID_SECONDS);
        coarser = loads;
    }
    if let Some(next) = levels.next().and_then(within) {
        let verifying = own + held(&coarser) + held(&next) + work(&next);
        estimate.bytes = estimate.bytes.max(to_bytes(verifying));
        estimate.seconds += analyses(&next).max(GRID_SECONDS);
    }
    Ok(estimate)
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;

    /// Example 1's spheres (the scene tests' spheres.toml) on a disk of
    /// spacing 0.001 in and radius 0.02 in.
    fn spheres() -> String {
        include_str!("../tests/scenes/common/spheres.toml")
            .replace("across = 41\nzone = 1.15", "spacing = 0.001\nradius = 0.02")
    }

    fn scene(text: &str) -> Scene {
        Scene::from_str(Path::new("t.toml"), text).unwrap()
    }

    fn bytes(matrices: f64, n: usize) -> u64 {
        to_bytes(matrices * 8.0 * (n * n) as f64)
    }

    #[test]
    fn the_subsurface_stresses_add_their_bytes_per_point_to_the_held_problem() {
        // The error estimate off: its finer grid's stage would hide the
        // subsurface's.
        let lattice = format!(
            "{}[solver]\nmethod = \"conjugate-gradient\"\nerror_estimate = false\n",
            spheres()
        );
        let plain = Estimate::of(&scene(&lattice)).unwrap();
        let on = Estimate::of(&scene(&format!("{lattice}[outputs]\nsubsurface = true\n"))).unwrap();
        let n = plain.points as f64;
        assert!(on.peak_bytes > plain.peak_bytes);
        let threads = rayon::current_num_threads() as f64;
        assert!(on.peak_bytes >= to_bytes(SUBSURFACE_BYTES_PER_POINT * threads * n) + BASELINE);
    }

    #[test]
    fn a_pressure_plot_adds_its_bytes_per_point() {
        let spheres = spheres();
        let plain = Estimate::of(&scene(&spheres)).unwrap();
        let plotted = Estimate::of(&scene(&format!(
            "{spheres}[outputs]\nplots = [\"pressure\"]\n"
        )))
        .unwrap();
        let n = plain.points as f64;
        assert_eq!(
            plotted.peak_bytes - plain.peak_bytes,
            to_bytes(PLOT_BYTES_PER_POINT * n)
        );
        assert_eq!(plotted.solve_bytes, plain.solve_bytes);
    }

    #[test]
    fn a_solve_counts_its_methods_matrices_on_the_folded_size() {
        let spheres = spheres();
        let folded = Estimate::of(&scene(&spheres)).unwrap();
        let n = folded.points;
        assert_eq!(n, 1257);
        // Eight mirror images: about N / 8 orbits.
        assert!(
            folded.unknowns > n / 8 && folded.unknowns < n / 6,
            "{}",
            folded.unknowns
        );
        assert_eq!(folded.solve_bytes, bytes(3.25, folded.unknowns));
        // The error estimate's finer grids (h/2: 4 N points; h/4: 16 N,
        // their S 256 times the scene's, within the 256 MiB allowance) are
        // solved while the scene's S is held.
        assert!(folded.peak_bytes > 16 * folded.solve_bytes, "{folded:?}");
        let alone = Estimate::of(&scene(&format!(
            "{spheres}[solver]\nerror_estimate = false\n"
        )))
        .unwrap();
        assert_eq!(alone.peak_bytes, alone.solve_bytes + BASELINE);
        let full =
            Estimate::of(&scene(&format!("{spheres}[solver]\nsymmetry = \"none\"\n"))).unwrap();
        assert_eq!(full.unknowns, n);
        assert_eq!(full.solve_bytes, bytes(3.25, n));
        // The tableau methods: the symmetric tableau under load, the
        // restricted simplex's general tableau under an approach.
        let lemke = format!("{spheres}[solver]\nmethod = \"lemke\"\nsymmetry = \"none\"\n");
        assert_eq!(
            Estimate::of(&scene(&lemke)).unwrap().solve_bytes,
            bytes(3.25, n)
        );
        let simplex = lemke.replace("lemke", "restricted-simplex");
        assert_eq!(
            Estimate::of(&scene(&simplex)).unwrap().solve_bytes,
            bytes(3.25, n)
        );
        let general = simplex.replace("load = 100.0", "approach = 0.0002");
        let e = Estimate::of(&scene(&general)).unwrap();
        assert_eq!(e.solve_bytes, bytes(7.75, n));
        assert!(e.seconds > Estimate::of(&scene(&simplex)).unwrap().seconds);
    }

    #[test]
    fn a_moment_or_a_misalignment_is_counted_as_the_analysis_solves_it() {
        let spheres = spheres();
        // A moment about y breaks the mirror about x = 0: folded by the
        // other mirror only (about half the points), and the restricted
        // simplex, with a free tilt beside the approach, is on the general
        // tableau.
        let moment =
            format!("{spheres}moment_y = 0.5\n[solver]\nmethod = \"restricted-simplex\"\n");
        let e = Estimate::of(&scene(&moment)).unwrap();
        assert!(
            e.unknowns > e.points / 2 && e.unknowns < e.points * 6 / 10,
            "{}",
            e.unknowns
        );
        assert_eq!(e.solve_bytes, bytes(7.75, e.unknowns));
        // A prescribed misalignment presses points in: the general tableau
        // too; Lemke's method keeps the symmetric one.
        let tilted = moment.replace("moment_y = 0.5", "tilt_y = 0.003");
        let e = Estimate::of(&scene(&tilted)).unwrap();
        assert_eq!(e.solve_bytes, bytes(7.75, e.unknowns));
        let lemke = tilted.replace("restricted-simplex", "lemke");
        let e = Estimate::of(&scene(&lemke)).unwrap();
        assert_eq!(e.solve_bytes, bytes(3.25, e.unknowns));
    }

    #[test]
    fn the_design_program_grows_like_the_square_of_all_cases_points() {
        // The scene tests' beam (beam.toml) on 200 points, designed.
        let beam = include_str!("../tests/scenes/common/beam.toml").replace("n = 16", "n = 200")
            + "[design]\nfamily = \"quadratic\"\n";
        let one = Estimate::of(&scene(&beam)).unwrap();
        let d1 = one.design.clone().unwrap();
        assert_eq!((d1.cases, d1.points), (1, 200));
        // R = 2 n + 1 + stations + 1 rows, C = n + 1 + 3 + 1 columns.
        assert_eq!(d1.program, Some((602, 205)));
        let four = beam.replace(
            "family = \"quadratic\"",
            "family = \"quadratic\"\nloads = [1000.0, 2000.0, 3000.0, 4000.0]\nmethod = \"program\"",
        );
        let d4 = Estimate::of(&scene(&four)).unwrap().design.unwrap();
        assert_eq!(d4.points, 800);
        // Four cases on the same 200 stations: 4 x 200 forces, 2 rows each.
        assert_eq!(d4.program, Some((1805, 808)));
        // Four times the points, more than twice four times the bytes: the
        // program's R x C grows like the square (16 times), beside the
        // analyses' matrices that grow with the loads.
        let ratio = d4.bytes as f64 / d1.bytes as f64;
        assert!(ratio > 8.0, "{ratio}");
        assert!(one.peak_bytes >= d1.bytes + BASELINE);
        // The descent holds S once per load and a step program of a column
        // per point: at most linear in the cases. 4 loads x 10
        // misalignments: 10 times the points of 4 loads alone, less than 10
        // times the bytes (the program's would be about 100 times).
        let auto = four.replace("method = \"program\"", "");
        let d4 = Estimate::of(&scene(&auto)).unwrap().design.unwrap();
        assert_eq!(d4.method, Some(elcon_design::DesignMethod::Descent));
        assert_eq!(d4.program, None);
        let forty = auto.replace(
            "loads = [1000.0, 2000.0, 3000.0, 4000.0]",
            "loads = [1000.0, 2000.0, 3000.0, 4000.0]\nmisalignments = [0.0, 1e-5, 2e-5, 3e-5, 4e-5, 5e-5, 6e-5, 7e-5, 8e-5, 9e-5]",
        );
        let d40 = Estimate::of(&scene(&forty)).unwrap().design.unwrap();
        assert_eq!((d40.cases, d40.points), (40, 8000));
        let ratio = d40.bytes as f64 / d4.bytes as f64;
        assert!((1.0..10.0).contains(&ratio), "{ratio}");
    }

    #[test]
    fn a_refined_design_s_memory_is_the_largest_of_its_grids() {
        // The beam on 200 points, designed on 200 and 400 cells, verified
        // on 600: the design on 400 cells (its program of about 4 x 1205 x
        // 406 entries, beside the 200 cells' S) outweighs the one on 200.
        let beam = include_str!("../tests/scenes/common/beam.toml").replace("n = 16", "n = 200")
            + "[design]\nfamily = \"quadratic\"\nmethod = \"program\"\n";
        let refined = Estimate::of(&scene(&beam)).unwrap().design.unwrap();
        let alone = Estimate::of(&scene(&format!("{beam}refine = false\n")))
            .unwrap()
            .design
            .unwrap();
        assert_eq!(alone.program, Some((602, 205)));
        // The second grid's program alone: 4.25 x 8 x R x C, R = 2 x 400 +
        // 1 + 400 + 1, C = 400 + 1 + 3 + 1.
        let program = to_bytes(4.25 * 8.0 * 1202.0 * 405.0);
        assert!(refined.bytes > alone.bytes, "{refined:?} {alone:?}");
        assert!(refined.bytes >= program, "{} {program}", refined.bytes);
        // The verifying grid's 600 points alone are dense S of 600^2
        // beside 400^2: within the estimate.
        assert!(refined.bytes >= to_bytes(8.0 * (600.0f64.powi(2) + 400.0f64.powi(2))));
    }

    #[test]
    fn bytes_round_up_and_saturate() {
        assert_eq!(to_bytes(1.5), 2);
        assert_eq!(to_bytes(u64::MAX as f64), u64::MAX);
        assert_eq!(to_bytes(f64::INFINITY), u64::MAX);
    }

    #[test]
    fn the_summary_prints_the_figure_and_its_class() {
        let e = Estimate::of(&scene(&spheres())).unwrap();
        let figure = TimeFigure::of(e.seconds);
        assert!(
            e.summary()
                .ends_with(&format!("; time: {figure} ({})", e.time)),
            "{}",
            e.summary()
        );
        assert_eq!(e.time, figure.class());
    }

    #[test]
    fn a_refusal_names_n_the_estimate_the_ceiling_and_what_helps() {
        let spheres = spheres();
        let s = scene(&format!("{spheres}[solver]\nsymmetry = \"none\"\n"));
        let e = Estimate::of(&s).unwrap();
        let ceiling = Ceiling::from_limits([(1 << 20, Limit::Option)]);
        assert!(!ceiling.admits(e.peak_bytes));
        let text = e.refusal(&s, &ceiling).to_string();
        for part in [
            "scene `t`: too big for the memory available: N = 1257 points needs about",
            "block-pivoting keeps about 3.25 matrices of 1257 x 1257",
            "the ceiling is 922 KiB (--memory-limit 1.00 MiB, less 10 %)",
            "folding by symmetry",
            "a coarser grid",
        ] {
            assert!(text.contains(part), "{part}: {text}");
        }
        // Only an address-space limit suggests raising ulimit -v.
        assert!(!text.contains("ulimit -v"), "{text}");
        let address = Ceiling::from_limits([(1 << 20, Limit::AddressSpace)]);
        let text = e.refusal(&s, &address).to_string();
        assert!(
            text.contains("a higher address-space limit (ulimit -v)"),
            "{text}"
        );
        assert!(text.contains("under RLIMIT_AS"), "{text}");
        assert!(
            e.summary().contains("1257 points; peak memory about"),
            "{}",
            e.summary()
        );
    }

    #[test]
    fn data_files_count_twice_their_bytes() {
        let path =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scenes/rough-sphere.toml");
        let scene = Scene::from_file(&path).unwrap();
        let map = path.parent().unwrap().join("data/rough-surface.npy");
        let bytes = std::fs::metadata(map).unwrap().len();
        let e = Estimate::of(&scene).unwrap();
        assert_eq!(e.data_bytes, 2 * bytes);
        let plain = Scene::from_str(
            &path,
            &std::fs::read_to_string(&path).unwrap().replace(
                "height_map = { file = \"data/rough-surface.npy\", spacing = [0.005, 0.005] }",
                "",
            ),
        )
        .unwrap();
        let p = Estimate::of(&plain).unwrap();
        assert_eq!(p.data_bytes, 0);
        assert!(e.peak_bytes >= 2 * bytes + e.solve_bytes + BASELINE);
    }

    /// examples/scenes/crowned-roller.toml with `lines` added to its
    /// `[design]` table.
    fn crowned_roller(lines: &str) -> Scene {
        let text = include_str!("../../../examples/scenes/crowned-roller.toml")
            .replace("axis = \"y\"", &format!("axis = \"y\"\n{lines}"));
        scene(&text)
    }

    #[test]
    fn a_stress_design_counts_a_descent_over_the_subsurface_on_each_finer_grid() {
        // Measured (docs/reliability.md): 2.6 to 2.9 s for the pressure
        // design, 13 s for von Mises (designed on 9 x 40 and 18 x 80
        // cells), 69 to 72 s for the largest shear (on 27 x 120 too).
        let seconds = |lines: &str| {
            let e = Estimate::of(&crowned_roller(lines)).unwrap();
            e.design.unwrap().seconds
        };
        let pressure = seconds("");
        let von_mises = seconds("objective = \"von-mises\"");
        let shear = seconds("objective = \"max-shear\"");
        assert!((1.2..5.4).contains(&pressure), "{pressure}");
        assert!((6.5..26.0).contains(&von_mises), "{von_mises}");
        assert!((36.0..140.0).contains(&shear), "{shear}");
    }

    #[test]
    fn a_misaligned_roller_s_finer_grid_counts_its_end_lift() {
        // Measured: 3.8 to 3.9 s at +-0.001 rad (a lift of 1.7 approaches
        // at 1 kN), 15 s at +-0.01 (17).
        let seconds = |m: f64| {
            let lines = format!("misalignments = [-{m}, {m}]");
            let e = Estimate::of(&crowned_roller(&lines)).unwrap();
            e.design.unwrap().seconds
        };
        let (small, large) = (seconds(0.001), seconds(0.01));
        assert!((2.1..8.4).contains(&small), "{small}");
        assert!((7.5..30.0).contains(&large), "{large}");
    }
}
