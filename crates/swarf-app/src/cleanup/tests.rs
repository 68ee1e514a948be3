use super::*;
use crate::model::load_model;

fn job(text: &str) -> Result<Job> {
    Job::parse(text, "test.toml")
}

const PENCIL: &str = r#"
    part = "builtin:v-grooves"
    tool = "ball:d=4"
    [parent]
    tool = "ball:d=12"
    [strategy]
    kind = "cleanup"
    pattern = "flow-cut"
    scallop = 0.01
"#;

#[test]
fn a_chain_cleans_up_after_each_tool_in_turn() {
    let text = PENCIL.replace(
        "kind = \"cleanup\"",
        "kind = \"cleanup\"\nchain = [\"ball:d=8\"]",
    );
    let j = job(&text).unwrap();
    let model = load_model(&j.part).unwrap();
    let stages = plan_cleanup_job(&j, &model, Path::new("."), None).unwrap();
    assert_eq!(stages.len(), 2);
    assert_eq!(
        (stages[0].reference.to_string(), stages[0].tool.to_string()),
        ("ball:d=12".into(), "ball:d=8".into())
    );
    assert_eq!(
        (stages[1].reference.to_string(), stages[1].tool.to_string()),
        ("ball:d=8".into(), "ball:d=4".into())
    );
    // Each stage's rest is the closed form of its reference ball in the 90 degree
    // groove: R / sin 45 - R.
    for s in &stages {
        let r = s.reference.radius();
        let exact = r * 2f64.sqrt() - r;
        let groove = s
            .detection
            .regions
            .iter()
            .find(|g| (g.deepest.x - 55.0).abs() < 1.0)
            .unwrap();
        assert!(
            (groove.depth - exact).abs() < 1e-6,
            "{} vs {exact}",
            groove.depth
        );
        assert!(!s.plan.toolpath.passes.is_empty());
    }
    assert_eq!(stage_file("out/pocket.ngc", 1), "out/pocket.1.ngc");
}

#[test]
fn cleanup_jobs_say_what_is_wrong() {
    let bad = |from: &str, to: &str| job(&PENCIL.replace(from, to)).unwrap_err().to_string();
    assert!(bad("[parent]\n    tool = \"ball:d=12\"", "").contains("[parent]"));
    assert!(
        bad(
            "tool = \"ball:d=12\"",
            "tool = \"ball:d=12\"\n    job = \"f.toml\""
        )
        .contains("exactly one")
    );
    assert!(
        bad(
            "pattern = \"flow-cut\"",
            "pattern = \"flow-cut\"\n    merge = 0"
        )
        .contains("strategy.merge")
    );
    assert!(
        bad(
            "pattern = \"flow-cut\"",
            "pattern = \"flow-cut\"\n    overlap = -1"
        )
        .contains("strategy.overlap")
    );
    assert!(
        bad(
            "pattern = \"flow-cut\"",
            "pattern = \"flow-cut\"\n    min_area = 0"
        )
        .contains("strategy.min_area")
    );
    assert!(
        bad(
            "pattern = \"flow-cut\"",
            "pattern = \"flow-cut\"\n    source = \"stock\""
        )
        .contains("parent job")
    );
    assert!(bad("pattern = \"flow-cut\"", "pattern = \"spiral\"").contains("expected `flow-cut`"));
    // A parent job that does not exist; a cleanup tool larger than the parent's.
    let j = job(&PENCIL.replace("tool = \"ball:d=12\"", "job = \"no-such-finish.toml\"")).unwrap();
    let model = load_model(&j.part).unwrap();
    let e = plan_cleanup_job(&j, &model, Path::new("/nonexistent"), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("no-such-finish.toml"), "{e}");
    let j = job(&PENCIL.replace("tool = \"ball:d=4\"", "tool = \"ball:d=16\"")).unwrap();
    let e = plan_cleanup_job(&j, &model, Path::new("."), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("ball:d=16") && e.contains("ball:d=12"), "{e}");
}

