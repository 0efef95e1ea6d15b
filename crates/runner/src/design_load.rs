//! A design load's problem, as the design stage builds it and as the
//! estimate plans it: on the grid of a fineness (1: the scene's own points
//! for that load, S held as the scene holds it; finer: the scene's layout
//! refined, S held as elcon-analysis decides for its size, matrix-free on
//! a large lattice), unfolded (a design reads every point), under the load
//! alone (a misalignment is set on the built problem, sharing its S).

use elcon_analysis::{Loading, ProblemBuilder, Storage};
use elcon_scene::{Scene, SceneError};

/// The builder of design load `load`'s problem on the grid of `fineness`
/// (see the module documentation).
///
/// # Errors
/// [`SceneError`] when the points cannot be laid out at that load and
/// fineness.
pub(crate) fn design_load(
    scene: &Scene,
    load: f64,
    fineness: f64,
) -> Result<ProblemBuilder<'_>, SceneError> {
    let points = if fineness == 1.0 {
        scene.points_for(load)?
    } else {
        scene
            .grid_for(load, fineness)?
            .points()
            .map_err(SceneError::points)?
    };
    let builder = scene.builder(points, Loading::load(load)).fold(false);
    Ok(if fineness == 1.0 {
        builder
    } else {
        builder.storage(Storage::Auto)
    })
}
