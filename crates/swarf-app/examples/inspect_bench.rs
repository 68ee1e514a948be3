//! `swarf inspect` throughput: a part of `N x N` bicubic Bezier patches (default
//! 100 x 100 = 10,000) tiling one smooth surface, written as a part file and then read
//! and summarised through the same entry points as the CLI ([`load_model`], then
//! [`inspect`]); prints the time of each step and per patch.
//!
//! The surface is `z = A sin(2 pi x / Lx) cos(2 pi y / Ly) + x / 20` over
//! 2000 x 2000 mm (`A` = 40 mm, `Lx` = 300 mm, `Ly` = 220 mm), each 20 x 20 mm cell a
//! bicubic Hermite patch (corner values, slopes and twist of `z`) in Bezier form, so the
//! tiling is C1 and every patch is curved in both directions.
//!
//! ```sh
//! cargo run --release -p swarf-app --example inspect_bench [-- N [KEEP.toml]]
//! ```
//!
//! With `KEEP.toml` the part file is written there and kept (for timing
//! `swarf inspect KEEP.toml` itself).

use std::f64::consts::TAU;
use std::fmt::Write as _;
use std::time::Instant;
use swarf_app::inspect::inspect;
use swarf_app::load_model;

/// Side of the square surface, mm.
const SIDE: f64 = 2000.0;
/// Amplitude of the waves, mm.
const AMP: f64 = 40.0;
/// Wavelengths along x and y, mm.
const WAVE: [f64; 2] = [300.0, 220.0];

/// `[z, z_x, z_y, z_xy]` of the surface at `(x, y)`.
fn height(x: f64, y: f64) -> [f64; 4] {
    let (kx, ky) = (TAU / WAVE[0], TAU / WAVE[1]);
    let (sx, cx) = (kx * x).sin_cos();
    let (sy, cy) = (ky * y).sin_cos();
    [
        AMP * sx * cy + x / 20.0,
        AMP * kx * cx * cy + 1.0 / 20.0,
        -AMP * ky * sx * sy,
        -AMP * kx * ky * cx * sy,
    ]
}

/// The part file text of the `n x n` tiling.
fn part_text(n: usize) -> String {
    let h = SIDE / n as f64;
    let mut s = format!("name = \"grid{n}\"\nunits = \"mm\"\n");
    for a in 0..n {
        for b in 0..n {
            let (x0, y0) = (a as f64 * h, b as f64 * h);
            // Bicubic Hermite -> Bezier: corner (i, j) in {0, 3}^2 holds z; the inner
            // points add h/3 times the slopes, and (h/3)^2 times the twist.
            let corner =
                |i: usize, j: usize| height(x0 + h * (i / 3) as f64, y0 + h * (j / 3) as f64);
            s += "[[patch]]\ndegree = [3, 3]\npoints = [\n";
            for i in 0..4 {
                for j in 0..4 {
                    let (ci, cj) = (if i < 2 { 0 } else { 3 }, if j < 2 { 0 } else { 3 });
                    let [z, zx, zy, zxy] = corner(ci, cj);
                    let sx = match i {
                        1 => 1.0,
                        2 => -1.0,
                        _ => 0.0,
                    };
                    let sy = match j {
                        1 => 1.0,
                        2 => -1.0,
                        _ => 0.0,
                    };
                    let t = h / 3.0;
                    let z = z + sx * t * zx + sy * t * zy + sx * sy * t * t * zxy;
                    let (x, y) = (x0 + h * i as f64 / 3.0, y0 + h * j as f64 / 3.0);
                    let _ = writeln!(s, "  [{x:?}, {y:?}, {z:?}],");
                }
            }
            s += "]\n";
        }
    }
    s
}

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(100);
    let keep = std::env::args().nth(2).map(std::path::PathBuf::from);
    let dir = std::env::temp_dir().join(format!("swarf-inspect-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    let path = keep.unwrap_or_else(|| dir.join(format!("grid{n}.toml")));
    let t = Instant::now();
    std::fs::write(&path, part_text(n)).expect("the part file is written");
    let write_s = t.elapsed().as_secs_f64();
    let arg = path.to_str().expect("a UTF-8 path");
    let t = Instant::now();
    let model = load_model(arg).expect("the part file reads");
    let read_s = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let text = inspect(&model, false).expect("the part inspects");
    let inspect_s = t.elapsed().as_secs_f64();
    let patches = n * n;
    println!(
        "inspect of {patches} bicubic patches ({n} x {n}, {} of text): write {write_s:.2} s, \
         read {read_s:.2} s, inspect {inspect_s:.2} s ({:.3} ms per patch), total {:.2} s",
        text.len(),
        1e3 * inspect_s / patches as f64,
        read_s + inspect_s
    );
    std::fs::remove_dir_all(&dir).expect("the scratch folder is removed");
}
