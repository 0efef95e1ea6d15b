//! result.json's `discretization` block: the grids the scene was solved
//! on again (`h -> 2h -> 4h`) and each quantity's error estimated by
//! generalized Richardson extrapolation (`elcon_analysis::discretization`).

use elcon_analysis::discretization::{Discretization, ErrorEstimate, GridRun, Quantity, Verdict};
use serde::{Deserialize, Serialize};

/// An estimate's verdict, by name (why one is not estimated is the
/// quantity's `reason`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VerdictJson {
    /// The changes shrink with the grid at the observed order.
    Converging,
    /// The changes do not shrink: no error is estimated.
    NotConverging,
    /// Every grid gives the same value.
    Exact,
    /// Not enough grids were solved.
    NotEstimated,
}

impl VerdictJson {
    /// Every verdict, in the order messages list them.
    pub const ALL: [VerdictJson; 4] = [
        VerdictJson::Converging,
        VerdictJson::NotConverging,
        VerdictJson::Exact,
        VerdictJson::NotEstimated,
    ];

    /// Its name: "converging", "not converging", "exact", "not estimated".
    pub const fn name(self) -> &'static str {
        match self {
            VerdictJson::Converging => "converging",
            VerdictJson::NotConverging => "not converging",
            VerdictJson::Exact => "exact",
            VerdictJson::NotEstimated => "not estimated",
        }
    }

    /// The verdict of an estimate.
    pub fn of(v: &Verdict) -> Self {
        match v {
            Verdict::Converging => VerdictJson::Converging,
            Verdict::NotConverging => VerdictJson::NotConverging,
            Verdict::Exact => VerdictJson::Exact,
            // `Verdict::NotEstimated`; a new verdict gets its own name here.
            _ => VerdictJson::NotEstimated,
        }
    }

    /// An estimated relative error as a table shows it: `1.2e-3`, `exact`,
    /// `n.c.` (not converging) or `-` (not estimated).
    pub fn short(self, relative_error: Option<f64>) -> String {
        match self {
            VerdictJson::Converging => relative_error.map_or("-".into(), |e| format!("{e:.1e}")),
            VerdictJson::Exact => "exact".into(),
            VerdictJson::NotConverging => "n.c.".into(),
            VerdictJson::NotEstimated => "-".into(),
        }
    }
}

elcon_num::named!(VerdictJson, "verdict");
elcon_num::named_serde!(VerdictJson);

/// One grid of the estimate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GridJson {
    /// Points N.
    pub points: usize,
    /// Spacing h (length): the disk's, `sqrt(dx dy)` of a rectangle's
    /// cells, a line's cell.
    pub spacing: f64,
    /// Seconds to build and solve it (the fine grid: assembly and solve).
    pub seconds: f64,
    /// Why its solve failed, if it did.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub failure: Option<String>,
}

/// One quantity's estimate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QuantityJson {
    /// The fine grid's value (the run's).
    pub value: f64,
    /// The value on each grid solved, the fine one first.
    pub values: Vec<f64>,
    /// Richardson's limit (null unless converging or exact).
    pub extrapolated: Option<f64>,
    /// The fine value's estimated error, the quantity's unit.
    pub error: Option<f64>,
    /// The error over the value's magnitude.
    pub relative_error: Option<f64>,
    /// The observed order p (three grids).
    pub order: Option<f64>,
    /// `converging`, `not converging`, `exact` or `not estimated`.
    pub verdict: VerdictJson,
    /// Why it is not estimated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
}

impl QuantityJson {
    fn of(e: &ErrorEstimate) -> Self {
        Self {
            value: e.value(),
            values: e.values.clone(),
            extrapolated: e.extrapolated,
            error: e.error,
            relative_error: e.relative_error(),
            order: e.order,
            verdict: VerdictJson::of(&e.verdict),
            reason: e.verdict.reason().map(String::from),
        }
    }

    /// The relative error as a table shows it: `1.2e-3`, `exact`, `n.c.`
    /// (not converging) or `-` (not estimated).
    pub fn short(&self) -> String {
        self.verdict.short(self.relative_error)
    }
}

/// Each quantity's estimate, by name.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QuantitiesJson {
    /// The approach.
    pub approach: QuantityJson,
    /// The peak pressure.
    pub max_pressure: QuantityJson,
    /// The contact radius or half-width.
    pub contact_extent: QuantityJson,
    /// The contact area or length.
    pub contact_measure: QuantityJson,
    /// The load.
    pub load: QuantityJson,
    /// The load centre's x.
    pub load_centre_x: QuantityJson,
    /// The load centre's y.
    pub load_centre_y: QuantityJson,
    /// The rotation about x.
    pub tilt_x: QuantityJson,
    /// The rotation about y.
    pub tilt_y: QuantityJson,
}

/// result.json's `discretization`: the grids solved (the run's first) and
/// each quantity's estimate, with what limited it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DiscretizationJson {
    /// The grids, the run's first.
    pub grids: Vec<GridJson>,
    /// Each quantity.
    pub quantities: QuantitiesJson,
    /// What limited the estimate (too few points for a coarser grid, a
    /// coarse solve that failed, separations given per point).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

impl DiscretizationJson {
    /// The block of an estimate.
    pub fn of(d: &Discretization) -> Self {
        let q = |quantity| {
            d.get(quantity)
                .map_or_else(|| QuantityJson::of(&unknown()), QuantityJson::of)
        };
        Self {
            grids: d.grids.iter().map(grid).collect(),
            quantities: QuantitiesJson {
                approach: q(Quantity::Approach),
                max_pressure: q(Quantity::MaxPressure),
                contact_extent: q(Quantity::ContactExtent),
                contact_measure: q(Quantity::ContactMeasure),
                load: q(Quantity::Load),
                load_centre_x: q(Quantity::LoadCentreX),
                load_centre_y: q(Quantity::LoadCentreY),
                tilt_x: q(Quantity::TiltX),
                tilt_y: q(Quantity::TiltY),
            },
            note: d.note.clone(),
        }
    }

    /// Seconds spent on the coarser grids.
    pub fn coarse_seconds(&self) -> f64 {
        self.grids.iter().skip(1).map(|g| g.seconds).sum()
    }
}

fn grid(g: &GridRun) -> GridJson {
    GridJson {
        points: g.points,
        spacing: g.spacing,
        seconds: g.seconds,
        failure: g.failure.clone(),
    }
}

fn unknown() -> ErrorEstimate {
    ErrorEstimate {
        values: Vec::new(),
        extrapolated: None,
        error: None,
        order: None,
        verdict: Verdict::NotEstimated("not computed".into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_verdict_keeps_elcon_analysis_s_name() {
        for v in [
            Verdict::Converging,
            Verdict::NotConverging,
            Verdict::Exact,
            Verdict::NotEstimated("one grid".into()),
        ] {
            assert_eq!(VerdictJson::of(&v).name(), v.name());
        }
        assert_eq!(VerdictJson::Converging.short(Some(1.23e-3)), "1.2e-3");
        assert_eq!(VerdictJson::NotConverging.short(Some(1.0)), "n.c.");
        assert_eq!(VerdictJson::NotEstimated.short(None), "-");
    }
}
