//! One contact stated in two unit systems gives one answer: a soft rubber
//! ball (E = 5 MPa, ν = 0.49, R = 10 mm) in a conforming groove turned by
//! 20 degrees (a 10.4 : 1 Hertz ellipse on 20,915 square cells), under
//! 1 mN and 10 mN, in mm-N-MPa and in m-N-Pa. Polonsky & Keer's entry
//! rule alone settled into a cycle in mm (the iteration cap after 57 s at
//! 1 mN); the guarded iteration converges in either system.

use std::path::Path;

use elcon_runner::run;
use elcon_scene::Scene;

/// The scene in `length` and `pressure` units (`scale` metres a length
/// unit), under `load` newtons.
fn rubber(length: &str, pressure: &str, scale: f64, load: f64) -> Scene {
    let modulus = 5e6 * scale * scale;
    let text = format!(
        "[scene]\nname = \"rubber_{length}\"\n\
         [units]\nlength = \"{length}\"\nforce = \"N\"\npressure = \"{pressure}\"\n\
         [body1]\nmodel = \"uniform-patch\"\nyoungs_modulus = {modulus:e}\npoissons_ratio = 0.49\n\
         [body2]\nmodel = \"uniform-patch\"\nyoungs_modulus = {modulus:e}\npoissons_ratio = 0.49\n\
         [geometry]\nsurface1 = {{ shape = \"sphere\", radius = {r1:e} }}\n\
         surface2 = {{ shape = \"quadric\", radius_x = {r2x:e}, radius_y = {r2y:e}, angle = 20.0 }}\n\
         [points]\ngrid = \"ellipse\"\nacross = 21\nzone = 1.2\n\
         [loading]\nload = {load:e}\n",
        r1 = 0.01 / scale,
        r2x = 0.02 / scale,
        r2y = -0.0104 / scale,
    );
    Scene::from_str(Path::new("rubber.toml"), &text).unwrap()
}

#[test]
fn a_rubber_ball_in_a_turned_groove_gives_one_answer_in_mm_and_in_m() {
    for load in [1e-3, 1e-2] {
        let mm = run(&rubber("mm", "MPa", 1e-3, load)).unwrap().result;
        let m = run(&rubber("m", "Pa", 1.0, load)).unwrap().result;
        assert_eq!(mm.header.points, 20915);
        // Both certified to about 1e-13: the answers agree to far better
        // than the 1e-9 asked here.
        let same = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs();
        assert!(
            same(mm.approach * 1e-3, m.approach),
            "{} mm, {} m",
            mm.approach,
            m.approach
        );
        assert!(
            same(mm.max_pressure * 1e6, m.max_pressure),
            "{} MPa, {} Pa",
            mm.max_pressure,
            m.max_pressure
        );
        let hertz = m.reference.as_ref().unwrap().errors.max_pressure.unwrap();
        assert!(hertz.abs() < 1e-2, "peak {hertz:e} from Hertz");
    }
}
