//! What a design is asked for: the family of the correction, how its
//! min-max problem is solved (the paper's program over all cases at once,
//! or the case-decomposed descent), and the options of both.

use elcon_analysis::{Method, Options};

use elcon_influence::Body;

use crate::{DesignError, Objective, Profile};

/// A profile family linear in its parameters, for the design program.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Family {
    /// The paper's `a s^2 + b s + c`.
    Quadratic,
    /// `sum_{i <= degree} c_i s^i`.
    Polynomial {
        /// The degree d (at least 0).
        degree: usize,
    },
    /// One drop per axial station.
    Free,
}

impl Family {
    /// The polynomial degree of the profile: 2 for the quadratic, d for a
    /// polynomial, `None` for a free profile (one drop per station).
    pub fn degree(&self) -> Option<usize> {
        match *self {
            Family::Quadratic => Some(2),
            Family::Polynomial { degree } => Some(degree),
            Family::Free => None,
        }
    }
}

/// How the min-max problem of a linear family is solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum DesignMethod {
    /// The program while all the cases' points together are at most
    /// [`PROGRAM_LIMIT`], the descent above (the default).
    #[default]
    Auto,
    /// The paper's linear program with complementarity constraints, every
    /// case a block of one tableau (Conry & Seireg's eq. 16): exact pivots,
    /// memory and time growing with the square of all the cases' points.
    Program,
    /// The case-decomposed descent: a trust-region sequential linear program
    /// over the profile parameters, each case an analysis sharing its S,
    /// sensitivities from each case's contact set: cost
    /// growing like the analyses, linearly in the cases.
    Descent,
}

impl DesignMethod {
    /// Every method, in the order messages list them.
    pub const ALL: [DesignMethod; 3] = [
        DesignMethod::Auto,
        DesignMethod::Program,
        DesignMethod::Descent,
    ];

    /// Its name in a scene's `design.method`: "auto", "program",
    /// "descent"; [`FromStr`](std::str::FromStr) reads it back.
    pub const fn name(self) -> &'static str {
        match self {
            DesignMethod::Auto => "auto",
            DesignMethod::Program => "program",
            DesignMethod::Descent => "descent",
        }
    }

    /// Whether the method can design cases that hold S's entries or not
    /// (`entries`): the program reads them, so a case held matrix-free is
    /// the descent's (or `Auto`'s, which resolves to it).
    ///
    /// # Errors
    /// [`DesignError::Incompatible`] naming `method` for the program on
    /// cases without entries.
    pub fn admits(self, entries: bool) -> Result<Self, DesignError> {
        if self == DesignMethod::Program && !entries {
            return Err(DesignError::Incompatible {
                field: "method",
                reason: "the program reads S's entries and these cases hold S matrix-free; \
                         use \"descent\" or \"auto\""
                    .into(),
            });
        }
        Ok(self)
    }

    /// The method that runs for `points` points over all cases: `Auto`
    /// resolved to the program up to [`PROGRAM_LIMIT`] points when every
    /// case holds S's entries (`entries`; the program reads them), the
    /// descent otherwise; a given method as it is.
    pub fn resolve(self, points: usize, entries: bool) -> Self {
        match self {
            DesignMethod::Auto if points <= PROGRAM_LIMIT && entries => DesignMethod::Program,
            DesignMethod::Auto => DesignMethod::Descent,
            given => given,
        }
    }
}

elcon_num::named!(DesignMethod, "design method");
#[cfg(feature = "serde")]
elcon_num::named_serde!(DesignMethod);

/// All the cases' points together up to which [`DesignMethod::Auto`] uses
/// the program (measured on Example 2 and the crowned roller:
/// docs/design.md §2, the method's table).
pub const PROGRAM_LIMIT: usize = 200;

/// The agreement a design is held to, at least, when its cases are solved
/// by the conjugate gradient (matrix-free, or [`DesignOptions::reanalysis`]
/// asks for it): it stops at a residual, so two solves of one design (the
/// descent's and the re-analysis', from different starts and separations
/// that differ by rounding) agree to that accuracy, not to rounding; the
/// conjugate gradient's approach agrees with the dense exact solve's to
/// 1e-8 (`examples/large_grid` asserts it), and this is ten times looser.
pub const ITERATIVE_AGREEMENT: f64 = 1e-7;

