//! `[loading]`: a load or an approach, and each rotation free under its
//! moment or prescribed.

use elcon_analysis::Loading;
use toml::Spanned;

use crate::ctx::Ctx;
use crate::error::SceneError;
use crate::sanity::MAX_ROTATION;
use crate::schema::LoadingToml;

pub(super) fn loading(ctx: &Ctx<'_>, l: &Spanned<LoadingToml>) -> Result<Loading, SceneError> {
    let t = l.get_ref();
    let mut loading = match (&t.load, &t.approach) {
        (Some(p), None) => Loading::load(ctx.positive(p, "loading.load")?),
        (None, Some(a)) => Loading::approach(ctx.finite(a, "loading.approach")?),
        _ => {
            return Err(ctx.invalid(
                l.span(),
                "loading",
                "",
                "give exactly one of load (force; load control) and approach (length; displacement control)",
            ));
        }
    };
    // Each rotation: free with its moment (default 0) or prescribed.
    type With = fn(Loading, f64) -> Loading;
    let axes: [(_, _, _, _, With, With); 2] = [
        (
            &t.moment_x,
            &t.tilt_x,
            "loading.moment_x",
            "loading.tilt_x",
            Loading::with_moment_x,
            Loading::with_tilt_x,
        ),
        (
            &t.moment_y,
            &t.tilt_y,
            "loading.moment_y",
            "loading.tilt_y",
            Loading::with_moment_y,
            Loading::with_tilt_y,
        ),
    ];
    for (moment, tilt, moment_field, tilt_field, with_moment, with_tilt) in axes {
        loading = match (moment, tilt) {
            (Some(_), Some(angle)) => {
                return Err(ctx.invalid(
                    angle.span(),
                    tilt_field,
                    angle.get_ref().to_string(),
                    format!(
                        "give one of {moment_field} (a free rotation balancing that moment) and \
                         {tilt_field} (a prescribed rotation, radians), not both"
                    ),
                ));
            }
            (Some(m), None) => with_moment(loading, ctx.finite(m, moment_field)?),
            (None, Some(angle)) => {
                let a = ctx.finite(angle, tilt_field)?;
                let why = format!(
                    "at most {MAX_ROTATION} rad in size, as a design's misalignments: the rigid \
                     rotation is linearized (theta x), which holds to 0.5 % of the angle up to \
                     {MAX_ROTATION} rad"
                );
                let a = ctx.ensure(a, a.abs() <= MAX_ROTATION, angle.span(), tilt_field, why)?;
                with_tilt(loading, a)
            }
            (None, None) => loading,
        };
    }
    Ok(loading)
}
