//! `swarf rest`: the rest material a finishing tool or job leaves, as regions
//! ([`crate::cleanup`] for the sources): `rest.json` (the regions), `rest.csv` (their
//! boundaries) and `rest.png` (the regions over the part), written as one set.

use crate::cleanup::{
    boundaries_csv, detect_after, part_mesh, read_parent, rest_json, source_name,
};
use crate::error::{AppError, Context, Result, bail};
use crate::model::{LoadOptions, load_model_with};
use crate::outputs::Outputs;
use crate::plan_job::part_arg;
use std::path::Path;
use swarf_geom::domain::excerpt;
use swarf_report::rest_picture::{RegionOutline, rest_png};
use swarf_rest::RestSource;
use swarf_rest::{Detection, RegionParams, Source, detect};
use swarf_sim::{Design, DesignSurface, Grid, Quiet};
use swarf_tool::Cutter;

/// Pixels along the longer side of the picture's height grid.
const PICTURE_CELLS: f64 = 800.0;

/// A rest detection as `swarf rest` asks for it.
#[derive(Debug, Clone, Copy)]
pub struct RestRequest<'a> {
    /// Design part (default: the parent job's).
    pub part: Option<&'a str>,
    /// Reference tool spec (instead of a parent job).
    pub reference: Option<&'a str>,
    /// Parent job file.
    pub job: Option<&'a Path>,
    /// Where the rest comes from.
    pub source: RestSource,
    /// Boundary operations.
    pub params: RegionParams,
    /// Machining tolerance, mm.
    pub tol: f64,
    /// Output directory.
    pub out: &'a Path,
}

/// What `swarf rest` found: the detection, the reference tool and the source.
#[derive(Debug)]
pub struct RestFound {
    /// The regions.
    pub detection: Detection,
    /// The tool whose rest it is.
    pub reference: Cutter,
    /// The source's name.
    pub source: &'static str,
}

/// Detects the rest `req` asks for and writes `rest.json`, `rest.csv` and `rest.png`
/// under `req.out`.
///
/// # Errors
/// Neither or both of a reference tool and a parent job; a part, job or tool that
/// cannot be read; a source the parent cannot give; the detection's errors; outputs
/// that cannot be written.
pub fn rest_request(req: &RestRequest<'_>) -> Result<RestFound> {
    let (found, part, mesh) = rest_detect(req)?;
    write_rest(&found, &part, &mesh, req.out)?;
    Ok(found)
}

/// Checks the numbers of a request against their domains, naming each as the flag
/// of `swarf rest` that gives it (`--merge`, `--min-area`, `--tol`).
///
/// # Errors
/// The first number outside its domain, with the domain and the nearest value that
/// fits.
pub fn check_flags(params: &RegionParams, tol: f64) -> Result<()> {
    for (name, value, domain) in params.domains() {
        domain
            .check_named(&format!("--{}", name.replace('_', "-")), value)
            .map_err(AppError::Message)?;
    }
    swarf_geom::domain::TOLERANCE
        .check_named("--tol", tol)
        .map_err(AppError::Message)?;
    Ok(())
}

/// [`rest_request`] without writing anything (`req.out` is not used): the detection,
/// the part as the request resolved it (the `part` of `rest.json`) and the mesh it
/// was detected on, for callers that take the regions as data (the Python package).
///
/// # Errors
/// As [`rest_request`], less the outputs.
pub fn rest_detect(req: &RestRequest<'_>) -> Result<(RestFound, String, swarf_geom::TriMesh)> {
    check_flags(&req.params, req.tol)?;
    let parent = match (req.reference, req.job) {
        (Some(_), Some(_)) | (None, None) => {
            bail!("expected one of --reference TOOL and --job PARENT.toml")
        }
        (None, Some(job)) => {
            let dir = job.parent().unwrap_or(Path::new("."));
            let rel = job
                .file_name()
                .map(|f| f.to_string_lossy().into_owned())
                .unwrap_or_default();
            Some(read_parent(&rel, dir, None)?)
        }
        (Some(_), None) => None,
    };
    let (part, opts) = match (req.part, &parent) {
        (Some(p), _) => (p.to_string(), LoadOptions::default()),
        (None, Some((job, dir))) => (part_arg(job, dir), job.load_options()),
        (None, None) => bail!("--part: expected the design part (or a parent --job that names it)"),
    };
    let model = load_model_with(&part, &opts)?;
    model.check_covers_xy(&part)?;
    let mesh = part_mesh(&model, req.tol).with_context(|| part.clone())?;
    let (detection, reference) = match (&parent, req.reference) {
        (Some((job, _)), _) => {
            let d = detect_after(job, &model, &mesh, req.source, (req.tol, &req.params))?;
            (d, job.tool)
        }
        (None, spec) => {
            let spec = spec.unwrap_or_default();
            if req.source != RestSource::Reference {
                bail!("--source {}: needs a parent --job", source_name(req.source));
            }
            let tool: Cutter = spec.parse().map_err(|e| {
                AppError::Message(format!("--reference {}: {e}", excerpt(spec, 60)))
            })?;
            (
                detect(&mesh, &tool, Source::Reference, req.tol, &req.params)?,
                tool,
            )
        }
    };
    let found = RestFound {
        detection,
        reference,
        source: source_name(req.source),
    };
    Ok((found, part, mesh.into_owned()))
}