/// Options of a design.
#[derive(Debug, Clone)]
pub struct DesignOptions {
    /// How the problem is solved (default [`DesignMethod::Auto`]).
    pub method: DesignMethod,
    /// The bound c_max on the constant of a polynomial family (length).
    /// Default: ten times the largest elastic deflection under a uniform
    /// pressure plus the largest initial separation, over the cases (and at
    /// least twice the constant of the fitted start).
    pub max_constant: Option<f64>,
    /// Options of the engine for the design program and the descent's
    /// linear programs.
    pub engine: Options,
    /// The method of the re-analysis and of the descent's analyses
    /// (default: block principal pivoting).
    pub reanalysis: Method,
    /// Options of the re-analysis.
    pub reanalysis_options: Options,
    /// Start from the uncorrected geometry, as the paper does (default
    /// true; a design refined from a coarser grid's starts from that
    /// design alone).
    pub uncorrected_start: bool,
    /// Also start from the least-squares fit of the uniform-pressure
    /// separation (line contacts only; default true).
    pub fitted_start: bool,
    /// More starting profiles (any family: each is sampled at the stations
    /// and fitted to the design's family by least squares, shifted to be
    /// non-negative). A design from a start is never worse than the start
    /// itself, so a known good crown given here bounds the result. Default
    /// none.
    pub starts: Vec<Profile>,
    /// Largest accepted relative difference between the design's objective
    /// and its re-analysis' (default 1e-9; at least [`ITERATIVE_AGREEMENT`]
    /// when the cases are solved by the conjugate gradient: matrix-free, or
    /// `reanalysis` asks for it).
    pub agreement: f64,
    /// Reference intensities r_l, one per load case (force per length or per
    /// area, > 0): the objective is the worst `p_max_l / r_l`. Default: all 1
    /// (the worst p_max itself).
    pub reference_intensities: Option<Vec<f64>>,
    /// The descent's iteration limit (default 500; each iteration analyses
    /// every case once).
    pub max_iterations: usize,
    /// A free profile's knots (axial positions, strictly increasing,
    /// length): its drops are the parameters, linear between knots and
    /// constant beyond, so the profile is a function of position that any
    /// grid can take. Default none: one drop per axial station of the
    /// cases' grid.
    pub knots: Option<Vec<f64>>,
    /// Keep the contact off the bodies' singular edges
    /// (`ContactProblem::singular_edge_points`: a roller's ends on a
    /// half-space) in every case, their intensities weighted by
    /// [`EDGE_WEIGHT`](crate::EDGE_WEIGHT) (at most a hundredth of the
    /// worst intensity is left there): a profile designed with the contact
    /// on such an edge fits its grid (the edge cell averages a peak that
    /// grows without bound as the grid refines), so a design that must hold
    /// on any grid clears them (default false: the cases' grid as it is).
    pub edge_clearance: bool,
    /// What the design minimizes (default [`Objective::Pressure`], the
    /// paper's worst intensity); a stress below the surface
    /// ([`Objective::VonMises`], [`Objective::MaxShear`]) is minimized by
    /// the descent alone, over the fields of [`DesignOptions::bodies`].
    pub objective: Objective,
    /// The bodies whose stresses below the surface a stress objective
    /// measures (the worst over those with a field: elastic half-spaces;
    /// twin bodies count once). Default none.
    pub bodies: Vec<Body>,
}

impl Default for DesignOptions {
    fn default() -> Self {
        Self {
            method: DesignMethod::Auto,
            max_constant: None,
            engine: Options::default(),
            reanalysis: Method::BlockPivoting,
            reanalysis_options: Options::default(),
            uncorrected_start: true,
            fitted_start: true,
            starts: Vec::new(),
            agreement: 1e-9,
            reference_intensities: None,
            max_iterations: 500,
            knots: None,
            edge_clearance: false,
            objective: Objective::Pressure,
            bodies: Vec::new(),
        }
    }
}
