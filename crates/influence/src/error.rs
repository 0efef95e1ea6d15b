//! The crate's one error type: every way a material, a point set or a body
//! can be rejected, each message naming the field, the value and the reason;
//! and the fallible allocation ([`try_vec`]) whose failure is one of them.
//!
//! No equation here; the checks enforce the ranges under which the influence
//! coefficients a_kj of the other modules are defined (E > 0, -1 < nu < 0.5,
//! finite positive sizes, d0 at least the extent of the zone).

use elcon_num::Num;

use crate::dimension::Dimension;

/// Everything that can stop the construction of a material, a point set or
/// an influence matrix.
///
/// Every variant names what the caller has to change; the messages state the
/// field, the value given and the admissible range.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InfluenceError {
    /// A material constant is out of its physical range.
    #[error("invalid material: {field} = {}: {reason}", Num(*value))]
    InvalidMaterial {
        /// The constant: `youngs_modulus` or `poissons_ratio`.
        field: &'static str,
        /// The value given.
        value: f64,
        /// Why it is rejected (the admissible range).
        reason: &'static str,
    },
    /// A parameter of a point-set constructor is out of range (a size, a
    /// count, a coordinate, a cell).
    #[error("invalid point set: {field} = {value}: {reason}")]
    InvalidPoints {
        /// The parameter, e.g. `spacing`, `n`, `xs[3]`.
        field: String,
        /// The value given, printed (a number in its shortest form, as
        /// [`Num`] shows it).
        value: String,
        /// Why it is rejected.
        reason: String,
    },
    /// The parameters describe a point set with no point in it.
    #[error("empty point set: {reason}")]
    EmptyPointSet {
        /// Which input is empty and what to give instead.
        reason: String,
    },
    /// A model was used on a point set of the wrong dimension.
    #[error("the {model} model does not apply to a {dimension} point set: {hint}")]
    DimensionMismatch {
        /// The model's name.
        model: &'static str,
        /// The dimension of the point set it was applied to.
        dimension: Dimension,
        /// Which model or point set to use instead.
        hint: &'static str,
    },
    /// A parameter of an influence model is out of range (Winkler modulus,
    /// plane-strain reference distance, beam rigidity or loaded point).
    #[error("invalid {model} parameter: {field} = {}: {reason}", Num(*value))]
    InvalidModel {
        /// The model's name.
        model: &'static str,
        /// The parameter.
        field: &'static str,
        /// The value given.
        value: f64,
        /// Why it is rejected (the admissible range).
        reason: String,
    },
    /// Every body given to [`assemble`](crate::assemble) is rigid (or none
    /// was given): there is no elasticity, the influence matrix would be zero.
    #[error(
        "no elastic body among the {bodies} bodies given (a rigid body contributes nothing): \
         the influence matrix S would be zero; give at least one body an elastic model"
    )]
    AllRigid {
        /// The number of bodies given.
        bodies: usize,
    },
    /// The lattice operator ([`LatticeOperator`](crate::LatticeOperator))
    /// was given points it cannot convolve over: a set without a lattice, a
    /// lattice much sparser than its bounding box, or two points on one
    /// lattice cell.
    #[error(
        "the lattice operator needs the points on a compact lattice: {reason}; \
         assemble the dense S instead (assemble), or use a grid constructor \
         (PointSet::grid_disk, grid_rectangle, line)"
    )]
    LatticeRequired {
        /// What is wrong with the point set, with its figures.
        reason: String,
    },
    /// A body's influence model is not a translation-invariant kernel (its
    /// coefficients depend on where the points are, not only on their
    /// offset), so the lattice operator, a convolution, cannot apply it.
    #[error(
        "the {model} model is not translation invariant (its coefficients depend on the \
         points' positions, not only on their offset): the lattice operator cannot apply it; \
         assemble the dense S instead (assemble)"
    )]
    NotTranslationInvariant {
        /// The model's name.
        model: &'static str,
    },
    /// A buffer of the given size could not be allocated (the memory is
    /// exhausted, or the size overflows).
    #[error(
        "could not allocate {bytes} bytes for the {what}: not enough memory; \
         use a coarser grid or free memory"
    )]
    AllocationFailed {
        /// What the buffer was for.
        what: &'static str,
        /// The size asked for (saturated at usize::MAX on overflow).
        bytes: usize,
    },
    /// The computation was cancelled (SIGINT, SIGTERM, Ctrl-C) before it
    /// ended: nothing of it is kept.
    #[error("cancelled (an interrupt) before the {what} were computed")]
    Cancelled {
        /// What was being computed.
        what: &'static str,
    },
}

impl InfluenceError {
    /// An [`InfluenceError::InvalidPoints`] from displayable parts.
    pub(crate) fn points(
        field: impl Into<String>,
        value: impl std::fmt::Display,
        reason: impl Into<String>,
    ) -> Self {
        Self::InvalidPoints {
            field: field.into(),
            value: value.to_string(),
            reason: reason.into(),
        }
    }
}

