//! Influence models and bodies: how one body deflects under unit forces at
//! the candidate points, `a_kj` = deflection at k due to a unit force at j.
//!
//! | model | a_kj | dimension |
//! |---|---|---|
//! | [`Model::PointForce`] (Boussinesq, the paper's) | `(1 - nu^2) / (pi E d_kj)`; self-term: centre deflection of the own cell under a uniform pressure of unit resultant, `(1 - nu^2)/(pi E) * love_rectangle(0, 0, dx, dy)` | surface |
//! | [`Model::UniformPatch`] (Love 1929) | `(1 - nu^2)/(pi E) * love_rectangle(x_k - x_j, y_k - y_j, dx, dy)` | surface |
//! | [`Model::PlaneStrainStrip`] | `2 (1 - nu^2)/(pi E) * plane_strain_strip(x_k - x_j, dx, d0)` | line |
//! | [`Model::Winkler`] | `delta_kj / (k A_k)` | both |
//! | [`Model::Beam`] (Euler-Bernoulli, the paper's Example 2) | `a^2 (3 b - a) / (6 E I)`, a, b the smaller and larger distance of k and j from the loaded point x0, on the same side of it; 0 across it | line |
//! | [`Model::Rigid`] | 0 | both |
//!
//! (kernels in [`crate::kernels`]). Units: with E in force/length^2 and
//! lengths in length, every a_kj is in length/force (Surface) or
//! length/(force per unit width) (Line); the Winkler modulus k is in
//! force/length^3 (Surface: pressure per deflection) or force/length^2
//! (Line: force per unit length per deflection, e.g. k_foundation * width).
//!
//! The beam is referenced at its loaded point x0 with its rotation there
//! held, as in Conry & Seireg's Example 2: each side of x0 is a cantilever
//! clamped at x0, and the approach alpha is the displacement of x0. Its
//! deflections are relative to the loaded point, so a point at x0 itself
//! does not deflect (the beam alone is then only positive semidefinite; a
//! foundation under it makes S positive definite). On a beam the forces are
//! forces (the beam's width is inside E I and k), and F_k / A_k is a load
//! intensity per unit length.

use crate::error::InfluenceError;
use crate::material::Material;

/// How a body deflects: the influence model, with its material and
/// parameters. New models (an Euler-Bernoulli beam) may be added, hence
/// `#[non_exhaustive]`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Model {
    /// A rigid body: contributes nothing to S.
    Rigid,
    /// Boussinesq point forces on an elastic half-space, `a_kj = (1 - nu^2) /
    /// (pi E d_kj)`, with the uniform-patch centre value as self-term
    /// (Surface only).
    PointForce {
        /// The half-space's material.
        material: Material,
    },
    /// Uniform pressure over each point's rectangular cell on an elastic
    /// half-space, deflection taken at the cell centres (Love 1929; Surface
    /// only).
    UniformPatch {
        /// The half-space's material.
        material: Material,
    },
    /// Plane-strain (2D) half-space loaded by uniform pressure on each
    /// point's strip, displacements relative to a datum at distance
    /// `reference_distance` (Line only).
    PlaneStrainStrip {
        /// The half-space's material.
        material: Material,
        /// The datum distance d0 (length) at which the 2D displacement is
        /// taken as zero; must be at least the extent of the point set.
        reference_distance: f64,
    },
    /// A Winkler foundation: each point deflects by its own pressure over
    /// `modulus`, independently of the others (either dimension).
    Winkler {
        /// The foundation modulus k: pressure per unit deflection
        /// (force/length^3) on a surface, force per unit length per unit
        /// deflection (force/length^2) on a line.
        modulus: f64,
    },
    /// An Euler-Bernoulli beam along x of flexural rigidity E I, deflections
    /// referenced at its loaded point `loaded_point` (x0) with its rotation
    /// there held: each side is a cantilever clamped at x0 (Line only).
    Beam {
        /// The flexural rigidity E I (force length^2).
        flexural_rigidity: f64,
        /// The x coordinate x0 of the loaded point (length).
        loaded_point: f64,
    },
}

