//! One file per subcommand.

pub mod batch;
pub mod classify;
pub mod compare;
pub mod demo;
pub mod drop;
pub mod dsm;
pub mod eval;
pub mod help;
pub mod inspect;
pub mod plan;
pub mod rest;
pub mod tessellate;
pub mod verify;
pub mod view;

use swarf_geom::domain::Domain;

/// Checks each `(flag, value, domain)`, the value in the units the flag is given in.
///
/// # Errors
/// The first value outside its domain, naming the flag, the range and the nearest
/// value that fits.
pub fn check_flags(flags: &[(&str, f64, Domain)]) -> anyhow::Result<()> {
    for &(flag, value, domain) in flags {
        domain
            .check_named(flag, value)
            .map_err(anyhow::Error::msg)?;
    }
    Ok(())
}

/// Slope angles given in degrees on the command line.
pub const SLOPE_DEG: Domain = Domain::new(0.0, 90.0, "degrees", "a slope angle");

/// Slope angles that must be above horizontal, degrees.
pub const STEEP_DEG: Domain = Domain::new(0.01, 90.0, "degrees", "a slope angle");
