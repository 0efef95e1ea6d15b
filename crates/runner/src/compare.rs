//! A run's comparison with the closed form that applies: the reference
//! values, the relative errors `computed / reference - 1` and the
//! reference pressure at each point.
//!
//! A Hertz contact whose load acts off the origin (the tilts free, with
//! moments) or whose tilts are prescribed is the Hertz contact translated
//! to its centre `e`: with the separation `|r|^2 / (2R)` (R the combined
//! radius; `x^2 / (2R)` on a line) and the gaps
//! `Y = S F + eps - alpha - θ_x y + θ_y x` (`elcon_analysis::loading`),
//! Hertz's pressure centred at e deflects the surfaces by
//! `delta_H - |r - e|^2 / (2R)` inside the contact, so `Y = 0` there when
//!
//! ```text
//!     θ_x = e_y / R,    θ_y = -e_x / R,    alpha = delta_H - |e|^2 / (2R)
//! ```
//!
//! (`|r|^2 - |r - e|^2 = 2 r.e - |e|^2`), with the pressure
//! `p0 sqrt(1 - |r - e|^2 / a^2)`, the same peak and radius. The centre is
//! `e = (-θ_y R, θ_x R)` for prescribed tilts, and the load centre
//! `e = (-M_y / P, M_x / P)` for free tilts (the moments of the contact
//! forces about the origin balance the applied ones). Under displacement
//! control the load, and with it the centre of a moment, is known only
//! after the solve: such a comparison is omitted with a note, as are the
//! flat punch's and the beam's under a moment or a tilt their closed forms
//! do not have. An elliptical Hertz contact is compared centred only (no
//! moment, no tilt): its approach, peak pressure, the radius `sqrt(a b)`
//! of its area, and each semi-axis against the contact's ellipse (the
//! ellipse of the outline's second moments,
//! `ContactSolution::contact_ellipse`).

use elcon_analysis::loading::Tilt;
use elcon_analysis::references::{
    FlatPunch, HertzCylinders, HertzEllipse, HertzSpheres, HetenyiBeam,
};
use elcon_analysis::{ContactProblem, ContactSolution, Loading, Normal};

use elcon_num::Num;
use elcon_report::{Errors, ReferenceJson, XY};
use elcon_scene::Reference;

/// `computed / reference - 1`.
fn rel(x: f64, r: f64) -> f64 {
    x / r - 1.0
}

/// `||p - p_ref||_2 / ||p_ref||_2` over the points.
/// Both are scaled by the largest reference pressure first: squares of
/// pressures near the ends of the doubles' range would underflow or
/// overflow.
fn l2(pressures: &[f64], reference: &[f64]) -> f64 {
    let scale = reference.iter().fold(0.0f64, |m, q| m.max(q.abs()));
    let (mut num, mut den) = (0.0, 0.0);
    for (p, q) in pressures.iter().zip(reference) {
        let (p, q) = (p / scale, q / scale);
        num += (p - q) * (p - q);
        den += q * q;
    }
    (num / den).sqrt()
}

/// The closed form's values, errors, and per-point reference pressures.
pub(crate) fn compare(
    reference: &Reference,
    problem: &ContactProblem,
    sol: &ContactSolution,
    loading: Loading,
) -> (ReferenceJson, Option<Vec<f64>>) {
    let mut json = ReferenceJson {
        kind: reference.kind().to_string(),
        approach: None,
        max_pressure: None,
        contact_extent: None,
        semi_axes: None,
        angle: None,
        load: None,
        load_centre: None,
        tilt: None,
        errors: Errors::default(),
        note: None,
    };
    let pressures = match *reference {
        Reference::HertzSpheres(h) => spheres(h, problem, sol, loading, &mut json),
        Reference::HertzEllipse(h) => ellipse(h, problem, sol, loading, &mut json),
        Reference::HertzCylinders { hertz, datum } => {
            cylinders(hertz, datum, problem, sol, loading, &mut json)
        }
        Reference::FlatPunch(punch) => flat_punch(punch, problem, sol, loading, &mut json),
        Reference::Hetenyi(beam) => hetenyi(beam, problem, sol, loading, &mut json),
    };
    (json, pressures)
}

