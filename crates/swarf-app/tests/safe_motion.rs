//! Safe motion on real stock: every shipped three-axis job, re-planned on a box
//! 5 mm wider than the part on every side and 10 mm above it (to the next whole
//! mm), is simulated by the
//! verifier on that box (the gate of `swarf plan`, rapids included): no rapid
//! removes material, no cell is gouged beyond the job's tolerance, and every rapid
//! stays at least the approach above the box (checked on the moves, apart from the
//! simulation). A gouge planted in a program is refused with its line; with
//! `AllowUnsafe` it is written and labelled. No move goes below the floor (the
//! part's lowest point, or `stock.floor`): passes that dive off a part's edge are
//! cut there, and a pass that leaves and comes back is split.

use std::path::{Path, PathBuf};
use swarf_app::Job;
use swarf_app::gate::{self, Gate};
use swarf_app::model::load_model_with;
use swarf_app::plan_job::{Planned, part_arg, plan_model_toolpath};
use swarf_app::stock::Stock;
use swarf_nc::read::GcodeReadOptions;
use swarf_sim::Quiet;
use swarf_sim::StockSpec;
use swarf_tool::Pose;
use swarf_toolpath::{Move, MoveKind};

fn jobs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../jobs")
}

/// Whether the shipped job `text` is a three-axis single job.
fn three_axis(text: &str) -> bool {
    let t: toml::Table = toml::from_str(text).unwrap();
    let kind = t
        .get("strategy")
        .and_then(|s| s.get("kind"))
        .and_then(|k| k.as_str())
        .unwrap_or_default();
    !t.contains_key("operation") && !t.contains_key("positioning") && kind != "drop-spin"
}

#[test]
fn every_shipped_three_axis_job_is_safe_on_a_box_ten_mm_above_the_part() {
    let mut names: Vec<PathBuf> = std::fs::read_dir(jobs())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    names.sort();
    let mut checked = 0;
    for path in names {
        let text = std::fs::read_to_string(&path).unwrap();
        if !three_axis(&text) {
            continue;
        }
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let mut job = Job::parse_in(&text, &name, &jobs()).unwrap();
        let model = load_model_with(&part_arg(&job, &jobs()), &job.load_options()).unwrap();
        let [floor, part_top] = model.z_range().unwrap();
        let top = (part_top + 10.0).ceil();
        job.stock = Stock {
            top: Some(top),
            margin: 5.0,
            ..Stock::default()
        };
        let dir = std::env::temp_dir().join(format!("swarf-safe-motion-{name}"));
        let mut out = swarf_app::Outputs::new(&dir);
        let planned = plan_model_toolpath(&job, &model, &jobs(), &mut out, &Quiet).unwrap();
        let v = &planned.summary["verification"];
        assert_eq!(v["stock"], format!("box, top {top} mm"), "{name}");
        assert_eq!(v["rapid_cuts"].as_array().unwrap().len(), 0, "{name}: {v}");
        assert_eq!(v["gouge_cells"], 0, "{name}: {v}");
        assert_eq!(v["floor"], floor, "{name}: {v}");
        assert_eq!(v["below_floor"].as_array().unwrap().len(), 0, "{name}: {v}");
        // Roughing comes down to its cleared levels (`Pass::clear_from`): the
        // simulation alone checks it.
        let tp = &planned.toolpath;
        let approach = tp.linking.approach;
        let cleared = tp.passes.iter().any(|p| p.clear_from.is_some());
        for (k, m) in tp.moves().iter().enumerate() {
            assert!(
                m.to.cl.z >= floor - 1e-9,
                "{name}: move {k} below the floor: {m:?}"
            );
            if m.kind == MoveKind::Rapid && k > 0 && !cleared {
                assert!(
                    m.to.cl.z >= top + approach - 1e-6,
                    "{name}: rapid {k} to z {} below the box top {top} + approach",
                    m.to.cl.z
                );
            }
        }
        checked += 1;
    }
    assert!(checked >= 10, "{checked} three-axis jobs");
}

