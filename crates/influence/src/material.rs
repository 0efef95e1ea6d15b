//! Isotropic linear elastic materials and the combined modulus of two bodies.
//!
//! A half-space of Young's modulus E and Poisson's ratio nu deflects under a
//! normal load in proportion to its compliance `(1 - nu^2) / E` (the inverse
//! of the plane-strain modulus `E' = E / (1 - nu^2)`). Two half-spaces in
//! contact add their compliances:
//!
//! ```text
//!     1 / E* = (1 - nu1^2) / E1 + (1 - nu2^2) / E2
//! ```
//!
//! the combined modulus E* of the Hertz formulas (a rigid body contributes 0).

use crate::error::InfluenceError;

/// An isotropic linear elastic material: Young's modulus E and Poisson's
/// ratio nu, validated (finite, E > 0, -1 < nu < 0.5).
///
/// Units: E in any stress unit (psi, Pa, ...); every influence coefficient
/// computed from it is then in length per force of the same unit system.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    youngs_modulus: f64,
    poissons_ratio: f64,
}

impl Material {
    /// A material of Young's modulus `youngs_modulus` (E, stress) and
    /// Poisson's ratio `poissons_ratio` (nu).
    ///
    /// # Errors
    /// [`InfluenceError::InvalidMaterial`] when E is not finite or not
    /// positive, or nu is not finite or not strictly inside (-1, 0.5)
    /// (nu = 0.5, incompressible, is excluded: its compliance would still be
    /// finite, but the bounds keep the constitutive law invertible).
    pub fn new(youngs_modulus: f64, poissons_ratio: f64) -> Result<Self, InfluenceError> {
        let bad = |field, value, reason| InfluenceError::InvalidMaterial {
            field,
            value,
            reason,
        };
        if !youngs_modulus.is_finite() {
            return Err(bad("youngs_modulus", youngs_modulus, "must be finite"));
        }
        if youngs_modulus <= 0.0 {
            return Err(bad("youngs_modulus", youngs_modulus, "must be positive"));
        }
        if !poissons_ratio.is_finite() {
            return Err(bad("poissons_ratio", poissons_ratio, "must be finite"));
        }
        if !(poissons_ratio > -1.0 && poissons_ratio < 0.5) {
            return Err(bad(
                "poissons_ratio",
                poissons_ratio,
                "must be in (-1, 0.5)",
            ));
        }
        Ok(Self {
            youngs_modulus,
            poissons_ratio,
        })
    }

    /// Young's modulus E (stress).
    pub fn youngs_modulus(&self) -> f64 {
        self.youngs_modulus
    }

    /// Poisson's ratio nu (dimensionless).
    pub fn poissons_ratio(&self) -> f64 {
        self.poissons_ratio
    }

    /// The half-space compliance `(1 - nu^2) / E` = 1/E' (inverse stress).
    pub fn compliance(&self) -> f64 {
        (1.0 - self.poissons_ratio * self.poissons_ratio) / self.youngs_modulus
    }

    /// The plane-strain modulus `E' = E / (1 - nu^2)` (stress).
    pub fn plane_strain_modulus(&self) -> f64 {
        self.youngs_modulus / (1.0 - self.poissons_ratio * self.poissons_ratio)
    }
}

/// The combined modulus E* of two elastic bodies,
/// `1 / E* = (1 - nu1^2) / E1 + (1 - nu2^2) / E2` (stress).
///
/// For a rigid partner use [`combined_modulus_of`].
pub fn combined_modulus(a: &Material, b: &Material) -> f64 {
    1.0 / (a.compliance() + b.compliance())
}

/// The combined modulus E* of two bodies of which either may be rigid
/// (`None`): a rigid body contributes zero compliance, so
/// `combined_modulus_of(Some(&m), None) == m.plane_strain_modulus()`.
///
/// Two rigid bodies give `f64::INFINITY` (zero compliance).
pub fn combined_modulus_of(a: Option<&Material>, b: Option<&Material>) -> f64 {
    let compliance = a.map_or(0.0, Material::compliance) + b.map_or(0.0, Material::compliance);
    1.0 / compliance
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn getters_and_derived_moduli() {
        let m = Material::new(200e9, 0.3).unwrap();
        assert_eq!(m.youngs_modulus(), 200e9);
        assert_eq!(m.poissons_ratio(), 0.3);
        // (1 - 0.09) / 200e9, to rounding.
        assert!((m.compliance() / (0.91 / 200e9) - 1.0).abs() < 1e-15);
        assert!((m.plane_strain_modulus() * m.compliance() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn rejects_every_out_of_range_constant() {
        for (e, nu, field) in [
            (f64::NAN, 0.3, "youngs_modulus"),
            (f64::INFINITY, 0.3, "youngs_modulus"),
            (0.0, 0.3, "youngs_modulus"),
            (-5.0, 0.3, "youngs_modulus"),
            (1.0, f64::NAN, "poissons_ratio"),
            (1.0, 0.5, "poissons_ratio"),
            (1.0, -1.0, "poissons_ratio"),
            (1.0, 0.7, "poissons_ratio"),
        ] {
            match Material::new(e, nu) {
                Err(InfluenceError::InvalidMaterial { field: f, .. }) => assert_eq!(f, field),
                other => panic!("({e}, {nu}) gave {other:?}"),
            }
        }
        // The open interval's inside is accepted, including auxetic materials.
        assert!(Material::new(1.0, -0.99).is_ok());
        assert!(Material::new(1.0, 0.4999).is_ok());
    }

    #[test]
    fn combined_modulus_of_two_steels_is_half_the_plane_strain_modulus() {
        let steel = Material::new(30e6, 0.3).unwrap();
        let e_star = combined_modulus(&steel, &steel);
        // E / (2 (1 - nu^2)) = 30e6 / 1.82 (the peers' ESTAR).
        assert!((e_star / (30e6 / 1.82) - 1.0).abs() < 1e-15);
        assert_eq!(combined_modulus_of(Some(&steel), Some(&steel)), e_star);
    }

    #[test]
    fn rigid_partner_contributes_no_compliance() {
        let m = Material::new(10e6, 0.33).unwrap();
        assert_eq!(combined_modulus_of(Some(&m), None), 1.0 / m.compliance());
        assert_eq!(combined_modulus_of(None, Some(&m)), 1.0 / m.compliance());
        assert_eq!(combined_modulus_of(None, None), f64::INFINITY);
    }
}
