//! One body's stress field below a solved contact, its maxima found and
//! refined, its section and depth profile (see the module documentation of
//! `crate::subsurface`).

use elcon_influence::{
    Body, Dimension, InfluenceError, PointSet, Stress, StressKernel, StressLayers,
};

use elcon_lcp::Cancel;
use rayon::prelude::*;

use crate::contact::ContactSolution;
use crate::edge::contact_spans;

/// Depths of the grid the maxima are first looked for on, down to
/// [`DEPTH_SPAN`] contact half-widths (or radii).
const DEPTHS: usize = 24;
/// How deep the depth grid reaches, in contact half-widths.
pub const DEPTH_SPAN: f64 = 2.0;
/// The most columns (x, y) the maxima are looked for at, before refining.
const COLUMNS: usize = 400;
/// Points across a section, and rows of its depth.
const SECTION_POINTS: usize = 161;
/// The pattern search ends when its step is below this fraction of the
/// contact's half-width.
const REFINED: f64 = 1e-4;

/// Tresca's shear is at most the von Mises stress times `1 / sqrt(3)`;
/// this factor holds that bound with a margin of 1e-9 for the rounding of
/// either.
const TRESCA_BOUND: f64 = 0.577_350_269_189_625_8 * (1.0 + 1e-9);

/// The measures looked for, in [`BodyStresses`]' order: von Mises, Tresca,
/// `|tau_xz|`, `|tau_yz|`.
const MEASURES: [fn(&Stress) -> f64; 4] = [
    |s| s.von_mises(),
    |s| s.tresca(),
    |s| s.xz.abs(),
    |s| s.yz.abs(),
];

/// Intervals the two layer spacings around a maximum's layer are cut into
/// when the compass search is skipped: the layers at the new depths are
/// computed and the parabola taken through the finer column, so its
/// vertex's error falls with the cube of the spacing (27 times for 3).
const FINER_DEPTHS: usize = 6;

/// Direct evaluations of the compass search, about, for a maximum.
const REFINE_EVALUATIONS: usize = 300;

/// The most kernel sums (points in contact times evaluations) a maximum's
/// compass search may take; above, the parabolic refinement of the layers
/// stands alone.
const DIRECT_BUDGET: usize = 400_000;

/// The size of a cell of `points`: its width on a line, its larger side
/// on a surface.
fn cell_size(points: &PointSet) -> f64 {
    let cell = points.cell();
    match points.dimension() {
        Dimension::Line => cell.dx,
        Dimension::Surface => cell.dx.max(cell.dy),
    }
}

/// `count` depths evenly spaced down to [`DEPTH_SPAN`] times `extent` (a
/// contact's half-width, [`StressField::half_width`]; at least a cell,
/// `cell_size`) below the surface of `points`: the grid the stresses'
/// maxima are first looked for on,
///
/// ```text
///     z_j = z_0 + (DEPTH_SPAN max(extent, cell) - z_0) j / count,   j = 1..count
/// ```
///
/// with `z_0` a cell for the point-force kernel (`point_force`: its
/// stresses are singular at the surface), 0 otherwise.
pub fn depth_grid(points: &PointSet, extent: f64, point_force: bool, count: usize) -> Vec<f64> {
    let size = cell_size(points);
    let scale = extent.max(size);
    let shallowest = if point_force { size } else { 0.0 };
    (1..=count)
        .map(|j| shallowest + (DEPTH_SPAN * scale - shallowest) * j as f64 / count as f64)
        .collect()
}

/// The half-width of a contact across its narrower direction: half the
/// span of the points `contact` (indices into `points`) along x or along
/// y, the smaller (x on a line), their cells included,
///
/// ```text
///     b = min( (max x - min x + dx) / 2, (max y - min y + dy) / 2 )
/// ```
///
/// `None` for an empty contact: no point, no width.
pub fn contact_half_width(
    points: &PointSet,
    contact: impl Iterator<Item = usize> + Clone,
) -> Option<f64> {
    contact_spans(points, contact).map(|(x, y)| 0.5 * y.map_or(x, |y| x.min(y)))
}

/// A peak below every value.
const LOWEST: Peak = Peak {
    value: f64::NEG_INFINITY,
    x: 0.0,
    y: 0.0,
    z: 0.0,
};

/// What the subsurface stresses are asked for with.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SubsurfaceOptions {
    /// The depths of the grid the maxima are looked for on, of the
    /// section and of the depth profile (length, each > 0, increasing);
    /// default 24 depths down to [`DEPTH_SPAN`] contact half-widths
    /// (a cell or more deep for the point-force model).
    pub depths: Option<Vec<f64>>,
}

