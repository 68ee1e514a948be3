//! The demo (`swarf demo [--out DIR]`): the main job on the built-in shared parts.
//!
//! 1. Inspects and tessellates every built-in part (STL within 0.01 mm).
//! 2. Plans the shipped example jobs (paper 004's experiment on wave.toml: ball r = 4,
//!    h = 0.15, tolerance 0.01, feed 300, spindle 1500; iso-parametric, iso-planar,
//!    iso-scallop, and the drop-cutter raster on the tessellated wave), writing their
//!    G-code, APT CL, pose CSV and JSON summaries.
//! 3. Verifies each program on a dexel stock and prints paper 004's Table 1 for our
//!    tool paths (`compare.md`, `compare.json`, deviation and tool path pictures).
//! 4. Thesis 000 ch. 8 on die.toml: the toroidal cutter R = 12.7, r = 6.35 fed 60
//!    degrees off X at a cross feed of 3.5 mm, inclined at alpha = 3 and 6 degrees and
//!    with the automatic gouge-free lead; each planned (five-axis G-code for the A/C
//!    trunnion, APT CL, summary with the sectioning gouge report) and verified on a
//!    dexel stock through its CL (`die/die.md`, pictures beside it).
//! 5. Thesis 002 on the built-in fillet pocket: finish, detect the rest, clean it
//!    up, verify both on one stock and tabulate the rest before and after
//!    (`rest/`, `demo_rest.rs`).
//! 6. Paper 003 on the two edge parts: the shipped drop-and-spin job (bull d = 12,
//!    r = 2, four passes per band, five-axis G-code for the A/C trunnion), and the
//!    snug drop-and-spin passes against the best three-axis pass and inclined
//!    single-point positioning along the same edge, cut on a dexel stock through
//!    their CL (`edges/edges.md`, `edges/edges.json`; [`crate::edge_compare`]).
//!
//! 7. Thesis 002 §4.1 on the fillet pocket: the shipped sequence job (adaptive
//!    roughing, rest roughing, finishing and cleanup from a box on one in-process
//!    stock, one program with its tool changes; `sequence/`, [`crate::sequence`]).
//!
//! Every program verified in steps 3 and 4 also gets its 3D view (`*.view/`: GLB
//! files, `view.json`, and the viewer page where it has been built; [`crate::view`]).
//!
//! Each section ends with the wall time it took. The edge comparison and the
//! sequence also get bar charts (`edges/*.left.png`, `sequence/stock.png`). The
//! whole run is written again as one page, `index.html` (every table, picture,
//! verification summary, 3D view link and section time; `demo_page.rs`), staged
//! with the rest and committed with it. The jobs are embedded so that the demo needs
//! no files; their parts and machine are built-in.

use crate::compare::{compare_all_views, five_axis_markdown, markdown};
use crate::demo_page::{Sections, program_blocks, row_summary};
use crate::error::{Context, Result};
use crate::inspect::{patch_text, summarise_patches};
use crate::job::Job;
use crate::outputs::Outputs;
use crate::plan_job::plan_job;
use crate::report::Reporter;
use crate::verify::SimSettings;
use std::io::Write;
use std::path::Path;
use swarf_report::chart::{Chart, Series};
use swarf_report::html::{Block, Figure};

/// Chordal tolerance of the demo tessellations, mm.
const DEMO_TOL: f64 = 0.01;

/// The example jobs shipped in `jobs/`.
const JOBS: [(&str, &str); 5] = [
    (
        "wave-iso-parametric.toml",
        include_str!("../../../jobs/wave-iso-parametric.toml"),
    ),
    (
        "wave-iso-planar.toml",
        include_str!("../../../jobs/wave-iso-planar.toml"),
    ),
    (
        "wave-iso-scallop.toml",
        include_str!("../../../jobs/wave-iso-scallop.toml"),
    ),
    (
        "wave-raster.toml",
        include_str!("../../../jobs/wave-raster.toml"),
    ),
    (
        "wave-steep-shallow.toml",
        include_str!("../../../jobs/wave-steep-shallow.toml"),
    ),
];

