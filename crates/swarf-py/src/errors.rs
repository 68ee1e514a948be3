//! How swarf's errors reach Python.
//!
//! - Everything swarf reports about its input (files, jobs, tool specs, parameters,
//!   planning, verification) raises [`SwarfError`], a subclass of `ValueError`, with
//!   the message the command line prints: the chain of causes joined by `": "`, so
//!   that it names the file, the line and the field.
//! - Arguments the binding checks itself (array shapes and dtypes, non-finite
//!   numbers, face indices) raise a plain `ValueError` naming the argument and the
//!   first bad index.
//! - Work runs with the GIL released ([`detached`]); a panic in it (a bug) is caught
//!   there and raised as [`SwarfError`] too, so that none crosses into Python.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::panic::{AssertUnwindSafe, catch_unwind};

pyo3::create_exception!(
    swarf,
    SwarfError,
    PyValueError,
    "An error swarf reports about its input: a file, a job, a tool, a parameter, a program. \
     The message is the command line's: it names the file, the line and the field."
);

/// The message of `e` and its causes, joined by `": "` (as `swarf` prints
/// `anyhow`'s `{:#}`).
pub fn chain(e: &(dyn std::error::Error + 'static)) -> String {
    let mut text = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        text.push_str(": ");
        text.push_str(&s.to_string());
        source = s.source();
    }
    text
}

/// A swarf error as a Python [`SwarfError`].
pub fn swarf_err(e: impl std::error::Error + 'static) -> PyErr {
    SwarfError::new_err(chain(&e))
}

/// A message as a Python [`SwarfError`].
pub fn swarf_msg(msg: impl Into<String>) -> PyErr {
    SwarfError::new_err(msg.into())
}

/// A message as a Python `ValueError`.
pub fn value_err(msg: impl Into<String>) -> PyErr {
    PyValueError::new_err(msg.into())
}

/// Runs `f` with the GIL released (other Python threads run meanwhile; rayon uses
/// every core); a panic in `f` becomes a [`SwarfError`] naming it as a bug.
///
/// # Errors
/// What `f` returns, or the panic.
pub fn detached<T, F>(py: Python<'_>, f: F) -> PyResult<T>
where
    F: Send + FnOnce() -> PyResult<T>,
    T: Send,
{
    py.detach(|| match catch_unwind(AssertUnwindSafe(f)) {
        Ok(r) => r,
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| (*s).to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            Err(swarf_msg(format!(
                "internal error (a bug in swarf, please report it): {what}"
            )))
        }
    })
}

#[cfg(test)]
mod tests {
    use super::chain;

    #[derive(Debug)]
    struct Outer(std::io::Error);

    impl std::fmt::Display for Outer {
        fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            write!(f, "job.toml: cannot read the job file")
        }
    }

    impl std::error::Error for Outer {
        fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
            Some(&self.0)
        }
    }

    #[test]
    fn causes_are_joined_as_the_command_line_prints_them() {
        let e = Outer(std::io::Error::other("no such file"));
        assert_eq!(
            chain(&e),
            "job.toml: cannot read the job file: no such file"
        );
    }
}