/// A pass on the wave (the ball dropped on it) that dips 1 mm below in its middle,
/// and a rapid
/// 0.5 mm into the box stock (above the design: the wave's top is 1 mm below the
/// box's).
fn planted(job: &Job, model: &swarf_app::model::Model) -> Vec<Move> {
    let mesh = model.triangles(0.001).unwrap();
    let dropper = swarf_tool::drop::MeshDropper::new(&mesh, &job.tool);
    let mut scratch = swarf_tool::drop::DropScratch::default();
    let mut z = |x: f64, y: f64| dropper.drop(x, y, &mut scratch).unwrap().z;
    let top = job.material_top.unwrap();
    let mut feed = |x: f64, y: f64, dz: f64| Move {
        kind: MoveKind::Feed,
        to: Pose::vertical(swarf_geom::Point3::new(x, y, z(x, y) + dz)),
        feed: 300.0,
        pass: Some(0),
    };
    let rapid = |x: f64, y: f64, h: f64| Move {
        kind: MoveKind::Rapid,
        to: Pose::vertical(swarf_geom::Point3::new(x, y, h)),
        feed: 0.0,
        pass: None,
    };
    vec![
        rapid(60.0, 40.0, top + 10.0),
        feed(60.0, 40.0, 0.5),
        feed(100.0, 40.0, -1.0),
        feed(140.0, 40.0, 0.5),
        rapid(140.0, 40.0, top + 10.0),
        rapid(140.0, 60.0, top + 10.0),
        rapid(140.0, 60.0, top - 0.5),
        rapid(140.0, 60.0, top + 10.0),
    ]
}

#[test]
fn a_planted_gouge_and_a_rapid_in_the_stock_are_refused_by_line_or_labelled() {
    let text = std::fs::read_to_string(jobs().join("wave-raster.toml")).unwrap();
    let job = Job::parse_in(&text, "wave-raster.toml", &jobs()).unwrap();
    let model = load_model_with(&part_arg(&job, &jobs()), &job.load_options()).unwrap();
    let job = job.on_stock(&model, &jobs()).unwrap();
    let moves = planted(&job, &model);
    let opts = swarf_nc::GcodeOptions::default();
    let gcode = swarf_nc::write_gcode(&moves, &job.feeds, &opts).unwrap();
    let read = GcodeReadOptions::default();
    let stock = StockSpec::Box {
        top: job.material_top,
    };
    let simulated = (&moves[..], Some(gcode.as_str()), &read);
    let mut report = gate::run(&job, &model, simulated, Some(&stock), 0.15)
        .unwrap()
        .unwrap();
    assert!(!report.safe());
    assert_eq!(report.rapid_cuts.len(), 1, "{report:?}");
    let deepest = report.rapid_cuts[0].depth;
    assert!((deepest - 0.5).abs() < 0.01, "{deepest}");
    assert!(report.gouge_cells > 0);
    assert!(report.worst_gouge_mm < -0.9, "{report:?}");
    // Refused, naming the rapid into the stock and the feed that gouged by their
    // lines as written.
    let refused = gate::conclude(&job, Some(&mut report), simulated, &[]).unwrap_err();
    let message = refused.to_string();
    let lines: Vec<&str> = gcode.lines().collect();
    let rapid_line = report.rapid_cuts[0].line.unwrap();
    let gouge_line = report.gouges[0].line.unwrap();
    // The rapid down at X140 Y60: a Z word alone (G0 modal from the move before).
    let down = lines[rapid_line - 1];
    assert!(down.starts_with('Z') || down.starts_with("G0 Z"), "{down}");
    let feed = lines[gouge_line - 1];
    assert!(feed.contains("X100.") || feed.contains("X140."), "{feed}");
    assert!(
        message.contains(&format!("line {rapid_line} (")),
        "{message}"
    );
    assert!(
        message.contains(&format!("line {gouge_line} (")),
        "{message}"
    );
    assert!(message.contains("nothing written"), "{message}");
    let allowed = Job {
        gate: Gate::AllowUnsafe,
        ..job
    };
    gate::conclude(&allowed, Some(&mut report), simulated, &[]).unwrap();
    assert!(report.written_unsafe);
    assert!(
        report
            .comment()
            .starts_with("UNSAFE, written with --allow-unsafe")
    );
}

