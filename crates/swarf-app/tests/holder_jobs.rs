//! Holder and shank checks outside sequences: a single-operation job naming a
//! library tool (`tools = ...`), a tilted five-axis pose beside a wall, and
//! `swarf verify --tool-library` resolving each tool section's T word.
//!
//! The part is the deep pocket (60 x 60 block, top z = 40, a pocket x in [25, 35],
//! y in [10, 50] down to z = 0; `swarf-io` rest parts). The tool is the shipped
//! library's `ball6-long` (T3): ball d = 6, 12 mm of flutes, shank a cone 5 -> 6
//! over 8 then d = 6, holder a nose cone 20 -> 32 over 20 above the face, stick-out
//! 30. Closed forms: the holder face (radius 10) cannot enter the 10 mm pocket, so a
//! tip at height `z` needs the face at or above the top, `S >= 40 - z`; a path down
//! to the floor needs 40 mm.

use std::path::{Path, PathBuf};
use swarf_app::holder::avoid::{Limits, avoid};
use swarf_app::holder::path::{check_path, collision_tilt, refusal};
use swarf_app::holder::{HolderRequest, POSE_SPACING, check_request, library_specs};
use swarf_app::model::load_model_with;
use swarf_app::plan_job::{part_arg, plan_model_toolpath};
use swarf_app::verify::{GcodeSetup, SimSettings, VerifyRequest, verify_in_memory};
use swarf_app::{Job, Outputs};
use swarf_geom::{Point3, Vec3};
use swarf_sim::Quiet;
use swarf_tool::Pose;
use swarf_tool::holder::tilted::{Tilt, TiltSearch};
use swarf_tool::library::ToolLibrary;
use swarf_toolpath::{Feeds, Linking, Pass, PathPoint, Toolpath};

fn jobs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../jobs")
}

fn library_file() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tooling/library.toml")
}

