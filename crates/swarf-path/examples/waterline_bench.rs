//! Waterline throughput on an STL: one drop field, then contours at the given levels.
//!
//! `cargo run --release -p swarf-path --example waterline_bench -- MESH.stl TOOL
//!  SAMPLING TOLERANCE THREADS OUT.csv Z [Z ...]`
//!
//! Prints the seconds spent preparing (index and drop field) and on each level, and
//! writes every level's loops to `OUT.csv` (`z,loop,x,y`). `tools/ocl/bench_waterline.py`
//! runs it beside OpenCAMLib's Waterline on the same mesh, levels and threads.

use std::io::Write;
use std::time::Instant;
use swarf_path::Finish;
use swarf_path::strategy::waterline::{Milling, Waterline, WaterlineParams};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 7 {
        return Err("usage: MESH.stl TOOL SAMPLING TOLERANCE THREADS OUT.csv Z [Z ...]".into());
    }
    let t0 = Instant::now();
    let mesh = swarf_io::stl::read_stl(std::path::Path::new(&args[0]))?;
    let read_s = t0.elapsed().as_secs_f64();
    let tool: swarf_tool::Cutter = args[1].parse()?;
    let params = WaterlineParams {
        finish: Finish {
            tolerance: args[3].parse()?,
            ..Finish::default()
        },
        sampling: Some(args[2].parse()?),
        ..WaterlineParams::new(0.01)
    };
    let threads: usize = args[4].parse()?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    let levels: Vec<f64> = args[6..]
        .iter()
        .map(|z| z.parse())
        .collect::<Result<_, _>>()?;
    let mut out = std::fs::File::create(&args[5])?;
    writeln!(out, "z,loop,x,y")?;
    let result = pool.install(|| -> Result<(), Box<dyn std::error::Error + Send + Sync>> {
        let t1 = Instant::now();
        let wl = Waterline::new(&mesh, &tool, &params)?;
        println!(
            "triangles {} read {read_s:.3} s prepare {:.3} s",
            mesh.len(),
            t1.elapsed().as_secs_f64()
        );
        for &z in &levels {
            let t2 = Instant::now();
            let level = wl.level(z, Milling::Climb);
            let points: usize = level.loops.iter().map(Vec::len).sum();
            println!(
                "level {z} loops {} points {points} seconds {:.3}",
                level.loops.len(),
                t2.elapsed().as_secs_f64()
            );
            for (k, lp) in level.loops.iter().enumerate() {
                for p in lp {
                    writeln!(out, "{z},{k},{:.9},{:.9}", p.pose.cl.x, p.pose.cl.y)?;
                }
            }
        }
        Ok(())
    });
    result.map_err(|e| e.to_string().into())
}
