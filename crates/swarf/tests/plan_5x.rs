//! `swarf plan` on five-axis jobs (thesis 000 ch. 8 on die.toml, with a wide cross
//! feed so that it runs in seconds): the G-code for the A/C trunnion is accepted by
//! LinuxCNC's `rs274` (when installed; required when `SWARF_REQUIRE_REFERENCES=1`) and
//! its canonical feeds, through the machine's forward kinematics, reach the APT CL's
//! poses in order (with the post's extra blocks on the chords between them); the CL carries the tilted axes (at the lead angle from the surface normal at
//! each CC point, to 1e-6 rad); the summary holds the positioning report; bad
//! five-axis jobs fail with the field or the place.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use swarf_fiveaxis::machine::Machine;
use swarf_fiveaxis::machine::kinematics::Joints;
use swarf_geom::{Point3, Vec3};
use swarf_testkit::machines::TRUNNION;
use swarf_testkit::rs274::run_rs274;

fn swarf(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swarf"))
        .args(args)
        .output()
        .expect("the swarf binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("swarf-5x-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn machine_text() -> String {
    TRUNNION.to_string()
}

/// Die, bull R 12.7 r 6.35, 60 degrees off X, cross feed 20 mm; the machine file
/// beside the job.
fn job(positioning: &str) -> String {
    format!(
        r#"name = "die, five-axis test"
part = "builtin:die"
tool = "bull:d=38.1,r=6.35"
positioning = {positioning}
[strategy]
kind = "iso-planar"
stepover = 20
tolerance = 0.01
angle = 60
[feeds]
feed = 150
spindle = 1200
[output]
machine = "trunnion.toml"
feed_mode = "inverse-time"
gcode = "die.ngc"
cl = "die.cl"
summary = "die.json"
"#
    )
}

fn plan(dir: &Path, text: &str) -> Output {
    plan_with(dir, text, &[])
}

/// [`plan`] with more arguments.
fn plan_with(dir: &Path, text: &str, more: &[&str]) -> Output {
    std::fs::write(dir.join("trunnion.toml"), machine_text()).unwrap();
    let path = dir.join("job.toml");
    std::fs::write(&path, text).unwrap();
    let mut args = vec!["plan", path.to_str().unwrap()];
    args.extend_from_slice(more);
    swarf(&args)
}

/// The feed `GOTO` poses of an APT CL file (those not after `RAPID`).
fn cl_feed_poses(text: &str) -> Vec<(Point3, Vec3)> {
    let mut out = Vec::new();
    let mut rapid = false;
    for line in text.lines() {
        if line == "RAPID" {
            rapid = true;
        } else if let Some(args) = line.strip_prefix("GOTO/") {
            let v: Vec<f64> = args.split(',').map(|s| s.parse().unwrap()).collect();
            assert_eq!(v.len(), 6, "{line}");
            if !rapid {
                out.push((Point3::new(v[0], v[1], v[2]), Vec3::new(v[3], v[4], v[5])));
            }
            rapid = false;
        }
    }
    out
}

/// `rs274 -g` on `program`: the machine positions of its `STRAIGHT_FEED` lines, or
/// `None` when rs274 is not installed.
fn rs274_feeds(program: &Path) -> Option<Vec<Joints>> {
    let text = std::fs::read_to_string(program).unwrap();
    let text = run_rs274(&text, "plan-5x")?.clean("die.ngc");
    let mut feeds = Vec::new();
    for line in text.lines() {
        if let Some(args) = line.split("STRAIGHT_FEED(").nth(1) {
            let v: Vec<f64> = args
                .trim_end_matches(')')
                .split(',')
                .map(|s| s.trim().parse().unwrap())
                .collect();
            feeds.push(Joints {
                linear: Vec3::new(v[0], v[1], v[2]),
                // A and C: the words of this machine.
                rotary: [v[3].to_radians(), v[5].to_radians()],
            });
        }
    }
    Some(feeds)
}

/// Every pose of `cl` is a feed end of `feeds` (through the trunnion's forward
/// kinematics), in order; the post's extra blocks (where a rotary axis turns) keep
/// the tip on the chord between two poses (path_tol 0.01 mm).
fn assert_feeds_reach(feeds: &[Joints], cl: &[(Point3, Vec3)]) {
    let m = Machine::parse(&machine_text(), "trunnion").unwrap();
    let mut k = 0;
    for j in feeds {
        let pose = m.forward(j, 0.0);
        let on = |i: usize| (pose.cl - cl[i].0).norm() < 2e-3;
        if k < cl.len() && on(k) {
            assert!(
                (pose.axis - cl[k].1).norm() < 1e-5,
                "{pose:?} vs {:?}",
                cl[k]
            );
            k += 1;
        } else {
            assert!(k > 0 && k < cl.len(), "a feed before or after the poses");
            let (a, b) = (cl[k - 1].0, cl[k].0);
            let t = ((pose.cl - a).dot(&(b - a)) / (b - a).norm_squared()).clamp(0.0, 1.0);
            let off = (pose.cl - (a + t * (b - a))).norm();
            assert!(off < 0.01 + 2e-3, "{off} mm off the chord before pose {k}");
        }
    }
    assert_eq!(k, cl.len(), "every pose is reached, in order");
}

/// The shipped drop-spin job (paper 003) on edge-concave: four passes in each band
/// over 19 stations, every pose reported in the contacts CSV with `P` on the face
/// dropped on and `Q` on the other, the CL tilted, the G-code accepted by `rs274`
/// with its feeds reaching the CL's poses in order, and the summary's A/C ranges
/// those of the program.
#[test]
fn drop_spin_job_writes_checked_five_axis_outputs() {
    let dir = temp_dir("drop-spin");
    let job = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../jobs/edge-concave-drop-spin.toml");
    let o = swarf(&[
        "plan",
        job.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let read = |f: &str| std::fs::read_to_string(dir.join(f)).unwrap();
    let summary: serde_json::Value =
        serde_json::from_str(&read("edge-concave-drop-spin.json")).unwrap();
    assert_eq!(summary["passes"], 8);
    let poses = summary["poses"].as_u64().unwrap() as usize;
    assert_eq!(summary["drop_spin"]["issues"].as_array().unwrap().len(), 0);
    let contacts = read("edge-concave-drop-spin-contacts.csv");
    assert_eq!(contacts.lines().count(), poses + 1);
    for line in contacts.lines().skip(1) {
        let v: Vec<&str> = line.split(',').collect();
        let y = |i: usize| v[i].parse::<f64>().unwrap();
        // Face 0 lies at y < 0, face 1 at y > 0.
        match v[1] {
            "0" => assert!(y(7) < 0.0 && y(10) > 0.0, "{line}"),
            _ => assert!(y(7) > 0.0 && y(10) < 0.0, "{line}"),
        }
    }
    assert_eq!(poses, 8 * 19);
    let cl = cl_feed_poses(&read("edge-concave-drop-spin.cl"));
    assert_eq!(cl.len(), poses);
    assert!(cl.iter().all(|(_, a)| a.angle(&Vec3::z()) > 0.3), "tilted");
    if let Some(feeds) = rs274_feeds(&dir.join("edge-concave-drop-spin.ngc")) {
        assert_feeds_reach(&feeds, &cl);
        for (k, name) in ["A", "C"].into_iter().enumerate() {
            let range = &summary["rotary_ranges_deg"][name];
            let (lo, hi) = feeds
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |r, j| {
                    let a = j.rotary[k].to_degrees();
                    (r.0.min(a), r.1.max(a))
                });
            eprintln!("{name}: summary {range}, rs274 feeds [{lo:.4}, {hi:.4}]");
            assert!(
                (range[0].as_f64().unwrap() - lo).abs() < 1e-3,
                "{name} {range} {lo}"
            );
            assert!(
                (range[1].as_f64().unwrap() - hi).abs() < 1e-3,
                "{name} {range} {hi}"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The same job planned in-process on its stock: the positioned passes with their
/// contacts (none where a pass is cut at the floor), and that floor.
fn positioned(text: &str) -> (Vec<swarf_toolpath::Pass>, f64) {
    let job = swarf_app::Job::parse(text, "job.toml").unwrap();
    let part = swarf_io::builtin_part("die").unwrap();
    let model = swarf_app::model::Model::Patches(part.clone());
    let job = job.on_stock(&model, Path::new(".")).unwrap();
    let mut plan = swarf_app::plan(&job, swarf_app::PlanInput::Part(&part)).unwrap();
    swarf_app::five_axis::position_plan(&job, &part, &mut plan, &|_, _| {}).unwrap();
    (plan.toolpath.passes, job.reach.unwrap().floor)
}

#[test]
fn inclined_die_job_writes_checked_five_axis_outputs() {
    let dir = temp_dir("inclined");
    let text = job(r#"{ method = "inclined", alpha = 6, sections = 2.0 }"#);
    // The fixed lead gouges the die: the gate refuses it, naming the moves.
    let refused = plan(&dir, &text);
    assert!(!refused.status.success());
    assert!(
        stderr(&refused).contains("gouged beyond 0.01 mm"),
        "{}",
        stderr(&refused)
    );
    assert!(!dir.join("die.ngc").exists());
    let o = plan_with(&dir, &text, &["--allow-unsafe"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("die.json")).unwrap()).unwrap();
    let poses = summary["poses"].as_u64().unwrap() as usize;
    let p = &summary["positioning"];
    assert_eq!(p["method"], "inclined");
    assert_eq!(p["poses"].as_u64(), Some(poses as u64));
    assert_eq!(p["alpha_range_deg"], serde_json::json!([6.0, 6.0]));
    assert!(p["gouging_poses"].as_u64().is_some() && p["worst_depth"].is_number());
    assert!(summary["machine"].as_str().unwrap().contains("trunnion"));
    // The CL carries the tilted axes: 6 degrees from the normal at each CC point.
    let cl = cl_feed_poses(&std::fs::read_to_string(dir.join("die.cl")).unwrap());
    let (passes, floor) = positioned(&text);
    let points: Vec<_> = passes.iter().flat_map(|p| &p.points).collect();
    assert_eq!(cl.len(), poses);
    assert_eq!(points.len(), poses);
    let alpha = 6f64.to_radians();
    let mut tilted_from_z = 0.0f64;
    // The tilted bull hangs over the die's edge, below its lowest point: the passes
    // are cut where the tool's lowest point meets that floor.
    let clipped = summary["report"]["clipped_points"].as_u64().unwrap_or(0);
    assert!(clipped > 0, "{}", summary["report"]);
    let tool = swarf_app::Job::parse(&text, "job.toml")
        .unwrap()
        .tool
        .profile();
    let mut cut_at_floor = 0;
    for ((cl_point, axis), p) in cl.iter().zip(&points) {
        assert!((cl_point - p.pose.cl).norm() < 1e-5);
        let lowest = p.pose.cl.z + tool.lowest_when_tilted(axis.z);
        let Some(contact) = p.contact else {
            cut_at_floor += 1;
            // On the floor, or a little above where the axis turns along the cut
            // segment (the depth is taken as linear between its ends).
            assert!(
                lowest > floor - 1e-4 && lowest < floor + 0.01,
                "{lowest} {floor}"
            );
            continue;
        };
        let normal = contact.normal;
        assert!(
            (axis.angle(&normal) - alpha).abs() < 1e-6,
            "{axis:?} {normal:?}"
        );
        tilted_from_z = tilted_from_z.max(axis.angle(&Vec3::z()));
    }
    assert!(tilted_from_z > 20f64.to_radians(), "{tilted_from_z}");
    assert!(cut_at_floor > 0 && cut_at_floor < 20, "{cut_at_floor}");
    // rs274 accepts the G-code; its feeds are the CL's poses, one per pose.
    let ngc = std::fs::read_to_string(dir.join("die.ngc")).unwrap();
    for want in [
        "G93",
        "(positioning inclined, lead 6 deg",
        "(machine A/C trunnion",
    ] {
        assert!(ngc.contains(want), "{want}");
    }
    if let Some(feeds) = rs274_feeds(&dir.join("die.ngc")) {
        assert_feeds_reach(&feeds, &cl);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn gouge_free_die_job_has_no_gouging_pose() {
    let dir = temp_dir("auto");
    let o = plan(
        &dir,
        &job(r#"{ method = "gouge-free", max_alpha = 25, sections = 1.0 }"#),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("die.json")).unwrap()).unwrap();
    let p = &summary["positioning"];
    assert_eq!(p["method"], "gouge-free");
    assert_eq!(p["gouging_poses"].as_u64(), Some(0));
    assert!(p["worst_depth"].as_f64().unwrap() <= 0.01);
    let [lo, hi] = [0, 1].map(|k| p["alpha_range_deg"][k].as_f64().unwrap());
    assert!(0.0 <= lo && lo < hi && hi < 25.0, "{lo} {hi}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_five_axis_jobs_fail_with_the_field_or_the_place() {
    let dir = temp_dir("bad");
    // No gouge-free lead up to 2 degrees: the pass, the point and the CC point.
    let o = plan(
        &dir,
        &job(r#"{ method = "gouge-free", max_alpha = 2, sections = 1.0 }"#),
    );
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(
        e.contains("no gouge-free lead angle up to max_alpha = 2") && e.contains("(CC ["),
        "{e}"
    );
    assert!(e.contains("pass ") && e.contains(", point "), "{e}");
    // A tilted path with G-code and no machine.
    let text =
        job(r#"{ method = "inclined", alpha = 6 }"#).replace("machine = \"trunnion.toml\"\n", "");
    let o = plan(&dir, &text);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("output.machine"), "{}", stderr(&o));
    // A machine file that is not there, and an unreachable pose.
    let text =
        job(r#"{ method = "inclined", alpha = 6 }"#).replace("trunnion.toml\"", "lathe.toml\"");
    let o = plan(&dir, &text);
    assert!(stderr(&o).contains("lathe.toml"), "{}", stderr(&o));
    std::fs::write(
        dir.join("tight.toml"),
        machine_text().replace("limits = [-30, 120]", "limits = [-5, 5]"),
    )
    .unwrap();
    let text =
        job(r#"{ method = "inclined", alpha = 6 }"#).replace("trunnion.toml\"", "tight.toml\"");
    let path = dir.join("tight-job.toml");
    std::fs::write(&path, text).unwrap();
    let o = swarf(&["plan", path.to_str().unwrap()]);
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(e.contains("pass 0, point ") && e.contains("axis A"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}