fn temp(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("swarf-holder-jobs-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A raster finish of the deep pocket with the library tool `tool`.
fn deep_job(library: &str, tool: &str) -> String {
    format!(
        "name = \"deep pocket\"\npart = \"builtin:deep-pocket\"\ntools = \"{library}\"\n\
         tool = {tool}\n\
         [strategy]\nkind = \"raster\"\nscallop = 0.5\ntolerance = 0.01\n\
         [output]\ngcode = \"deep.ngc\"\nsummary = \"deep.json\"\n"
    )
}

#[test]
fn a_single_job_with_a_library_tool_is_refused_naming_the_stick_out_that_clears() {
    let job = Job::parse_in(
        &deep_job("../tooling/library.toml", "\"ball6-long\""),
        "deep.toml",
        &jobs(),
    )
    .unwrap();
    let tool = job.library_tool.as_ref().unwrap();
    assert_eq!(
        (tool.number, job.tool.to_string()),
        (3, "ball:d=6,length=12".into())
    );
    assert_eq!(
        (job.feeds.feed, job.feeds.spindle, job.feeds.plunge),
        (1200.0, 12000.0, 300.0),
        "the library's feeds"
    );
    let mut out = Outputs::new(&temp("refused"));
    let err = swarf_app::plan_job(&job, &jobs(), &mut out, &Quiet)
        .unwrap_err()
        .to_string();
    eprintln!("{err}");
    assert!(
        err.contains("holder: deep pocket with T3 \"ball6-long\" at stick-out 30 mm")
            && err.contains("collide (first: pass ")
            && err.contains(", line "),
        "{err}"
    );
    // Closed form of the first collision: the face 30 above the tip at height z
    // is 40 - 30 - z below the top.
    let (depth, at) = err
        .split_once("holder[0] ")
        .and_then(|(_, rest)| rest.split_once(" mm into the part at ("))
        .unwrap();
    let z: f64 = at.split([',', ')']).nth(2).unwrap().trim().parse().unwrap();
    let depth: f64 = depth.parse().unwrap();
    assert!((depth - (10.0 - z)).abs() < 2e-3, "{depth} at z {z}");
    // Closed form: 40 - 0 (the floor).
    assert!(
        err.contains("shortest stick-out that clears: 40.000 mm"),
        "{err}"
    );
    // The same by T number; a number the library lacks names the line and lists the
    // library; a library key without a library.
    let by_number = Job::parse_in(
        &deep_job("../tooling/library.toml", "3"),
        "deep.toml",
        &jobs(),
    )
    .unwrap();
    assert_eq!(by_number.library_tool, job.library_tool);
    let err = Job::parse_in(
        &deep_job("../tooling/library.toml", "7"),
        "deep.toml",
        &jobs(),
    )
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("deep.toml") && err.contains("line 4: tool") && err.contains("ball6-long"),
        "{err}"
    );
    let text = deep_job("x", "3").replace("tools = \"x\"\n", "");
    let err = Job::parse_in(&text, "deep.toml", &jobs())
        .unwrap_err()
        .to_string();
    assert!(err.contains("no `tools` library"), "{err}");
    // An error after the tool keeps its line.
    let bad = deep_job("../tooling/library.toml", "3").replace("scallop = 0.5", "scallop = -1");
    let err = Job::parse_in(&bad, "deep.toml", &jobs())
        .unwrap_err()
        .to_string();
    assert!(err.contains("strategy.scallop"), "{err}");
}

#[test]
fn with_enough_stick_out_the_job_plans_and_reports_the_clearance() {
    let dir = temp("clears");
    let shipped = std::fs::read_to_string(library_file()).unwrap();
    let longer = shipped.replace("stick_out = 30", "stick_out = 41");
    std::fs::write(dir.join("library.toml"), longer).unwrap();
    let job = Job::parse_in(&deep_job("library.toml", "3"), "deep.toml", &dir).unwrap();
    let mut out = Outputs::new(&dir);
    let summary = swarf_app::plan_job(&job, &dir, &mut out, &Quiet).unwrap();
    let h = &summary["holder"];
    eprintln!("{h}");
    assert_eq!(h["number"], 3);
    assert_eq!(
        (h["stick_out"].as_f64(), h["tilted"].as_u64()),
        (Some(41.0), Some(0))
    );
    let shortest = h["shortest"]["Clears"]["stick_out"].as_f64().unwrap();
    assert!((shortest - 40.0).abs() < 1e-9, "{shortest}");
    // The holder face clears the top by 41 - 40 = 1 mm at the floor, and nothing
    // comes closer (the shank, radius 3 as the ball's, stands off the walls).
    let least = h["min_clearance"].as_f64().unwrap();
    assert!((least - 1.0).abs() < 1e-9, "{least}");
    let poses = h["poses"].as_u64().unwrap();
    assert!(poses as usize >= summary["poses"].as_u64().unwrap() as usize);
    out.commit().unwrap();
    let program = std::fs::read_to_string(dir.join("deep.ngc")).unwrap();
    assert!(
        program.contains("T3 M6") || program.contains("T3M6"),
        "the library's T number"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// One pass of tips at z = 5 through the points `xy`, the axis tilted `t0` from +z
/// toward -x.
fn tilted_path(t0: f64, xy: impl Iterator<Item = (f64, f64)>) -> Toolpath {
    let axis = Vec3::new(-t0.sin(), 0.0, t0.cos());
    let pass = Pass {
        points: xy
            .map(|(x, y)| PathPoint::new(Pose::new(Point3::new(x, y, 5.0), axis).unwrap()))
            .collect(),
        ..Pass::default()
    };
    Toolpath {
        passes: vec![pass],
        feeds: Feeds::default(),
        linking: Linking::default(),
    }
}

/// A tool tilted away from the block's wall x = 0 with its tip at (-3, 30, 5): the
/// holder's nose cone (radius 10 + 0.3 h, h above the face 30 above the tip) meets
/// the block's top edge (x = 0, z = 40). In the tool frame at tilt `t` from +z toward
/// -x the edge is at height `z' = 35 cos t - 3 sin t` and radius `rho = 3 cos t + 35
/// sin t`; the cone clears it once `rho = 10 + 0.3 (z' - 30)`, i.e.
/// `35.9 sin t - 7.5 cos t = 1`: `t = atan2(7.5, 35.9) + asin(1 / hypot(35.9, 7.5))`.
#[test]
fn a_tilted_pose_beside_a_wall_names_the_tilt_that_clears() {
    let library = ToolLibrary::read(&library_file()).unwrap();
    let tool = library.get("ball6-long").unwrap();
    let mesh = swarf_io::builtin_mesh("deep-pocket").unwrap();
    let t0 = 12f64.to_radians();
    let toolpath = tilted_path(t0, [30.0, 30.5].map(|y| (-3.0, y)).into_iter());
    let check = check_path(&mesh, &toolpath, tool, "five-axis").unwrap();
    assert_eq!((check.poses, check.tilted), (2, 2));
    let first = check.collisions[0];
    assert_eq!(first.pass, Some([0, 0]));
    // Closed form of the depth at t0: the edge at rho0 = 3 cos t0 + 35 sin t0 > 10
    // sits under the cone, whose bottom there is 30 + (rho0 - 10) / 0.3.
    let (z0, rho0) = (
        35.0 * t0.cos() - 3.0 * t0.sin(),
        3.0 * t0.cos() + 35.0 * t0.sin(),
    );
    let depth = z0 - (30.0 + (rho0 - 10.0) / 0.3);
    assert!((first.depth - depth).abs() < 1e-6, "{first:?} vs {depth}");
    let t_clear = 7.5f64.atan2(35.9) + (1.0 / 35.9f64.hypot(7.5)).asin();
    let Tilt::Clears { tilt, .. } =
        collision_tilt(&mesh, tool, &first, &TiltSearch::default()).unwrap()
    else {
        panic!("no tilt clears");
    };
    eprintln!(
        "extra tilt {:.5} deg, closed form {:.5} deg",
        tilt.to_degrees(),
        (t_clear - t0).to_degrees()
    );
    assert!((tilt - (t_clear - t0)).abs() < 2e-4, "{tilt}");
    let s = refusal(&mesh, tool, &check, Some(25f64.to_radians())).unwrap();
    assert!(
        s.contains("tilting the axis at pass 0, pose 0 a further 1.36")
            && s.contains("leads up to 25.000 deg"),
        "{s}"
    );
}

/// The pose above, on a pass that comes toward the wall along x from x = -30 to -3,
/// tilted clear by holder avoidance: the ball turns about its centre `C` (the cut is
/// unchanged), so the tip moves to `C - 3 a(t)`. With `(p, q) = E - C = (3 + 3 sin
/// t0, 35 - 3 cos t0)` from `C` to the edge `E`, the edge sits in the frame of tilt
/// `t` at `z' = q cos t - p sin t + 3` and `rho = p cos t + q sin t`, and the cone
/// clears it once `(q + 0.3 p) sin t + (p - 0.3 q) cos t = 1.9`. The least tilt is
/// applied where the pass meets the wall, tilts change by at most the rate limit per
/// mm, far poses are untouched, and the path clears.
#[test]
fn holder_avoidance_tilts_a_pass_beside_a_wall_clear_about_the_ball_centre() {
    let library = ToolLibrary::read(&library_file()).unwrap();
    let tool = library.get("ball6-long").unwrap();
    let mesh = swarf_io::builtin_mesh("deep-pocket").unwrap();
    let t0 = 12f64.to_radians();
    let mut toolpath = tilted_path(t0, (0..=27).map(|i| (-30.0 + f64::from(i), 30.0)));
    let before = toolpath.clone();
    assert!(
        !check_path(&mesh, &toolpath, tool, "")
            .unwrap()
            .collisions
            .is_empty()
    );
    let rate = 0.5f64.to_radians();
    let limits = Limits {
        max_rate: rate,
        max_tilt: 60f64.to_radians(),
        max_lean: None,
    };
    let a = avoid(&mesh, tool, &mut toolpath, &limits).unwrap().unwrap();
    let after = check_path(&mesh, &toolpath, tool, "").unwrap();
    assert!(
        after.collisions.is_empty(),
        "{:?}",
        after.collisions.first()
    );
    let (p, q) = (3.0 + 3.0 * t0.sin(), 35.0 - 3.0 * t0.cos());
    let (ca, cb) = (q + 0.3 * p, p - 0.3 * q);
    let closed = (1.9 / ca.hypot(cb)).asin() - cb.atan2(ca) - t0;
    let old = &before.passes[0].points;
    let new = &toolpath.passes[0].points;
    let tilts: Vec<f64> = old
        .iter()
        .zip(new)
        .map(|(o, n)| o.pose.axis.angle(&n.pose.axis))
        .collect();
    let last = tilts[tilts.len() - 1];
    eprintln!(
        "applied tilt at the wall {:.5} deg, closed form {:.5} deg; {} poses tilted, up to {:.4} deg in {} rounds",
        last.to_degrees(),
        closed.to_degrees(),
        a.tilted_poses,
        a.largest_tilt_deg,
        a.rounds
    );
    assert!(
        (last - closed).abs().to_degrees() < 0.01,
        "{last} vs {closed}"
    );
    assert_eq!(
        tilts[0], 0.0,
        "the pose 27 mm from the wall clears as it is"
    );
    for (k, w) in tilts.windows(2).enumerate() {
        assert!((w[1] - w[0]).abs() <= rate * 1.0 + 1e-9, "pose {k}: {w:?}");
    }
    for (o, n) in old.iter().zip(new) {
        let centre = |q: &PathPoint| q.pose.cl + 3.0 * q.pose.axis;
        assert!((centre(o) - centre(n)).norm() < 1e-9);
        assert!(n.pose.axis.y.abs() < 1e-12 && n.pose.axis.x <= o.pose.axis.x + 1e-12);
    }
    assert_eq!(a.tilted_poses, tilts.iter().filter(|&&t| t > 0.0).count());
}

/// The deep pocket's outer wall as a part file: the floor z = 0 for x in [-40, 0],
/// the wall x = 0 up to z = 40 and its top for x in [0, 20], y in [0, 60] (three
/// planar patches, normals out of the material).
const WALL_FLOOR: &str = "name = \"wall-floor\"
units = \"mm\"
[[patch]]
degree = [1, 1]
points = [[-40, 0, 0], [-40, 60, 0], [0, 0, 0], [0, 60, 0]]
[[patch]]
degree = [1, 1]
points = [[0, 0, 0], [0, 60, 0], [0, 0, 40], [0, 60, 40]]
[[patch]]
degree = [1, 1]
points = [[0, 0, 40], [0, 60, 40], [20, 0, 40], [20, 60, 40]]
";

/// A five-axis job beside that wall: the floor finished along y, one way, by the
/// `ball6-long` inclined 12 degrees sideways away from the wall, its centre at most
/// 3 from the wall. On the floor the ball's centre `C` stays 3 above it whatever the
/// axis; where the holder's nose cone meets the top edge `E = (0, 40)` the axis is
/// tilted further about `C` to the least total tilt `t` with `(q + 0.3 p) sin t +
/// (p - 0.3 q) cos t = 1.9`, `(p, q) = E - C` (the closed form above, from the
/// vertical); the poses farther out keep their 12 degrees, the plan clears and the
/// positioning's gouge check finds nothing on the tilted poses.
#[test]
fn a_five_axis_job_beside_a_wall_plans_with_the_clearing_tilt() {
    let dir = temp("wall");
    std::fs::write(dir.join("wall-floor.toml"), WALL_FLOOR).unwrap();
    let text = format!(
        "part = \"wall-floor.toml\"\ntools = {:?}\ntool = \"ball6-long\"\n\
         [strategy]\nkind = \"raster\"\nangle = 90\nstepover = 1\nzigzag = false\n\
         boundary = [-12, 20, -3.05, 40]\n\
         [positioning]\nmethod = \"inclined\"\nalpha = 0\ntilt = 12\n",
        library_file().display().to_string()
    );
    let job = Job::parse_in(&text, "wall.toml", &dir).unwrap();
    let model = load_model_with(&part_arg(&job, &dir), &job.load_options()).unwrap();
    let mut out = Outputs::new(&dir);
    let planned = plan_model_toolpath(&job, &model, &dir, &mut out, &Quiet).unwrap();
    let avoided = &planned.summary["holder"]["avoidance"];
    eprintln!("{avoided}");
    let t0 = 12f64.to_radians();
    let (mut tilted, mut largest) = (0, 0f64);
    for pass in &planned.toolpath.passes {
        for q in &pass.points {
            let Pose { cl, axis } = q.pose;
            let centre = cl + 3.0 * axis;
            assert!((centre.z - 3.0).abs() < 1e-6, "{q:?}");
            let t = axis.angle(&Vec3::z());
            let (p, q) = (-centre.x, 40.0 - centre.z);
            let (ca, cb) = (q + 0.3 * p, p - 0.3 * q);
            let need = (1.9 / ca.hypot(cb)).asin() - cb.atan2(ca);
            let expected = if need > t0 { need } else { t0 };
            assert!(axis.x < 0.0, "away from the wall: {axis:?}");
            assert!(
                (t - expected).abs().to_degrees() < 0.01,
                "{t} vs {expected} at {cl:?}"
            );
            if need > t0 {
                tilted += 1;
                largest = largest.max(need - t0);
            }
        }
    }
    eprintln!(
        "{tilted} poses tilted, up to {:.4} deg more",
        largest.to_degrees()
    );
    assert!(tilted > 0);
    // The holder check after the tilt (the plan would be refused otherwise).
    let least = planned.summary["holder"]["min_clearance"].as_f64().unwrap();
    assert!(least >= 0.0, "{least}");
    // The positioning's gouge check, run again on the tilted poses.
    let positioned = &planned.summary["positioning"];
    assert_eq!(positioned["gouging_poses"], 0, "{positioned}");
    assert!(positioned["max_axis_rate_deg_per_mm"].as_f64().unwrap() <= 0.5 + 1e-9);
    assert_eq!(avoided["tilted_poses"], tilted);
    assert!((avoided["largest_tilt_deg"].as_f64().unwrap() - largest.to_degrees()).abs() < 0.01);
    let _ = std::fs::remove_dir_all(&dir);
}

fn holder_request<'a>(
    programs: &'a [PathBuf],
    library: &'a Path,
    tools: &'a [String],
    gcode: &'a GcodeSetup,
) -> HolderRequest<'a> {
    HolderRequest {
        part: "builtin:deep-pocket",
        programs,
        library,
        tools,
        gcode,
        machine: None,
        tool_length: None,
        tol: 0.01,
        spacing: POSE_SPACING,
    }
}

/// Two tools in one program on the deep pocket: T1 (flat d=10) skims 0.5 mm into
/// the top (a gouge), T3 (ball d=6) runs along the pocket's floor (its holder hits
/// the top).
const TWO_TOOLS: &str = "G21 G90 G17\nT1 M6\nS9000 M3\nG0 X-10 Y5 Z60\nG0 Z39.5\n\
G1 X70 F900\nG0 Z60\nT3 M6\nS12000 M3\nG0 X30 Y20\nG0 Z10\nG1 Z0 F300\nG1 Y40\nG0 Z60\nM30\n";

#[test]
fn verify_looks_up_each_tool_sections_t_word_in_the_library() {
    let dir = temp("verify");
    let program = dir.join("two.ngc");
    std::fs::write(&program, TWO_TOOLS).unwrap();
    let programs = [program.clone()];
    let gcode = GcodeSetup::default();
    let library = library_file();
    let explicit = ["1".to_string(), "3".to_string()];
    let request = |tools| holder_request(&programs, &library, tools, &gcode);
    let by_t = library_specs(&request(&[])).unwrap();
    assert_eq!(by_t, library_specs(&request(&explicit)).unwrap());
    assert_eq!(by_t, ["flat:d=10,length=22", "ball:d=6,length=12"]);
    let sim = SimSettings {
        cell: Some(0.5),
        tol: Some(0.01),
        ..SimSettings::default()
    };
    let verify = |tools: &[String]| {
        let req = VerifyRequest {
            part: "builtin:deep-pocket",
            programs: &programs,
            tools,
            gcode: &gcode,
            machine: None,
            tool_length: None,
            sim: &sim,
            out: &dir,
            partial: false,
        };
        let v = verify_in_memory(&req, &Quiet).unwrap().verification;
        let s = &v.deviation.summary;
        (
            s.gouge.cells,
            s.gouge.worst,
            s.excess.cells,
            format!("{s:?}"),
        )
    };
    let lib = ToolLibrary::read(&library).unwrap();
    let specs: Vec<String> = explicit
        .iter()
        .map(|k| lib.get(k).unwrap().assembly.cutter.to_string())
        .collect();
    let (a, b) = (verify(&by_t), verify(&specs));
    assert_eq!(a, b);
    // The flat skims 0.5 mm into the top: gouge cells, worst 0.5 mm deep.
    eprintln!("gouge cells {}, worst {}, excess cells {}", a.0, a.1, a.2);
    assert!(a.0 > 0 && (a.1 + 0.5).abs() < 0.02, "{a:?}");
    // The holder check per tool section: T1 clears, T3's holder sits 10 mm into the
    // top at the floor (closed form 40 - 30).
    let checks = check_request(&request(&[])).unwrap();
    assert_eq!(checks.len(), 2);
    assert_eq!((checks[0].number, checks[1].number), (1, 3));
    assert!(
        checks[0].collisions.is_empty(),
        "{:?}",
        checks[0].collisions
    );
    let deepest = checks[1]
        .collisions
        .iter()
        .map(|c| c.depth)
        .fold(0.0, f64::max);
    assert!((deepest - 10.0).abs() < 1e-9, "{deepest}");
    assert_eq!(checks, check_request(&request(&explicit)).unwrap());
    // A T number the library lacks: the line where it cuts and the library file.
    let missing = dir.join("missing.ngc");
    std::fs::write(&missing, TWO_TOOLS.replace("T3 M6", "T7 M6")).unwrap();
    let missing = [missing];
    let req = HolderRequest {
        programs: &missing,
        ..request(&[])
    };
    let err = library_specs(&req).unwrap_err().to_string();
    assert!(
        err.contains("line 10: T7") && err.contains("library.toml") && err.contains("ball6-long"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