/// Thesis 000 ch. 8 on the die (`jobs/die-*.toml`).
const DIE_JOBS: [(&str, &str); 3] = [
    (
        "die-inclined-3.toml",
        include_str!("../../../jobs/die-inclined-3.toml"),
    ),
    (
        "die-inclined-6.toml",
        include_str!("../../../jobs/die-inclined-6.toml"),
    ),
    (
        "die-gouge-free.toml",
        include_str!("../../../jobs/die-gouge-free.toml"),
    ),
];

/// Paper 003's job on the concave edge part (`jobs/edge-concave-drop-spin.toml`).
const DROP_SPIN_JOB: &str = include_str!("../../../jobs/edge-concave-drop-spin.toml");

/// Thesis 002 §4.1 on the fillet pocket: from a box to the part in one job
/// (`jobs/fillet-pocket-sequence.toml`).
const SEQUENCE_JOB: &str = include_str!("../../../jobs/fillet-pocket-sequence.toml");

/// The demo's sections (for the progress of [`demo`]).
const DEMO_SECTIONS: usize = 7;

/// Runs the demo into the directory `dir`, writing what it does to `text`, and its
/// page (`index.html`: its tables, pictures, summaries, 3D view links and section
/// times, [`swarf_report::html`]). Every file is staged and the whole set
/// is renamed into place at the end.
///
/// # Errors
/// An output that cannot be written; any failure of a job (none is expected: the
/// jobs and parts are built in).
pub fn demo(dir: &Path, text: &mut dyn Write, reporter: &dyn Reporter) -> Result<()> {
    let start = std::time::Instant::now();
    let mut outputs = Outputs::new(dir);
    let out = &mut outputs;
    let mut s = Sections {
        text,
        done: Vec::new(),
    };
    reporter.job(0, DEMO_SECTIONS, "demo: parts");
    s.run("parts", |t| tessellate_parts(out, t))?;
    reporter.job(1, DEMO_SECTIONS, "demo: tool paths");
    let mut paths = Vec::new();
    s.run("tool paths (paper 004 on wave.toml)", |t| {
        tool_paths(out, t, reporter, &mut paths)
    })?;
    reporter.job(2, DEMO_SECTIONS, "demo: verification");
    s.run(
        "verification (dexel simulation against the design; paper 004, Table 1)",
        |t| verification(out, t, reporter, &paths),
    )?;
    reporter.job(3, DEMO_SECTIONS, "demo: five-axis");
    s.run(
        "five-axis (thesis 000 ch. 8 on die.toml), verified by dexel through the APT CL",
        |t| die(out, t, reporter),
    )?;
    reporter.job(4, DEMO_SECTIONS, "demo: rest and cleanup");
    s.run(
        "rest material and cleanup (thesis 002 on the built-in fillet pocket)",
        |t| {
            let done = out.in_dir("rest", |out| {
                crate::demo_rest::cleanup_section(out, t, reporter)
            })?;
            Ok(done
                .iter()
                .flat_map(|(stem, summary)| program_blocks(out, "rest", stem, summary))
                .collect())
        },
    )?;
    reporter.job(5, DEMO_SECTIONS, "demo: drop and spin");
    s.run(
        "drop and spin at the common edge (paper 003 on the edge parts)",
        |t| edges(out, t, reporter),
    )?;
    reporter.job(6, DEMO_SECTIONS, "demo: stock to part");
    s.run(
        "from stock to part (thesis 002 §4.1 on the fillet pocket: rough, rest-rough, finish, clean up)",
        |t| sequence(out, t),
    )?;
    reporter.jobs_done();
    let views = views_line(dir);
    writeln!(s.text, "\n{views}")?;
    let total = start.elapsed().as_secs_f64();
    crate::demo_page::stage_page(out, s.done, total)?;
    outputs.commit()?;
    writeln!(
        s.text,
        "\nall results in {} ({total:.1} s); open {}",
        dir.display(),
        dir.join("index.html").display()
    )?;
    Ok(())
}