/// A rigid flat punch: the load of the approach or the approach of the
/// load. The pressure is singular at the edge: no peak or L2 comparison.
fn flat_punch(
    punch: FlatPunch,
    problem: &ContactProblem,
    sol: &ContactSolution,
    loading: Loading,
    json: &mut ReferenceJson,
) -> Option<Vec<f64>> {
    json.contact_extent = Some(punch.radius);
    let points = problem.points().len();
    if !aligned(loading) && sol.contact.len() < points {
        // Lifted off at an edge, the punch no longer presses its whole
        // face: the superposition below does not hold.
        json.note = Some(format!(
            "the moment or tilt lifts the punch off at {} of its {points} points: the closed \
             forms are those of a punch pressing its whole face (under a moment, its load and \
             approach at the centre are a central punch's only while the face stays in \
             contact), so they are not compared",
            points - sol.contact.len()
        ));
        return None;
    }
    // A uniform separation e0 (the punch's face e0 from the other
    // surface) offsets the approach: Boussinesq's indentation is
    // delta - e0.
    let e0 = problem.separation().first().copied().unwrap_or(0.0);
    let mut notes = Vec::new();
    if e0 != 0.0 {
        notes.push(format!(
            "the uniform separation {} offsets the approach: Boussinesq's indentation is the \
             approach minus it",
            Num(e0)
        ));
    }
    match loading.normal {
        Normal::Approach(d) if d - e0 > 0.0 => {
            let p = punch.load(d - e0);
            json.load = Some(p);
            json.errors.load = Some(rel(sol.load, p));
        }
        Normal::Approach(_) => notes.push(
            "the approach does not press the punch past the separation: no load to compare".into(),
        ),
        Normal::Load(p) => {
            let d = punch.approach(p) + e0;
            json.approach = Some(d);
            json.errors.approach = Some(rel(sol.approach, d));
        }
    }
    if !aligned(loading) {
        // Superposed on the central load, a moment or a tilt turns the
        // punch about its centre and leaves the approach and the load there
        // as they are while the whole face stays in contact (above); their
        // closed forms stand.
        notes.push(
            "a moment or a tilt turns the punch about its centre; its whole face stays in \
             contact, so the load and the approach at the centre are those of the central \
             punch and are compared, the tilt is not"
                .into(),
        );
    }
    json.note = (!notes.is_empty()).then(|| notes.join("; "));
    None
}

/// Hetenyi's beam on a Winkler foundation under a central load alone: its
/// centre deflection, peak intensity and intensities at the points.
fn hetenyi(
    beam: HetenyiBeam,
    problem: &ContactProblem,
    sol: &ContactSolution,
    loading: Loading,
    json: &mut ReferenceJson,
) -> Option<Vec<f64>> {
    centred_only(
        loading,
        json,
        "Hetenyi's solution is that of a central load alone: with a moment or a tilt the \
         beam's errors are not computed",
    )?;
    let points = problem.points();
    let p: Vec<f64> = (0..points.len())
        .map(|k| beam.load_intensity(points.x(k)))
        .collect();
    json.approach = Some(beam.centre_deflection());
    json.max_pressure = Some(beam.load_intensity(0.0));
    json.errors.approach = Some(rel(sol.approach, beam.centre_deflection()));
    json.errors.max_pressure = Some(rel(sol.max_pressure, beam.load_intensity(0.0)));
    json.errors.pressure_l2 = Some(l2(&sol.pressures, &p));
    if sol.contact.len() < points.len() {
        json.note = Some(format!(
            "Hetenyi's solution is that of a bonded foundation; this tensionless one lifted off \
             at {} of {} points, so the errors measure the lift-off as well as the \
             discretization",
            points.len() - sol.contact.len(),
            points.len()
        ));
    }
    Some(p)
}

/// `Some(())` for a loading without moment or tilt; otherwise `None`, with
/// `note` (why the closed form is not compared) on the reference.
fn centred_only(loading: Loading, json: &mut ReferenceJson, note: &str) -> Option<()> {
    if aligned(loading) {
        return Some(());
    }
    json.note = Some(note.into());
    None
}

/// Whether the loading has neither a moment nor a non-zero prescribed tilt.
fn aligned(loading: Loading) -> bool {
    let zero = |t: Tilt| match t {
        Tilt::Free { moment } => moment == 0.0,
        Tilt::Prescribed { angle } => angle == 0.0,
    };
    zero(loading.tilt_x) && zero(loading.tilt_y)
}

