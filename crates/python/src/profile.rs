//! A designed profile from Python: result.json's `design.profile` block
//! (elcon-report's `ProfileJson`) read back into elcon-design's `Profile`,
//! evaluated by elcon-design (`Profile::separations`), the same code that
//! designed and verified it. Nothing of the spline or the families is
//! written here.

use elcon_design::Profile;
use elcon_report::ProfileJson;
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;

use crate::errors::{DesignError, InputError};

/// A free profile's knots and their drops, as numpy arrays.
type Knots<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// A designed profile `y(s)`: the block it was read from and the profile
/// it defines.
#[pyclass(module = "elcon._elcon", name = "Profile", frozen)]
pub(crate) struct PyProfile {
    block: ProfileJson,
    profile: Profile,
}

#[pymethods]
impl PyProfile {
    /// The profile of a `design.profile` block, as JSON text.
    #[new]
    fn new(block: &str) -> PyResult<Self> {
        let block: ProfileJson = serde_json::from_str(block)
            .map_err(|e| InputError::new_err(format!("`profile`: not a design's profile: {e}")))?;
        let profile = block
            .profile()
            .map_err(|e| DesignError::new_err(e.to_string()))?;
        Ok(Self { block, profile })
    }

    /// The drop at each axial position of `s` (finite, the scene's length
    /// unit), as a float64 array of the same length.
    fn drops_at<'py>(
        &self,
        py: Python<'py>,
        s: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let s = s.as_slice()?;
        if let Some(bad) = s.iter().find(|v| !v.is_finite()) {
            return Err(InputError::new_err(format!(
                "`s`: positions must be finite (got {bad})"
            )));
        }
        let drops = self
            .profile
            .separations(s)
            .map_err(|e| DesignError::new_err(e.to_string()))?;
        Ok(PyArray1::from_vec(py, drops))
    }

    /// The family: "free", "quadratic", "polynomial", "circular-crown" or
    /// "logarithmic-crown" (the block's `family`).
    #[getter]
    fn family(&self) -> &'static str {
        self.block.family()
    }

    /// A free profile's knots and their drops; `None` for a family.
    fn knots<'py>(&self, py: Python<'py>) -> Option<Knots<'py>> {
        match &self.block {
            ProfileJson::Free { knots, drops, .. } => Some((
                PyArray1::from_slice(py, knots),
                PyArray1::from_slice(py, drops),
            )),
            _ => None,
        }
    }
}
