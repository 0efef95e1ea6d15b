//! `[outputs]`: the plots asked for, whether to write pressure.csv, and
//! whether to compute the stresses below the surface (and on which depths).

use elcon_analysis::Num;
use elcon_analysis::subsurface::SubsurfaceOptions;

use crate::ctx::Ctx;
use crate::error::SceneError;
use crate::schema::OutputsToml;
pub use crate::schema::Plot;

/// The most depths `outputs.subsurface_depths` may list (each a layer of
/// the field over the whole grid).
pub const MAX_SUBSURFACE_DEPTHS: usize = 400;

/// The deepest `outputs.subsurface_depths` may reach, in sizes of the
/// candidate zone: deeper, the field is a point force's (falling like
/// `P / z^2`, a hundredth of the surface's peak and less), which the depth
/// layers on the zone's box no longer resolve, and each layer's cost grows
/// with its depth.
pub const MAX_DEPTH_IN_ZONES: f64 = 10.0;

/// What to write (each read through its accessor).
#[derive(Debug, Clone, PartialEq)]
pub struct Outputs {
    plots: Vec<Plot>,
    pressure_csv: bool,
    subsurface: Option<SubsurfaceOptions>,
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

    /// The options of the stresses below the surface when
    /// `outputs.subsurface = true` (off by default).
    pub fn subsurface(&self) -> Option<&SubsurfaceOptions> {
        self.subsurface.as_ref()
    }
}

pub(super) fn outputs(
    ctx: &Ctx<'_>,
    o: Option<&OutputsToml>,
    has_design: bool,
    zone: f64,
) -> Result<Outputs, SceneError> {
    let mut out = Outputs {
        plots: Vec::new(),
        pressure_csv: true,
        subsurface: None,
    };
    let Some(o) = o else { return Ok(out) };
    if let Some(c) = o.pressure_csv {
        out.pressure_csv = c;
    }
    out.subsurface = subsurface(ctx, o, zone)?;
    if let Some(plots) = &o.plots {
        for p in plots.get_ref() {
            let plot = *p.get_ref();
            let needs = match plot {
                Plot::Design if !has_design => Some("needs a [design] section"),
                Plot::Subsurface if out.subsurface.is_none() => {
                    Some("needs outputs.subsurface = true")
                }
                _ => None,
            };
            if let Some(reason) = needs {
                let name = format!("{:?}", plot.name());
                return Err(ctx.invalid(p.span(), "outputs.plots", name, reason));
            }
            if !out.plots.contains(&plot) {
                out.plots.push(plot);
            }
        }
    }
    Ok(out)
}

/// `outputs.subsurface` and `outputs.subsurface_depths`: depths each
/// finite and > 0, increasing, at most [`MAX_SUBSURFACE_DEPTHS`], none
/// deeper than [`MAX_DEPTH_IN_ZONES`] times the candidate zone's size `zone`.
fn subsurface(
    ctx: &Ctx<'_>,
    o: &OutputsToml,
    zone: f64,
) -> Result<Option<SubsurfaceOptions>, SceneError> {
    let on = o.subsurface.as_ref().is_some_and(|s| *s.get_ref());
    let Some(given) = &o.subsurface_depths else {
        return Ok(on.then(SubsurfaceOptions::default));
    };
    let field = "outputs.subsurface_depths";
    if !on {
        return Err(ctx.invalid(
            given.span(),
            field,
            "[...]",
            "needs outputs.subsurface = true",
        ));
    }
    let depths = given.get_ref();
    if depths.is_empty() || depths.len() > MAX_SUBSURFACE_DEPTHS {
        return Err(ctx.invalid(
            given.span(),
            field,
            format!("{} depths", depths.len()),
            format!("must list 1 to {MAX_SUBSURFACE_DEPTHS} depths"),
        ));
    }
    let mut previous = 0.0;
    for d in depths {
        let z = *d.get_ref();
        if !(z.is_finite() && z > previous) {
            return Err(ctx.invalid(
                d.span(),
                field,
                z,
                "depths must be finite, > 0 and increasing (lengths below the surface)",
            ));
        }
        if z > MAX_DEPTH_IN_ZONES * zone {
            return Err(ctx.invalid(
                d.span(),
                field,
                Num(z),
                format!(
                    "is deeper than {MAX_DEPTH_IN_ZONES} times the candidate zone's size, {}: \
                     the field there is a point force's, which the depth layers on the \
                     zone's box do not resolve; give depths within {}",
                    Num(zone),
                    Num(MAX_DEPTH_IN_ZONES * zone)
                ),
            ));
        }
        previous = z;
    }
    Ok(Some(SubsurfaceOptions {
        depths: Some(depths.iter().map(|d| *d.get_ref()).collect()),
    }))
}