#[test]
fn no_rest_gives_an_empty_program_that_says_so() {
    let dir = std::env::temp_dir().join(format!("swarf-cleanup-empty-{}", std::process::id()));
    // Rest thinner than 100 mm is left alone: none is left to clean up.
    let text = PENCIL.replace("scallop = 0.01", "scallop = 0.01\n    threshold = 100")
        + "[output]\ngcode = \"empty.ngc\"\n";
    let j = job(&text).unwrap();
    let summary = plan_into(&j, Path::new("."), &dir);
    assert_eq!(summary["passes"], 0);
    assert_eq!(summary["rest"]["regions"].as_array().unwrap().len(), 0);
    let g = std::fs::read_to_string(dir.join("empty.ngc")).unwrap();
    assert!(
        g.contains("no passes: nothing to cut") && g.contains("M30"),
        "{g}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Plans `j` and writes its outputs under `dir`.
fn plan_into(j: &Job, job_dir: &Path, dir: &Path) -> serde_json::Value {
    let mut out = crate::Outputs::new(dir);
    let summary = crate::plan_job::plan_job(j, job_dir, &mut out, &swarf_sim::Quiet).unwrap();
    out.commit().unwrap();
    summary
}

/// The shipped jobs directory.
fn jobs_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../jobs")
}

fn steep_job(edit: impl Fn(String) -> String) -> Result<Job> {
    let text = std::fs::read_to_string(jobs_dir().join("boss-steep-cleanup.toml")).unwrap();
    job(&edit(text))
}

#[test]
fn steep_cleanup_levels_the_walls_the_raster_leaves() {
    let dir = std::env::temp_dir().join(format!("swarf-cleanup-steep-{}", std::process::id()));
    let j = steep_job(|t| t).unwrap();
    let summary = plan_into(&j, &jobs_dir(), &dir);
    // Ball d = 10 at 0.6306 mm (140 / 222) leaves 0.015 mm at
    // acos(0.6306 / (2 sqrt(2 R t - t²))) = 35.40 degrees; the four walls are steep.
    let spacing = 140.0 / (140.0f64 / 0.632).ceil();
    let exact = (spacing / (2.0 * (2.0 * 5.0 * 0.015 - 0.015f64 * 0.015).sqrt())).acos();
    let s = &summary["steep_rest"];
    let angle = s["angle_deg"].as_f64().unwrap();
    assert!((angle - exact.to_degrees()).abs() < 1e-6, "{angle}");
    let walls: f64 = [45f64, 65.0, 80.0, 90.0]
        .iter()
        .map(|a| 1600.0 / a.to_radians().sin())
        .sum();
    assert!((s["surface_area_mm2"].as_f64().unwrap() - walls).abs() < 1e-3);
    assert!(summary["passes"].as_u64().unwrap() > 100);
    assert_eq!(summary["rest"]["regions"].as_array().unwrap().len(), 0);
    let g = std::fs::read_to_string(dir.join("boss-steep-cleanup.ngc")).unwrap();
    assert!(!g.contains("no steep rest") && g.contains("M30"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn passes_down_the_walls_leave_an_empty_program_that_says_why() {
    let dir = std::env::temp_dir().join(format!("swarf-cleanup-nosteep-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let parent = std::fs::read_to_string(jobs_dir().join("boss-raster.toml")).unwrap();
    let parent = parent.replace("angle = 0 ", "angle = 90 ");
    std::fs::write(dir.join("boss-raster.toml"), parent).unwrap();
    let j = steep_job(|t| t).unwrap();
    let summary = plan_into(&j, &dir, &dir);
    assert_eq!(summary["passes"], 0);
    assert_eq!(summary["steep_rest"]["cells"], 0);
    let g = std::fs::read_to_string(dir.join("boss-steep-cleanup.ngc")).unwrap();
    assert!(
        g.contains("no steep rest") && g.contains("nothing to cut") && g.contains("M30"),
        "{g}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn steep_cleanup_jobs_say_what_is_wrong() {
    let bad = |from: &str, to: &str| steep_job(|t| t.replace(from, to)).unwrap_err().to_string();
    let e = steep_job(|t| {
        t.replace("[\"steep\"]", "[]")
            .replace("direction = \"climb\"", "")
    })
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("strategy.restmaterial") && e.contains("one or more"),
        "{e}"
    );
    let e = bad("[\"steep\"]", "[\"steep\", \"valley\", \"steep\"]");
    assert!(e.contains("\"steep\" is listed twice"), "{e}");
    let e = bad("[\"steep\"]", "[\"wall\"]");
    assert!(e.contains("line 13") && e.contains("`steep`"), "{e}");
    let e = bad("job = \"boss-raster.toml\"", "tool = \"ball:d=10\"");
    assert!(e.contains("needs a parent raster job"), "{e}");
    let e = bad("direction = \"climb\"", "chain = [\"ball:d=12\"]");
    assert!(
        e.contains("strategy.chain") && e.contains("one stage"),
        "{e}"
    );
    let e = bad("direction = \"climb\"", "direction = \"u\"");
    assert!(e.contains("\"u\" is a parameter direction"), "{e}");
    // Valley cleanup takes no milling direction.
    let e = bad("[\"steep\"]", "[\"valley\"]");
    assert!(e.contains("\"climb\" is a milling direction"), "{e}");
    // Steep rest after a parent that is not a raster.
    let dir = std::env::temp_dir().join(format!("swarf-cleanup-wl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let parent = std::fs::read_to_string(jobs_dir().join("boss-raster.toml")).unwrap();
    std::fs::write(
        dir.join("boss-raster.toml"),
        parent
            .replace("kind = \"raster\"", "kind = \"waterline\"")
            .replace("angle = 0 ", "# waterline has no angle "),
    )
    .unwrap();
    let j = steep_job(|t| t).unwrap();
    let model = load_model(&j.part).unwrap();
    let e = plan_cleanup_job(&j, &model, &dir, None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("the parent job is \"waterline\""), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_parent_staged_by_the_same_command_is_read_from_the_set() {
    // The demo stages the jobs it runs; nothing is on disk before its set commits.
    let dir = std::env::temp_dir().join(format!("swarf-staged-parent-{}", std::process::id()));
    let mut out = crate::Outputs::new(&dir);
    let text = std::fs::read_to_string(jobs_dir().join("fillet-pocket-finish.toml")).unwrap();
    out.write("finish.toml", text.as_bytes()).unwrap();
    let (parent, _) = read_parent("finish.toml", out.dir(), Some(&out)).unwrap();
    assert_eq!(parent.tool.to_string(), "ball:d=12");
    let e = read_parent("finish.toml", out.dir(), None).unwrap_err();
    assert!(e.to_string().contains("cannot read the parent job"), "{e}");
    drop(out);
    std::fs::remove_dir_all(&dir).ok();
}
