//! Systems of contacts: several contact zones sharing rigid bodies (a
//! bearing's rings and rolling elements, a gear's tooth pairs, a flange's
//! bolts), solved as one problem.
//!
//! Each zone is a contact problem of today ([`ContactProblem`]): its
//! candidate points in the zone's own frame, its influence `S_z`, its
//! separations `eps_z`. Its two bodies move rigidly; the motion of body `a`
//! toward body `b` along the zone's normal `n` gives the zone's approach
//! and tilts (the levers of `crate::rigid`),
//!
//! ```text
//!     alpha_z = n.(u_a - u_b) + w_a.((o - c_a) x n) - w_b.((o - c_b) x n)
//!     θx_z = (w_a - w_b).e1,   θy_z = (w_a - w_b).e2,
//! ```
//!
//! with `u`, `w` a body's translation and rotation about its centre `c`,
//! `o` the zone's origin and `(e1, e2, n)` its right-handed axes: the
//! zone's modes `m_z = T_z λ + t_z` of the bodies' free motions λ (the
//! border unknowns) and their prescribed ones. The contact conditions of
//! every zone and the equilibrium of every body,
//!
//! ```text
//!     Y_z = S_z F_z + eps_z - L_z m_z >= 0,  F_z >= 0,  F_z.Y_z = 0,
//!     sum_z T_z^T L_z^T F_z = b,
//! ```
//!
//! (`L_z` the levers `1, y, -x` at the zone's points, `b` the loads on the
//! free motions) are one bordered complementarity problem with a
//! block-diagonal S. [`System::solve`] solves it (module `solve`); the
//! certificate covers every zone's complementarity and every body's
//! equilibrium.

mod solve;

pub use solve::{SystemCertificate, SystemSettings, SystemSolution, ZoneSolution};

use elcon_influence::Dimension;
use faer::{Mat, Side};

use crate::{AnalysisError, ContactProblem};

/// One of a rigid body's six motions: translations along and rotations
/// about the body's axes (through its centre; the system's axes unless
/// the body has its own, [`RigidBody::with_axes`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Motion {
    /// Translation along the body's first axis, x (length).
    X,
    /// Translation along its second axis, y (length).
    Y,
    /// Translation along its third axis, z (length).
    Z,
    /// Rotation about its x axis (radians).
    RotX,
    /// Rotation about its y axis (radians).
    RotY,
    /// Rotation about its z axis (radians).
    RotZ,
}

impl Motion {
    /// The six motions in order.
    pub const ALL: [Motion; 6] = [
        Motion::X,
        Motion::Y,
        Motion::Z,
        Motion::RotX,
        Motion::RotY,
        Motion::RotZ,
    ];

    /// The motion in words, for messages.
    pub fn describe(self) -> &'static str {
        match self {
            Motion::X => "translation along x",
            Motion::Y => "translation along y",
            Motion::Z => "translation along z",
            Motion::RotX => "rotation about x",
            Motion::RotY => "rotation about y",
            Motion::RotZ => "rotation about z",
        }
    }

    fn index(self) -> usize {
        self as usize
    }
}

/// How one motion of a body is held.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Dof {
    /// Held at zero.
    Fixed,
    /// Free under a load: a force along a translation (force), a moment
    /// about a rotation (force length); 0 for a free element.
    Free {
        /// The applied force or moment.
        load: f64,
    },
    /// Moved by a given amount (length, or radians).
    Prescribed {
        /// The translation or rotation.
        value: f64,
    },
}

/// A rigid body of a system: a ring, a rolling element, a housing.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidBody {
    /// Its name, used in results and messages.
    pub name: String,
    /// The point its rotations are about (length).
    pub centre: [f64; 3],
    /// Its axes x, y, z in the system (orthonormal, right-handed): its
    /// motions are along and about them (a rolling element's radial
    /// direction, say).
    pub axes: [[f64; 3]; 3],
    /// How each motion is held, in the order of [`Motion::ALL`].
    pub dofs: [Dof; 6],
}