/// A vector of `len` copies of `value`, or [`InfluenceError::AllocationFailed`]
/// naming `what` when the memory cannot be reserved.
pub(crate) fn try_vec<T: Clone>(
    len: usize,
    value: T,
    what: &'static str,
) -> Result<Vec<T>, InfluenceError> {
    let mut v = Vec::new();
    v.try_reserve_exact(len)
        .map_err(|_| InfluenceError::AllocationFailed {
            what,
            bytes: len.saturating_mul(std::mem::size_of::<T>()),
        })?;
    v.resize(len, value);
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Body, Cell, Material, PointSet, assemble};

    #[test]
    fn invalid_material_names_field_and_range() {
        let e = Material::new(30e6, 0.5).unwrap_err();
        assert!(matches!(
            e,
            InfluenceError::InvalidMaterial {
                field: "poissons_ratio",
                ..
            }
        ));
        assert_eq!(
            e.to_string(),
            "invalid material: poissons_ratio = 0.5: must be in (-1, 0.5)"
        );
        let e = Material::new(-1.0, 0.3).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid material: youngs_modulus = -1: must be positive"
        );
        // Tiny and huge values in their shortest form, never hundreds of digits.
        let e = Material::new(-1e-300, 0.3).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid material: youngs_modulus = -1e-300: must be positive"
        );
        let e = Material::new(30e6, -1e300).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid material: poissons_ratio = -1e300: must be in (-1, 0.5)"
        );
    }

    #[test]
    fn invalid_points_names_parameter() {
        let e = PointSet::grid_disk(0.0, 1.0).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid point set: spacing = 0: must be positive"
        );
        let e = PointSet::line(0.0, 1.0, 0).unwrap_err();
        assert!(
            e.to_string().starts_with("invalid point set: n = 0:"),
            "{e}"
        );
        let e = PointSet::grid_disk(-1e-300, 1.0).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid point set: spacing = -1e-300: must be positive"
        );
        let e = PointSet::line(1e-300, -1e-300, 3).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid point set: end = -1e-300: must exceed start = 1e-300"
        );
        let e = PointSet::grid_disk(1e-300, 1e300).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("invalid point set: radius / spacing = inf:"),
            "{e}"
        );
        let e = PointSet::grid_disk(1.0, 1e300).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("invalid point set: radius / spacing = 1e300:"),
            "{e}"
        );
    }

    #[test]
    fn empty_point_set_says_which_input() {
        let e = PointSet::from_points(
            crate::Dimension::Surface,
            vec![],
            vec![],
            Cell { dx: 1.0, dy: 1.0 },
        )
        .unwrap_err();
        assert!(matches!(e, InfluenceError::EmptyPointSet { .. }));
        assert!(
            e.to_string().starts_with("empty point set: xs and ys"),
            "{e}"
        );
    }

    #[test]
    fn dimension_mismatch_names_model_and_dimension() {
        let steel = Material::new(30e6, 0.3).unwrap();
        let line = PointSet::line(-1.0, 1.0, 5).unwrap();
        let e = assemble(&line, &[&Body::uniform_patch(steel)]).unwrap_err();
        assert!(
            e.to_string().starts_with(
                "the uniform-patch (Love) model does not apply to a line (2D) point set"
            ),
            "{e}"
        );
        let disk = PointSet::grid_disk(0.1, 0.3).unwrap();
        let e = assemble(&disk, &[&Body::plane_strain(steel, 10.0)]).unwrap_err();
        assert!(
            e.to_string().starts_with(
                "the plane-strain strip model does not apply to a surface (3D) point set"
            ),
            "{e}"
        );
    }

    #[test]
    fn invalid_model_names_parameter() {
        let line = PointSet::line(-1.0, 1.0, 5).unwrap();
        let e = assemble(&line, &[&Body::winkler(f64::NAN)]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid Winkler foundation parameter: modulus = NaN: must be finite"
        );
        let e = assemble(&line, &[&Body::winkler(-1e-300)]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid Winkler foundation parameter: modulus = -1e-300: must be positive"
        );
        let steel = Material::new(30e6, 0.3).unwrap();
        let e = assemble(&line, &[&Body::plane_strain(steel, 1.5)]).unwrap_err();
        assert!(
            e.to_string().starts_with(
                "invalid plane-strain strip parameter: reference_distance = 1.5: \
                 must be at least the extent of the point set (2)"
            ),
            "{e}"
        );
    }

    #[test]
    fn all_rigid_counts_bodies() {
        let line = PointSet::line(-1.0, 1.0, 5).unwrap();
        let rigid = Body::rigid();
        let e = assemble(&line, &[&rigid, &rigid]).unwrap_err();
        assert_eq!(e, InfluenceError::AllRigid { bodies: 2 });
        assert!(
            e.to_string()
                .starts_with("no elastic body among the 2 bodies given"),
            "{e}"
        );
    }
}
