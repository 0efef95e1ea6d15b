//! The designed profile as result.json gives it (`design.profile`): what
//! defines it everywhere along its axis, typed: a free profile's knots,
//! their drops and how it is interpolated between and beyond them, or a
//! family's name and coefficients. It reads back into elcon-design's
//! [`Profile`], which evaluates it (Python's `Design.profile`). And
//! profile.csv, the profile sampled along the design grid's extent.

use std::io;

use elcon_design::{DesignError, LogCrown, LogEnd, Profile};
use serde::{Deserialize, Serialize};

/// How a free profile is defined between its knots.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Interpolation {
    /// The natural cubic spline through the knots: continuous slope and
    /// curvature, no curvature at the end knots (a scene's design, which
    /// holds on any grid).
    NaturalCubicSpline,
    /// Straight between the knots (a design made on the points given,
    /// one drop per station: Python's design over problems).
    Linear,
}

impl Interpolation {
    /// Both, in the order messages list them.
    pub const ALL: [Interpolation; 2] = [Interpolation::NaturalCubicSpline, Interpolation::Linear];

    /// Its name: "natural-cubic-spline" or "linear".
    pub const fn name(self) -> &'static str {
        match self {
            Interpolation::NaturalCubicSpline => "natural-cubic-spline",
            Interpolation::Linear => "linear",
        }
    }
}

elcon_num::named!(Interpolation, "interpolation");
elcon_num::named_serde!(Interpolation);

/// How a free profile goes on beyond its end knots.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Beyond {
    /// Straight on along its slopes at the end knots (the natural cubic
    /// spline's).
    EndSlopes,
    /// Flat, at its drops at the end knots (the linear interpolation's).
    EndValues,
}

impl Beyond {
    /// Both, in the order messages list them.
    pub const ALL: [Beyond; 2] = [Beyond::EndSlopes, Beyond::EndValues];

    /// Its name: "end-slopes" or "end-values".
    pub const fn name(self) -> &'static str {
        match self {
            Beyond::EndSlopes => "end-slopes",
            Beyond::EndValues => "end-values",
        }
    }
}

elcon_num::named!(Beyond, "continuation beyond the end knots");
elcon_num::named_serde!(Beyond);

/// How a logarithmic crown ends (elcon-design's [`LogEnd`] by name; the
/// Fujiwara-Kawase end's parameters are the crown's `k1` and `end_drop`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CrownEnd {
    /// Johns & Gohar's finite end drop.
    JohnsGohar,
    /// Lundberg's own profile.
    Lundberg,
    /// Fujiwara & Kawase's three-parameter crown.
    FujiwaraKawase,
}

impl CrownEnd {
    /// Every end, in the order messages list them.
    pub const ALL: [CrownEnd; 3] = [
        CrownEnd::JohnsGohar,
        CrownEnd::Lundberg,
        CrownEnd::FujiwaraKawase,
    ];

    /// Its name, [`LogEnd::name`]'s: "johns-gohar", "lundberg",
    /// "fujiwara-kawase".
    pub const fn name(self) -> &'static str {
        match self {
            CrownEnd::JohnsGohar => "johns-gohar",
            CrownEnd::Lundberg => "lundberg",
            CrownEnd::FujiwaraKawase => "fujiwara-kawase",
        }
    }
}

elcon_num::named!(CrownEnd, "crown end");
elcon_num::named_serde!(CrownEnd);

