//! The bodies reduced to their influence terms, and the half-space
//! coefficient at a lattice offset: the one kernel evaluation shared by the
//! dense assembly ([`crate::assemble`]) and the matrix-free lattice operator
//! ([`crate::LatticeOperator`]).
//!
//! Half-space bodies that share a kernel K (same model, same datum d0) are
//! summed before any kernel is evaluated, `c1 K + c2 K = (c1 + c2) K`, so the
//! translation-invariant part of S is
//!
//! ```text
//!     S_kj = sum_K c_K K(x_k - x_j, y_k - y_j)       (c_K = summed compliance (1 - nu^2)/E)
//!     K = boussinesq / pi (point force; the own cell's love_rectangle(0, 0) / pi at k = j),
//!         love_rectangle / pi (uniform patch), 2/pi plane_strain_strip (line)
//! ```
//!
//! On a lattice these depend only on the offset `(|i_k - i_j|, |j_k - j_j|)`
//! (translation invariance and the cell's symmetry): [`Terms::table`]
//! evaluates them once per offset. The Winkler diagonal `sum 1/(k A_k)` and
//! the beams' cantilever coefficients are kept apart: they are not
//! translation-invariant kernels.

use std::f64::consts::PI;

use elcon_num::Num;
use faer::Mat;

use crate::error::InfluenceError;
use crate::kernels::{LoveRows, boussinesq, love_rectangle, plane_strain_strip};
use crate::models::{Body, Model, positive};
use crate::points::{Cell, Dimension, LatticeBox, PointSet};

/// A translation-invariant kernel shared by half-space bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Kernel {
    PointForce,
    UniformPatch,
    Strip { reference_distance: f64 },
}

/// The bodies reduced to distinct kernels with summed compliances, plus the
/// summed Winkler compliance `sum 1/k` and the beams' summed flexibilities
/// `sum 1/(E I)` per loaded point.
#[derive(Debug)]
pub(crate) struct Terms {
    pub(crate) kernels: Vec<(Kernel, f64)>,
    winkler_compliance: f64,
    /// (x0, sum of 1/(E I)) per distinct loaded point.
    beams: Vec<(f64, f64)>,
    cell: Cell,
    /// love_rectangle(0, 0, dx, dy): the point-force self-term's kernel.
    centre: f64,
}

/// One body's part of S, validated against the point set.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Term {
    /// Nothing (a rigid body).
    Rigid,
    /// A translation-invariant kernel and its compliance `(1 - nu^2)/E`.
    Kernel(Kernel, f64),
    /// A Winkler foundation's compliance `1/k`.
    Winkler(f64),
    /// A beam's flexibility `1/(E I)` about its loaded point x0.
    Beam { loaded_point: f64, flexibility: f64 },
}

impl Term {
    /// The term of a body of `model` on `points`.
    ///
    /// # Errors
    /// [`InfluenceError::DimensionMismatch`] for a model of the other
    /// dimension; [`InfluenceError::InvalidModel`] for a parameter out of
    /// range.
    fn of(model: &Model, points: &PointSet) -> Result<Self, InfluenceError> {
        let dimension = points.dimension();
        // The model applies to `wanted` point sets only; `hint` says what to use.
        let require = |wanted: Dimension, hint| {
            if dimension == wanted {
                Ok(())
            } else {
                Err(InfluenceError::DimensionMismatch {
                    model: model.name(),
                    dimension,
                    hint,
                })
            }
        };
        Ok(match *model {
            Model::Rigid => Self::Rigid,
            Model::PointForce { material } | Model::UniformPatch { material } => {
                require(
                    Dimension::Surface,
                    "use Body::plane_strain on a line, or a surface point set \
                     (PointSet::grid_disk, grid_rectangle)",
                )?;
                let kernel = if matches!(model, Model::PointForce { .. }) {
                    Kernel::PointForce
                } else {
                    Kernel::UniformPatch
                };
                Self::Kernel(kernel, material.compliance())
            }
            Model::PlaneStrainStrip {
                material,
                reference_distance,
            } => {
                require(
                    Dimension::Line,
                    "use Body::uniform_patch or Body::point_force on a surface, \
                     or a line point set (PointSet::line)",
                )?;
                check_reference_distance(model.name(), reference_distance, points)?;
                Self::Kernel(Kernel::Strip { reference_distance }, material.compliance())
            }
            Model::Winkler { modulus } => {
                Self::Winkler(1.0 / positive(model.name(), "modulus", modulus)?)
            }
            Model::Beam {
                flexural_rigidity,
                loaded_point,
            } => {
                require(
                    Dimension::Line,
                    "a beam lies along x: use a line point set (PointSet::line)",
                )?;
                check_beam(model.name(), flexural_rigidity, loaded_point)?;
                Self::Beam {
                    loaded_point,
                    flexibility: 1.0 / flexural_rigidity,
                }
            }
        })
    }
}

