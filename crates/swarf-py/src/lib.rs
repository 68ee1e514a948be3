//! swarf-py: the `swarf` Python package's native module (`swarf._swarf`), built with
//! PyO3 and rust-numpy by maturin (`pip install ./python`).
//!
//! A thin layer over the library the command line uses: every function calls the
//! same swarf-app, swarf-io, swarf-tool and swarf-geom entry points as the matching
//! `swarf` subcommand, so the numbers are the command line's, bit for bit. Nothing
//! here computes geometry; this crate converts arguments and results:
//!
//! - [`arrays`]: numpy arrays in and out, checked (shape, dtype, finite numbers,
//!   index ranges) with a `ValueError` naming the argument and the first bad index;
//! - [`errors`]: swarf's errors as `SwarfError` (a `ValueError`) with the command
//!   line's messages; work runs with the GIL released, and a panic is caught there;
//! - [`model`]: parts and meshes (`load`, `Part`, `Mesh`), patch evaluation on arrays
//!   of `(u, v)` (`swarf eval`), tessellation (`swarf tessellate`);
//! - [`tool`]: `Tool` from a spec string or keyword arguments;
//! - [`mod@drop`]: drop-cutter heights on every core (`swarf drop`);
//! - [`job`], [`plan`]: jobs from files, TOML text or dicts, planned as arrays plus
//!   the summary, G-code and APT CL (`swarf plan`); waterline and raster passes;
//! - [`loaded`]: a job's part passed in already loaded (`plan(job, part=...)`),
//!   held to the job's reading options;
//! - [`sequence`]: sequence jobs (stock to part, several tools) planned into their
//!   report, program and rest cells (`swarf plan` of a sequence);
//! - [`verify`]: the report and the deviation grid (`swarf verify`);
//! - [`rest`]: rest regions as polygons (`swarf rest`);
//! - [`ocl`]: the native half of `swarf.ocl`, the OpenCAMLib-compatible layer
//!   (waterline levels, single-triangle drops).
//!
//! Units: mm and radians inside, degrees where the job file and the command line
//! take degrees.

pub mod arrays;
pub mod drop;
pub mod errors;
pub mod job;
pub mod loaded;
pub mod model;
pub mod ocl;
pub mod plan;
pub mod rest;
pub mod sequence;
pub mod tool;
pub mod verify;

use pyo3::prelude::*;

/// The native module, `swarf._swarf`; the package `swarf` re-exports it.
#[pymodule]
fn _swarf(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("SwarfError", py.get_type::<errors::SwarfError>())?;
    m.add("FEATURES", drop::FEATURES.to_vec())?;
    m.add("MOVE_RAPID", plan::MOVE_RAPID)?;
    m.add("MOVE_FEED", plan::MOVE_FEED)?;
    m.add_class::<model::Part>()?;
    m.add_class::<model::Mesh>()?;
    m.add_class::<tool::Tool>()?;
    m.add_class::<drop::Dropper>()?;
    m.add_class::<drop::DropContacts>()?;
    m.add_class::<job::Job>()?;
    m.add_class::<plan::Plan>()?;
    m.add_class::<sequence::SequencePlan>()?;
    m.add_class::<verify::Verification>()?;
    m.add_class::<rest::Rest>()?;
    m.add_class::<rest::RestRegion>()?;
    m.add_function(wrap_pyfunction!(model::load, m)?)?;
    m.add_function(wrap_pyfunction!(drop::drop, m)?)?;
    m.add_function(wrap_pyfunction!(plan::plan, m)?)?;
    m.add_function(wrap_pyfunction!(plan::waterline, m)?)?;
    m.add_function(wrap_pyfunction!(plan::raster, m)?)?;
    m.add_function(wrap_pyfunction!(verify::verify, m)?)?;
    m.add_function(wrap_pyfunction!(rest::rest, m)?)?;
    m.add_class::<ocl::OclWaterline>()?;
    m.add_function(wrap_pyfunction!(ocl::triangle_drop_at, m)?)?;
    Ok(())
}
