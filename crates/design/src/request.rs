//! A design as asked for, whoever asks (a scene, Python, a Rust caller):
//! the family with its own parameters, the axis along which the profile
//! runs, how a linear family's min-max problem is solved, and how each
//! load case's worst intensity is measured. [`DesignRequest::run`] is the
//! one dispatch over the families:
//!
//! | family | how the correction is found |
//! |---|---|
//! | [`Family`] (quadratic, polynomial, free) | designed: the min-max problem `min_theta max_l max_k F_lk(theta) / (r_l A_k)` ([`design`]) |
//! | [`DesignFamily::CircularCrown`] | searched: the crown radius of least worst `p_max_l / r_l` ([`crown_search`]) |
//! | [`DesignFamily::LogarithmicCrown`] | set: Johns & Gohar's (or Lundberg's) crown for the design load, from the roller's Hertz line contact |
//!
//! Every outcome is re-analysed under every case with elcon-analysis and
//! certified.

use elcon_analysis::{ContactProblem, Method, Options};

use crate::crown::{SearchOptions, crown_search};
use crate::evaluate::{Analysis, Evaluation, evaluate};
use crate::optimize::{StartOutcome, design};
use crate::{
    Axis, DesignError, DesignMethod, DesignOptions, Family, LogCrown, LogEnd, Objective, Profile,
};
use elcon_influence::Body;

/// The roller a logarithmic crown is set for: its Hertz line contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Roller {
    /// The combined modulus E* of the two bodies (stress).
    pub combined_modulus: f64,
    /// The roller's radius, combined with its race's (length).
    pub radius: f64,
    /// The roller's effective length (length).
    pub length: f64,
}

/// The family of a design, with its own parameters.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum DesignFamily {
    /// A family linear in its parameters (quadratic, polynomial, free):
    /// designed.
    Linear(Family),
    /// A circular crown, its radius searched in `radius_range`.
    CircularCrown {
        /// The search bracket (length).
        radius_range: (f64, f64),
        /// Flat middle (length).
        flat_length: f64,
    },
    /// A logarithmic crown for `design_load`, set in closed form.
    LogarithmicCrown {
        /// The design load (force).
        design_load: f64,
        /// Flat middle (length).
        flat_length: f64,
        /// Lundberg's end, or Johns & Gohar's finite end drop.
        end: LogEnd,
        /// The roller's Hertz line contact.
        roller: Roller,
    },
}

/// A family by name, without its parameters: what a scene's
/// `design.family` says.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FamilyKind {
    /// The paper's quadratic.
    Quadratic,
    /// A polynomial of a given degree.
    Polynomial,
    /// One drop per axial station.
    Free,
    /// A circular crown, its radius searched.
    CircularCrown,
    /// A logarithmic crown, set in closed form.
    LogarithmicCrown,
}

impl FamilyKind {
    /// Every family, in the order messages list them.
    pub const ALL: [FamilyKind; 5] = [
        FamilyKind::Quadratic,
        FamilyKind::Polynomial,
        FamilyKind::Free,
        FamilyKind::CircularCrown,
        FamilyKind::LogarithmicCrown,
    ];

    /// Its name in a scene's `design.family`: "quadratic", "polynomial",
    /// "free", "circular-crown", "logarithmic-crown".
    pub const fn name(self) -> &'static str {
        match self {
            FamilyKind::Quadratic => "quadratic",
            FamilyKind::Polynomial => "polynomial",
            FamilyKind::Free => "free",
            FamilyKind::CircularCrown => "circular-crown",
            FamilyKind::LogarithmicCrown => "logarithmic-crown",
        }
    }

    /// Whether the family is linear in its parameters (designed by the
    /// program or the descent), not a crown searched or set.
    pub const fn is_linear(self) -> bool {
        matches!(
            self,
            FamilyKind::Quadratic | FamilyKind::Polynomial | FamilyKind::Free
        )
    }
}

elcon_num::named!(FamilyKind, "family");

#[cfg(feature = "serde")]
elcon_num::named_serde!(FamilyKind);

