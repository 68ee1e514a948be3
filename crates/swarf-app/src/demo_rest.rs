//! The demo's cleanup section (thesis 002 on the built-in fillet pocket): finish
//! with a ball d=12, detect the rest it leaves, clean it up with a ball d=4 in
//! follow-pocket rings, verify the finish alone and the finish followed by the
//! cleanup on one dexel stock, and tabulate the rest before and after: the excess
//! the dexel measures along the design normals, and the rest regions found again on
//! the in-process stock after each.

use crate::error::Result;
use crate::job::Job;
use crate::model::load_model;
use crate::outputs::Outputs;
use crate::plan_job::plan_job;
use crate::report::Reporter;
use crate::verify::{context, verify_and_write};
use std::io::Write;
use swarf_rest::{RegionParams, Source, detect};
use swarf_sim::Stage;
use swarf_sim::{StockSpec, Verification, VerifyOptions};

/// The finishing and cleanup jobs of the section (`jobs/fillet-pocket-*.toml`).
const JOBS: [(&str, &str); 2] = [
    (
        "fillet-pocket-finish.toml",
        include_str!("../../../jobs/fillet-pocket-finish.toml"),
    ),
    (
        "fillet-pocket-cleanup.toml",
        include_str!("../../../jobs/fillet-pocket-cleanup.toml"),
    ),
];

/// Dexel cell of the section's verifications, mm.
const CELL: f64 = 0.1;

/// Runs the section into `out` (the demo's `rest` directory), printing its table
/// to `text`; the verification summary of each of its checks, by the stem of its
/// files (`finish`, `finish+cleanup`).
///
/// # Errors
/// A job that fails; an output that cannot be written.
pub fn cleanup_section(
    out: &mut Outputs,
    text: &mut dyn Write,
    reporter: &dyn Reporter,
) -> Result<Vec<(String, String)>> {
    let dir = out.dir().to_path_buf();
    for (name, job_text) in JOBS {
        out.write(name, job_text.as_bytes())?;
    }
    let mut cutters = Vec::new();
    for (name, job_text) in JOBS {
        let job = Job::parse(job_text, name)?;
        let summary = plan_job(&job, &dir, out, reporter)?;
        let rest = &summary["rest"]["regions"];
        writeln!(
            text,
            "{name}: {} passes, {:.0} mm cutting, {:.1} min{}",
            summary["passes"],
            summary["cutting_length_mm"].as_f64().unwrap_or(f64::NAN),
            summary["estimated_time_s"].as_f64().unwrap_or(f64::NAN) / 60.0,
            rest.as_array()
                .map(|r| format!(", cleaning {} rest regions", r.len()))
                .unwrap_or_default()
        )?;
        cutters.push((job.output.gcode.clone().unwrap_or_default(), job.tool));
    }
    let model = load_model("builtin:fillet-pocket")?;
    let programs = cutters
        .iter()
        .map(|(file, _)| out.read_program(file))
        .collect::<Result<Vec<_>>>()?;
    let opts = VerifyOptions {
        cell: Some(CELL),
        stock: StockSpec::Box { top: None },
        along_normals: true,
        ..VerifyOptions::default()
    };
    writeln!(
        text,
        "\n| programs | excess cells | worst excess mm | gouge cells | rest regions on the stock | verify s |\n|---|---|---|---|---|---|"
    )?;
    let mut summaries = Vec::new();
    for (n, prefix) in [(1, "finish."), (2, "finish+cleanup.")] {
        let stages: Vec<Stage<'_>> = programs[..n]
            .iter()
            .zip(&cutters)
            .map(|(program, (_, cutter))| Stage { program, cutter })
            .collect();
        let ctx = context("builtin:fillet-pocket", &stages, &opts);
        let start = std::time::Instant::now();
        let v = verify_and_write(&model, &stages, &opts, (&mut *out, prefix), &ctx, reporter)?;
        let regions = stock_regions(&model, &v, &cutters[0].1)?;
        let d = &v.deviation.summary;
        let names: Vec<&str> = cutters[..n].iter().map(|(f, _)| f.as_str()).collect();
        writeln!(
            text,
            "| {} | {} | {:.3} | {} | {regions} | {:.1} |",
            names.join(" + "),
            d.excess.cells,
            d.excess.worst,
            d.gouge.cells,
            start.elapsed().as_secs_f64()
        )?;
        summaries.push((
            prefix.trim_end_matches('.').to_string(),
            format!(
                "{}: {} cells of excess (worst {:.3} mm), {} gouge cells, {regions} rest \
                 regions found again on the stock",
                names.join(" + "),
                d.excess.cells,
                d.excess.worst,
                d.gouge.cells
            ),
        ));
    }
    writeln!(
        text,
        "pictures: {}/*.deviation.png, *.toolpath.png",
        dir.display()
    )?;
    Ok(summaries)
}

/// The rest regions found on the in-process stock of `v` (threshold: the
/// verification's tolerance plus the finishing scallop limit).
fn stock_regions(
    model: &crate::model::Model,
    v: &Verification,
    reference: &swarf_tool::Cutter,
) -> Result<usize> {
    let mesh = crate::cleanup::part_mesh(model, v.deviation.summary.tol)?;
    let source = Source::Stock {
        grid: &v.grid,
        excess: &v.deviation.values,
        design: &v.design.heights,
    };
    let params = RegionParams {
        threshold: 2.0 * v.deviation.summary.tol,
        ..RegionParams::default()
    };
    Ok(
        detect(&mesh, reference, source, v.deviation.summary.tol, &params)?
            .regions
            .len(),
    )
}