/// Plans the shipped example jobs (staged under `jobs/`, their paths pushed to
/// `paths`) and prints their figures.
fn tool_paths(
    out: &mut Outputs,
    text: &mut dyn Write,
    reporter: &dyn Reporter,
    paths: &mut Vec<std::path::PathBuf>,
) -> Result<Vec<Block>> {
    let mut links = Vec::new();
    for (name, job_text) in JOBS {
        let job = Job::parse(job_text, name)?;
        let summary = plan_job(&job, Path::new("."), out, reporter)?;
        writeln!(
            text,
            "{name}: {} passes, {:.0} mm cutting, {:.1} min, predicted scallop <= {:.4} mm",
            summary["passes"],
            summary["cutting_length_mm"].as_f64().unwrap_or(f64::NAN),
            summary["estimated_time_s"].as_f64().unwrap_or(f64::NAN) / 60.0,
            summary["report"]["predicted_max_scallop"]
                .as_f64()
                .unwrap_or(f64::NAN),
        )?;
        let rel = format!("jobs/{name}");
        out.write(&rel, job_text.as_bytes())?;
        paths.push(out.path(&rel));
        links.push((rel, name.to_string()));
        for file in [&job.output.gcode, &job.output.cl, &job.output.summary]
            .into_iter()
            .flatten()
        {
            if out.is_staged(file) {
                links.push((file.clone(), file.clone()));
            }
        }
    }
    Ok(vec![Block::Links(links)])
}

/// Verifies the planned wave programs (`compare/`), prints Table 1 and says where
/// strategies coincide.
fn verification(
    out: &mut Outputs,
    text: &mut dyn Write,
    reporter: &dyn Reporter,
    paths: &[std::path::PathBuf],
) -> Result<Vec<Block>> {
    let (rows, _) = out.in_dir("compare", |out| {
        compare_all_views(paths, &SimSettings::default(), out, reporter, true)
    })?;
    write!(text, "{}", markdown(&rows))?;
    let mut blocks = Vec::new();
    for note in crate::demo_page::coinciding(&rows, "wave") {
        writeln!(text, "{note}")?;
        blocks.push(Block::Note(note));
    }
    for (path, row) in paths.iter().zip(&rows) {
        let stem = stem_of(path);
        blocks.extend(program_blocks(out, "compare", &stem, &row_summary(row)));
    }
    blocks.push(Block::Links(
        ["compare.md", "compare.json"]
            .map(|f| (format!("compare/{f}"), f.to_string()))
            .to_vec(),
    ));
    Ok(blocks)
}

/// The file stem of `path`.
fn stem_of(path: &Path) -> String {
    path.file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned())
}

/// Where the 3D views are (the page of each is embedded in swarf).
fn views_line(dir: &Path) -> String {
    format!(
        "3D views: {}/compare/*.view/index.html, die/*.view/index.html (open through a web server on \
         127.0.0.1, as `swarf view --serve` does; browsers do not run them from file://)",
        dir.display()
    )
}

