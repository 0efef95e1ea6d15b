//! Python values to the TOML a scene holds, and solutions to numpy arrays.

use elcon_analysis::{ContactSolution, PointSet};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

use crate::errors::InputError;

/// A Python value as the TOML value a scene would hold: dicts as tables,
/// lists, tuples and numpy arrays as arrays, numbers (numpy's too),
/// strings and booleans as themselves. NaN and infinities pass (the
/// scene's checks refuse them by field); `None` and other objects are
/// refused naming the key (`path`).
fn toml_value(v: &Bound<'_, PyAny>, path: &str) -> PyResult<toml::Value> {
    if v.is_none() {
        return Err(InputError::new_err(format!(
            "`{path}` = None: a scene has no None; leave the key out"
        )));
    }
    if let Ok(b) = v.cast::<PyBool>() {
        return Ok(toml::Value::Boolean(b.is_true()));
    }
    if v.is_instance_of::<PyInt>() {
        return v.extract::<i64>().map(toml::Value::Integer).map_err(|_| {
            InputError::new_err(format!("`{path}` = {v}: a whole number beyond 64 bits"))
        });
    }
    if let Ok(f) = v.cast::<PyFloat>() {
        return Ok(toml::Value::Float(f.value()));
    }
    if let Ok(s) = v.cast::<PyString>() {
        return Ok(toml::Value::String(s.to_string()));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        return toml_table(d, path).map(toml::Value::Table);
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let mut items = Vec::new();
        for (i, item) in v.try_iter()?.enumerate() {
            let item = item?;
            items.push(toml_value(&item, &format!("{path}[{i}]"))?);
        }
        return Ok(toml::Value::Array(items));
    }
    // numpy arrays and scalars: their Python values.
    if let Ok(list) = v.call_method0("tolist")
        && !list.is(v)
    {
        return toml_value(&list, path);
    }
    if let Ok(i) = v.extract::<i64>() {
        return Ok(toml::Value::Integer(i));
    }
    if let Ok(f) = v.extract::<f64>() {
        return Ok(toml::Value::Float(f));
    }
    let kind = v
        .get_type()
        .name()
        .map_or_else(|_| "value".to_string(), |n| n.to_string());
    Err(InputError::new_err(format!(
        "`{path}`: a {kind} has no form in a scene (numbers, strings, booleans, lists and dicts)"
    )))
}

/// A dict as a TOML table; `path` prefixes its keys in messages.
pub(crate) fn toml_table(d: &Bound<'_, PyDict>, path: &str) -> PyResult<toml::Table> {
    let mut table = toml::Table::new();
    for (k, v) in d.iter() {
        let key: String = k.extract().map_err(|_| {
            InputError::new_err(format!(
                "`{path}`: the key {k} is not a string (a scene's keys are names)"
            ))
        })?;
        let full = if path.is_empty() {
            key.clone()
        } else {
            format!("{path}.{key}")
        };
        table.insert(key, toml_value(&v, &full)?);
    }
    Ok(table)
}

/// TOML text of `table`.
pub(crate) fn toml_text(table: &toml::Table) -> PyResult<String> {
    toml::to_string(table)
        .map_err(|e| InputError::new_err(format!("cannot be written as TOML: {e}")))
}

/// TOML text of a scene's sections given as dicts (`[name]` for each
/// section given; those that are `None` left out).
pub(crate) fn sections_text(sections: &[(&str, Option<&Bound<'_, PyDict>>)]) -> PyResult<String> {
    let mut table = toml::Table::new();
    for &(name, dict) in sections {
        if let Some(d) = dict {
            table.insert(name.into(), toml::Value::Table(toml_table(d, name)?));
        }
    }
    toml_text(&table)
}

/// The per-point arrays of a solution, and the separations.
pub(crate) fn arrays<'py>(
    py: Python<'py>,
    points: &PointSet,
    solution: &ContactSolution,
    separation: &[f64],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("x", PyArray1::from_slice(py, &points.xs()))?;
    d.set_item("y", PyArray1::from_slice(py, &points.ys()))?;
    d.set_item("force", PyArray1::from_slice(py, &solution.forces))?;
    d.set_item("pressure", PyArray1::from_slice(py, &solution.pressures))?;
    d.set_item("gap", PyArray1::from_slice(py, &solution.gaps))?;
    d.set_item("separation", PyArray1::from_slice(py, separation))?;
    Ok(d)
}
