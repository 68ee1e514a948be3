//! `swarf classify`: the steep, horizontal and other areas of a part (thesis 002
//! §6.1, [`swarf_path::classify`]): `classify.json` (parameters, areas and counts
//! per class) and `classify.png` (the classes over the part), written as one set.

use crate::cleanup::part_mesh;
use crate::error::{Context, Result};
use crate::model::load_model;
use crate::outputs::Outputs;
use crate::rest::{polygon_rings, relief_heights};
use serde_json::json;
use std::path::Path;
use swarf_geom::TriMesh;
use swarf_path::PathError;
use swarf_path::classify::{Classification, ClassifyParams, SurfaceClass, classify};
use swarf_report::classify_picture::{ClassRings, classify_png};

/// A classification as `swarf classify` asks for it.
#[derive(Debug, Clone, Copy)]
pub struct ClassifyRequest<'a> {
    /// The part: a part file, a mesh file or a built-in name.
    pub part: &'a str,
    /// Thresholds and cell size (radians, mm).
    pub params: ClassifyParams,
    /// Chordal tolerance for tessellating a parametric part, mm (a tenth of it is
    /// used, as for the other commands).
    pub tol: f64,
    /// Output directory.
    pub out: &'a Path,
}

/// Classifies the part `req` names and writes `classify.json` and `classify.png`
/// under `req.out`.
///
/// # Errors
/// A part that cannot be read or tessellated; parameters out of range (naming the
/// part and the flag: `--steep-angle`, `--flat-angle` or `--cell`); outputs that
/// cannot be written.
pub fn classify_request(req: &ClassifyRequest<'_>) -> Result<Classification> {
    let model = load_model(req.part)?;
    model.check_covers_xy(req.part)?;
    let mesh = part_mesh(&model, req.tol).with_context(|| req.part.to_string())?;
    // The parameters came from `swarf classify`'s flags: name the flag.
    let c = classify(&mesh, &req.params)
        .map_err(|e| match e {
            PathError::InvalidParameter { field, message } => PathError::InvalidParameter {
                field: field
                    .strip_prefix("classify.")
                    .map_or(field.clone(), |f| format!("--{}", f.replace('_', "-"))),
                message,
            },
            e => e,
        })
        .with_context(|| req.part.to_string())?;
    let png = picture(&c, req, &mesh)?;
    let mut set = Outputs::new(req.out);
    set.write_json("classify.json", &classify_json(&c, req))?;
    set.write("classify.png", &png)?;
    set.commit()?;
    Ok(c)
}

/// The summary: part, parameters (degrees and mm), counts, and per class its XY and
/// surface areas, triangles and cells.
pub fn classify_json(c: &Classification, req: &ClassifyRequest<'_>) -> serde_json::Value {
    let p = &req.params;
    let mut classes = serde_json::Map::new();
    for class in SurfaceClass::ALL {
        let r = c.region(class);
        classes.insert(
            class.name().into(),
            json!({
                "xy_area_mm2": r.xy_area,
                "surface_area_mm2": r.surface_area,
                "triangles": r.triangles,
                "cells": r.cells,
                "polygons": r.region.0.len(),
            }),
        );
    }
    json!({
        "part": req.part,
        "parameters": {
            "steep_angle_deg": swarf_geom::units::degrees(p.steep_angle),
            "flat_angle_deg": swarf_geom::units::degrees(p.flat_angle),
            "cell_mm": p.cell,
        },
        "triangles": c.triangle_classes.len(),
        "degenerate": c.degenerate,
        "facing_down": c.facing_down,
        "grid": { "nx": c.grid.nx, "ny": c.grid.ny, "origin": c.grid.origin },
        "classes": classes,
    })
}

/// The classes over the part's relief (PNG bytes).
fn picture(c: &Classification, req: &ClassifyRequest<'_>, mesh: &TriMesh) -> Result<Vec<u8>> {
    let (grid, heights) = relief_heights(mesh)?;
    let layer = |class: SurfaceClass| ClassRings {
        name: class.name().into(),
        rings: c
            .region(class)
            .region
            .0
            .iter()
            .flat_map(polygon_rings)
            .collect(),
    };
    let classes = SurfaceClass::ALL.map(layer);
    let p = &req.params;
    let title = format!(
        "steep above {} deg, horizontal below {} deg: {}",
        swarf_geom::units::degrees(p.steep_angle),
        swarf_geom::units::degrees(p.flat_angle),
        req.part
    );
    let footer: Vec<String> = SurfaceClass::ALL
        .iter()
        .map(|&class| {
            let r = c.region(class);
            format!(
                "{}: {:.1} mm2 seen from above, {:.1} mm2 of surface, {} triangles",
                class.name(),
                r.xy_area,
                r.surface_area,
                r.triangles
            )
        })
        .chain(std::iter::once(format!(
            "Go board {} x {} cells of {} mm (thesis 002, 6.1)",
            c.grid.nx, c.grid.ny, p.cell
        )))
        .collect();
    Ok(classify_png(&grid, &heights, &classes, &title, &footer)?)
}
