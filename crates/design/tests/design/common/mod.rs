//! What the design tests alone share: the design of one case with the
//! default options (the cases themselves are elcon-fixtures'
//! `design_cases`).

use elcon_analysis::ContactProblem;
use elcon_design::{Axis, Design, DesignError, DesignOptions, Family, design};

/// The design of the one case `case` along `axis` in `family`, with the
/// default options.
pub fn design_one(
    case: &ContactProblem,
    axis: Axis,
    family: Family,
) -> Result<Design, DesignError> {
    design(
        std::slice::from_ref(case),
        axis,
        family,
        &DesignOptions::default(),
    )
}
