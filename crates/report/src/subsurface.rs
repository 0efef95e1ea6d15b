//! result.json's `subsurface` block (each body's largest von Mises
//! stress, Tresca shear and orthogonal shears with their places) and the
//! section and depth-profile CSVs. Stresses are in the scene's pressure
//! unit, tension positive; depth z is measured down from the surface.

use std::io;

use elcon_analysis::subsurface::{Peak, Section, Subsurface};
use elcon_scene::ModelKind;
use serde::{Deserialize, Serialize};

/// Where a stress is largest, as written.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PeakJson {
    /// The value (the pressure unit; signed for an orthogonal shear).
    pub value: f64,
    /// Position x (length).
    pub x: f64,
    /// Position y (length; 0 on a line).
    pub y: f64,
    /// Depth below the surface (length).
    pub depth: f64,
}

impl From<Peak> for PeakJson {
    fn from(p: Peak) -> Self {
        Self {
            value: p.value,
            x: p.x,
            y: p.y,
            depth: p.z,
        }
    }
}

/// One body's maxima below the surface, or why it has none.
#[serde_with::skip_serializing_none]
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BodySubsurfaceJson {
    /// Whether the body is an elastic half-space with a field.
    pub applicable: bool,
    /// Why not (a rigid body, a beam, a foundation, no contact).
    pub reason: Option<String>,
    /// The range of validity, where the model limits it (the point-force
    /// model: a cell or more below the surface).
    pub note: Option<String>,
    /// The body's Poisson's ratio.
    pub poissons_ratio: Option<f64>,
    /// The largest von Mises stress.
    pub von_mises: Option<PeakJson>,
    /// The largest shear stress (Tresca).
    pub tresca: Option<PeakJson>,
    /// The orthogonal shear tau_xz of largest magnitude.
    pub orthogonal_xz: Option<PeakJson>,
    /// The orthogonal shear tau_yz of largest magnitude (0 on a line).
    pub orthogonal_yz: Option<PeakJson>,
}

impl BodySubsurfaceJson {
    /// The block of `s`, a body of `model`.
    pub fn of(s: &Subsurface, model: ModelKind) -> Self {
        match s {
            Subsurface::Stresses(b) => Self {
                applicable: true,
                reason: None,
                note: (model == ModelKind::PointForce).then(|| {
                    "point-force model: valid a cell or more below the surface".to_string()
                }),
                poissons_ratio: Some(b.poissons_ratio),
                von_mises: Some(b.von_mises.into()),
                tresca: Some(b.tresca.into()),
                orthogonal_xz: Some(b.orthogonal_xz.into()),
                orthogonal_yz: Some(b.orthogonal_yz.into()),
            },
            Subsurface::NotApplicable(why) => Self {
                applicable: false,
                reason: Some((*why).to_string()),
                note: None,
                poissons_ratio: None,
                von_mises: None,
                tresca: None,
                orthogonal_xz: None,
                orthogonal_yz: None,
            },
        }
    }
}

/// result.json's `subsurface` block.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SubsurfaceJson {
    /// The stresses' unit (the scene's pressure unit), tension positive.
    pub stress_unit: String,
    /// Body 1's maxima.
    pub body1: BodySubsurfaceJson,
    /// Body 2's maxima.
    pub body2: BodySubsurfaceJson,
    /// Seconds the fields took, both bodies.
    pub seconds: f64,
}

/// A section as CSV: one row per (x, depth), x-major; lengths in
/// `length`, stresses in `stress`.
pub(crate) fn section_csv(
    section: &Section,
    length: &str,
    stress: &str,
    w: &mut dyn io::Write,
) -> io::Result<()> {
    writeln!(
        w,
        "x_{length},y_{length},depth_{length},sigma_x_{stress},sigma_y_{stress},\
         sigma_z_{stress},tau_xy_{stress},tau_xz_{stress},tau_yz_{stress},\
         von_mises_{stress},tresca_{stress}"
    )?;
    let rows = section.depths.len();
    for (i, x) in section.xs.iter().enumerate() {
        for (j, z) in section.depths.iter().enumerate() {
            let s = &section.stresses[i * rows + j];
            writeln!(
                w,
                "{x},{},{z},{},{},{},{},{},{},{},{}",
                section.y,
                s.xx,
                s.yy,
                s.zz,
                s.xy,
                s.xz,
                s.yz,
                s.von_mises(),
                s.tresca()
            )?;
        }
    }
    Ok(())
}