impl DesignFamily {
    /// Its family by name.
    pub fn kind(&self) -> FamilyKind {
        match self {
            DesignFamily::Linear(Family::Quadratic) => FamilyKind::Quadratic,
            DesignFamily::Linear(Family::Polynomial { .. }) => FamilyKind::Polynomial,
            DesignFamily::Linear(Family::Free) => FamilyKind::Free,
            DesignFamily::CircularCrown { .. } => FamilyKind::CircularCrown,
            DesignFamily::LogarithmicCrown { .. } => FamilyKind::LogarithmicCrown,
        }
    }

    /// Its name as a scene writes it: "quadratic", "polynomial (degree d)",
    /// "free", "circular-crown", "logarithmic-crown".
    pub fn describe(&self) -> String {
        match self {
            DesignFamily::Linear(Family::Quadratic) => "quadratic".into(),
            DesignFamily::Linear(Family::Polynomial { degree }) => {
                format!("polynomial (degree {degree})")
            }
            other => other.kind().name().into(),
        }
    }
}

/// A design asked for: see the [module documentation](self).
#[derive(Debug, Clone)]
pub struct DesignRequest {
    /// The family and its parameters.
    pub family: DesignFamily,
    /// The axial coordinate the profile runs along.
    pub axis: Axis,
    /// How a linear family's min-max problem is solved (ignored by the
    /// crowns).
    pub method: DesignMethod,
    /// The bound c_max on a polynomial family's constant (length); default
    /// as [`DesignOptions::max_constant`].
    pub max_constant: Option<f64>,
    /// Reference intensities r_l, one per case (default all 1: the worst
    /// p_max itself).
    pub reference_intensities: Option<Vec<f64>>,
    /// The method every case is analysed by; `None` (the default): the
    /// cases' own ([`ContactProblem::default_method`]: block pivoting on a
    /// dense S, the conjugate gradient matrix-free), the conjugate gradient
    /// for all when their own differ.
    pub reanalysis: Option<Method>,
    /// The options of those analyses.
    pub reanalysis_options: Options,
    /// A free profile's knots ([`DesignOptions::knots`]); default: one drop
    /// per axial station of the cases.
    pub knots: Option<Vec<f64>>,
    /// Profiles to start a linear family's design from, besides its own
    /// starts ([`DesignOptions::starts`]).
    pub starts: Vec<Profile>,
    /// Whether a linear family's design also starts from the uncorrected
    /// geometry and (on a line) the fitted uniform-pressure separation
    /// (default true; a design refined from a coarser grid's starts from
    /// that design alone).
    pub own_starts: bool,
    /// Keep the contact off the bodies' singular edges in every case
    /// ([`DesignOptions::edge_clearance`]; default true: a design must
    /// hold on any grid).
    pub edge_clearance: bool,
    /// What a linear family's design minimizes ([`DesignOptions::objective`];
    /// default the worst intensity). The crowns refuse a stress objective.
    pub objective: Objective,
    /// The bodies a stress objective measures ([`DesignOptions::bodies`]).
    pub bodies: Vec<Body>,
}

impl DesignRequest {
    /// A request for `family` along `axis`, every other setting its default
    /// (the method `auto`, the cases analysed by their own default method).
    pub fn new(family: DesignFamily, axis: Axis) -> Self {
        Self {
            family,
            axis,
            method: DesignMethod::Auto,
            max_constant: None,
            reference_intensities: None,
            reanalysis: None,
            reanalysis_options: Options::default(),
            knots: None,
            starts: Vec::new(),
            own_starts: true,
            edge_clearance: true,
            objective: Objective::Pressure,
            bodies: Vec::new(),
        }
    }