/// Where a stress quantity is largest.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Peak {
    /// The value (stress; signed for an orthogonal shear, its largest
    /// magnitude).
    pub value: f64,
    /// Position x (length).
    pub x: f64,
    /// Position y (length; 0 on a line).
    pub y: f64,
    /// Depth z below the surface (length).
    pub z: f64,
}

/// A section of the field: `stresses[i * depths.len() + j]` at
/// `(xs[i], y, depths[j])`.
#[derive(Debug, Clone, PartialEq)]
pub struct Section {
    /// The section's y (length; 0 on a line).
    pub y: f64,
    /// The positions along x (length).
    pub xs: Vec<f64>,
    /// The depths (length).
    pub depths: Vec<f64>,
    /// The stresses, x-major.
    pub stresses: Vec<Stress>,
}

/// One body's stresses below the contact.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyStresses {
    /// Its Poisson's ratio.
    pub poissons_ratio: f64,
    /// The largest von Mises stress.
    pub von_mises: Peak,
    /// The largest shear stress (Tresca: half the principal stresses'
    /// spread).
    pub tresca: Peak,
    /// The orthogonal shear `tau_xz` of largest magnitude.
    pub orthogonal_xz: Peak,
    /// The orthogonal shear `tau_yz` of largest magnitude (0 on a line).
    pub orthogonal_yz: Peak,
    /// The section (x against depth) through the largest von Mises stress.
    pub section: Section,
    /// The stresses along depth below the peak pressure (a section of one
    /// x).
    pub profile: Section,
}

/// A body's subsurface stresses, or why it has none.
#[derive(Debug, Clone, PartialEq)]
pub enum Subsurface {
    /// An elastic half-space: its field.
    Stresses(Box<BodyStresses>),
    /// A rigid body, a beam or a foundation: why not.
    NotApplicable(&'static str),
}

/// The stress of one body at any point below a solved contact.
pub struct StressField<'a> {
    points: &'a PointSet,
    /// The points in contact and their pressures.
    loaded: Vec<(usize, f64)>,
    kind: StressKernel,
    nu: f64,
    /// The token of the thread that made the field: its layers, on the
    /// pool's threads, poll it (an interrupt stops the stage within a
    /// layer, a column or a section row).
    cancel: Option<Cancel>,
}

