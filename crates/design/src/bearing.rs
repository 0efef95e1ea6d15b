//! A roller bearing's crown designed over its own rollers: the bearing is
//! solved as a system (elcon-elements), each loaded roller's inner contact
//! under its load and its tilt relative to the ring becomes a load case,
//! the crown is designed over those cases (the paper's min-max of the peak
//! pressure, [`design`]), and the bearing is solved again with the
//! designed crown, which is what the workshop makes.
//!
//! The cases are the inner contacts (the raceway more curved against the
//! roller, the higher pressure); the crown is the roller's, so it enters
//! both of its contacts in the re-solved bearing. The rollers' loads and
//! tilts shift when the crown changes (a crowned roller is softer, and the
//! load zone narrows), so the design is made again over the re-solved
//! bearing's rollers, at most [`ROUNDS`] times, until the re-solved
//! bearing's peak pressure is within [`ROUND_AGREEMENT`] of the design's
//! objective: the re-solved bearing's peak pressure, not the objective, is
//! the answer.

use elcon_analysis::Loading;
use elcon_analysis::system::SystemSettings;
use elcon_elements::bearing::BearingSolution;
use elcon_elements::roller::{Crown, RollerBearing, RollerGrid};

use crate::{Axis, Design, DesignError, DesignOptions, Family, design};

/// The most rounds of design and re-solve.
pub const ROUNDS: usize = 3;

/// The re-solved bearing's peak inner pressure agrees with the design's
/// objective to this (relative): the rollers' loads and tilts have
/// settled.
pub const ROUND_AGREEMENT: f64 = 0.01;

/// One loaded roller as a design case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrownCase {
    /// The roller (its index from the load's direction).
    pub roller: usize,
    /// Its load (force).
    pub load: f64,
    /// Its inner contact's tilt, the ring's rotation less the roller's
    /// about its rolling direction (radians).
    pub tilt: f64,
}

/// A crown designed over a bearing's own rollers.
#[derive(Debug, Clone)]
pub struct BearingCrown {
    /// The cases of the last round: each loaded roller of the bearing as
    /// re-solved with the previous round's crown (as given, in the first).
    pub cases: Vec<CrownCase>,
    /// The design over them.
    pub design: Design,
    /// The designed crown as a table of drops at the design's stations
    /// along the roller (what is made, read linearly between stations).
    pub crown: Crown,
    /// The bearing as given.
    pub before: BearingSolution,
    /// The bearing re-solved with the designed crown.
    pub after: BearingSolution,
    /// Rounds of design and re-solve made.
    pub rounds: usize,
}

impl BearingCrown {
    /// The largest inner-contact pressure of the bearing as given and
    /// with the designed crown.
    pub fn max_pressures(&self) -> (f64, f64) {
        let worst = |s: &BearingSolution| {
            s.elements
                .iter()
                .fold(0.0f64, |a, e| a.max(e.max_pressure_inner))
        };
        (worst(&self.before), worst(&self.after))
    }
}

/// Designs the crown of `bearing`'s rollers (family `family`, along the
/// roller) over its own loaded rollers on `grid`, and re-solves the
/// bearing with it.
///
/// # Errors
/// [`DesignError::Element`] when the bearing cannot be built or solved;
/// the design's own errors ([`design`]).
pub fn roller_crown(
    bearing: &RollerBearing,
    grid: &RollerGrid,
    family: Family,
    options: &DesignOptions,
) -> Result<BearingCrown, DesignError> {
    let settings = SystemSettings::default();
    let before = bearing.system(grid)?.solve(&settings)?;
    let straight = RollerBearing {
        crown: Crown::Straight,
        ..bearing.clone()
    };
    let template = straight.templates(grid)?.swap_remove(0);
    // A matrix-free contact is re-analysed by the method that can.
    let mut options = options.clone();
    if template.entries("reanalysis").is_err() {
        options.reanalysis = template.default_method();
    }
    let mut rollers = before.clone();
    let mut rounds = 0;
    loop {
        rounds += 1;
        let cases = cases_of(&rollers);
        let problems = cases
            .iter()
            .map(|c| {
                template
                    .with_loading(Loading::load(c.load).with_tilt_x(c.tilt).with_tilt_y(0.0))
                    .map_err(|source| DesignError::Analysis {
                        stage: format!("roller {}'s inner contact", c.roller),
                        source,
                    })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let design = design(&problems, Axis::Y, family, &options)?;
        let rows: Vec<(f64, f64)> = design.profile.table(&design.stations)?;
        let crown = Crown::Table(std::sync::Arc::new(rows));
        let crowned = RollerBearing {
            crown: crown.clone(),
            ..bearing.clone()
        };
        let after = crowned.system(grid)?.solve(&settings)?;
        let worst = after
            .elements
            .iter()
            .fold(0.0f64, |a, e| a.max(e.max_pressure_inner));
        if rounds == ROUNDS || (worst / design.objective - 1.0).abs() <= ROUND_AGREEMENT {
            return Ok(BearingCrown {
                cases,
                design,
                crown,
                before,
                after,
                rounds,
            });
        }
        rollers = after;
    }
}

/// Each loaded roller of `solution` as a case: its load and its inner
/// contact's tilt.
fn cases_of(solution: &BearingSolution) -> Vec<CrownCase> {
    solution
        .elements
        .iter()
        .enumerate()
        .filter(|(_, e)| e.load > 0.0)
        .map(|(j, e)| CrownCase {
            roller: j,
            load: e.load,
            tilt: solution.system.zones[2 * j].tilt_x,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_crown_designed_over_the_bearing_takes_the_edge_peak_away() {
        let bearing = elcon_fixtures::bearings::roller(Crown::Straight, 1e-3);
        let grid = RollerGrid {
            across: 7,
            along: 30,
            zone: 1.5,
        };
        let c = roller_crown(&bearing, &grid, Family::Free, &DesignOptions::default()).unwrap();
        assert_eq!(c.cases.len(), 7);
        let (before, after) = c.max_pressures();
        // The straight roller's end peak is gone: the designed crown's
        // worst inner pressure is well below it, and the re-solved bearing
        // agrees with the last round's design.
        assert!(after < 0.8 * before, "{after} vs {before}");
        assert!(c.rounds <= ROUNDS);
        let agreement = (after / c.design.objective - 1.0).abs();
        assert!(
            agreement <= ROUND_AGREEMENT || c.rounds == ROUNDS,
            "{agreement}"
        );
        assert!(agreement < 0.03, "{after} vs {}", c.design.objective);
        assert!(c.after.system.certificate.holds());
    }
}
