//! Thesis 000 ch. 8 on die.toml, the full experiment: the inclined tool at fixed lead
//! angles and the automatic gouge-free lead, with timings.
//! `cargo run --release -p swarf-fiveaxis --example die_ch8 -- [feed angle] [tool] [out dir]`
//! (defaults: 60 degrees off X, `bull:d=38.1,r=6.35`). With an output directory it
//! writes the automatic path as five-axis G-code for the A/C trunnion of
//! `machines/xyzac-trunnion.toml`, as APT CL, and its machined surface as STL.

use std::time::Instant;
use swarf_fiveaxis::design::DesignSurface;
use swarf_fiveaxis::gouge::{GougeOptions, pose_gouge};
use swarf_fiveaxis::machine::Machine;
use swarf_fiveaxis::positioning::{Positioning, PositioningReport, position};
use swarf_fiveaxis::post::{PostOptions, write_gcode_5x};
use swarf_fiveaxis::sections::Sections;
use swarf_fiveaxis::swept::SweptSurface;
use swarf_fiveaxis::{CurveOptions, incline_pass};
use swarf_testkit::die_cc;
use swarf_tool::ProfileTable;
use swarf_tool::{Cutter, Pose};
use swarf_toolpath::{Feeds, Linking, Pass, Toolpath};

fn show(name: &str, r: &PositioningReport, secs: f64) {
    let worst = r.gouges.first();
    println!(
        "{name:>10}: alpha {:.2}..{:.2} deg (max at pass {} point {}), gouging poses {}/{}, \
         deepest {:.4} mm{}, axis turn <= {:.2} deg/mm, {} checks ({} whole-tool), {} raised, {:.2} s",
        r.alpha_range_deg[0],
        r.alpha_range_deg[1],
        r.max_alpha_at[0],
        r.max_alpha_at[1],
        r.gouging_poses,
        r.poses,
        r.worst_depth,
        worst.map_or(String::new(), |g| format!(
            " at ({:.1}, {:.1}, {:.1}) {} half, pass {} point {}",
            g.at[0], g.at[1], g.at[2], g.half, g.pass, g.index
        )),
        r.max_axis_rate_deg_per_mm,
        r.evaluations,
        r.whole_tool_evaluations,
        r.raised,
        secs
    );
}

/// Mean time of one sectioning check per pose, without and with the whole tool.
fn time_checks(design: &DesignSurface, cutter: &Cutter, passes: &[Pass], angle: f64) -> [f64; 2] {
    let profile = cutter.profile();
    let table = ProfileTable::new(&profile);
    let mut g = GougeOptions {
        sections: Sections::along(angle, 1.0).expect("sections"),
        tolerance: 0.01,
        curve: CurveOptions::default(),
        cap_meridians: 96,
        whole_tool: false,
    };
    let mut out = [0.0; 2];
    for (k, whole) in [false, true].into_iter().enumerate() {
        g.whole_tool = whole;
        let t = Instant::now();
        let mut n = 0;
        for pass in passes {
            let poses: Vec<Pose> = pass.points.iter().map(|p| p.pose).collect();
            for i in 0..poses.len() {
                std::hint::black_box(pose_gouge(design, &table, &poses, i, &g));
                n += 1;
            }
        }
        out[k] = t.elapsed().as_secs_f64() / n as f64;
    }
    out
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let angle = args
        .get(1)
        .and_then(|a| a.parse::<f64>().ok())
        .unwrap_or(60.0);
    let spec = args
        .get(2)
        .cloned()
        .unwrap_or_else(|| "bull:d=38.1,r=6.35".into());
    let part = swarf_io::builtin_part("die").expect("built-in die");
    let design = DesignSurface::new(&part).expect("design");
    let cc = die_cc(&part, &spec, angle, 3.5, 0.01);
    let cutter: Cutter = spec.parse().expect("tool");
    println!(
        "die.toml, {spec}, feed {angle} deg off X, cross feed 3.5 mm, chordal tolerance 0.01 mm: {} passes, {} poses; \
         sections 1 mm parallel to the feed, tolerance 0.01 mm",
        cc.len(),
        cc.iter().map(Vec::len).sum::<usize>()
    );
    for alpha in [3.0, 6.0] {
        let t = Instant::now();
        let p = Positioning::Inclined {
            alpha,
            tilt: 0.0,
            sections: 1.0,
        };
        let (_, r) = position(&cutter, &part, &cc, &p, 0.01).expect("inclined");
        show(&format!("alpha {alpha}"), &r, t.elapsed().as_secs_f64());
    }
    let fixed: Vec<Pass> = cc
        .iter()
        .enumerate()
        .map(|(k, c)| incline_pass(&cutter, c, &[6f64.to_radians()], 0.0, k).expect("pose"))
        .collect();
    let [curves, whole] = time_checks(&design, &cutter, &fixed, angle.to_radians());
    println!(
        "sectioning check per pose: generating curves {:.1} us, with the whole tool {:.1} us",
        curves * 1e6,
        whole * 1e6
    );
    let t = Instant::now();
    let auto = Positioning::GougeFree {
        max_alpha: 25.0,
        sections: 1.0,
        tilt: 0.0,
        max_rate: 0.5,
        tolerance: None,
    };
    let (passes, r) = position(&cutter, &part, &cc, &auto, 0.01).expect("gouge-free");
    show("automatic", &r, t.elapsed().as_secs_f64());
    if let Some(dir) = args.get(3) {
        write_outputs(std::path::Path::new(dir), &cutter, passes);
    }
}

fn write_outputs(dir: &std::path::Path, cutter: &Cutter, passes: Vec<Pass>) {
    std::fs::create_dir_all(dir).expect("output directory");
    let top = passes
        .iter()
        .flat_map(|p| &p.points)
        .map(|p| p.pose.cl.z)
        .fold(f64::NEG_INFINITY, f64::max);
    let tp = Toolpath {
        passes,
        feeds: Feeds {
            feed: 150.0,
            spindle: 1200.0,
            ..Feeds::default()
        },
        linking: Linking {
            clearance: top + 10.0,
            approach: 2.0,
            ..Linking::default()
        },
    };
    let m = Machine::parse(
        include_str!("../../../machines/xyzac-trunnion.toml"),
        "trunnion",
    )
    .expect("machine");
    let opts = PostOptions {
        comments: vec!["die.toml, thesis 000 ch. 8, automatic gouge-free lead".into()],
        ..PostOptions::default()
    };
    let ngc = write_gcode_5x(&m, &tp, &opts).expect("post");
    std::fs::write(dir.join("die-auto-trunnion.ngc"), ngc).expect("write");
    let cl =
        swarf_nc::write_cl(&tp.moves(), &tp.feeds, cutter, "die", swarf_nc::Units::Mm).expect("cl");
    std::fs::write(dir.join("die-auto.cl"), cl).expect("write");
    let poses: Vec<Vec<Pose>> = tp
        .passes
        .iter()
        .map(|p| p.points.iter().map(|q| q.pose).collect())
        .collect();
    let swept =
        SweptSurface::new(&cutter.profile(), &poses, &CurveOptions::default()).expect("swept");
    let mut out = swarf_io::OutputSet::new();
    swarf_io::write_stl(
        &mut out,
        &dir.join("die-auto-machined.stl"),
        swept.mesh(),
        "die auto",
    )
    .expect("stl");
    out.commit().expect("stl");
    println!("wrote {}", dir.display());
}