impl RigidBody {
    /// A body held in place (every motion fixed): a housing, an outer ring.
    pub fn fixed(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            centre: [0.0; 3],
            axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            dofs: [Dof::Fixed; 6],
        }
    }

    /// The body with its own axes `x` and `y` (unit, orthogonal; `z = x x
    /// y`): its motions are along and about them.
    pub fn with_axes(mut self, x: [f64; 3], y: [f64; 3]) -> Self {
        self.axes = [x, y, cross(x, y)];
        self
    }

    /// A body with every motion fixed but for the `free` ones, which carry
    /// no load (a free element, or a body loaded by [`RigidBody::with_load`]).
    pub fn free(name: impl Into<String>, centre: [f64; 3], free: &[Motion]) -> Self {
        let mut body = Self::fixed(name);
        body.centre = centre;
        for &m in free {
            body.dofs[m.index()] = Dof::Free { load: 0.0 };
        }
        body
    }

    /// The body with `motion` free under `load` (force, or moment).
    pub fn with_load(mut self, motion: Motion, load: f64) -> Self {
        self.dofs[motion.index()] = Dof::Free { load };
        self
    }

    /// The body with `motion` prescribed to `value` (length, or radians).
    pub fn with_prescribed(mut self, motion: Motion, value: f64) -> Self {
        self.dofs[motion.index()] = Dof::Prescribed { value };
        self
    }
}

/// A zone's frame in the system: its origin (the zone's `(0, 0)`) and its
/// right-handed axes `e1` (the zone's x), `e2` (its y) and the normal
/// `n = e1 x e2`, along which body `a` approaches body `b`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// The zone's origin (length).
    pub origin: [f64; 3],
    /// The zone's x axis (a unit vector).
    pub e1: [f64; 3],
    /// The zone's y axis (a unit vector, orthogonal to `e1`).
    pub e2: [f64; 3],
}

impl Frame {
    /// The normal `n = e1 x e2`.
    pub fn normal(&self) -> [f64; 3] {
        cross(self.e1, self.e2)
    }
}

/// A contact zone of a system: a contact problem between two of its bodies.
/// (In a [`System`], the problem's separations include the clearance.)
#[derive(Debug, Clone)]
pub struct SystemZone {
    /// Its name, used in results and messages.
    pub name: String,
    /// The body whose surface 1 it is (index into the system's bodies);
    /// it approaches `body_b` along the frame's normal.
    pub body_a: usize,
    /// The body whose surface 2 it is.
    pub body_b: usize,
    /// The zone's frame in the system.
    pub frame: Frame,
    /// The contact problem in the zone's frame: its points, S and
    /// separations (its loading is replaced by the bodies' motions). Built
    /// unfolded, on a surface.
    pub problem: ContactProblem,
    /// A clearance added to every separation (length; negative: an
    /// interference).
    pub clearance: f64,
}

/// A free motion of the system: a border unknown.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeMotion {
    /// The body (index).
    pub body: usize,
    /// Which motion.
    pub motion: Motion,
    /// Its load (force or moment).
    pub load: f64,
}

/// A system of contact zones sharing rigid bodies, validated: every body
/// restrained, every zone between two distinct bodies.
#[derive(Debug, Clone)]
pub struct System {
    bodies: Vec<RigidBody>,
    zones: Vec<SystemZone>,
    free: Vec<FreeMotion>,
    /// Per zone: its modes (approach, θx, θy) as `T_z` (3 x free) and the
    /// prescribed part `t_z`.
    maps: Vec<ZoneMap>,
    /// A stiffness per free motion to scale the Newton step's damping by
    /// ([`System::reference_stiffness`]).
    reference: Vec<f64>,
    /// Each free motion's lever, the largest root-mean-square over the
    /// zones' points (1 for a translation along a zone's normal; an arm
    /// for a rotation): what a force becomes in its equilibrium row.
    levers: Vec<f64>,
}

/// A zone's modes from the bodies' motions: `m = T λ + t`.
#[derive(Debug, Clone)]
struct ZoneMap {
    /// 3 rows (approach, θx, θy), one column per free motion.
    t: Mat<f64>,
    /// The prescribed motions' part (and the clearance is not here: it is
    /// in the separations).
    shift: [f64; 3],
}