/// The designed profile `y(s)` as result.json's `design.profile` gives it,
/// s the scene's coordinate along the design's axis, in its length unit:
/// what defines it everywhere (docs/results.md); serialized with its
/// `family` as the tag, read back into elcon-design's [`Profile`] by
/// [`ProfileJson::profile`].
#[serde_with::skip_serializing_none]
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "family", rename_all = "kebab-case")]
pub enum ProfileJson {
    /// A drop at each knot, interpolated between them and continued beyond.
    Free {
        /// How it is interpolated between the knots.
        interpolation: Interpolation,
        /// How it goes on beyond the end knots.
        beyond: Beyond,
        /// The knots, increasing (length).
        knots: Vec<f64>,
        /// The drop at each knot (length).
        drops: Vec<f64>,
    },
    /// `y = a s^2 + b s + c` (the paper's).
    Quadratic {
        /// a (1/length).
        a: f64,
        /// b (dimensionless).
        b: f64,
        /// c (length).
        c: f64,
    },
    /// `y = sum_i coefficients[i] s^i`.
    Polynomial {
        /// c_0, c_1, ..., c_d (c_i in length^(1-i)).
        coefficients: Vec<f64>,
    },
    /// 0 on a flat middle of length l_f, `R - sqrt(R^2 - t^2)` beyond it,
    /// `t = abs(s) - l_f / 2`.
    CircularCrown {
        /// The crown radius R (length).
        radius: f64,
        /// The flat middle's length l_f (length).
        flat_length: f64,
    },
    /// A logarithmic crown (docs/design.md §1, elcon-design's [`LogCrown`]).
    LogarithmicCrown {
        /// How it ends.
        end: CrownEnd,
        /// The design load Q (force).
        design_load: f64,
        /// The roller's effective length l (length).
        length: f64,
        /// The combined modulus E* of roller and raceway (stress).
        combined_modulus: f64,
        /// Their combined transverse radius R (length).
        radius: f64,
        /// The flat middle's length l_f (length).
        flat_length: f64,
        /// Fujiwara & Kawase's load coefficient K1 (their end only).
        k1: Option<f64>,
        /// Fujiwara & Kawase's end drop z_m (length; their end only).
        end_drop: Option<f64>,
    },
}

impl ProfileJson {
    /// Its family, as its `family` tag names it: "free", "quadratic",
    /// "polynomial", "circular-crown" or "logarithmic-crown".
    pub const fn family(&self) -> &'static str {
        match self {
            ProfileJson::Free { .. } => "free",
            ProfileJson::Quadratic { .. } => "quadratic",
            ProfileJson::Polynomial { .. } => "polynomial",
            ProfileJson::CircularCrown { .. } => "circular-crown",
            ProfileJson::LogarithmicCrown { .. } => "logarithmic-crown",
        }
    }

    /// The block of `profile`.
    ///
    /// # Errors
    /// [`DesignError::Incompatible`] naming `profile` for a kind of
    /// profile result.json has no form for.
    pub fn of(profile: &Profile) -> Result<Self, DesignError> {
        Ok(match profile {
            Profile::Spline { positions, drops } => ProfileJson::Free {
                interpolation: Interpolation::NaturalCubicSpline,
                beyond: Beyond::EndSlopes,
                knots: positions.clone(),
                drops: drops.clone(),
            },
            Profile::Free { positions, drops } => ProfileJson::Free {
                interpolation: Interpolation::Linear,
                beyond: Beyond::EndValues,
                knots: positions.clone(),
                drops: drops.clone(),
            },
            Profile::Quadratic { a, b, c } => ProfileJson::Quadratic {
                a: *a,
                b: *b,
                c: *c,
            },
            Profile::Polynomial { coefficients } => ProfileJson::Polynomial {
                coefficients: coefficients.clone(),
            },
            Profile::CircularCrown {
                radius,
                flat_length,
            } => ProfileJson::CircularCrown {
                radius: *radius,
                flat_length: *flat_length,
            },
            Profile::LogarithmicCrown(c) => Self::log_crown(c)?,
            other => {
                return Err(DesignError::Incompatible {
                    field: "profile",
                    reason: format!("a {} profile has no form in result.json", other.family()),
                });
            }
        })
    }

    /// A logarithmic crown's block.
    fn log_crown(c: &LogCrown) -> Result<Self, DesignError> {
        let (end, k1, end_drop) = match c.end {
            LogEnd::JohnsGohar => (CrownEnd::JohnsGohar, None, None),
            LogEnd::Lundberg => (CrownEnd::Lundberg, None, None),
            LogEnd::FujiwaraKawase { k1, end_drop } => {
                (CrownEnd::FujiwaraKawase, Some(k1), Some(end_drop))
            }
            other => {
                return Err(DesignError::Incompatible {
                    field: "profile",
                    reason: format!(
                        "a logarithmic crown's end `{}` has no form in result.json",
                        other.name()
                    ),
                });
            }
        };
        Ok(ProfileJson::LogarithmicCrown {
            end,
            design_load: c.design_load,
            length: c.length,
            combined_modulus: c.combined_modulus,
            radius: c.radius,
            flat_length: c.flat_length,
            k1,
            end_drop,
        })
    }

    /// The profile this block defines, checked ([`Profile::validate`]), to
    /// evaluate (elcon-design's [`Profile::separations`]).
    ///
    /// # Errors
    /// [`DesignError::Incompatible`] naming the field for a free profile's
    /// `beyond` that is not its interpolation's, or a crown end's
    /// parameters given to another end or missing from their own; the
    /// profile's own checks.
    pub fn profile(&self) -> Result<Profile, DesignError> {
        let profile = match self {
            ProfileJson::Free {
                interpolation,
                beyond,
                knots,
                drops,
            } => {
                let (positions, drops) = (knots.clone(), drops.clone());
                match (interpolation, beyond) {
                    (Interpolation::NaturalCubicSpline, Beyond::EndSlopes) => {
                        Profile::Spline { positions, drops }
                    }
                    (Interpolation::Linear, Beyond::EndValues) => {
                        Profile::Free { positions, drops }
                    }
                    _ => {
                        return Err(DesignError::Incompatible {
                            field: "profile.beyond",
                            reason: format!(
                                "\"{beyond}\" with interpolation \"{interpolation}\": a natural \
                                 cubic spline goes on along its end slopes (\"end-slopes\"), a \
                                 linear profile at its end values (\"end-values\")"
                            ),
                        });
                    }
                }
            }
            ProfileJson::Quadratic { a, b, c } => Profile::Quadratic {
                a: *a,
                b: *b,
                c: *c,
            },
            ProfileJson::Polynomial { coefficients } => Profile::Polynomial {
                coefficients: coefficients.clone(),
            },
            ProfileJson::CircularCrown {
                radius,
                flat_length,
            } => Profile::CircularCrown {
                radius: *radius,
                flat_length: *flat_length,
            },
            ProfileJson::LogarithmicCrown {
                end,
                design_load,
                length,
                combined_modulus,
                radius,
                flat_length,
                k1,
                end_drop,
            } => Profile::LogarithmicCrown(LogCrown {
                design_load: *design_load,
                length: *length,
                combined_modulus: *combined_modulus,
                radius: *radius,
                flat_length: *flat_length,
                end: crown_end(*end, *k1, *end_drop)?,
            }),
        };
        profile.validate()?;
        Ok(profile)
    }
}

