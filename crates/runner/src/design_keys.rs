//! A design's failure in its user's words: elcon-design names a parameter
//! by its own name (`circular_crown.radius`); a scene's user wrote a key
//! (`design.radius_range`), a Python caller of `design` over problems an
//! argument (`roller.radius`). One map per caller, here, for the scene's
//! design stage and the Python package alike.

use elcon_design::DesignError;
use elcon_num::Num;

/// Who asked for the design, and so which words name its parameters.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DesignCaller {
    /// A scene's `[design]` (its keys).
    Scene,
    /// Python's `design` over problems (its arguments), the logarithmic
    /// crown's roller given by the call or derived from the problems.
    Problems {
        /// Whether the call gave the roller (`roller={...}`).
        roller_given: bool,
    },
}

/// The key a user wrote for a parameter elcon-design names by its own
/// name (`circular_crown.radius`), as a failure's message shows it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct DesignKey {
    /// The key (`design.radius_range`).
    key: &'static str,
    /// What the value is, when it is not the key's own but one derived from
    /// it (`a crown radius searched in it`).
    what: Option<&'static str>,
}

impl DesignKey {
    /// The key `key`, whose value is `what` when given.
    const fn new(key: &'static str, what: Option<&'static str>) -> Self {
        Self { key, what }
    }
}

/// What a scene's user wrote for a parameter elcon-design names by its
/// own name: the scene's key, and, when the value is not that key's own
/// but one derived from it, what the value is. `None` for a name the
/// scene has no key for.
fn scene_design_key(field: &str) -> Option<DesignKey> {
    let key = DesignKey::new;
    Some(match field {
        "circular_crown.radius" => {
            key("design.radius_range", Some("a crown radius searched in it"))
        }
        "circular_crown.flat_length" | "log_crown.flat_length" => key("design.flat_length", None),
        "log_crown.design_load" => key(
            "design.design_load",
            Some("the design load, by default the largest of design.loads"),
        ),
        "log_crown.length" => key("points.half_y", Some("the roller's length, twice it")),
        "log_crown.radius" => key("geometry", Some("the roller's radius, from its surfaces")),
        "log_crown.combined_modulus" => key(
            "body1, body2",
            Some("the roller's combined modulus, from the bodies' materials"),
        ),
        "family.degree" => key("design.degree", None),
        "max_constant" => key("design.max_constant", None),
        "grid_tolerance" => key("design.grid_tolerance", None),
        "profile_spacing" => key("design.profile_spacing", None),
        "cases" => key(
            "design.loads",
            Some("the load cases, each load at each misalignment"),
        ),
        "reference_intensities" => key("design.relative_to", Some("the reference intensities")),
        "reanalysis" => key("solver.method", Some("the method of the analyses")),
        _ => return None,
    })
}

/// What a caller of `design` over problems wrote for a parameter
/// elcon-design names by its own name: the call's arguments where they
/// differ from a scene's keys (the problems are the cases, the roller
/// given by the call), else the scene's key.
fn problems_design_key(field: &str, roller_given: bool) -> Option<DesignKey> {
    let key = DesignKey::new;
    match field {
        "cases" => Some(key("problems", Some("the load cases, one per problem"))),
        "reference_intensities" => Some(key("reference_intensities", None)),
        "reanalysis" => Some(key(
            "problems",
            Some("the method of the analyses, the first problem's default"),
        )),
        "log_crown.length" if roller_given => Some(key("roller.length", None)),
        "log_crown.radius" if roller_given => Some(key("roller.radius", None)),
        "log_crown.combined_modulus" if roller_given => Some(key("roller.combined_modulus", None)),
        _ => scene_design_key(field),
    }
}

/// A design's failure as its user reads it: a parameter elcon-design
/// names by its own name (`circular_crown.radius`) is named by the key
/// the `caller` wrote for it, its value in the shortest form ([`Num`]);
/// the other failures as elcon-design says them. The scene's design stage
/// and the Python package both say a design's failure through it.
pub fn design_reason(e: &DesignError, caller: DesignCaller) -> String {
    let key_of = |field: &str| match caller {
        DesignCaller::Scene => scene_design_key(field),
        DesignCaller::Problems { roller_given } => problems_design_key(field, roller_given),
    };
    let named = |field: &str, rest: String| match key_of(field) {
        Some(DesignKey { key, what: None }) => format!("`{key}`{rest}"),
        Some(DesignKey {
            key,
            what: Some(what),
        }) => format!("`{key}` ({what}){rest}"),
        None => format!("`{field}`{rest}"),
    };
    match e {
        DesignError::InvalidInput {
            field,
            value,
            reason,
        } => named(field, format!(" = {}: {reason}", Num(*value))),
        DesignError::Incompatible { field, reason } => named(field, format!(": {reason}")),
        _ => e.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_caller_reads_a_parameter_in_its_own_words() {
        let radius = DesignError::InvalidInput {
            field: "log_crown.radius",
            value: -1.0,
            reason: "must be > 0",
        };
        let scene = design_reason(&radius, DesignCaller::Scene);
        assert!(
            scene.starts_with("`geometry` (the roller's radius"),
            "{scene}"
        );
        let given = design_reason(&radius, DesignCaller::Problems { roller_given: true });
        assert_eq!(given, "`roller.radius` = -1: must be > 0");
        let derived = design_reason(
            &radius,
            DesignCaller::Problems {
                roller_given: false,
            },
        );
        assert_eq!(derived, scene);
        let cases = DesignError::Incompatible {
            field: "cases",
            reason: "none given".into(),
        };
        assert!(design_reason(&cases, DesignCaller::Scene).starts_with("`design.loads`"));
        assert!(
            design_reason(
                &cases,
                DesignCaller::Problems {
                    roller_given: false
                }
            )
            .starts_with("`problems` (the load cases, one per problem)")
        );
        let unnamed = DesignError::Incompatible {
            field: "unheard_of",
            reason: "no".into(),
        };
        assert_eq!(
            design_reason(&unnamed, DesignCaller::Scene),
            "`unheard_of`: no"
        );
    }
}
