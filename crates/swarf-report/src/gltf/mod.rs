//! glTF 2.0 (GLB) export for 3D viewers (three.js, Blender, the Windows 3D viewer):
//! the design, the tool path, the cutter and the simulated stock.
//!
//! - [`glb`]: the GLB writer (one buffer, accessors, meshes, nodes, materials).
//! - [`part`]: the design's triangles (node `part`).
//! - [`toolpath`]: line sets `cuts`, `links`, `rapids` and five-axis `tool axes`.
//! - [`cutter`]: the cutter's profile revolved, placed at a pose (node `cutter`).
//! - [`stock`]: the dexel stock coloured by deviation, decimated with its height
//!   error stated (node `stock`).
//!
//! Coordinates are the part frame's, in millimetres, +z up (glTF has no units; one
//! unit is one millimetre here). Each scene is one file of its own, so that a viewer
//! loads and toggles them apart.

pub mod cutter;
pub mod glb;
pub mod part;
pub mod stock;
pub mod toolpath;

use crate::error::ReportError;
use glb::Glb;
pub use stock::{StockMesh, StockMeshOptions};
use swarf_geom::TriMesh;
use swarf_sim::Verification;
use swarf_tool::{Cutter, Pose};
use swarf_toolpath::Motion;

/// The bytes of `glb`, refused when the file would pass the GLB format's 4 GiB.
fn finish(glb: &Glb, what: &str) -> Result<Vec<u8>, ReportError> {
    let bytes = glb.to_bytes();
    if u32::try_from(bytes.len()).is_err() {
        return Err(ReportError::Write {
            path: format!("<{what}.glb>"),
            message: format!(
                "{} bytes: beyond the 4 GiB a GLB file can hold (use coarser cells)",
                bytes.len()
            ),
        });
    }
    Ok(bytes)
}

/// The design as a GLB scene (node `part`).
///
/// # Errors
/// A file beyond 4 GiB.
pub fn part_glb(mesh: &TriMesh) -> Result<Vec<u8>, ReportError> {
    let mut glb = Glb::new();
    part::add_part(&mut glb, mesh);
    finish(&glb, "part")
}

/// The program's tool path as a GLB scene (nodes `cuts`, `links`, `rapids`, and
/// `tool axes` half as long as the cutter's flutes (at most twice its diameter) for a
/// five-axis program).
///
/// # Errors
/// A file beyond 4 GiB.
pub fn toolpath_glb(motions: &[Motion], cutter: &Cutter) -> Result<Vec<u8>, ReportError> {
    let mut glb = Glb::new();
    toolpath::add_toolpath(
        &mut glb,
        motions,
        0.5 * cutter.length().min(4.0 * cutter.radius()),
    );
    finish(&glb, "toolpath")
}

/// The cutter at `pose` as a GLB scene (node `cutter`).
///
/// # Errors
/// A file beyond 4 GiB.
pub fn cutter_glb(cutter: &Cutter, pose: &Pose) -> Result<Vec<u8>, ReportError> {
    let mut glb = Glb::new();
    cutter::add_cutter(&mut glb, cutter, pose);
    finish(&glb, "cutter")
}

/// The simulated stock of `v` as a GLB scene (node `stock`) and what the mesh holds
/// (stride, counts, the stated height error).
///
/// # Errors
/// A file beyond 4 GiB.
pub fn stock_glb(
    v: &Verification,
    opts: &StockMeshOptions,
) -> Result<(Vec<u8>, StockMesh), ReportError> {
    let mut glb = Glb::new();
    let mesh = stock::add_stock(&mut glb, v, opts);
    Ok((finish(&glb, "stock")?, mesh))
}