impl Terms {
    /// Validates every body against the point set and groups the kernels.
    pub(crate) fn collect(points: &PointSet, bodies: &[&Body]) -> Result<Self, InfluenceError> {
        let cell = points.cell();
        let mut kernels: Vec<(Kernel, f64)> = Vec::new();
        let mut winkler_compliance = 0.0;
        let mut beams: Vec<(f64, f64)> = Vec::new();
        let mut elastic = 0;
        for body in bodies {
            match Term::of(body.model(), points)? {
                Term::Rigid => continue,
                Term::Kernel(kernel, compliance) => {
                    match kernels.iter_mut().find(|(k, _)| *k == kernel) {
                        Some((_, c)) => *c += compliance,
                        None => kernels.push((kernel, compliance)),
                    }
                }
                Term::Winkler(compliance) => winkler_compliance += compliance,
                Term::Beam {
                    loaded_point,
                    flexibility,
                } => match beams.iter_mut().find(|(x0, _)| *x0 == loaded_point) {
                    Some((_, f)) => *f += flexibility,
                    None => beams.push((loaded_point, flexibility)),
                },
            }
            elastic += 1;
        }
        if elastic == 0 {
            return Err(InfluenceError::AllRigid {
                bodies: bodies.len(),
            });
        }
        Ok(Self {
            kernels,
            winkler_compliance,
            beams,
            cell,
            centre: love_rectangle(0.0, 0.0, cell.dx, cell.dy),
        })
    }

    /// Adds the terms that are not translation invariant: the Winkler
    /// diagonal `1 / (k A_k)` and the beams' cantilever coefficients.
    /// S must be symmetric (the beams' terms are added to the lower triangle
    /// and mirrored).
    pub(crate) fn add_local(&self, points: &PointSet, s: &mut Mat<f64>) {
        if self.winkler_compliance > 0.0 {
            let diagonal = self.winkler_diagonal(points);
            for k in 0..points.len() {
                s[(k, k)] += diagonal;
            }
        }
        if self.beams.is_empty() {
            return;
        }
        let xs = points.xs();
        for c in 0..xs.len() {
            for r in c..xs.len() {
                let v = self.add_beams(s[(r, c)], xs[r], xs[c]);
                s[(r, c)] = v;
                s[(c, r)] = v;
            }
        }
    }

    /// The Winkler foundations' diagonal `sum 1/k` over the cell's measure
    /// (0 without a foundation).
    pub(crate) fn winkler_diagonal(&self, points: &PointSet) -> f64 {
        self.winkler_compliance / points.cell().measure(points.dimension())
    }

    /// `v` plus the beams' coefficients between abscissae `xk` and `xj`,
    /// added beam by beam.
    pub(crate) fn add_beams(&self, v: f64, xk: f64, xj: f64) -> f64 {
        self.beams.iter().fold(v, |v, &(x0, flexibility)| {
            v + cantilever(flexibility, xk - x0, xj - x0)
        })
    }

    /// The half-space part of S at every lattice offset `(di, dj)`,
    /// `0 <= di < ni`, `0 <= dj < nj`, at index `di * nj + dj`
    /// ([`TableLayout::offset`]): one kernel evaluation per distinct
    /// offset, at `(di dx, dj dy)`, the self-term at (0, 0) (see
    /// [`Terms::fill_table`]).
    pub(crate) fn table(&self, ni: usize, nj: usize) -> Vec<f64> {
        let mut table = vec![0.0; ni * nj];
        self.fill_table(ni, nj, &mut table, (nj, 1));
        table
    }

    /// Writes the half-space part of S at lattice offset `(di, dj)`,
    /// `0 <= di < ni`, `0 <= dj < nj`, to `out[di * strides.0 + dj *
    /// strides.1]`, rows di in order. Love's patch is evaluated row by row
    /// from edge terms shared between neighbouring cells ([`LoveRows`]),
    /// the other kernels offset by offset ([`Terms::kernel_at`]). On
    /// square cells (dx = dy) the kernels are symmetric bit for bit,
    /// `K(di, dj) = K(dj, di)` (Love's patch sums the same edge terms in the
    /// other order, Boussinesq's `hypot` is symmetric), so an offset below
    /// the diagonal whose mirror lies in the table is copied from it,
    /// evaluated once: about half the evaluations of a square box.
    pub(crate) fn fill_table(
        &self,
        ni: usize,
        nj: usize,
        out: &mut [f64],
        strides: (usize, usize),
    ) {
        let Cell { dx, dy } = self.cell;
        self.fill_table_mirrored(ni, nj, out, strides, dx == dy);
    }