/// `rest.json` of a detection: the regions ([`rest_json`]) with the part, the
/// reference tool and the source.
pub fn rest_report(f: &RestFound, part: &str) -> serde_json::Value {
    let mut json = rest_json(&f.detection);
    json["part"] = serde_json::json!(part);
    json["reference_tool"] = serde_json::json!(f.reference.to_string());
    json["source"] = serde_json::json!(f.source);
    json
}

/// Writes the three files of a detection (`rest.json`, `rest.csv`, `rest.png`) under
/// `out` as one set; `part` and `mesh` as [`rest_detect`] gives them.
///
/// # Errors
/// A picture that cannot be drawn; outputs that cannot be written.
pub fn write_rest(f: &RestFound, part: &str, mesh: &swarf_geom::TriMesh, out: &Path) -> Result<()> {
    let json = rest_report(f, part);
    let png = picture(f, part, mesh)?;
    let csv = boundaries_csv(&f.detection);
    let mut set = Outputs::new(out);
    set.write_json("rest.json", &json)?;
    set.write("rest.csv", csv.as_bytes())?;
    set.write("rest.png", &png)?;
    set.commit()
}

/// The regions over the part's relief (PNG bytes).
fn picture(f: &RestFound, part: &str, mesh: &swarf_geom::TriMesh) -> Result<Vec<u8>> {
    let (grid, heights) = relief_heights(mesh)?;
    let outlines: Vec<RegionOutline> = f
        .detection
        .regions
        .iter()
        .enumerate()
        .map(|(k, r)| RegionOutline {
            boundary: polygon_rings(&r.boundary),
            raw: r.raw.0.iter().flat_map(polygon_rings).collect(),
            label: (k + 1).to_string(),
        })
        .collect();
    let deepest = f
        .detection
        .regions
        .iter()
        .map(|r| r.depth)
        .fold(0.0, f64::max);
    let title = format!("rest after {} ({}): {}", f.reference, f.source, part);
    let footer = [format!(
        "{} regions, deepest {:.3} mm, {} samples",
        outlines.len(),
        deepest,
        f.detection.samples
    )];
    Ok(rest_png(&grid, &heights, &outlines, &title, &footer)?)
}

/// The part's heights seen from above on a grid of [`PICTURE_CELLS`] cells along
/// its longer side, for the relief under a picture.
///
/// # Errors
/// A mesh the height query refuses; a grid too large.
pub(crate) fn relief_heights(mesh: &swarf_geom::TriMesh) -> Result<(Grid, Vec<f64>)> {
    let surface = DesignSurface::new(Design::Mesh(mesh))?;
    let b = surface.bounds();
    let cell = (b.max.x - b.min.x).max(b.max.y - b.min.y) / PICTURE_CELLS;
    let grid = Grid::covering([b.min.x, b.min.y], [b.max.x, b.max.y], cell, 1 << 28)?;
    let heights = surface.heights(&grid, false, &Quiet).heights;
    Ok((grid, heights))
}

/// The rings of a polygon (outer first, then holes) as XY points, mm.
pub fn polygon_rings(p: &geo::Polygon<f64>) -> Vec<Vec<[f64; 2]>> {
    std::iter::once(p.exterior())
        .chain(p.interiors())
        .map(|r| r.coords().map(|c| [c.x, c.y]).collect())
        .collect()
}