/// A plunge 2 mm below the floor (the part's lowest point) beside the wave, and the
/// retract from there: both go below the floor, and the gate refuses them by line.
#[test]
fn a_motion_below_the_floor_is_refused_by_line() {
    let text = std::fs::read_to_string(jobs().join("wave-raster.toml")).unwrap();
    let job = Job::parse_in(&text, "wave-raster.toml", &jobs()).unwrap();
    let model = load_model_with(&part_arg(&job, &jobs()), &job.load_options()).unwrap();
    let job = job.on_stock(&model, &jobs()).unwrap();
    let floor = job.reach.unwrap().floor;
    assert_eq!(floor, model.z_range().unwrap()[0]);
    let b = model.bounds();
    let (x, y, high) = (
        b.min.x - 20.0,
        b.min.y - 20.0,
        job.material_top.unwrap() + 10.0,
    );
    let to = |kind, z: f64| Move {
        kind,
        to: Pose::vertical(swarf_geom::Point3::new(x, y, z)),
        feed: if kind == MoveKind::Feed { 300.0 } else { 0.0 },
        pass: None,
    };
    let moves = vec![
        to(MoveKind::Rapid, high),
        to(MoveKind::Feed, floor - 2.0),
        to(MoveKind::Rapid, high),
    ];
    let gcode =
        swarf_nc::write_gcode(&moves, &job.feeds, &swarf_nc::GcodeOptions::default()).unwrap();
    let read = GcodeReadOptions::default();
    let simulated = (&moves[..], Some(gcode.as_str()), &read);
    let stock = StockSpec::Box {
        top: job.material_top,
    };
    let mut report = gate::run(&job, &model, simulated, Some(&stock), 0.15)
        .unwrap()
        .unwrap();
    assert_eq!(report.floor, Some(floor));
    let depths: Vec<f64> = report.below_floor.iter().map(|f| f.depth).collect();
    assert_eq!(depths.len(), 2, "{report:?}");
    assert!(depths.iter().all(|d| (d - 2.0).abs() < 1e-3), "{depths:?}");
    assert!(
        report.rapid_cuts.is_empty() && report.gouge_cells == 0,
        "{report:?}"
    );
    assert!(!report.safe());
    let message = gate::conclude(&job, Some(&mut report), simulated, &[])
        .unwrap_err()
        .to_string();
    // The first is the plunge: the feed that ends 2 mm below the floor.
    let plunge = report.below_floor[0].line.unwrap();
    let read = swarf_nc::read::parse_gcode(&gcode, "planted", &read).unwrap();
    let m = read.motions.iter().find(|m| m.line == plunge).unwrap();
    assert!(
        m.feed > 0.0 && (m.end.cl.z - (floor - 2.0)).abs() < 1e-3,
        "{m:?}"
    );
    assert!(
        message.contains("2 motions go below the floor")
            && message.contains(&format!("line {plunge} (2.000 mm below)")),
        "{message}"
    );
}

/// Plans the job `text` on its stock under `gate`.
fn planned(text: &str, name: &str, gate: Gate) -> swarf_app::Result<Planned> {
    let mut job = Job::parse_in(text, name, &jobs()).unwrap();
    job.gate = gate;
    let model = load_model_with(&part_arg(&job, &jobs()), &job.load_options()).unwrap();
    let dir = std::env::temp_dir().join(format!("swarf-safe-motion-{name}"));
    let mut out = swarf_app::Outputs::new(&dir);
    plan_model_toolpath(&job, &model, &jobs(), &mut out, &Quiet)
}

/// The gate's verdict on the job `text` planned under `gate`.
fn verdict(text: &str, name: &str, gate: Gate) -> serde_json::Value {
    planned(text, name, gate).unwrap().summary["verification"].clone()
}

/// The lowest tool tip of `planned`'s moves, mm.
fn lowest(planned: &Planned) -> f64 {
    planned
        .toolpath
        .moves()
        .iter()
        .map(|m| m.to.cl.z)
        .fold(f64::INFINITY, f64::min)
}

/// Waterline levels 10 mm apart on the boss: the highest level is below the ribs'
/// tops, and the rapids, above the stock, clear them.
#[test]
fn waterline_rapids_clear_the_ribs_above_the_highest_level() {
    let text = r#"
part = "builtin:boss"
tool = "ball:d=10"
[strategy]
kind = "waterline"
level_step = 10
tolerance = 0.01
[output]
gcode = "boss-waterline.ngc"
"#;
    let v = verdict(text, "boss-waterline.toml", Gate::Verify);
    assert_eq!(v["rapid_cuts"].as_array().unwrap().len(), 0, "{v}");
    assert_eq!(v["gouge_cells"], 0, "{v}");
}

/// An open 45-degree V-groove mesh, 20 mm deep and 40 mm wide, rotated 30 degrees
/// about z, as ASCII STL.
fn groove_stl() -> String {
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let p = |u: f64, v: f64| [u * c - v * s, u * s + v * c, -20.0 + u.abs()];
    let quads = [
        [(-20.0, -30.0), (0.0, -30.0), (0.0, 30.0), (-20.0, 30.0)],
        [(0.0, -30.0), (20.0, -30.0), (20.0, 30.0), (0.0, 30.0)],
    ];
    let mut text = String::from("solid groove\n");
    for q in quads {
        for t in [[q[0], q[1], q[2]], [q[0], q[2], q[3]]] {
            text.push_str("facet normal 0 0 0\nouter loop\n");
            for (u, v) in t {
                let [x, y, z] = p(u, v);
                text.push_str(&format!("vertex {x} {y} {z}\n"));
            }
            text.push_str("endloop\nendfacet\n");
        }
    }
    text + "endsolid groove\n"
}