    /// [`Terms::fill_table`], copying the offsets below the diagonal from
    /// their mirror if `mirror` (square cells only).
    fn fill_table_mirrored(
        &self,
        ni: usize,
        nj: usize,
        out: &mut [f64],
        strides: (usize, usize),
        mirror: bool,
    ) {
        let Cell { dx, dy } = self.cell;
        let at = |di: usize, dj: usize| di * strides.0 + dj * strides.1;
        let mut love = self
            .kernels
            .iter()
            .any(|&(kernel, _)| kernel == Kernel::UniformPatch)
            .then(|| LoveRows::new(dx, dy, nj));
        for di in 0..ni {
            // The offsets evaluated: those at or above the diagonal where
            // the mirror applies, all of the row otherwise.
            let from = if mirror && di < nj { di } else { 0 };
            if let Some(love) = love.as_mut() {
                love.next_row(from);
            }
            for dj in 0..from {
                out[at(di, dj)] = out[at(dj, di)];
            }
            for dj in from..nj {
                let (x, y) = (di as f64 * dx, dj as f64 * dy);
                out[at(di, dj)] = self
                    .kernels
                    .iter()
                    .map(|&(kernel, compliance)| {
                        let k = match (kernel, love.as_ref()) {
                            (Kernel::UniformPatch, Some(love)) => love.cell(dj) / PI,
                            _ => self.kernel_at(kernel, x, y, di == 0 && dj == 0),
                        };
                        compliance * k
                    })
                    .sum();
            }
        }
    }

    /// The half-space part of S for an offset (x, y) = field point minus
    /// loaded point; `same_point` selects the self-terms.
    pub(crate) fn coefficient(&self, x: f64, y: f64, same_point: bool) -> f64 {
        self.kernels
            .iter()
            .map(|&(kernel, compliance)| compliance * self.kernel_at(kernel, x, y, same_point))
            .sum()
    }

    /// One kernel's value (without its compliance) at the offset (x, y);
    /// `same_point` selects the point force's self-term.
    fn kernel_at(&self, kernel: Kernel, x: f64, y: f64, same_point: bool) -> f64 {
        let Cell { dx, dy } = self.cell;
        match kernel {
            Kernel::PointForce if same_point => self.centre / PI,
            Kernel::PointForce => boussinesq(x, y) / PI,
            Kernel::UniformPatch => love_rectangle(x, y, dx, dy) / PI,
            Kernel::Strip { reference_distance } => {
                2.0 / PI * plane_strain_strip(x, dx, reference_distance)
            }
        }
    }
}

/// The cantilever coefficient `a^2 (3 b - a) / (6 E I)` of a beam of
/// flexibility `1 / (E I)` between points at signed distances `dk`, `dj`
/// from its clamp, `a` and `b` the smaller and larger distance; 0 for points
/// on opposite sides or at the clamp.
fn cantilever(flexibility: f64, dk: f64, dj: f64) -> f64 {
    if dk * dj <= 0.0 {
        return 0.0;
    }
    let (a, b) = (dk.abs().min(dj.abs()), dk.abs().max(dj.abs()));
    flexibility * a * a * (3.0 * b - a) / 6.0
}

/// E I must be finite and positive, x0 finite.
fn check_beam(
    model: &'static str,
    flexural_rigidity: f64,
    loaded_point: f64,
) -> Result<(), InfluenceError> {
    let bad = |field, value, reason: &str| InfluenceError::InvalidModel {
        model,
        field,
        value,
        reason: reason.into(),
    };
    if !(flexural_rigidity.is_finite() && flexural_rigidity > 0.0) {
        return Err(bad(
            "flexural_rigidity",
            flexural_rigidity,
            "E I must be finite and positive",
        ));
    }
    if !loaded_point.is_finite() {
        return Err(bad("loaded_point", loaded_point, "must be finite"));
    }
    Ok(())
}

/// d0 must be finite, positive and at least the extent of the set.
fn check_reference_distance(
    model: &'static str,
    d0: f64,
    points: &PointSet,
) -> Result<(), InfluenceError> {
    let bad = |reason: String| InfluenceError::InvalidModel {
        model,
        field: "reference_distance",
        value: d0,
        reason,
    };
    if !d0.is_finite() {
        return Err(bad("must be finite".into()));
    }
    let extent = points.extent().0;
    if !(d0 >= extent) {
        return Err(bad(format!(
            "must be at least the extent of the point set ({}): the 2D displacement is \
             measured from a datum outside the loaded zone, and the logarithmic kernel is \
             positive definite only when d0 exceeds a quarter of the extent",
            Num(extent)
        )));
    }
    Ok(())
}