impl System {
    /// The system of `bodies` and `zones`.
    ///
    /// # Errors
    /// [`AnalysisError::System`] naming the field for no zone, a body index
    /// out of range, a zone between a body and itself, a frame whose axes
    /// are not orthonormal, a zone on a line or folded by its symmetry, a
    /// non-finite load, centre or clearance; [`AnalysisError::Unrestrained`]
    /// naming the body and motion that no zone's candidate points hold.
    pub fn new(bodies: Vec<RigidBody>, zones: Vec<SystemZone>) -> Result<Self, AnalysisError> {
        validate(&bodies, &zones)?;
        let free: Vec<FreeMotion> = bodies
            .iter()
            .enumerate()
            .flat_map(|(body, b)| {
                Motion::ALL
                    .into_iter()
                    .filter_map(move |motion| match b.dofs[motion.index()] {
                        Dof::Free { load } => Some(FreeMotion { body, motion, load }),
                        _ => None,
                    })
            })
            .collect();
        let maps = zones
            .iter()
            .map(|z| ZoneMap::of(z, &bodies, &free))
            .collect();
        let zones = zones
            .into_iter()
            .map(|z| {
                let separation = z
                    .problem
                    .separation()
                    .iter()
                    .map(|e| e + z.clearance)
                    .collect();
                let problem = z.problem.with_separation(separation)?;
                Ok(SystemZone { problem, ..z })
            })
            .collect::<Result<Vec<_>, AnalysisError>>()?;
        let mut system = Self {
            bodies,
            zones,
            free,
            maps,
            reference: Vec::new(),
            levers: Vec::new(),
        };
        system.check_restraint()?;
        system.reference = system.reference_stiffness()?;
        system.levers = system.lever_scales();
        Ok(system)
    }

    /// The bodies.
    pub fn bodies(&self) -> &[RigidBody] {
        &self.bodies
    }

    /// The zones.
    pub fn zones(&self) -> &[SystemZone] {
        &self.zones
    }

    /// The free motions (the border unknowns), in order.
    pub fn free_motions(&self) -> &[FreeMotion] {
        &self.free
    }

    /// The number of candidate points over every zone.
    pub fn points(&self) -> usize {
        self.zones.iter().map(|z| z.problem.points().len()).sum()
    }

    /// Refuses a free motion (or a combination) that no zone's candidate
    /// points restrain: the "all points in contact" stiffness
    /// `sum_z T_z^T (L_z^T L_z) T_z` must be positive definite. Each
    /// motion is scaled to a unit diagonal first; a zero diagonal names
    /// its motion, a null combination its largest part.
    fn check_restraint(&self) -> Result<(), AnalysisError> {
        let d = self.free.len();
        if d == 0 {
            return Ok(());
        }
        let mut gram = Mat::<f64>::zeros(d, d);
        for (zone, map) in self.zones.iter().zip(&self.maps) {
            let l = lever_gram(&zone.problem);
            gram += map.t.transpose() * &l * &map.t;
        }
        let unrestrained = |i: usize| {
            let FreeMotion { body, motion, .. } = self.free[i];
            AnalysisError::Unrestrained {
                body: self.bodies[body].name.clone(),
                motion: motion.describe(),
            }
        };
        let diag: Vec<f64> = (0..d).map(|i| gram[(i, i)]).collect();
        let largest = diag.iter().fold(0.0f64, |a, &v| a.max(v));
        if let Some(i) = (0..d).find(|&i| !(diag[i] > 1e-12 * largest)) {
            return Err(unrestrained(i));
        }
        let scaled = Mat::from_fn(d, d, |i, j| gram[(i, j)] / (diag[i] * diag[j]).sqrt());
        let eigen = scaled
            .self_adjoint_eigen(Side::Lower)
            .map_err(|_| AnalysisError::System {
                field: "bodies".into(),
                reason: "the restraint check's eigenvalues did not converge".into(),
            })?;
        let values = eigen.S();
        // Ascending: the smallest first. A combination held by no point
        // has a zero eigenvalue (to rounding of a d x d sum).
        if values[0] <= 1e-10 * values[d - 1].max(1.0) {
            let v = eigen.U().col(0);
            let i = (0..d)
                .max_by(|&a, &b| v[a].abs().total_cmp(&v[b].abs()))
                .expect("d > 0");
            return Err(unrestrained(i));
        }
        Ok(())
    }
}