impl<'a> StressField<'a> {
    /// The field of `body` under `solution` on `points`, or why there is
    /// none.
    pub fn new(
        points: &'a PointSet,
        solution: &ContactSolution,
        body: &Body,
    ) -> Result<Self, &'static str> {
        let (kind, nu) = StressKernel::of(body)?;
        Ok(Self::of_kernel(points, solution, kind, nu))
    }

    /// The field of the stress kernel `kind` with Poisson's ratio `nu` (a
    /// body's, [`StressKernel::of`]) under `solution` on `points`.
    pub fn of_kernel(
        points: &'a PointSet,
        solution: &ContactSolution,
        kind: StressKernel,
        nu: f64,
    ) -> Self {
        let loaded = solution
            .pressures
            .iter()
            .enumerate()
            .filter(|(_, p)| **p > 0.0)
            .map(|(k, p)| (k, *p))
            .collect();
        Self {
            points,
            loaded,
            kind,
            nu,
            cancel: Cancel::watched(),
        }
    }

    /// Whether the interrupt this field's thread watches was given.
    fn cancelled(&self) -> bool {
        self.cancel.as_ref().is_some_and(Cancel::is_cancelled)
    }

    /// [`InfluenceError::Cancelled`] when the interrupt was given.
    fn poll(&self) -> Result<(), InfluenceError> {
        match self.cancelled() {
            true => Err(InfluenceError::Cancelled {
                what: "subsurface stresses",
            }),
            false => Ok(()),
        }
    }

    /// The contact's half-width across its narrower direction
    /// ([`contact_half_width`] of the points in contact). It scales the
    /// depths: a long contact's stresses lie within a few of its narrow
    /// half-widths. `None` when no point is in contact: there is no field
    /// to scale ([`Subsurface::of`] says so).
    pub fn half_width(&self) -> Option<f64> {
        contact_half_width(self.points, self.loaded.iter().map(|&(k, _)| k))
    }

    /// The stresses at every point of the set at each of `depths` (one
    /// layer a depth, in the points' order): by FFT on a lattice
    /// (`StressLayers`), by direct sums over the points in contact
    /// elsewhere.
    ///
    /// # Errors
    /// [`InfluenceError::AllocationFailed`] when a layer's buffers cannot
    /// be allocated.
    pub fn layers_at(&self, depths: &[f64]) -> Result<Vec<Vec<Stress>>, InfluenceError> {
        if let Some(layers) = self.layers()? {
            return depths
                .iter()
                .map(|&z| self.poll().and_then(|()| layers.layer(z)))
                .collect();
        }
        let points = self.points;
        Ok(depths
            .iter()
            .map(|&z| {
                (0..points.len())
                    .map(|q| self.at(points.x(q), points.y(q), z))
                    .collect()
            })
            .collect())
    }

    /// The stress at `(x, y, z)`, z > 0.
    pub fn at(&self, x: f64, y: f64, z: f64) -> Stress {
        let cell = self.points.cell();
        let mut total = Stress::default();
        for &(k, p) in &self.loaded {
            let (dx, dy) = (x - self.points.x(k), y - self.points.y(k));
            let unit = self.kind.unit((dx, dy, z), (cell.dx, cell.dy), self.nu);
            total.add_scaled(p, &unit);
        }
        total
    }

    /// The body's stresses: maxima, section and profile (see the module
    /// documentation), `extent` the contact's half-width (narrower
    /// direction) or radius ([`StressField::half_width`]). On a
    /// lattice the depth layers are convolutions (`StressLayers`: every
    /// point at every depth); on other points the maxima are looked for at
    /// up to 400 of the points in contact.
    ///
    /// # Errors
    /// [`InfluenceError::AllocationFailed`] when a layer's buffers cannot
    /// be allocated.
    pub fn stresses(
        &self,
        extent: f64,
        options: &SubsurfaceOptions,
    ) -> Result<BodyStresses, InfluenceError> {
        let scale = extent.max(cell_size(self.points));
        let depths = options.depths.clone().unwrap_or_else(|| {
            let point_force = self.kind == StressKernel::PointForce;
            depth_grid(self.points, extent, point_force, DEPTHS)
        });
        let peak = self.peak_pressure_point();
        let (peaks, section, profile) = match self.layers()? {
            Some(layers) => self.layered(&layers, peak, &depths, scale)?,
            None => {
                let peaks: Vec<Peak> = MEASURES
                    .iter()
                    .zip(self.sweep_direct(&depths))
                    .map(|(m, p)| self.refine(p, m, scale))
                    .collect();
                let section = self.section(peaks[0].y, &depths, scale);
                let profile = Section {
                    y: self.points.y(peak),
                    xs: vec![self.points.x(peak)],
                    depths: depths.clone(),
                    stresses: depths
                        .iter()
                        .map(|&z| self.at(self.points.x(peak), self.points.y(peak), z))
                        .collect(),
                };
                (peaks, section, profile)
            }
        };
        // The direct sums stop early on an interrupt: what they found is
        // not the field's.
        self.poll()?;
        let signed = |p: Peak, of: fn(&Stress) -> f64| Peak {
            value: of(&self.at(p.x, p.y, p.z)),
            ..p
        };
        Ok(BodyStresses {
            poissons_ratio: self.nu,
            von_mises: peaks[0],
            tresca: peaks[1],
            orthogonal_xz: signed(peaks[2], |s| s.xz),
            orthogonal_yz: signed(peaks[3], |s| s.yz),
            section,
            profile,
        })
    }

    /// The depth layers by FFT, when the points are a lattice.
    fn layers(&self) -> Result<Option<StressLayers>, InfluenceError> {
        if self.points.lattice().is_none() {
            return Ok(None);
        }
        let mut pressures = vec![0.0; self.points.len()];
        for &(k, p) in &self.loaded {
            pressures[k] = p;
        }
        StressLayers::new(self.points, &pressures, self.kind, self.nu).map(Some)
    }

    /// The maxima, section and profile from the depth layers: every point
    /// at every depth, the section along the lattice row of the peak
    /// pressure (again along the row of the largest von Mises stress, when
    /// that is another), the profile below the peak pressure. Each maximum
    /// is refined by a parabola through the largest of its layer and of the
    /// layers above and below it, then by the compass search where the
    /// direct sums are cheap ([`DIRECT_BUDGET`]), else by finer layers
    /// around it ([`FINER_DEPTHS`]).
    fn layered(
        &self,
        layers: &StressLayers,
        peak: usize,
        depths: &[f64],
        scale: f64,
    ) -> Result<(Vec<Peak>, Section, Section), InfluenceError> {
        let y = self.points.y(peak);
        let (per_layer, mut section, profile) = self.sweep_layers(layers, depths, y, peak)?;
        let peaks: Vec<Peak> = if self.loaded.len() * REFINE_EVALUATIONS <= DIRECT_BUDGET {
            (0..MEASURES.len())
                .map(|m| {
                    let column: Vec<Peak> = per_layer.iter().map(|layer| layer[m]).collect();
                    self.refine(parabolic(&column), &MEASURES[m], scale)
                })
                .collect()
        } else {
            self.deepen(layers, &per_layer)?
        };
        let largest = per_layer
            .iter()
            .map(|layer| layer[0])
            .fold(LOWEST, |a, b| if b.value > a.value { b } else { a });
        // The row of the peak pressure already holds the largest von Mises
        // stress (to rounding: a symmetric contact's maxima tie across
        // rows): no second sweep.
        let on_row = section
            .stresses
            .iter()
            .fold(0.0f64, |a, s| a.max(s.von_mises()));
        if on_row < largest.value * (1.0 - 1e-9) && largest.y != y {
            let row_y = largest.y;
            section = self.sweep_layers(layers, depths, row_y, peak)?.1;
        }
        Ok((peaks, section, profile))
    }

    /// Each measure's largest refined in depth from `per_layer` (each
    /// layer's largest of every measure, by depth): the layers between the
    /// neighbours above and below its largest layer at [`FINER_DEPTHS`]
    /// intervals (computed once for the measures whose largest is in the
    /// same layer, the known layers reused), and the parabola through the
    /// largest of that finer column and its neighbours. At the top or the
    /// bottom of the column, the column's own parabola.
    fn deepen(
        &self,
        layers: &StressLayers,
        per_layer: &[[Peak; 4]],
    ) -> Result<Vec<Peak>, InfluenceError> {
        let largest = |m: usize| {
            (0..per_layer.len())
                .max_by(|&a, &b| per_layer[a][m].value.total_cmp(&per_layer[b][m].value))
                .unwrap_or(0)
        };
        let mut finer: Vec<(usize, Vec<[Peak; 4]>)> = Vec::new();
        let mut peaks = Vec::with_capacity(MEASURES.len());
        for m in 0..MEASURES.len() {
            let j = largest(m);
            if j == 0 || j + 1 >= per_layer.len() {
                let column: Vec<Peak> = per_layer.iter().map(|layer| layer[m]).collect();
                peaks.push(parabolic(&column));
                continue;
            }
            if !finer.iter().any(|(at, _)| *at == j) {
                finer.push((j, self.finer_column(layers, per_layer, j)?));
            }
            let (_, column) = finer.iter().find(|(at, _)| *at == j).expect("just made");
            let column: Vec<Peak> = column.iter().map(|layer| layer[m]).collect();
            peaks.push(parabolic(&column));
        }
        Ok(peaks)
    }

    /// Each measure's largest on the layers from `per_layer`'s layer
    /// `j - 1` to `j + 1` at [`FINER_DEPTHS`] intervals: the three known
    /// layers reused, the others computed (in parallel).
    fn finer_column(
        &self,
        layers: &StressLayers,
        per_layer: &[[Peak; 4]],
        j: usize,
    ) -> Result<Vec<[Peak; 4]>, InfluenceError> {
        let (lo, hi) = (per_layer[j - 1][0].z, per_layer[j + 1][0].z);
        let half = FINER_DEPTHS / 2;
        (0..=FINER_DEPTHS)
            .into_par_iter()
            .map(|i| match i {
                0 => Ok(per_layer[j - 1]),
                i if i == half => Ok(per_layer[j]),
                i if i == FINER_DEPTHS => Ok(per_layer[j + 1]),
                i => {
                    let z = if i < half {
                        lo + (per_layer[j][0].z - lo) * i as f64 / half as f64
                    } else {
                        per_layer[j][0].z
                            + (hi - per_layer[j][0].z) * (i - half) as f64 / half as f64
                    };
                    self.poll()?;
                    Ok(self.layer_best(&layers.layer(z)?, z))
                }
            })
            .collect()
    }

    /// Each measure's largest over `layer`, the stresses at depth `z`.
    /// Tresca's shear (principal stresses by Jacobi rotations, the
    /// costliest measure) is taken only where it could reach its value at
    /// the largest von Mises stress: it is at most the von Mises stress
    /// over sqrt(3) (equal principal spreads), a bound kept with a margin
    /// for rounding, so the largest found, and the first point that holds
    /// it, are those of a sweep over every point.
    fn layer_best(&self, layer: &[Stress], z: f64) -> [Peak; 4] {
        let peak = |value, k: usize| Peak {
            value,
            x: self.points.x(k),
            y: self.points.y(k),
            z,
        };
        let mut best = [LOWEST; 4];
        let mut largest = None;
        for (k, s) in layer.iter().enumerate() {
            for m in [0, 2, 3] {
                let v = MEASURES[m](s);
                if v > best[m].value {
                    best[m] = peak(v, k);
                    if m == 0 {
                        largest = Some(k);
                    }
                }
            }
        }
        let floor = largest.map_or(f64::NEG_INFINITY, |k| layer[k].tresca());
        for (k, s) in layer.iter().enumerate() {
            if s.von_mises() * TRESCA_BOUND < floor {
                continue;
            }
            let v = MEASURES[1](s);
            if v > best[1].value {
                best[1] = peak(v, k);
            }
        }
        best
    }

    /// Each measure's largest in each layer, the section along the lattice
    /// row at `y` and the profile below point `peak`.
    fn sweep_layers(
        &self,
        layers: &StressLayers,
        depths: &[f64],
        y: f64,
        peak: usize,
    ) -> Result<(Vec<[Peak; 4]>, Section, Section), InfluenceError> {
        let mut row: Vec<usize> = (0..self.points.len())
            .filter(|&k| self.points.y(k) == y)
            .collect();
        row.sort_by(|&a, &b| self.points.x(a).total_cmp(&self.points.x(b)));
        // Each layer on a thread of the pool, one layer a thread held at a
        // time; gathered in depth order, so the result does not depend on
        // the threads.
        let per_depth: Vec<([Peak; 4], Vec<Stress>, Stress)> = depths
            .par_iter()
            .map(|&z| {
                self.poll()?;
                let layer = layers.layer(z)?;
                let best = self.layer_best(&layer, z);
                let on_row: Vec<Stress> = row.iter().map(|&k| layer[k]).collect();
                Ok((best, on_row, layer[peak]))
            })
            .collect::<Result<_, InfluenceError>>()?;
        let mut stresses = vec![Stress::default(); row.len() * depths.len()];
        let mut below = Vec::with_capacity(depths.len());
        let mut per_layer = Vec::with_capacity(depths.len());
        for (j, (best, on_row, under)) in per_depth.into_iter().enumerate() {
            per_layer.push(best);
            for (i, s) in on_row.into_iter().enumerate() {
                stresses[i * depths.len() + j] = s;
            }
            below.push(under);
        }
        let section = Section {
            y,
            xs: row.iter().map(|&k| self.points.x(k)).collect(),
            depths: depths.to_vec(),
            stresses,
        };
        let profile = Section {
            y: self.points.y(peak),
            xs: vec![self.points.x(peak)],
            depths: depths.to_vec(),
            stresses: below,
        };
        Ok((per_layer, section, profile))
    }

    /// Each measure's largest over up to [`COLUMNS`] points in contact and
    /// the depths, by direct sums.
    fn sweep_direct(&self, depths: &[f64]) -> [Peak; 4] {
        let mut best = [LOWEST; 4];
        for (x, y) in self.columns() {
            if self.cancelled() {
                break;
            }
            for &z in depths {
                let s = self.at(x, y, z);
                for (b, m) in best.iter_mut().zip(MEASURES) {
                    let v = m(&s);
                    if v > b.value {
                        *b = Peak { value: v, x, y, z };
                    }
                }
            }
        }
        best
    }

    /// The point of peak pressure.
    fn peak_pressure_point(&self) -> usize {
        self.loaded
            .iter()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map_or(0, |&(k, _)| k)
    }

    /// At most [`COLUMNS`] of the points in contact (every one, or an even
    /// subsample), where the maxima are first looked for.
    fn columns(&self) -> Vec<(f64, f64)> {
        let step = self.loaded.len().div_ceil(COLUMNS).max(1);
        self.loaded
            .iter()
            .step_by(step)
            .map(|&(k, _)| (self.points.x(k), self.points.y(k)))
            .collect()
    }

    /// `start` refined by a compass search in (x, y, z) (y held on a line,
    /// z kept positive), its step halved until below [`REFINED`] of
    /// `scale`.
    fn refine(&self, start: Peak, measure: &fn(&Stress) -> f64, scale: f64) -> Peak {
        let line = self.points.dimension() == Dimension::Line;
        let mut best = start;
        let mut step = 0.25 * scale / DEPTHS as f64 * DEPTH_SPAN * 4.0;
        let floor = if self.kind == StressKernel::PointForce {
            self.points.cell().dx.max(self.points.cell().dy)
        } else {
            1e-3 * scale
        };
        while step > REFINED * scale && !self.cancelled() {
            let mut moved = false;
            for (ddx, ddy, ddz) in [
                (1.0, 0.0, 0.0),
                (-1.0, 0.0, 0.0),
                (0.0, 1.0, 0.0),
                (0.0, -1.0, 0.0),
                (0.0, 0.0, 1.0),
                (0.0, 0.0, -1.0),
            ] {
                if line && ddy != 0.0 {
                    continue;
                }
                let (x, y, z) = (
                    best.x + step * ddx,
                    best.y + step * ddy,
                    best.z + step * ddz,
                );
                if z < floor {
                    continue;
                }
                let v = measure(&self.at(x, y, z));
                if v > best.value {
                    best = Peak { value: v, x, y, z };
                    moved = true;
                }
            }
            if !moved {
                step *= 0.5;
            }
        }
        best
    }

    /// The section at `y`: [`SECTION_POINTS`] positions across the
    /// contact and 50 % beyond it on either side, at every depth.
    fn section(&self, y: f64, depths: &[f64], scale: f64) -> Section {
        let (lo, hi) = self
            .loaded
            .iter()
            .map(|&(k, _)| self.points.x(k))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(x), b.max(x))
            });
        let (lo, hi) = if lo <= hi { (lo, hi) } else { (-scale, scale) };
        let margin = 0.5 * (hi - lo).max(scale);
        let xs: Vec<f64> = (0..SECTION_POINTS)
            .map(|i| {
                lo - margin + (hi - lo + 2.0 * margin) * i as f64 / (SECTION_POINTS - 1) as f64
            })
            .collect();
        let stresses = xs
            .iter()
            .flat_map(|&x| depths.iter().map(move |&z| (x, z)))
            .map(|(x, z)| self.at(x, y, z))
            .collect();
        Section {
            y,
            xs,
            depths: depths.to_vec(),
            stresses,
        }
    }
}