/// A logarithmic crown's end from its block's `end`, `k1` and `end_drop`:
/// Fujiwara & Kawase's needs both parameters, the others take neither.
fn crown_end(end: CrownEnd, k1: Option<f64>, end_drop: Option<f64>) -> Result<LogEnd, DesignError> {
    match (end, k1, end_drop) {
        (CrownEnd::FujiwaraKawase, Some(k1), Some(end_drop)) => {
            Ok(LogEnd::FujiwaraKawase { k1, end_drop })
        }
        (CrownEnd::FujiwaraKawase, _, _) => Err(DesignError::Incompatible {
            field: "profile.end",
            reason: "\"fujiwara-kawase\" needs its `k1` and `end_drop`".into(),
        }),
        (CrownEnd::JohnsGohar, None, None) => Ok(LogEnd::JohnsGohar),
        (CrownEnd::Lundberg, None, None) => Ok(LogEnd::Lundberg),
        _ => Err(DesignError::Incompatible {
            field: "profile.end",
            reason: format!(
                "\"{end}\" takes no `k1` or `end_drop` (Fujiwara & Kawase's parameters)"
            ),
        }),
    }
}

/// profile.csv: the header `# <axis>_<length>,drop_<length>` (`# y_mm,drop_mm`,
/// a comment, so that the file reads back as a scene's profile)
/// and one row per sample, `(position, drop)`, written row by row.
pub(crate) fn profile_csv(
    axis: &str,
    length: &str,
    rows: &[(f64, f64)],
    w: &mut dyn io::Write,
) -> io::Result<()> {
    writeln!(w, "# {axis}_{length},drop_{length}")?;
    for (s, y) in rows {
        writeln!(w, "{s},{y}")?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every kind of profile reads back from its block as itself.
    #[test]
    fn each_profile_reads_back_from_its_block() {
        let crown = LogCrown {
            design_load: 1e4,
            length: 10.0,
            combined_modulus: 115_384.6,
            radius: 5.0,
            flat_length: 1.0,
            end: LogEnd::FujiwaraKawase {
                k1: 0.97,
                end_drop: 0.0118,
            },
        };
        let profiles = [
            Profile::Spline {
                positions: vec![-1.0, 0.0, 2.0],
                drops: vec![0.5, 0.0, 1.0],
            },
            Profile::Free {
                positions: vec![-1.0, 0.0, 2.0],
                drops: vec![0.5, 0.0, 1.0],
            },
            Profile::Quadratic {
                a: 2.0,
                b: -1.0,
                c: 0.5,
            },
            Profile::Polynomial {
                coefficients: vec![0.5, 0.0, 1e-3, 0.0, 2e-6],
            },
            Profile::CircularCrown {
                radius: 1e3,
                flat_length: 2.0,
            },
            Profile::LogarithmicCrown(crown),
            Profile::LogarithmicCrown(LogCrown {
                end: LogEnd::JohnsGohar,
                ..crown
            }),
            Profile::LogarithmicCrown(LogCrown {
                end: LogEnd::Lundberg,
                ..crown
            }),
        ];
        for p in profiles {
            let block = ProfileJson::of(&p).unwrap();
            let text = serde_json::to_string(&block).unwrap();
            let read: ProfileJson = serde_json::from_str(&text).unwrap();
            assert_eq!(read, block, "{text}");
            let tag = serde_json::to_value(&block).unwrap()["family"].clone();
            assert_eq!(tag, block.family(), "{text}");
            assert_eq!(read.profile().unwrap(), p, "{text}");
        }
    }

    #[test]
    fn a_free_profile_says_how_it_is_interpolated_and_continued() {
        let p = Profile::Spline {
            positions: vec![-1.0, 1.0],
            drops: vec![1.0, 0.0],
        };
        let text = serde_json::to_string(&ProfileJson::of(&p).unwrap()).unwrap();
        assert_eq!(
            text,
            r#"{"family":"free","interpolation":"natural-cubic-spline","beyond":"end-slopes","knots":[-1.0,1.0],"drops":[1.0,0.0]}"#
        );
        let q = ProfileJson::of(&Profile::Quadratic {
            a: 1.0,
            b: 0.0,
            c: 2.0,
        })
        .unwrap();
        assert_eq!(
            serde_json::to_string(&q).unwrap(),
            r#"{"family":"quadratic","a":1.0,"b":0.0,"c":2.0}"#
        );
    }

    #[test]
    fn a_block_that_defines_no_profile_is_refused_by_field() {
        let mismatched = r#"{"family":"free","interpolation":"linear","beyond":"end-slopes","knots":[0.0,1.0],"drops":[0.0,1.0]}"#;
        let e = serde_json::from_str::<ProfileJson>(mismatched)
            .unwrap()
            .profile()
            .unwrap_err();
        assert!(e.to_string().starts_with("`profile.beyond`"), "{e}");
        let crown = r#"{"family":"logarithmic-crown","end":"lundberg","design_load":1e4,"length":10.0,
            "combined_modulus":1e5,"radius":5.0,"flat_length":0.0,"k1":1.0}"#;
        let e = serde_json::from_str::<ProfileJson>(crown)
            .unwrap()
            .profile()
            .unwrap_err();
        assert!(e.to_string().starts_with("`profile.end`"), "{e}");
        let knots = r#"{"family":"free","interpolation":"linear","beyond":"end-values","knots":[1.0,0.0],"drops":[0.0,1.0]}"#;
        let e = serde_json::from_str::<ProfileJson>(knots)
            .unwrap()
            .profile()
            .unwrap_err();
        assert!(e.to_string().contains("strictly increasing"), "{e}");
    }

    #[test]
    fn profile_csv_names_its_columns_with_their_unit() {
        let mut out = Vec::new();
        profile_csv("y", "mm", &[(-5.0, 0.01), (0.0, 0.0)], &mut out).unwrap();
        assert_eq!(
            String::from_utf8(out).unwrap(),
            "# y_mm,drop_mm\n-5,0.01\n0,0\n"
        );
    }
}