impl Model {
    /// A short name for messages ("uniform-patch (Love)", ...).
    pub fn name(&self) -> &'static str {
        match self {
            Self::Rigid => "rigid",
            Self::PointForce { .. } => "point-force (Boussinesq)",
            Self::UniformPatch { .. } => "uniform-patch (Love)",
            Self::PlaneStrainStrip { .. } => "plane-strain strip",
            Self::Winkler { .. } => "Winkler foundation",
            Self::Beam { .. } => BEAM,
        }
    }

    /// The elastic material, for the half-space models.
    pub fn material(&self) -> Option<&Material> {
        match self {
            Self::PointForce { material }
            | Self::UniformPatch { material }
            | Self::PlaneStrainStrip { material, .. } => Some(material),
            Self::Rigid | Self::Winkler { .. } | Self::Beam { .. } => None,
        }
    }
}

/// The beam model's name ([`Model::name`]).
const BEAM: &str = "Euler-Bernoulli beam";

/// The parameters of an Euler-Bernoulli beam along x, for [`Body::beam`]
/// (the paper's Example 2): its flexural rigidity is `E I`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Beam {
    /// Young's modulus E (stress: force/length^2).
    pub youngs_modulus: f64,
    /// The second moment of area I of the section (length^4); for a
    /// rectangular section of width w and depth d, `I = w d^3 / 12`.
    pub second_moment: f64,
    /// The x coordinate x0 of the loaded point (length): the deflections
    /// are referenced there, with the beam's rotation held.
    pub loaded_point: f64,
}

/// `value` if finite and positive, else an [`InfluenceError::InvalidModel`]
/// naming the parameter `field` of `model` and why.
pub(crate) fn positive(
    model: &'static str,
    field: &'static str,
    value: f64,
) -> Result<f64, InfluenceError> {
    let bad = |reason: &str| InfluenceError::InvalidModel {
        model,
        field,
        value,
        reason: reason.into(),
    };
    if !value.is_finite() {
        Err(bad("must be finite"))
    } else if value <= 0.0 {
        Err(bad("must be positive"))
    } else {
        Ok(value)
    }
}

/// One of the bodies in contact: its influence model (with material).
///
/// Two bodies add: `S = A(1) + A(2)` ([`assemble`](crate::assemble)). The
/// constructors do not validate the model parameters against a point set
/// (nor, but for [`Body::beam`], at all); [`assemble`](crate::assemble) and
/// [`influence`](crate::influence) do.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    model: Model,
}

impl Body {
    /// A body of the given model.
    pub fn new(model: Model) -> Self {
        Self { model }
    }

    /// A rigid body (no deflection).
    pub fn rigid() -> Self {
        Self::new(Model::Rigid)
    }

    /// An elastic half-space with Boussinesq point-force coefficients (the
    /// paper's model; Surface only).
    pub fn point_force(material: Material) -> Self {
        Self::new(Model::PointForce { material })
    }

    /// An elastic half-space with uniform pressure on each rectangular cell
    /// (Love; Surface only).
    pub fn uniform_patch(material: Material) -> Self {
        Self::new(Model::UniformPatch { material })
    }

    /// An elastic plane-strain half-space with uniform pressure on each strip,
    /// displacements relative to a datum at `reference_distance` d0 (Line only).
    pub fn plane_strain(material: Material, reference_distance: f64) -> Self {
        Self::new(Model::PlaneStrainStrip {
            material,
            reference_distance,
        })
    }

    /// A Winkler foundation of modulus k (see [`Model::Winkler`] for units).
    pub fn winkler(modulus: f64) -> Self {
        Self::new(Model::Winkler { modulus })
    }

    /// An Euler-Bernoulli beam of Young's modulus E and second moment of
    /// area I ([`Beam`]), deflections referenced at its loaded point x0 with
    /// its rotation there held (Line only): [`Model::Beam`] of flexural
    /// rigidity `E I`.
    ///
    /// ```
    /// use elcon_influence::{Beam, Body, Model};
    ///
    /// // Conry & Seireg's Example 2: a steel beam of square section, 4 in deep.
    /// let second_moment = 4f64.powi(4) / 12.0; // in^4
    /// let beam = Body::beam(Beam {
    ///     youngs_modulus: 30e6, // psi
    ///     second_moment,
    ///     loaded_point: 0.0, // in
    /// })
    /// .unwrap();
    /// assert_eq!(
    ///     *beam.model(),
    ///     Model::Beam {
    ///         flexural_rigidity: 30e6 * second_moment,
    ///         loaded_point: 0.0
    ///     }
    /// );
    /// ```
    ///
    /// # Errors
    /// [`InfluenceError::InvalidModel`] naming the parameter and why: E
    /// (`youngs_modulus`) or I (`second_moment`) not finite and positive,
    /// each on its own (a negative E and a negative I do not make a beam);
    /// their product E I (`flexural_rigidity`) overflowing or underflowing
    /// to 0; x0 (`loaded_point`) not finite.
    pub fn beam(beam: Beam) -> Result<Self, InfluenceError> {
        let e = positive(BEAM, "youngs_modulus", beam.youngs_modulus)?;
        let i = positive(BEAM, "second_moment", beam.second_moment)?;
        let flexural_rigidity = e * i;
        if !(flexural_rigidity.is_finite() && flexural_rigidity > 0.0) {
            return Err(InfluenceError::InvalidModel {
                model: BEAM,
                field: "flexural_rigidity",
                value: flexural_rigidity,
                reason: "E I must be finite and positive: the product of youngs_modulus and \
                         second_moment overflows or underflows"
                    .into(),
            });
        }
        if !beam.loaded_point.is_finite() {
            return Err(InfluenceError::InvalidModel {
                model: BEAM,
                field: "loaded_point",
                value: beam.loaded_point,
                reason: "must be finite".into(),
            });
        }
        Ok(Self::new(Model::Beam {
            flexural_rigidity,
            loaded_point: beam.loaded_point,
        }))
    }