/// The largest of `column` (each layer's largest, by depth) refined by the
/// parabola through it and its neighbours in depth: its depth and value
/// (its position the layer's).
fn parabolic(column: &[Peak]) -> Peak {
    let j = (0..column.len())
        .max_by(|&a, &b| column[a].value.total_cmp(&column[b].value))
        .unwrap_or(0);
    let best = column.get(j).copied().unwrap_or(LOWEST);
    if j == 0 || j + 1 >= column.len() {
        return best;
    }
    let (a, b, c) = (column[j - 1], best, column[j + 1]);
    let (h1, h2) = (b.z - a.z, c.z - b.z);
    // The parabola through the three (z, value), its vertex.
    let d1 = (b.value - a.value) / h1;
    let d2 = (c.value - b.value) / h2;
    let curvature = (d2 - d1) / (0.5 * (h1 + h2));
    if !(curvature < 0.0) {
        return best;
    }
    let slope_at_b = (d1 * h2 + d2 * h1) / (h1 + h2);
    let shift = (-slope_at_b / curvature).clamp(-h1, h2);
    Peak {
        value: b.value + slope_at_b * shift + 0.5 * curvature * shift * shift,
        z: b.z + shift,
        ..b
    }
}

impl Subsurface {
    /// The stresses below `solution` on `points` of `body` (see the module
    /// documentation).
    pub fn of(
        points: &PointSet,
        solution: &ContactSolution,
        body: &Body,
        options: &SubsurfaceOptions,
    ) -> Self {
        let field = match StressField::new(points, solution, body) {
            Ok(field) => field,
            Err(why) => return Subsurface::NotApplicable(why),
        };
        let Some(half_width) = field.half_width() else {
            return Subsurface::NotApplicable("no point is in contact");
        };
        match field.stresses(half_width, options) {
            Ok(stresses) => Subsurface::Stresses(Box::new(stresses)),
            Err(InfluenceError::Cancelled { .. }) => {
                Subsurface::NotApplicable("cancelled (an interrupt) before they were computed")
            }
            Err(_) => Subsurface::NotApplicable(
                "the stress layers' buffers could not be allocated: not enough memory",
            ),
        }
    }
}