/// Plans the shipped sequence job into `out/sequence` and prints its operations.
fn sequence(out: &mut Outputs, text: &mut dyn Write) -> Result<Vec<Block>> {
    let name = "fillet-pocket-sequence.toml";
    let seq = crate::sequence::Sequence::parse(SEQUENCE_JOB, name, Path::new("."))?;
    let dir = out.path("sequence");
    out.write(dir.join(name), SEQUENCE_JOB.as_bytes())?;
    let report = out.in_dir("sequence", |out| {
        crate::sequence::plan_sequence(&seq, Path::new("."), out)
    })?;
    for line in report.lines() {
        writeln!(text, "{line}")?;
    }
    writeln!(
        text,
        "program and summary: {}/fillet-pocket-sequence.*",
        dir.display()
    )?;
    let chart = "sequence/stock.png";
    out.write(
        chart,
        &swarf_report::chart::chart_png(&sequence_chart(&report))?,
    )?;
    let figure = Figure {
        src: chart.into(),
        caption: "the stock after each operation".into(),
    };
    let links = [name.to_string()]
        .into_iter()
        .chain(seq.output.gcode.clone())
        .chain(seq.output.summary.clone())
        .map(|f| format!("sequence/{f}"))
        .filter(|f| out.is_staged(f))
        .map(|f| (f.clone(), f))
        .collect();
    Ok(vec![Block::Figures(vec![figure]), Block::Links(links)])
}

/// Plans and verifies the die jobs into `out/die` and prints their table.
fn die(out: &mut Outputs, text: &mut dyn Write, reporter: &dyn Reporter) -> Result<Vec<Block>> {
    let jobs_dir = out.path("jobs");
    let mut paths = Vec::new();
    for (name, job_text) in DIE_JOBS {
        let path = jobs_dir.join(name);
        out.write(&path, job_text.as_bytes())?;
        paths.push(path);
    }
    let dir = out.path("die");
    let (_, rows) = out.in_dir("die", |out| {
        compare_all_views(&paths, &SimSettings::default(), out, reporter, true)
    })?;
    let table = five_axis_markdown(&rows);
    out.write(dir.join("die.md"), table.as_bytes())?;
    write!(text, "{table}")?;
    for r in &rows {
        writeln!(
            text,
            "{}: planned in {:.1} s, verified in {:.1} s",
            r.job, r.planning_s, r.verify_s
        )?;
    }
    writeln!(
        text,
        "pictures: {}/die-*.deviation.png, die-*.toolpath.png",
        dir.display()
    )?;
    let mut blocks = Vec::new();
    for (path, row) in paths.iter().zip(&rows) {
        let summary = crate::demo_page::five_axis_summary(row);
        blocks.extend(program_blocks(out, "die", &stem_of(path), &summary));
    }
    blocks.push(Block::Links(vec![("die/die.md".into(), "die.md".into())]));
    Ok(blocks)
}

/// Plans the shipped drop-spin job into `out/edges` and prints the comparison of
/// the methods on both edge parts.
fn edges(out: &mut Outputs, text: &mut dyn Write, reporter: &dyn Reporter) -> Result<Vec<Block>> {
    let dir = out.path("edges");
    let job = Job::parse(DROP_SPIN_JOB, "edge-concave-drop-spin.toml")?;
    let start = std::time::Instant::now();
    let summary = out.in_dir("edges", |out| plan_job(&job, Path::new("."), out, reporter))?;
    let range = |axis: &str| {
        let r = |k: usize| {
            summary["rotary_ranges_deg"][axis][k]
                .as_f64()
                .unwrap_or(f64::NAN)
        };
        format!("[{:.2}, {:.2}]", r(0), r(1))
    };
    writeln!(
        text,
        "edge-concave-drop-spin.toml: {} passes, {} poses, planned and posted in {:.1} s; A {} deg, C {} deg",
        summary["passes"],
        summary["poses"],
        start.elapsed().as_secs_f64(),
        range("A"),
        range("C")
    )?;
    let mut all = Vec::new();
    for name in ["edge-concave", "edge-convex"] {
        let job = Job::parse(&DROP_SPIN_JOB.replace("edge-concave", name), name)?;
        let part =
            swarf_io::builtin_part(name).with_context(|| format!("no built-in part {name}"))?;
        all.push(crate::edge_compare::compare_edge(&job, &part)?);
    }
    let table = format!(
        "tool {}, material left at the edge a quarter, half and three quarters along it:\n\n{}",
        job.tool,
        crate::edge_compare::edge_markdown(&all)
    );
    out.write(dir.join("edges.md"), table.as_bytes())?;
    out.write_json(dir.join("edges.json"), &all)?;
    write!(text, "{table}")?;
    let mut figures = Vec::new();
    for cmp in &all {
        let file = format!("edges/{}.left.png", cmp.part);
        out.write(&file, &swarf_report::chart::chart_png(&edge_chart(cmp))?)?;
        figures.push(Figure {
            src: file,
            caption: format!("{}: material left at the edge, by method", cmp.part),
        });
    }
    let links = ["edges.md", "edges.json"]
        .map(|f| (format!("edges/{f}"), f.to_string()))
        .to_vec();
    Ok(vec![Block::Figures(figures), Block::Links(links)])
}