/// Where a lattice table applies: the points' lattice indices shifted to
/// start at 0, and the table's extent.
pub(crate) struct TableLayout {
    pub(crate) i: Vec<usize>,
    pub(crate) j: Vec<usize>,
    pub(crate) ni: usize,
    pub(crate) nj: usize,
}

impl TableLayout {
    /// The table index of the offset between points k and j.
    pub(crate) fn offset(&self, k: usize, j: usize) -> usize {
        self.i[k].abs_diff(self.i[j]) * self.nj + self.j[k].abs_diff(self.j[j])
    }
}

/// The table layout if the set has a lattice and the table (one entry per
/// offset in the bounding box) is not much larger than the set.
pub(crate) fn table_layout(points: &PointSet) -> Option<TableLayout> {
    let lattice = points.lattice()?;
    let bounds = LatticeBox::of_lattice(lattice)?;
    if !bounds.is_dense(points.len()) {
        return None;
    }
    let (i, j) = lattice.iter().map(|l| bounds.local(l)).unzip();
    Some(TableLayout {
        i,
        j,
        ni: bounds.ni,
        nj: bounds.nj,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Material;

    /// The table entry by entry, each offset evaluated on its own.
    fn evaluated(terms: &Terms, ni: usize, nj: usize) -> Vec<f64> {
        let Cell { dx, dy } = terms.cell;
        (0..ni)
            .flat_map(|di| (0..nj).map(move |dj| (di, dj)))
            .map(|(di, dj)| terms.coefficient(di as f64 * dx, dj as f64 * dy, di == 0 && dj == 0))
            .collect()
    }

    /// The table without the mirror: every offset of every row evaluated.
    fn unmirrored(terms: &Terms, ni: usize, nj: usize) -> Vec<f64> {
        let mut table = vec![0.0; ni * nj];
        terms.fill_table_mirrored(ni, nj, &mut table, (nj, 1), false);
        table
    }

    #[test]
    fn the_table_mirrors_bit_for_bit_and_equals_every_offset_evaluated() {
        let steel = Material::new(210e9, 0.3).unwrap();
        let soft = Material::new(3e9, 0.45).unwrap();
        let (patch, force) = (Body::uniform_patch(steel), Body::point_force(soft));
        let sets = [
            PointSet::grid_disk(0.1, 0.73).unwrap(),
            PointSet::grid_rectangle(1.0, 2.5, 4, 7).unwrap(),
            PointSet::grid_rectangle(1.0, 1.0, 9, 9).unwrap(),
            PointSet::grid_rectangle(0.3, 1.7, 1, 5).unwrap(),
        ];
        for points in &sets {
            let terms = Terms::collect(points, &[&patch, &force]).unwrap();
            let forces = Terms::collect(points, &[&force]).unwrap();
            // Boxes wider, taller and square, odd and even.
            for (ni, nj) in [(7, 7), (5, 9), (9, 4), (1, 6), (6, 1), (8, 8)] {
                let table = terms.table(ni, nj);
                assert_eq!(table, unmirrored(&terms, ni, nj), "{ni} x {nj}");
                // Boussinesq alone: the per-offset kernel, bit for bit.
                assert_eq!(forces.table(ni, nj), evaluated(&forces, ni, nj));
                // Love's patch from shared edges: the per-offset kernel to
                // its rounding (a few ulps this close; see
                // kernels::tests::shared_edges_agree_with_each_cell_evaluated_to_its_rounding).
                for (t, e) in table.iter().zip(evaluated(&terms, ni, nj)) {
                    assert!((t / e - 1.0).abs() < 64.0 * f64::EPSILON, "{t} vs {e}");
                }
                // Transposed into a wider buffer: the same entries.
                let stride = ni + 2;
                let mut out = vec![f64::NAN; stride * nj];
                terms.fill_table(ni, nj, &mut out, (1, stride));
                for (di, dj) in (0..ni).flat_map(|di| (0..nj).map(move |dj| (di, dj))) {
                    assert_eq!(out[dj * stride + di], table[di * nj + dj]);
                }
            }
        }
        // Square cells mirror; the evaluations agree with their mirror.
        let terms = Terms::collect(&sets[0], &[&patch, &force]).unwrap();
        let (dx, dy) = (terms.cell.dx, terms.cell.dy);
        assert_eq!(dx, dy);
        for (a, b) in [(1, 3), (0, 5), (2, 7)] {
            let at = |i: usize, j: usize| terms.coefficient(i as f64 * dx, j as f64 * dy, false);
            assert_eq!(at(a, b), at(b, a));
        }
        let table = unmirrored(&terms, 9, 9);
        for (a, b) in (0..9).flat_map(|a| (0..9).map(move |b| (a, b))) {
            assert_eq!(table[a * 9 + b], table[b * 9 + a]);
        }
    }
}