/// The raster on the open groove on a box stock: pass starts off the part are
/// below its top, and no approach rapid enters the box.
#[test]
fn raster_approaches_on_an_open_groove_stay_above_the_box() {
    let dir = std::env::temp_dir().join("swarf-safe-motion-groove");
    std::fs::create_dir_all(&dir).unwrap();
    let stl = dir.join("groove.stl");
    std::fs::write(&stl, groove_stl()).unwrap();
    let text = format!(
        "part = {:?}\ntool = \"ball:d=12\"\n[strategy]\nkind = \"raster\"\nscallop = 0.05\n\
         tolerance = 0.01\n[stock]\ntop = 5\n[output]\ngcode = \"groove.ngc\"\n",
        stl.display().to_string()
    );
    // The raster's own gouges at the groove's open ends crossed at an angle are the
    // tolerance's business; here the links are checked.
    let p = planned(&text, "groove.toml", Gate::AllowUnsafe).unwrap();
    let v = &p.summary["verification"];
    assert_eq!(v["stock"], "box, top 5 mm", "{v}");
    assert_eq!(v["rapid_cuts"].as_array().unwrap().len(), 0, "{v}");
    // Off the groove's open ends the ball's drop falls below the bottom (-20):
    // those starts are cut at the floor.
    assert!(p.summary["report"]["clipped_points"].as_u64().unwrap() > 0);
    assert!(lowest(&p) >= -20.0 - 1e-9, "{}", lowest(&p));
}

/// A STEP solid (OpenCASCADE's drilled plate, z 0 to 5) on a box 5 mm wider: the
/// raster's passes that roll off the plate's outer edges are cut at its bottom and
/// stay within the tool's radius of the box; with the floor raised to 2 the passes
/// over the through hole are split there and linked.
#[test]
fn a_raster_on_a_solid_stays_above_the_floor_and_in_the_stock() {
    let job = |floor: &str| {
        format!(
            "part = \"../parts/cad/plate-hole.step\"\ntool = \"ball:d=10\"\n[strategy]\n\
             kind = \"raster\"\nscallop = 0.05\n[stock]\nmargin = 5\ntop = 15\n{floor}"
        )
    };
    let whole = planned(&job(""), "plate-raster.toml", Gate::Skip).unwrap();
    assert!(whole.summary["report"]["clipped_points"].as_u64().unwrap() > 0);
    // The patches' lowest point is known within the 0.01 mm tessellation.
    assert!(lowest(&whole) >= -0.01 - 1e-9, "{}", lowest(&whole));
    for m in whole.toolpath.moves() {
        let [x, y] = [m.to.cl.x, m.to.cl.y];
        assert!((-10.0 - 1e-9..=50.0 + 1e-9).contains(&x), "x {x}");
        assert!((-10.0 - 1e-9..=40.0 + 1e-9).contains(&y), "y {y}");
    }
    let raised = planned(&job("floor = 2"), "plate-raster-2.toml", Gate::Skip).unwrap();
    assert!(lowest(&raised) >= 2.0 - 1e-9, "{}", lowest(&raised));
    let splits = raised.summary["report"]["split_passes"].as_u64().unwrap();
    assert!(splits > 0, "{}", raised.summary["report"]);
    assert!(raised.toolpath.passes.len() > whole.toolpath.passes.len());
}

/// A floor above the part (the boss's ribs are 10 high), or not a number, is
/// refused naming `stock.floor`.
#[test]
fn a_floor_above_the_part_is_refused() {
    let text = |floor: &str| {
        format!(
            "part = \"builtin:boss\"\ntool = \"ball:d=10\"\n[strategy]\nkind = \"raster\"\n\
             scallop = 0.1\n[stock]\nfloor = {floor}\n"
        )
    };
    let above = planned(&text("11"), "floor.toml", Gate::Skip)
        .err()
        .unwrap()
        .to_string();
    assert!(
        above.contains("stock.floor") && above.contains("above the part's top"),
        "{above}"
    );
    let nan = Job::parse_in(&text("nan"), "floor.toml", &jobs())
        .err()
        .unwrap()
        .to_string();
    assert!(
        nan.contains("stock.floor") && nan.contains("expected a height"),
        "{nan}"
    );
}