    /// The correction over `cases` (each under a load), found as its
    /// family is, with its certified analysis of every case.
    ///
    /// # Errors
    /// As [`design`], [`crown_search`] and [`evaluate`] for the family.
    pub fn run(&self, cases: &[ContactProblem]) -> Result<Outcome, DesignError> {
        let method = self.method_for(cases);
        if self.objective.is_stress() && !matches!(self.family, DesignFamily::Linear(_)) {
            return Err(DesignError::Objective {
                objective: self.objective.name(),
                reason: format!(
                    "a {} is searched or set for the worst intensity; a stress objective designs a \
                     linear family (quadratic, polynomial, free)",
                    self.family.describe()
                ),
            });
        }
        match &self.family {
            DesignFamily::Linear(family) => self.designed(cases, *family, method),
            DesignFamily::CircularCrown {
                radius_range,
                flat_length,
            } => self.searched(cases, (*radius_range, *flat_length), method),
            DesignFamily::LogarithmicCrown {
                design_load,
                flat_length,
                end,
                roller,
            } => {
                let profile = Profile::LogarithmicCrown(LogCrown {
                    design_load: *design_load,
                    length: roller.length,
                    combined_modulus: roller.combined_modulus,
                    radius: roller.radius,
                    flat_length: *flat_length,
                    end: *end,
                });
                let evaluation = evaluate(
                    cases,
                    self.axis,
                    &profile,
                    &Analysis::new(method, &self.reanalysis_options),
                )?;
                Ok(Outcome {
                    profile,
                    evaluation,
                    found: Found::Set { end: *end },
                })
            }
        }
    }

    /// The method the cases are analysed by: the one asked for, else their
    /// own default, the conjugate gradient when theirs differ (it solves
    /// every storage).
    pub fn method_for(&self, cases: &[ContactProblem]) -> Method {
        self.reanalysis.unwrap_or_else(|| {
            let first = cases
                .first()
                .map_or(Method::BlockPivoting, |c| c.default_method());
            if cases.iter().all(|c| c.check_method(first).is_ok()) {
                first
            } else {
                Method::ConjugateGradient
            }
        })
    }

    fn designed(
        &self,
        cases: &[ContactProblem],
        family: Family,
        method: Method,
    ) -> Result<Outcome, DesignError> {
        let options = DesignOptions {
            method: self.method,
            max_constant: self.max_constant,
            reanalysis: method,
            reanalysis_options: self.reanalysis_options.clone(),
            reference_intensities: self.reference_intensities.clone(),
            knots: self.knots.clone(),
            starts: self.starts.clone(),
            uncorrected_start: self.own_starts,
            fitted_start: self.own_starts,
            edge_clearance: self.edge_clearance,
            objective: self.objective,
            bodies: self.bodies.clone(),
            ..DesignOptions::default()
        };
        let d = design(cases, self.axis, family, &options)?;
        Ok(Outcome {
            profile: d.profile,
            evaluation: d.evaluation,
            found: Found::Designed {
                method: d.solver.method(),
                starts: d.starts,
                objective: d.criterion,
                value: d.objective,
                worst_stress: d.worst_stress,
            },
        })
    }

    fn searched(
        &self,
        cases: &[ContactProblem],
        ((low, high), flat_length): ((f64, f64), f64),
        method: Method,
    ) -> Result<Outcome, DesignError> {
        let search = crown_search(
            cases,
            self.axis,
            |radius| {
                Ok(Profile::CircularCrown {
                    radius,
                    flat_length,
                })
            },
            low,
            high,
            &SearchOptions {
                method,
                options: self.reanalysis_options.clone(),
                reference_intensities: self.reference_intensities.clone(),
                ..SearchOptions::default()
            },
        )?;
        Ok(Outcome {
            profile: search.profile,
            evaluation: search.evaluation,
            found: Found::Searched {
                analyses: search.samples.len(),
            },
        })
    }
}

/// How a request's correction was found.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum Found {
    /// Designed by a linear family's method, from several starts.
    Designed {
        /// The method that ran (the program or the descent).
        method: DesignMethod,
        /// Every start and where it ended.
        starts: Vec<StartOutcome>,
        /// What it minimized.
        objective: Objective,
        /// Its objective's value: the worst intensity (or stress) over
        /// r_l, over the cases.
        value: f64,
        /// For a stress objective, the worst stress measure over the cases
        /// (stress), on each case's grid of depths.
        worst_stress: Option<f64>,
    },
    /// A circular crown's radius searched.
    Searched {
        /// The analyses the search made.
        analyses: usize,
    },
    /// A logarithmic crown set in closed form.
    Set {
        /// Its end.
        end: LogEnd,
    },
}