/// The material each method leaves at the stations of `cmp`, with the ball bound.
fn edge_chart(cmp: &crate::edge_compare::EdgeComparison) -> Chart {
    Chart {
        title: format!(
            "{}: material left at the edge, tool {} (the dashes: the ball bound r (sec b - 1), \
             the least a spun tool can leave)",
            cmp.part, cmp.tool
        ),
        unit: "mm left".into(),
        categories: cmp
            .stations
            .iter()
            .map(|s| format!("station {s:.1} mm"))
            .collect(),
        series: cmp
            .rows
            .iter()
            .map(|r| Series {
                name: format!("{} ({} passes)", r.method, r.passes),
                values: r.left_mm.clone(),
            })
            .collect(),
        marks: Some(("ball bound".into(), cmp.ball_bound_mm.clone())),
        footer: Vec::new(),
    }
}

/// The stock after each operation of a sequence: the share of its cells still above
/// the operation's limit and below the design.
fn sequence_chart(report: &crate::sequence::SequenceReport) -> Chart {
    let ops = &report.operations;
    let (nx, ny, _) = report.grid;
    let share = |n: usize| 100.0 * n as f64 / (nx * ny).max(1) as f64;
    Chart {
        title: format!(
            "{}: the stock after each operation, share of its cells above what the \
             operation was to leave (plus the tolerance) and below the design",
            report.name.as_deref().unwrap_or("sequence")
        ),
        unit: "% of the stock's cells".into(),
        categories: ops
            .iter()
            .map(|o| format!("T{} {}", o.number, o.name))
            .collect(),
        series: vec![
            Series {
                name: "above the operation's limit".into(),
                values: ops.iter().map(|o| share(o.rest_cells)).collect(),
            },
            Series {
                name: "gouged".into(),
                values: ops.iter().map(|o| share(o.gouge_cells)).collect(),
            },
        ],
        marks: None,
        footer: ops
            .iter()
            .map(|o| {
                format!(
                    "T{} {} ({}): {} cells above {:.3} mm, highest {:.3} mm; {} gouge cells",
                    o.number,
                    o.name,
                    o.strategy,
                    o.rest_cells,
                    o.rest_limit_mm,
                    o.max_rest_mm,
                    o.gouge_cells
                )
            })
            .collect(),
    }
}

/// Inspects and tessellates every built-in part, linking the STL files.
fn tessellate_parts(out: &mut Outputs, text: &mut dyn Write) -> Result<Vec<Block>> {
    let mut links = Vec::new();
    for (name, _) in swarf_io::builtin_parts() {
        let part = swarf_io::builtin_part(name)
            .with_context(|| "built-in part does not load".to_string())?;
        let summaries = summarise_patches(&part)?;
        write!(text, "{}", patch_text(&part.name, &summaries))?;
        let mesh = part.tessellate(DEMO_TOL)?;
        let path = out.path(format!("{name}.stl"));
        out.write_stl(&path, &mesh, name)?;
        links.push((format!("{name}.stl"), format!("{name}.stl")));
        writeln!(
            text,
            "  tessellated within {DEMO_TOL} mm: {} triangles -> {}",
            mesh.triangles.len(),
            path.display()
        )?;
    }
    Ok(vec![Block::Links(links)])
}