    /// The body's model.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The elastic material, for the half-space models.
    pub fn material(&self) -> Option<&Material> {
        self.model.material()
    }

    /// Whether the body is rigid (contributes nothing to S).
    pub fn is_rigid(&self) -> bool {
        matches!(self.model, Model::Rigid)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constructors_hold_their_model() {
        let m = Material::new(2.0, 0.25).unwrap();
        assert!(Body::rigid().is_rigid());
        assert!(!Body::winkler(1.0).is_rigid());
        assert_eq!(Body::point_force(m).material(), Some(&m));
        assert_eq!(
            Body::uniform_patch(m).model().name(),
            "uniform-patch (Love)"
        );
        assert_eq!(
            *Body::plane_strain(m, 3.0).model(),
            Model::PlaneStrainStrip {
                material: m,
                reference_distance: 3.0
            }
        );
        assert_eq!(Body::winkler(5.0).material(), None);
        assert_eq!(
            *Body::beam(Beam {
                youngs_modulus: 30e6,
                second_moment: 4.0,
                loaded_point: 0.5
            })
            .unwrap()
            .model(),
            Model::Beam {
                flexural_rigidity: 120e6,
                loaded_point: 0.5
            }
        );
        assert_eq!(Body::rigid().material(), None);
    }

    /// The field and reason of a refused beam.
    fn refusal(
        youngs_modulus: f64,
        second_moment: f64,
        loaded_point: f64,
    ) -> (&'static str, String) {
        let beam = Beam {
            youngs_modulus,
            second_moment,
            loaded_point,
        };
        match Body::beam(beam) {
            Err(InfluenceError::InvalidModel {
                model: "Euler-Bernoulli beam",
                field,
                reason,
                ..
            }) => (field, reason),
            other => panic!("{beam:?}: expected an InvalidModel error, got {other:?}"),
        }
    }

    #[test]
    fn a_beam_refuses_each_parameter_by_name() {
        for e in [0.0, -30e6, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(refusal(e, 64.0 / 12.0, 0.0).0, "youngs_modulus", "E = {e}");
        }
        for i in [0.0, -64.0 / 12.0, f64::NAN, f64::INFINITY] {
            assert_eq!(refusal(30e6, i, 0.0).0, "second_moment", "I = {i}");
        }
        // A negative E and a negative I: E I > 0, but no beam; E is named.
        let e = Body::beam(Beam {
            youngs_modulus: -30e6,
            second_moment: -64.0 / 12.0,
            loaded_point: 0.0,
        })
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid Euler-Bernoulli beam parameter: youngs_modulus = -30000000: must be positive"
        );
        assert_eq!(
            refusal(30e6, f64::NAN, 0.0).1,
            "must be finite",
            "the reason, apart from the field"
        );
        assert_eq!(refusal(30e6, -1.0, 0.0).1, "must be positive");
        // Each finite and positive, their product not.
        assert_eq!(refusal(1e200, 1e200, 0.0).0, "flexural_rigidity");
        assert_eq!(refusal(1e-200, 1e-200, 0.0).0, "flexural_rigidity");
        for x0 in [f64::NAN, f64::INFINITY] {
            let (field, reason) = refusal(30e6, 1.0, x0);
            assert_eq!((field, reason.as_str()), ("loaded_point", "must be finite"));
        }
    }
}