impl Found {
    /// The method's name: "program", "descent", "search" or "set".
    pub fn method(&self) -> &'static str {
        match self {
            Found::Designed { method, .. } => method.name(),
            Found::Searched { .. } => "search",
            Found::Set { .. } => "set",
        }
    }

    /// What it minimized: a design's [`Objective`]; the worst intensity for
    /// a crown.
    pub fn minimized(&self) -> Objective {
        match self {
            Found::Designed { objective, .. } => *objective,
            _ => Objective::Pressure,
        }
    }

    /// A stress objective's worst stress over the cases (stress), on each
    /// case's grid of depths; none for the worst intensity.
    pub fn worst_stress(&self) -> Option<f64> {
        match self {
            Found::Designed { worst_stress, .. } => *worst_stress,
            _ => None,
        }
    }

    /// One line per start (designed), or how the crown was found.
    pub fn starts(&self) -> Vec<String> {
        match self {
            Found::Designed { starts, .. } => starts
                .iter()
                .map(|s| match &s.result {
                    Ok(v) => format!("{}: objective {v:.6e} ({} pivots)", s.label, s.pivots),
                    Err(e) => format!("{}: failed: {e}", s.label),
                })
                .collect(),
            Found::Searched { analyses } => vec![format!("searched: {analyses} analyses")],
            Found::Set { end } => vec![format!(
                "set from the design load ({})",
                match end {
                    LogEnd::JohnsGohar => "Johns-Gohar",
                    LogEnd::Lundberg => "Lundberg",
                    LogEnd::FujiwaraKawase { .. } => "Fujiwara-Kawase",
                }
            )],
        }
    }
}

/// A request's correction with its certified analysis of every case.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The correction.
    pub profile: Profile,
    /// Every case analysed with it.
    pub evaluation: Evaluation,
    /// How it was found.
    pub found: Found,
}

#[cfg(test)]
mod tests {
    use super::*;
    use elcon_analysis::{Geometry, Loading};
    use elcon_influence::{Beam, PointSet};

    /// Conry & Seireg's Example 2 beam (steel, 1 in x 4 in, 8.9 in long, 80
    /// points, 50,000 lbf at its centre) on a Winkler foundation of
    /// `modulus` lbf/in per in.
    fn example2_on(modulus: f64) -> ContactProblem {
        let points = PointSet::line(-4.45, 4.45, 80).unwrap();
        let beam = Body::beam(Beam {
            youngs_modulus: 30e6,
            second_moment: 64.0 / 12.0,
            loaded_point: 0.0,
        })
        .unwrap();
        let foundation = Body::winkler(modulus);
        let separation = Geometry::Separation(vec![0.0; 80]);
        ContactProblem::new(points, &beam, &foundation, &separation, Loading::load(5e4)).unwrap()
    }

    #[test]
    fn auto_hands_a_program_without_its_certificate_to_the_descent() {
        // On a foundation of 0.5 lbf/in^2 the beam sinks 11,000 in and bends
        // by thousandths of that: the program's tableau, which mixes forces,
        // lengths and intensities, ends short of its certificate.
        let cases = [example2_on(0.5)];
        let quadratic = DesignFamily::Linear(Family::Quadratic);
        let program = DesignRequest {
            method: DesignMethod::Program,
            ..DesignRequest::new(quadratic.clone(), Axis::X)
        };
        let e = program.run(&cases).unwrap_err();
        assert!(
            matches!(
                e,
                DesignError::Engine(elcon_lcp::LcpError::Inaccurate { .. })
            ),
            "{e}"
        );
        // Auto (80 points: the program's range) falls back on the descent,
        // whose design certifies.
        let auto = DesignRequest::new(quadratic, Axis::X);
        assert_eq!(auto.method, DesignMethod::Auto);
        let outcome = auto.run(&cases).unwrap();
        assert_eq!(outcome.found.method(), "descent");
        let solution = &outcome.evaluation.solutions[0];
        assert!(solution.certificate.holds(), "{:?}", solution.certificate);
        assert!(
            (solution.load - 5e4).abs() <= 1e-9 * 5e4,
            "{}",
            solution.load
        );
        // On the paper's foundation (1e7 lbf/in^2) Auto's program designs
        // it itself.
        let paper = auto.run(&[example2_on(1e7)]).unwrap();
        assert_eq!(paper.found.method(), "program");
    }
}
