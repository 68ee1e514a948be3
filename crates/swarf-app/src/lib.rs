//! swarf-app: the application layer. It reads job files (the TOML schema, [`job`]),
//! runs the pipeline plan -> position -> post -> verify -> rest -> cleanup
//! ([`plan_job()`], [`five_axis`], [`verify`] reading its programs with [`programs`]
//! and checking their holders with [`holder`],
//! [`cleanup`]), tabulates the comparison of paper 004 and thesis 000 ([`compare`]),
//! writes 3D views of verified programs ([`view`]) and runs the demo ([`demo`]). It calls the kernel crates; it does not compute
//! geometry. The `swarf` command line and the Python package are thin layers over it.

pub mod classify;
pub mod cleanup;
pub mod compare;
pub mod demo;
mod demo_page;
mod demo_rest;
pub mod drop_spin;
pub mod dsm;
pub mod edge_compare;
pub mod error;
pub mod five_axis;
pub mod gate;
pub mod holder;
pub mod inspect;
pub mod job;
pub mod job_reference;
pub mod model;
pub mod outputs;
pub mod plan;
pub mod plan_job;
pub mod plan_record;
mod plan_summary;
pub mod programs;
pub mod report;
pub mod rest;
pub mod sequence;
pub mod stock;
pub mod strategy;
pub mod verify;
pub mod view;

pub use error::{AppError, Result};
pub use job::Job;
pub use model::{FaceRef, LoadOptions, Model, load_model, load_model_with, load_part};
pub use outputs::Outputs;
pub use plan::{PlanInput, plan};
pub use plan_job::{Planned, plan_job, plan_model_toolpath};
pub use report::Reporter;
pub use strategy::Strategy;
