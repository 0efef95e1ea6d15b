//! The stresses below the surface of a scene's run (`[outputs] subsurface
//! = true`): each body's field from the solved contact forces and its own
//! Poisson's ratio (elcon-analysis's `subsurface`,
//! `sigma(x, y, z) = sum_k p_k T(x - x_k, y - y_k, z; cell_k, nu)`),
//! result.json's `subsurface` block, and the section and depth-profile
//! CSVs. Stresses are in the scene's pressure unit, tension positive (a
//! contact's compression is negative); depth z is measured down from the
//! surface.

use std::time::Instant;

use elcon_analysis::ContactSolution;
use elcon_analysis::subsurface::{Subsurface, SubsurfaceOptions};
use elcon_influence::PointSet;
use elcon_report::{BodySubsurfaceJson, SubsurfaceJson};
use elcon_scene::{BodySpec, Scene};

/// Both bodies' fields below a solution; computed once when the two have
/// the same model and Poisson's ratio (the field does not depend on E).
pub(crate) fn subsurface_of(
    scene: &Scene,
    points: &PointSet,
    solution: &ContactSolution,
    options: &SubsurfaceOptions,
) -> [Subsurface; 2] {
    let [b1, b2] = scene.bodies();
    let first = Subsurface::of(points, solution, b1.body(), options);
    let nu = |b: &BodySpec| b.material().map(|m| m.poissons_ratio());
    let twins = b1.model() == b2.model() && nu(b1).is_some() && nu(b1) == nu(b2);
    let second = if twins {
        first.clone()
    } else {
        Subsurface::of(points, solution, b2.body(), options)
    };
    [first, second]
}

/// The fields of a run and their block (`None` unless the scene asks).
pub(crate) fn subsurface(
    scene: &Scene,
    points: &PointSet,
    solution: &ContactSolution,
) -> Option<([Subsurface; 2], SubsurfaceJson)> {
    let options = scene.outputs().subsurface()?;
    let start = Instant::now();
    let fields = subsurface_of(scene, points, solution, options);
    let [m1, m2] = scene.bodies().each_ref().map(|b| b.model());
    let json = SubsurfaceJson {
        stress_unit: scene.units().pressure().to_string(),
        body1: BodySubsurfaceJson::of(&fields[0], m1),
        body2: BodySubsurfaceJson::of(&fields[1], m2),
        seconds: start.elapsed().as_secs_f64(),
    };
    Some((fields, json))
}
