//! glTF export of a large stock: the iso-scallop program of wave
//! (`jobs/wave-iso-scallop.toml`) verified on 0.05 mm cells (4001 x 2001, 8M
//! cells), then its stock written as GLB at full resolution (every cell a vertex)
//! and decimated to 1,000,000 and 250,000 (the default) vertices: export time, file
//! size and the stated height error of each; the design, tool path and cutter
//! files beside them.
//!
//! ```sh
//! cargo run --release -p swarf-app --example view_bench
//! ```

use std::path::Path;
use std::time::Instant;
use swarf_app::{Job, Outputs, load_model};
use swarf_report::gltf::{StockMeshOptions, cutter_glb, part_glb, stock_glb, toolpath_glb};
use swarf_sim::progress::Quiet;
use swarf_sim::{Design, VerifyOptions, verify};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let jobs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../jobs");
    let text = std::fs::read_to_string(jobs.join("wave-iso-scallop.toml"))?;
    let mut job = Job::parse(&text, "wave-iso-scallop.toml")?;
    (job.output.cl, job.output.csv, job.output.summary) = (None, None, None);
    let dir = std::env::temp_dir().join(format!("swarf-view-bench-{}", std::process::id()));
    let mut out = Outputs::new(&dir);
    swarf_app::plan_job(&job, &jobs, &mut out, &Quiet)?;
    let program = out.read_program("wave-iso-scallop.ngc")?;
    let model = load_model("builtin:wave")?;
    let swarf_app::Model::Patches(part) = &model else {
        return Err("wave is a patch part".into());
    };
    let opts = VerifyOptions {
        cell: Some(0.05),
        allowed_excess: 0.15,
        along_normals: true,
        ..VerifyOptions::default()
    };
    let start = Instant::now();
    let v = verify(Design::Part(part), &program, &job.tool, &opts, &Quiet)?;
    println!(
        "verified {} motions on {} x {} = {} cells of {} mm in {:.1} s",
        program.motions.len(),
        v.grid.nx,
        v.grid.ny,
        v.grid.len(),
        v.grid.cell,
        start.elapsed().as_secs_f64()
    );
    println!(
        "| stock mesh | stride | vertices | triangles | GLB size | export time | stated height error |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (name, max) in [
        ("full", usize::MAX),
        ("1M", 1_000_000),
        ("default 250k", StockMeshOptions::default().max_vertices),
    ] {
        let start = Instant::now();
        let (bytes, mesh) = stock_glb(&v, &StockMeshOptions { max_vertices: max })?;
        let s = start.elapsed().as_secs_f64();
        println!(
            "| {name} | {} | {} | {} | {:.1} MB | {s:.2} s | {:.4} mm |",
            mesh.stride,
            mesh.vertices,
            mesh.triangles,
            bytes.len() as f64 / 1e6,
            mesh.height_error
        );
    }
    let start = Instant::now();
    let mesh = part.tessellate(job.tolerance())?;
    let sizes = [
        part_glb(&mesh)?.len(),
        toolpath_glb(&program.motions, &job.tool)?.len(),
    ];
    let first = program
        .motions
        .first()
        .map(|m| m.start)
        .ok_or("no motions")?;
    let cutter = cutter_glb(&job.tool, &first)?.len();
    println!(
        "design (tessellated within {} mm) {:.1} MB, tool path {:.2} MB, cutter {:.3} MB: {:.2} s",
        job.tolerance(),
        sizes[0] as f64 / 1e6,
        sizes[1] as f64 / 1e6,
        cutter as f64 / 1e6,
        start.elapsed().as_secs_f64()
    );
    drop(out);
    let _ = std::fs::remove_dir_all(&dir);
    Ok(())
}