impl System {
    /// A stiffness for each free motion to scale the Newton step's damping
    /// by: every candidate point in contact on a spring of its own cell's
    /// stiffness `1 / S_kk`, the diagonal of `sum_z T_z^T (L_z^T L_z /
    /// S_kk) T_z`.
    fn reference_stiffness(&self) -> Result<Vec<f64>, AnalysisError> {
        let mut reference = vec![0.0; self.free.len()];
        for (zone, map) in self.zones.iter().zip(&self.maps) {
            let mut unit = vec![0.0; zone.problem.points().len()];
            unit[0] = 1.0;
            let own = zone.problem.deflection(&unit)?[0];
            let l = lever_gram(&zone.problem);
            let k = map.t.transpose() * &l * &map.t;
            for (j, r) in reference.iter_mut().enumerate() {
                *r += k[(j, j)] / own;
            }
        }
        Ok(reference)
    }
}

impl System {
    /// Each free motion's root-mean-square lever, the largest over the
    /// zones: `sqrt((T^T L^T L T)_jj / n_z)`.
    fn lever_scales(&self) -> Vec<f64> {
        let mut levers = vec![0.0f64; self.free.len()];
        for (zone, map) in self.zones.iter().zip(&self.maps) {
            let n = zone.problem.points().len() as f64;
            let k = map.t.transpose() * lever_gram(&zone.problem) * &map.t;
            for (j, l) in levers.iter_mut().enumerate() {
                *l = l.max((k[(j, j)] / n).sqrt());
            }
        }
        levers
    }
}

impl ZoneMap {
    /// The zone's modes from the bodies' motions (module documentation).
    fn of(zone: &SystemZone, bodies: &[RigidBody], free: &[FreeMotion]) -> Self {
        let n = zone.frame.normal();
        let mut t = Mat::<f64>::zeros(3, free.len());
        let mut shift = [0.0; 3];
        for (body, sign) in [(zone.body_a, 1.0), (zone.body_b, -1.0)] {
            let b = &bodies[body];
            let arm = cross(sub(zone.frame.origin, b.centre), n);
            for motion in Motion::ALL {
                let i = motion.index();
                let axis = b.axes[i % 3];
                let modes = if i < 3 {
                    [dot(n, axis), 0.0, 0.0]
                } else {
                    [
                        dot(arm, axis),
                        dot(zone.frame.e1, axis),
                        dot(zone.frame.e2, axis),
                    ]
                };
                let modes = modes.map(|v| sign * v);
                match b.dofs[i] {
                    Dof::Fixed => {}
                    Dof::Prescribed { value } => {
                        for r in 0..3 {
                            shift[r] += modes[r] * value;
                        }
                    }
                    Dof::Free { .. } => {
                        let j = free
                            .iter()
                            .position(|f| f.body == body && f.motion == motion)
                            .expect("every free motion is listed");
                        for r in 0..3 {
                            t[(r, j)] += modes[r];
                        }
                    }
                }
            }
        }
        Self { t, shift }
    }

    /// The zone's modes `T λ + t`.
    fn modes(&self, lambda: &[f64]) -> [f64; 3] {
        std::array::from_fn(|r| {
            self.shift[r]
                + (0..lambda.len())
                    .map(|j| self.t[(r, j)] * lambda[j])
                    .sum::<f64>()
        })
    }
}

/// `L^T L` over a zone's points: the levers `(1, y, -x)` of its approach
/// and tilts.
fn lever_gram(problem: &ContactProblem) -> Mat<f64> {
    let mut l = Mat::<f64>::zeros(3, 3);
    problem.points().positions().for_each(|(x, y)| {
        let v = [1.0, y, -x];
        for i in 0..3 {
            for j in 0..3 {
                l[(i, j)] += v[i] * v[j];
            }
        }
    });
    l
}

