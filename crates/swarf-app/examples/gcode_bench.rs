//! G-code reading throughput: a 1,000,000-line RS274/NGC program with parameters,
//! expressions, subroutines and loops, read by swarf (lines and motions per second)
//! and, when it is installed, by LinuxCNC's `rs274 -g` in the same run (the peer);
//! then verified on the built-in `wave` part (time and size of the result).
//!
//! ```sh
//! cargo run --release -p swarf-app --example gcode_bench [-- LINES]
//! ```

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;
use swarf_app::verify::{GcodeSetup, SimSettings, VerifyRequest, verify_request};
use swarf_nc::read::{GcodeReadOptions, parse_gcode};
use swarf_sim::progress::Quiet;

/// A raster over wave's 200 x 100 mm: rows of `per_row` G1 lines whose X is a number
/// and whose Y and Z are expressions of parameters, each row entered through a
/// subroutine call and a small loop.
fn program(lines: usize) -> String {
    let per_row = 1000;
    let rows = (lines / per_row).max(1);
    let mut g = String::with_capacity(lines * 48);
    g.push_str("(swarf G-code throughput benchmark)\nG21 G90 G17 G94\n#<_amp> = 4\n#<_top> = 46\n");
    g.push_str(
        "o<enter> sub\n  G0 X#1 Y#2 Z[#<_top> + 5]\n  o<down> repeat [2]\n    \
         G1 Z[#<_top> + 1] F600\n  o<down> endrepeat\no<enter> endsub\n",
    );
    for r in 0..rows {
        let y = 100.0 * (r as f64 + 0.5) / rows as f64;
        let _ = writeln!(g, "#<y> = {y:.4}\no<enter> call [0] [#<y>]\nF1800");
        for k in 1..per_row {
            let x = 200.0 * k as f64 / per_row as f64;
            let _ = writeln!(
                g,
                "G1 X{x:.3} Y#<y> Z[#<_top> + #<_amp> * sin[{:.2}] * cos[#<y> * 3]]",
                x * 3.0
            );
        }
        g.push_str("G0 Z[#<_top> + 5]\n");
    }
    g.push_str("M2\n");
    g
}

fn main() {
    let lines: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(1_000_000);
    let text = program(lines);
    let count = text.lines().count();
    let dir = std::env::temp_dir().join(format!("swarf-gcode-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("bench.ngc");
    std::fs::write(&path, &text).expect("program written");

    let t = Instant::now();
    let p = parse_gcode(&text, "bench.ngc", &GcodeReadOptions::default()).expect("readable");
    let read = t.elapsed().as_secs_f64();
    assert!(p.stopped.is_none(), "{:?}", p.stopped);
    println!(
        "swarf reads {count} lines ({} motions) in {read:.2} s: {:.0} lines/s, {:.0} motions/s",
        p.motions.len(),
        count as f64 / read,
        p.motions.len() as f64 / read
    );

    let t = Instant::now();
    let peer = std::process::Command::new("rs274")
        .arg("-g")
        .arg(&path)
        .current_dir(&dir)
        .env("HOME", &dir)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status();
    match peer {
        Ok(s) if s.success() => {
            let rs274 = t.elapsed().as_secs_f64();
            println!(
                "rs274 -g reads it in {rs274:.2} s: {:.0} lines/s; swarf / rs274 speed: {:.1}x",
                count as f64 / rs274,
                rs274 / read
            );
        }
        Ok(s) => println!("rs274 -g failed ({s}): no peer figure"),
        Err(e) => println!("rs274 not run ({e}): no peer figure"),
    }

    let sim = SimSettings {
        stock: swarf_app::verify::StockChoice::Offset { allowance: 2.0 },
        cell: Some(0.25),
        tol: Some(0.05),
        ..SimSettings::default()
    };
    let programs = [path.clone()];
    let tools = ["ball:d=6".to_string()];
    let out: PathBuf = dir.join("verify");
    let req = VerifyRequest {
        part: "wave",
        programs: &programs,
        tools: &tools,
        gcode: &GcodeSetup::default(),
        machine: None,
        tool_length: None,
        sim: &sim,
        out: &out,
        partial: false,
    };
    let t = Instant::now();
    let done = verify_request(&req, &Quiet).expect("verifies");
    println!(
        "swarf verify (wave, ball d=6, cells 0.25 mm) in {:.1} s, reading included: {} motions, {:.1} m of cut",
        t.elapsed().as_secs_f64(),
        done.verification.program.motions,
        done.verification.program.cutting_length_mm / 1000.0
    );
    let _ = std::fs::remove_dir_all(&dir);
}
