//! Five-axis verification speed: the die's automatic gouge-free lead program
//! (jobs/die-gouge-free.toml) planned for each built-in five-axis machine, its G-code
//! verified at several cell sizes with the default sampling (second order where it
//! applies, `swarf_sim::sweep_bound`) and, at the coarsest cell, with the first-order
//! reference sweep in the same run: times, motions/s, cell updates/s, the ratio, and
//! the worst cell difference between the two over what their bounds allow.
//!
//! ```sh
//! cargo run --release -p swarf-app --example verify5x_bench [-- CELL... MACHINE...]
//! ```
//! (default cells 1, 0.5 and 0.1 mm, the reference at the first; default machines
//! the three built-in ones).

use std::path::{Path, PathBuf};
use std::time::Instant;
use swarf_app::job::Job;
use swarf_app::verify::{GcodeSetup, SimSettings, Verified, VerifyRequest, verify_in_memory};
use swarf_sim::progress::Quiet;
use swarf_testkit::heights::worst_height_ratio;

const MACHINES: [&str; 3] = ["xyzac-trunnion", "xyzbc-head", "xyzbc-table-head"];

/// Plans the die job for `machine` into `dir`; returns the G-code's path.
fn plan(jobs: &Path, dir: &Path, machine: &str) -> PathBuf {
    let text = std::fs::read_to_string(jobs.join("die-gouge-free.toml")).expect("shipped job");
    // (head machines position the gauge line: a 150 mm tool)
    let length = if machine.contains("head") {
        "\ntool_length = 150.0"
    } else {
        ""
    };
    let text = text.replace(
        "machine = \"builtin:xyzac-trunnion\"",
        &format!("machine = \"builtin:{machine}\"{length}"),
    );
    let job = Job::parse_in(&text, "die-gouge-free.toml", jobs).expect("valid job");
    let mut out = swarf_app::Outputs::new(dir);
    swarf_app::plan_job::plan_job(&job, jobs, &mut out, &Quiet).expect("plans");
    out.commit().expect("written");
    dir.join("die-gouge-free.ngc")
}

fn verify(program: &Path, cell: f64, first_order: bool) -> (Verified, f64) {
    let sim = SimSettings {
        cell: Some(cell),
        first_order_sweep: first_order,
        ..SimSettings::default()
    };
    let programs = [program.to_path_buf()];
    let out = program.with_extension("verify");
    let req = VerifyRequest {
        part: "builtin:die",
        programs: &programs,
        tools: &[],
        gcode: &GcodeSetup::default(),
        machine: None,
        tool_length: None,
        sim: &sim,
        out: &out,
        partial: false,
    };
    let t = Instant::now();
    let v = verify_in_memory(&req, &Quiet).expect("verifies");
    (v, t.elapsed().as_secs_f64())
}

/// The worst cell difference of the two stocks over the sum of their bounds (3D),
/// among the cells some motion cut ([`worst_height_ratio`]).
fn worst_ratio(fast: &Verified, slow: &Verified) -> (f64, usize) {
    let (f, s) = (&fast.verification, &slow.verification);
    let allowed = f.sim.max_sample_bound.min(f.sample_tol) + s.sample_tol + 1e-9;
    let g = s.grid;
    let last = s.stock.last_motion();
    worst_height_ratio(
        (s.stock.heights(), f.stock.heights()),
        (g.nx, g.ny, g.cell),
        allowed,
        |k| last[k] != swarf_sim::dexel::NO_MOTION,
    )
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut cells: Vec<f64> = args.iter().filter_map(|a| a.parse().ok()).collect();
    let named: Vec<&str> = MACHINES
        .into_iter()
        .filter(|m| args.iter().any(|a| a == m))
        .collect();
    let machines = if named.is_empty() {
        MACHINES.to_vec()
    } else {
        named
    };
    if cells.is_empty() {
        cells = vec![1.0, 0.5, 0.1];
    }
    let jobs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../jobs");
    let scratch = std::env::temp_dir().join(format!("swarf-verify5x-{}", std::process::id()));
    println!("{} threads", rayon::current_num_threads());
    for machine in machines {
        let dir = scratch.join(machine);
        let program = plan(&jobs, &dir, machine);
        let mut fast_at_first = None;
        for &cell in &cells {
            let (v, wall) = verify(&program, cell, false);
            let s = &v.verification.sim;
            let sim_s = v.verification.timings.simulate_s;
            println!(
                "{machine:<17} cell {cell:>4} mm: {wall:6.2} s end to end, simulate {sim_s:6.2} s; \
                 {} motions ({:.0}/s), {} positions, {:.2e} cell updates ({:.2e}/s), \
                 {} of {} sampled motions second order, bound {:.4} mm; gouge cells {}, excess cells {}",
                s.motions,
                s.motions as f64 / sim_s,
                s.primitives,
                s.cells_visited as f64,
                s.cells_visited as f64 / sim_s,
                s.second_order_motions,
                s.sampled_motions,
                v.verification.sample_tol,
                v.verification.deviation.summary.gouge.cells,
                v.verification.deviation.summary.excess.cells,
            );
            if fast_at_first.is_none() {
                fast_at_first = Some((v, sim_s, cell));
            }
        }
        let Some((fast, fast_s, cell)) = fast_at_first else {
            continue;
        };
        let (slow, _) = verify(&program, cell, true);
        let slow_s = slow.verification.timings.simulate_s;
        let (worst, count) = worst_ratio(&fast, &slow);
        println!(
            "{machine:<17} cell {cell:>4} mm, first-order reference: simulate {slow_s:6.2} s, \
             {} positions; {:.1}x faster by default; worst cell difference {worst:.3} of the \
             allowed over {count} cells; gouge cells {} vs {}, excess cells {} vs {}",
            slow.verification.sim.primitives,
            slow_s / fast_s,
            fast.verification.deviation.summary.gouge.cells,
            slow.verification.deviation.summary.gouge.cells,
            fast.verification.deviation.summary.excess.cells,
            slow.verification.deviation.summary.excess.cells,
        );
    }
    let _ = std::fs::remove_dir_all(&scratch);
}