/// The centre `e` of the Hertz contact of combined radius `radius` under
/// `loading` (see the module documentation), or why it is not known before
/// the solve. `load` is P under load control.
fn hertz_centre(loading: Loading, radius: f64) -> Result<(f64, f64), &'static str> {
    let load = loading.load_value();
    let offset = |tilt: Tilt, sign: f64| match (tilt, load) {
        (Tilt::Prescribed { angle }, _) => Ok(sign * angle * radius),
        (Tilt::Free { moment: 0.0 }, _) => Ok(0.0),
        (Tilt::Free { moment }, Some(p)) => Ok(sign * moment / p),
        (Tilt::Free { .. }, None) => Err(
            "under displacement control the load, and with it where a moment centres the \
             contact, is known only after the solve: the translated Hertz solution is not \
             compared",
        ),
    };
    Ok((offset(loading.tilt_y, -1.0)?, offset(loading.tilt_x, 1.0)?))
}

/// Writes the centre and the tilts of a translated reference (when off the
/// origin) and the tilts' errors, where the reference's tilt is not (nearly)
/// zero: a centre offset below `sqrt(eps)` of the contact's `size` (its
/// radius or half-width) is within the solve's rounding of the origin, and
/// a relative error against a tilt that small would be the solve's
/// rounding over nothing; it is omitted with a note.
fn translated(
    json: &mut ReferenceJson,
    sol: &ContactSolution,
    (ex, ey): (f64, f64),
    radius: f64,
    size: f64,
) {
    if (ex, ey) == (0.0, 0.0) {
        return;
    }
    let (tilt_x, tilt_y) = (ey / radius, -ex / radius);
    json.load_centre = Some(XY { x: ex, y: ey });
    json.tilt = Some(XY {
        x: tilt_x,
        y: tilt_y,
    });
    let resolved = |offset: f64| offset.abs() > f64::EPSILON.sqrt() * size;
    json.errors.tilt_x = resolved(ey).then(|| rel(sol.tilt_x, tilt_x));
    json.errors.tilt_y = resolved(ex).then(|| rel(sol.tilt_y, tilt_y));
    let unresolved: Vec<&str> = [("tilt_x", ey), ("tilt_y", ex)]
        .into_iter()
        .filter(|&(_, offset)| offset != 0.0 && !resolved(offset))
        .map(|(name, _)| name)
        .collect();
    if !unresolved.is_empty() {
        let note = format!(
            "the reference {} of the load centre's offset is within rounding of zero (the \
             offset is below 1.5e-8 of the contact's size): no relative error is given for it",
            unresolved.join(" and ")
        );
        json.note = Some(match json.note.take() {
            Some(n) => format!("{n}; {note}"),
            None => note,
        });
    }
}

/// The centre of a Hertz contact translated under `loading` (combined
/// radius `r`), or `None` with the reason in the block's note.
fn centre(loading: Loading, r: f64, json: &mut ReferenceJson) -> Option<(f64, f64)> {
    hertz_centre(loading, r)
        .map_err(|why| json.note = Some(why.into()))
        .ok()
}

/// The closed form's peak pressure and contact extent with the run's
/// errors against them, and the pressure's L2 error against `p`, the
/// closed form at each point.
fn peak_and_extent(
    json: &mut ReferenceJson,
    sol: &ContactSolution,
    (peak, extent): (f64, f64),
    p: &[f64],
) {
    json.max_pressure = Some(peak);
    json.contact_extent = Some(extent);
    json.errors.max_pressure = Some(rel(sol.max_pressure, peak));
    json.errors.contact_extent = Some(rel(sol.contact_extent, extent));
    json.errors.pressure_l2 = Some(l2(&sol.pressures, p));
}

