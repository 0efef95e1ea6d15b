//! result.json's `discretization` block: the grids the scene was solved
//! on again (`h -> 2h -> 4h`, or `h/2 -> h -> 2h` where 4h would not
//! resolve the contact) and each quantity's error estimated by generalized
//! Richardson extrapolation (`elcon_analysis::discretization`).

use elcon_analysis::discretization::{Discretization, ErrorEstimate, GridRun, Quantity, Verdict};
use serde::{Deserialize, Serialize};

/// An estimate's verdict, by name (why one is not estimated is the
/// quantity's `reason`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VerdictJson {
    /// The changes shrink with the grid at the observed order.
    Converging,
    /// The grids do not show convergence, or the input limits the
    /// quantity: no error is estimated (the reason says why).
    NotResolved,
    /// Every grid gives the same value.
    Exact,
    /// Not enough grids were solved.
    NotEstimated,
}

impl VerdictJson {
    /// Every verdict, in the order messages list them.
    pub const ALL: [VerdictJson; 4] = [
        VerdictJson::Converging,
        VerdictJson::NotResolved,
        VerdictJson::Exact,
        VerdictJson::NotEstimated,
    ];

    /// Its name: "converging", "not resolved", "exact", "not estimated".
    pub const fn name(self) -> &'static str {
        match self {
            VerdictJson::Converging => "converging",
            VerdictJson::NotResolved => "not resolved",
            VerdictJson::Exact => "exact",
            VerdictJson::NotEstimated => "not estimated",
        }
    }

    /// The verdict of an estimate.
    pub fn of(v: &Verdict) -> Self {
        match v {
            Verdict::Converging => VerdictJson::Converging,
            Verdict::NotResolved(_) => VerdictJson::NotResolved,
            Verdict::Exact => VerdictJson::Exact,
            // `Verdict::NotEstimated`; a new verdict gets its own name here.
            _ => VerdictJson::NotEstimated,
        }
    }

    /// An estimated relative error as a table shows it: `1.2e-3`, `exact`,
    /// `n.r.` (not resolved) or `-` (not estimated).
    pub fn short(self, relative_error: Option<f64>) -> String {
        match self {
            VerdictJson::Converging => relative_error.map_or("-".into(), |e| format!("{e:.1e}")),
            VerdictJson::Exact => "exact".into(),
            VerdictJson::NotResolved => "n.r.".into(),
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
    /// Its spacing over the run's own: 1 the run's own grid, 0.5 the finer
    /// grid h/2, 2 the coarser 2h, about 1.41 a grid between (absent in
    /// files written before it was added).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ratio: Option<f64>,
    /// Why its solve failed, if it did.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub failure: Option<String>,
}

/// One quantity's estimate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QuantityJson {
    /// The run's own grid's value.
    pub value: f64,
    /// The value on each grid solved, the finest first (the run's own at
    /// the block's `own_grid`).
    pub values: Vec<f64>,
    /// Richardson's limit (null unless converging or exact).
    pub extrapolated: Option<f64>,
    /// The run's value's estimated error, the quantity's unit.
    pub error: Option<f64>,
    /// The error over the value's magnitude.
    pub relative_error: Option<f64>,
    /// The observed order p (three grids), or the least-squares fit's.
    pub order: Option<f64>,
    /// The least-squares fit's standard deviation, the quantity's unit
    /// (where the estimate is a fit over more than three grids).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scatter: Option<f64>,
    /// `converging`, `not resolved`, `exact` or `not estimated`.
    pub verdict: VerdictJson,
    /// Why it is not resolved or not estimated.
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
            scatter: e.scatter,
            verdict: VerdictJson::of(&e.verdict),
            reason: e.verdict.reason().map(String::from),
        }
    }

    /// The relative error as a table shows it: `1.2e-3`, `exact`, `n.r.`
    /// (not resolved) or `-` (not estimated).
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

/// result.json's `discretization`: the grids solved (the finest first)
/// and each quantity's estimate, with what limited it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DiscretizationJson {
    /// The grids, the finest first.
    pub grids: Vec<GridJson>,
    /// The index in `grids` of the run's own grid (0 unless finer grids
    /// were solved).
    #[serde(default)]
    pub own_grid: usize,
    /// The estimate's cost: seconds spent on the grids other than the run's
    /// own, finer ones included (result.json's `seconds.error_estimate`).
    #[serde(default)]
    pub seconds: f64,
    /// Points of the grids other than the run's own, together.
    #[serde(default)]
    pub points: usize,
    /// Each quantity.
    pub quantities: QuantitiesJson,
    /// What limited the estimate (too few points for a coarser grid, a
    /// finer grid over its memory allowance, a solve that failed,
    /// separations given per point).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
    /// What in the input limits a quantity whatever the grid (a surface
    /// interpolated with slope kinks), each naming the input: the same
    /// text is among the run's warnings.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub limits: Vec<String>,
}

impl DiscretizationJson {
    /// The block of an estimate.
    pub fn of(d: &Discretization) -> Self {
        let q = |quantity| {
            d.get(quantity)
                .map_or_else(|| QuantityJson::of(&unknown()), QuantityJson::of)
        };
        let own = d.grids.get(d.own).map_or(f64::NAN, |g| g.spacing);
        Self {
            grids: d.grids.iter().map(|g| grid(g, own)).collect(),
            own_grid: d.own,
            seconds: d.extra_seconds(),
            points: (d.grids.iter().enumerate())
                .filter(|&(i, _)| i != d.own)
                .map(|(_, g)| g.points)
                .sum(),
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
            limits: d.limits.iter().map(ToString::to_string).collect(),
        }
    }

    /// Seconds spent on the grids other than the run's own: the
    /// estimate's cost (result.json's `seconds.error_estimate`).
    pub fn extra_seconds(&self) -> f64 {
        (self.grids.iter().enumerate())
            .filter(|&(i, _)| i != self.own_grid)
            .fold(0.0, |sum, (_, g)| sum + g.seconds)
    }
}

/// A grid's block, `own` the run's own grid's spacing.
fn grid(g: &GridRun, own: f64) -> GridJson {
    let ratio = g.spacing / own;
    GridJson {
        points: g.points,
        spacing: g.spacing,
        seconds: g.seconds,
        ratio: ratio.is_finite().then_some(ratio),
        failure: g.failure.clone(),
    }
}

fn unknown() -> ErrorEstimate {
    ErrorEstimate {
        values: Vec::new(),
        own: 0,
        extrapolated: None,
        error: None,
        order: None,
        scatter: None,
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
            Verdict::NotResolved("alternating".into()),
            Verdict::Exact,
            Verdict::NotEstimated("one grid".into()),
        ] {
            assert_eq!(VerdictJson::of(&v).name(), v.name());
        }
        assert_eq!(VerdictJson::Converging.short(Some(1.23e-3)), "1.2e-3");
        assert_eq!(VerdictJson::NotResolved.short(Some(1.0)), "n.r.");
        assert_eq!(VerdictJson::NotEstimated.short(None), "-");
    }
}
