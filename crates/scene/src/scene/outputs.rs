//! `[outputs]`: the plots asked for and whether to write pressure.csv.

use crate::ctx::Ctx;
use crate::error::SceneError;
use crate::schema::OutputsToml;
pub use crate::schema::Plot;

/// What to write.
#[derive(Debug, Clone, PartialEq)]
pub struct Outputs {
    /// The plots asked for (default none).
    plots: Vec<Plot>,
    /// Whether to write pressure.csv (default true).
    pressure_csv: bool,
}

impl Outputs {
    /// The plots asked for (default none), each once.
    pub fn plots(&self) -> &[Plot] {
        &self.plots
    }

    /// Whether to write pressure.csv (default true).
    pub fn pressure_csv(&self) -> bool {
        self.pressure_csv
    }
}

pub(super) fn outputs(
    ctx: &Ctx<'_>,
    o: Option<&OutputsToml>,
    has_design: bool,
) -> Result<Outputs, SceneError> {
    let mut out = Outputs {
        plots: Vec::new(),
        pressure_csv: true,
    };
    let Some(o) = o else { return Ok(out) };
    if let Some(c) = o.pressure_csv {
        out.pressure_csv = c;
    }
    if let Some(plots) = &o.plots {
        for p in plots.get_ref() {
            let plot = *p.get_ref();
            if plot == Plot::Design && !has_design {
                return Err(ctx.invalid(
                    p.span(),
                    "outputs.plots",
                    "\"design\"",
                    "needs a [design] section",
                ));
            }
            if !out.plots.contains(&plot) {
                out.plots.push(plot);
            }
        }
    }
    Ok(out)
}