/// Validates the bodies and zones of a system (names each field).
fn validate(bodies: &[RigidBody], zones: &[SystemZone]) -> Result<(), AnalysisError> {
    let bad = |field: String, reason: &str| AnalysisError::System {
        field,
        reason: reason.to_string(),
    };
    if zones.is_empty() {
        return Err(bad(
            "zones".into(),
            "a system needs at least one contact zone",
        ));
    }
    for (i, b) in bodies.iter().enumerate() {
        if b.centre.iter().any(|v| !v.is_finite()) {
            return Err(bad(
                format!("bodies[{i}] ({}).centre", b.name),
                "must be finite",
            ));
        }
        if !orthonormal(b.axes[0], b.axes[1]) {
            return Err(bad(
                format!("bodies[{i}] ({}).axes", b.name),
                "needs orthonormal axes x, y",
            ));
        }
        for (motion, dof) in Motion::ALL.into_iter().zip(b.dofs) {
            let value = match dof {
                Dof::Fixed => 0.0,
                Dof::Free { load } => load,
                Dof::Prescribed { value } => value,
            };
            if !value.is_finite() {
                return Err(bad(
                    format!("bodies[{i}] ({}): {}", b.name, motion.describe()),
                    "its load or value must be finite",
                ));
            }
        }
    }
    overlaps(zones)?;
    for (i, z) in zones.iter().enumerate() {
        let field = |what: &str| format!("zones[{i}] ({}).{what}", z.name);
        for (what, body) in [("body_a", z.body_a), ("body_b", z.body_b)] {
            if body >= bodies.len() {
                return Err(bad(field(what), "names no body of the system"));
            }
        }
        if z.body_a == z.body_b {
            return Err(bad(
                field("body_b"),
                "a zone is between two different bodies",
            ));
        }
        let f = z.frame;
        if f.origin.iter().any(|v| !v.is_finite()) || !orthonormal(f.e1, f.e2) {
            return Err(bad(
                field("frame"),
                "needs a finite origin and orthonormal axes e1, e2",
            ));
        }
        if !z.clearance.is_finite() {
            return Err(bad(field("clearance"), "must be finite"));
        }
        if z.problem.points().dimension() != Dimension::Surface {
            return Err(bad(
                field("problem"),
                "a system's zone is a surface contact (a line contact has no place in 3D)",
            ));
        }
        if z.problem.folding().is_some() {
            return Err(bad(
                field("problem"),
                "build a system's zone unfolded (ProblemBuilder::fold(false)): its bodies' \
                 motions need not respect the zone's symmetry",
            ));
        }
    }
    Ok(())
}

/// Refuses two zones between the same two bodies, facing the same way,
/// whose candidate zones overlap (their origins nearer than the larger of
/// their half-diagonals): one contact counted twice.
fn overlaps(zones: &[SystemZone]) -> Result<(), AnalysisError> {
    let reach = |z: &SystemZone| {
        let (mut lo, mut hi) = (
            (f64::INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        z.problem.points().positions().for_each(|(x, y)| {
            lo = (lo.0.min(x), lo.1.min(y));
            hi = (hi.0.max(x), hi.1.max(y));
        });
        0.5 * (hi.0 - lo.0).hypot(hi.1 - lo.1)
    };
    let pair = |z: &SystemZone| (z.body_a.min(z.body_b), z.body_a.max(z.body_b));
    for (i, a) in zones.iter().enumerate() {
        for (j, b) in zones.iter().enumerate().skip(i + 1) {
            let d = sub(a.frame.origin, b.frame.origin);
            let facing = dot(a.frame.normal(), b.frame.normal()).abs() > 0.99;
            if pair(a) == pair(b) && facing && dot(d, d).sqrt() < reach(a).max(reach(b)) {
                return Err(AnalysisError::System {
                    field: format!("zones[{j}] ({})", b.name),
                    reason: format!(
                        "overlaps zones[{i}] ({}): both are between the same two bodies, facing \
                         the same way, their candidate points over the same place (one contact \
                         counted twice)",
                        a.name
                    ),
                });
            }
        }
    }
    Ok(())
}

/// Whether `a` and `b` are unit vectors at right angles (to 1e-9).
fn orthonormal(a: [f64; 3], b: [f64; 3]) -> bool {
    let unit = |v: [f64; 3]| (dot(v, v) - 1.0).abs() <= 1e-9;
    unit(a) && unit(b) && dot(a, b).abs() <= 1e-9
}

/// `a x b`.
pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a . b`.
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a - b`.
fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