/// Hertz spheres, translated to the load centre.
fn spheres(
    h: HertzSpheres,
    problem: &ContactProblem,
    sol: &ContactSolution,
    loading: Loading,
    json: &mut ReferenceJson,
) -> Option<Vec<f64>> {
    let r = h.radius;
    let (ex, ey) = centre(loading, r, json)?;
    let shift = (ex * ex + ey * ey) / (2.0 * r);
    // Under displacement control the Hertz contact is the one of approach
    // delta_H = alpha + |e|^2 / (2R): P = 4 E* a^3 / (3 R), a = sqrt(R delta_H).
    let h = match loading.normal {
        Normal::Approach(d) if shift > 0.0 => {
            let load = 4.0 * h.combined_modulus * (r * (d + shift)).powf(1.5) / (3.0 * r);
            HertzSpheres::new(h.combined_modulus, r, load).ok()?
        }
        _ => h,
    };
    let points = problem.points();
    let p: Vec<f64> = (0..points.len())
        .map(|k| h.pressure((points.x(k) - ex).hypot(points.y(k) - ey)))
        .collect();
    peak_and_extent(json, sol, (h.peak_pressure(), h.contact_radius()), &p);
    match loading.normal {
        Normal::Load(_) => {
            let approach = h.approach() - shift;
            json.approach = Some(approach);
            json.errors.approach = Some(rel(sol.approach, approach));
        }
        Normal::Approach(_) => {
            json.load = Some(h.load);
            json.errors.load = Some(rel(sol.load, h.load));
        }
    }
    translated(json, sol, (ex, ey), r, h.contact_radius());
    Some(p)
}

/// Hertz cylinders, translated along x to the load centre.
fn cylinders(
    hertz: HertzCylinders,
    datum: Option<f64>,
    problem: &ContactProblem,
    sol: &ContactSolution,
    loading: Loading,
    json: &mut ReferenceJson,
) -> Option<Vec<f64>> {
    let r = hertz.radius;
    let (ex, _) = centre(loading, r, json)?;
    let points = problem.points();
    let p: Vec<f64> = (0..points.len())
        .map(|k| hertz.pressure(points.x(k) - ex))
        .collect();
    peak_and_extent(json, sol, (hertz.peak_pressure(), hertz.half_width()), &p);
    if let Some(d0) = datum
        && let Ok(a) = hertz.approach(d0)
    {
        let approach = a - ex * ex / (2.0 * r);
        json.approach = Some(approach);
        json.errors.approach = Some(rel(sol.approach, approach));
    }
    translated(json, sol, (ex, 0.0), r, hertz.half_width());
    Some(p)
}

/// Hertz's elliptical contact, centred: the approach (or the load), the
/// peak pressure, the equivalent radius and both semi-axes.
fn ellipse(
    h: HertzEllipse,
    problem: &ContactProblem,
    sol: &ContactSolution,
    loading: Loading,
    json: &mut ReferenceJson,
) -> Option<Vec<f64>> {
    centred_only(
        loading,
        json,
        "the elliptical Hertz solution is compared centred only: with a moment or a tilt \
         its errors are not computed",
    )?;
    let points = problem.points();
    let p: Vec<f64> = (0..points.len())
        .map(|k| h.pressure(points.x(k), points.y(k)))
        .collect();
    let (a, b) = (h.semi_major(), h.semi_minor());
    peak_and_extent(json, sol, (h.peak_pressure(), h.equivalent_radius()), &p);
    json.semi_axes = Some([a, b]);
    json.angle = Some(h.angle().to_degrees());
    if let Some(e) = sol.contact_ellipse {
        json.errors.semi_major = Some(rel(e.semi_major, a));
        json.errors.semi_minor = Some(rel(e.semi_minor, b));
    }
    match loading.normal {
        Normal::Load(_) => {
            json.approach = Some(h.approach());
            json.errors.approach = Some(rel(sol.approach, h.approach()));
        }
        Normal::Approach(_) => {
            json.load = Some(h.load());
            json.errors.load = Some(rel(sol.load, h.load()));
        }
    }
    Some(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_l2_error_holds_at_the_ends_of_the_doubles_range() {
        let reference = [1.0, 2.0, 2.0];
        let computed = [1.0, 2.0, 1.0];
        let e = l2(&computed, &reference);
        assert!((e - 1.0 / 3.0).abs() < 1e-15, "{e}");
        for scale in [1e-200, 1e200] {
            let (r, c): (Vec<f64>, Vec<f64>) = reference
                .iter()
                .zip(&computed)
                .map(|(r, c)| (r * scale, c * scale))
                .unzip();
            let e = l2(&c, &r);
            assert!((e - 1.0 / 3.0).abs() < 1e-15, "{scale}: {e}");
        }
    }
}
