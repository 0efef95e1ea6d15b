//! A run's stresses below the surface as numpy arrays: each body's section
//! (x against depth through its largest von Mises stress) and its profile
//! along depth below the peak pressure, each component an array of shape
//! `(len(x), len(depth))`; the maxima are in result.json's `subsurface`
//! block.

use elcon_analysis::subsurface::{Section, Subsurface};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// One component or measure of a stress tensor.
type Component = fn(&elcon_influence::Stress) -> f64;

/// The components a section's dict holds, by name.
const COMPONENTS: [(&str, Component); 8] = [
    ("sigma_x", |s| s.xx),
    ("sigma_y", |s| s.yy),
    ("sigma_z", |s| s.zz),
    ("tau_xy", |s| s.xy),
    ("tau_xz", |s| s.xz),
    ("tau_yz", |s| s.yz),
    ("von_mises", |s| s.von_mises()),
    ("tresca", |s| s.tresca()),
];

/// `{"y": float, "x": (n,), "depth": (m,), "sigma_x": (n, m), ...}`.
fn section<'py>(py: Python<'py>, s: &Section) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("y", s.y)?;
    d.set_item("x", PyArray1::from_slice(py, &s.xs))?;
    d.set_item("depth", PyArray1::from_slice(py, &s.depths))?;
    let (n, m) = (s.xs.len(), s.depths.len());
    for (name, of) in COMPONENTS {
        let values: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..m).map(|j| of(&s.stresses[i * m + j])).collect())
            .collect();
        d.set_item(name, PyArray2::from_vec2(py, &values)?)?;
    }
    Ok(d)
}

/// `{"body1": {"section": ..., "profile": ...} or None, "body2": ...}`: a
/// body without a field (rigid, a beam, a foundation) is None.
pub(crate) fn subsurface_arrays<'py>(
    py: Python<'py>,
    fields: &[Subsurface; 2],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (i, field) in fields.iter().enumerate() {
        let name = format!("body{}", i + 1);
        match field {
            Subsurface::Stresses(b) => {
                let body = PyDict::new(py);
                body.set_item("section", section(py, &b.section)?)?;
                body.set_item("profile", section(py, &b.profile)?)?;
                d.set_item(name, body)?;
            }
            Subsurface::NotApplicable(_) => d.set_item(name, py.None())?,
        }
    }
    Ok(d)
}
