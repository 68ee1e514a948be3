//! numpy arrays in and out: the checks every array argument passes (shape, dtype,
//! finite numbers within the coordinate domain, index ranges), each failure a
//! `ValueError` naming the argument and the first bad index.

use crate::errors::value_err;
use numpy::ndarray::{Array1, Array2};
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArrayDescrMethods, PyArrayMethods, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use swarf_geom::domain::COORDINATE;

/// `obj` as a numpy array: arrays as they are; lists, tuples and other sequences
/// through `numpy.asarray` with `dtype` (so that `[[0, 1], [2, 3]]` is accepted).
fn as_array<'py>(
    arg: &str,
    obj: &Bound<'py, PyAny>,
    dtype: &str,
) -> PyResult<Bound<'py, PyUntypedArray>> {
    if let Ok(a) = obj.cast::<PyUntypedArray>() {
        return Ok(a.clone());
    }
    let np = obj.py().import("numpy")?;
    let converted = np
        .call_method1("asarray", (obj, dtype))
        .map_err(|e| value_err(format!("{arg}: expected an array of numbers: {e}")))?;
    converted
        .cast_into::<PyUntypedArray>()
        .map_err(|_| value_err(format!("{arg}: expected an array of numbers")))
}

/// Describes an array's dtype and shape for messages: `an array of dtype float32 and
/// shape (4, 2)`.
fn describe(a: &Bound<'_, PyUntypedArray>) -> String {
    let shape: Vec<String> = a.shape().iter().map(ToString::to_string).collect();
    let shape = match shape.len() {
        1 => format!("({},)", shape[0]),
        _ => format!("({})", shape.join(", ")),
    };
    let dtype = a
        .dtype()
        .str()
        .map_or_else(|_| "?".to_string(), |s| s.to_string());
    format!("an array of dtype {dtype} and shape {shape}")
}

/// Checks the shape `(rows, K)` of an array argument (`rows` names the row count in
/// the message: `N`, `M`).
fn check_rows<const K: usize>(
    arg: &str,
    a: &Bound<'_, PyUntypedArray>,
    what: &str,
    rows: &str,
) -> PyResult<()> {
    if a.ndim() != 2 || a.shape()[1] != K {
        return Err(value_err(format!(
            "{arg}: expected {what} of shape ({rows}, {K}), found {}",
            describe(a)
        )));
    }
    Ok(())
}

/// An `(N, K)` float64 array argument as rows, every number finite and within the
/// coordinate domain (±1e6 mm).
///
/// # Errors
/// `ValueError` naming `arg`: another dtype or shape; the first row with a
/// non-finite or out-of-domain number.
pub fn coordinate_rows<const K: usize>(
    arg: &str,
    obj: &Bound<'_, PyAny>,
) -> PyResult<Vec<[f64; K]>> {
    let rows = float_rows::<K>(arg, obj)?;
    for (i, row) in rows.iter().enumerate() {
        for (k, &x) in row.iter().enumerate() {
            COORDINATE
                .check(x)
                .map_err(|m| value_err(format!("{arg}[{i}, {k}]: {m}")))?;
        }
    }
    Ok(rows)
}

/// An `(N, K)` float64 array argument as rows, every number finite.
///
/// # Errors
/// `ValueError` naming `arg`: another dtype or shape; the first row with a
/// non-finite number.
pub fn float_rows<const K: usize>(arg: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec<[f64; K]>> {
    let a = as_array(arg, obj, "float64")?;
    let what = "a float64 array";
    if !a.dtype().is_equiv_to(&numpy::dtype::<f64>(obj.py())) {
        return Err(value_err(format!(
            "{arg}: expected {what} of shape (N, {K}), found {} (convert it with .astype(numpy.float64))",
            describe(&a)
        )));
    }
    check_rows::<K>(arg, &a, what, "N")?;
    let typed = a.cast::<PyArray2<f64>>()?.readonly();
    let view = typed.as_array();
    let mut out = Vec::with_capacity(view.nrows());
    for (i, r) in view.rows().into_iter().enumerate() {
        let mut row = [0.0; K];
        for (k, (o, &x)) in row.iter_mut().zip(r.iter()).enumerate() {
            if !x.is_finite() {
                return Err(value_err(format!(
                    "{arg}[{i}, {k}]: {x} is not a finite number"
                )));
            }
            *o = x;
        }
        out.push(row);
    }
    Ok(out)
}

/// An `(M, 3)` integer array of vertex indices, each in `0..vertices`.
///
/// # Errors
/// `ValueError` naming `arg`: a dtype that is not an integer, another shape, the
/// first index that is negative or not below `vertices`.
pub fn index_rows(arg: &str, obj: &Bound<'_, PyAny>, vertices: usize) -> PyResult<Vec<[u32; 3]>> {
    let a = as_array(arg, obj, "int64")?;
    let kind = a.dtype().kind();
    if kind != b'i' && kind != b'u' {
        return Err(value_err(format!(
            "{arg}: expected an integer array of shape (M, 3), found {}",
            describe(&a)
        )));
    }
    check_rows::<3>(arg, &a, "an integer array", "M")?;
    let wide = if kind == b'u' { "uint64" } else { "int64" };
    let wide = a.call_method1("astype", (wide,))?;
    if kind == b'u' {
        let typed = wide.cast::<PyArray2<u64>>()?.readonly();
        checked_indices(arg, typed.as_array().rows(), vertices)
    } else {
        let typed = wide.cast::<PyArray2<i64>>()?.readonly();
        checked_indices(arg, typed.as_array().rows(), vertices)
    }
}

/// The rows of an index array, each index checked to be in `0..vertices`.
fn checked_indices<'a, T>(
    arg: &str,
    rows: impl IntoIterator<Item = numpy::ndarray::ArrayView1<'a, T>>,
    vertices: usize,
) -> PyResult<Vec<[u32; 3]>>
where
    T: Copy + Into<i128> + std::fmt::Display + 'a,
{
    let mut out = Vec::new();
    for (i, r) in rows.into_iter().enumerate() {
        let mut row = [0u32; 3];
        for (k, (o, &x)) in row.iter_mut().zip(r.iter()).enumerate() {
            let wide: i128 = x.into();
            if wide < 0 || wide >= vertices as i128 {
                return Err(value_err(format!(
                    "{arg}[{i}, {k}]: vertex index {x} out of range: expected 0 to {} \
                     ({vertices} vertices)",
                    vertices as i128 - 1
                )));
            }
            *o = wide as u32;
        }
        out.push(row);
    }
    Ok(out)
}

/// Rows of `K` numbers as an `(N, K)` float64 array.
pub fn rows_out<'py, const K: usize>(
    py: Python<'py>,
    rows: &[[f64; K]],
) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = rows.iter().flatten().copied().collect();
    grid_out(py, flat, rows.len(), K)
}

/// `values` (row-major, `rows x cols`) as a 2D float64 array.
pub fn grid_out(
    py: Python<'_>,
    values: Vec<f64>,
    rows: usize,
    cols: usize,
) -> Bound<'_, PyArray2<f64>> {
    match Array2::from_shape_vec((rows, cols), values) {
        Ok(a) => a.into_pyarray(py),
        Err(_) => PyArray2::zeros(py, [0, cols], false),
    }
}

/// A vector as a 1D array.
pub fn vec_out<T: numpy::Element>(py: Python<'_>, values: Vec<T>) -> Bound<'_, PyArray1<T>> {
    Array1::from_vec(values).into_pyarray(py)
}
