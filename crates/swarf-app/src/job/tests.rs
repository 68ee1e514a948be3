//! Tests of job parsing and validation.

use super::*;
use crate::strategy::Strategy;
use swarf_fiveaxis::dsm::{BandChoice, SpinChoice, ZoneChoice};

const GOOD: &str = r#"
part = "builtin:wave"
tool = "ball:d=8"
[strategy]
kind = "iso-scallop"
scallop = 0.15
tolerance = 0.01
[feeds]
feed = 300
spindle = 1500
[linking]
clearance = 60
[output]
gcode = "a.ngc"
"#;

#[test]
fn parses_a_good_job() {
    let job = Job::parse(GOOD, "job.toml").unwrap();
    assert!(matches!(job.strategy, Strategy::IsoScallop(_)));
    assert_eq!(job.strategy.scallop(), Some(0.15));
    assert_eq!(job.feeds.feed, 300.0);
    assert_eq!(job.feeds.plunge, Feeds::default().plunge);
    assert!(job.strategy.finish().zigzag);
    assert_eq!(job.output.gcode.as_deref(), Some("a.ngc"));
}

#[test]
fn bad_jobs_name_the_field() {
    let cases = [
        (
            GOOD.replace("scallop = 0.15", "scallop = -1"),
            "strategy.scallop",
        ),
        (
            GOOD.replace("scallop = 0.15", "scallop = 5"),
            "strategy.scallop",
        ),
        (
            GOOD.replace("tolerance = 0.01", "tolerance = 0"),
            "strategy.tolerance",
        ),
        (
            GOOD.replace("scallop = 0.15", ""),
            "strategy: expected `scallop`",
        ),
        (GOOD.replace("feed = 300", "feed = -3"), "feeds.feed"),
        (
            GOOD.replace("kind = \"iso-scallop\"", "kind = \"spiral\""),
            "line 5",
        ),
        (GOOD.replace("feed = 300", "fed = 300"), "fed"),
        (GOOD.replace("ball:d=8", "ball:d=-8"), "line 3"),
        (format!("{GOOD}[stock]\ntop = nan\n"), "stock.top: NaN mm"),
        (format!("{GOOD}[stock]\nmargin = -1\n"), "stock.margin"),
        (
            format!("{GOOD}[stock]\nkind = \"mesh\"\n"),
            "stock.file: a mesh stock needs its file",
        ),
    ];
    for (text, want) in cases {
        let e = Job::parse(&text, "job.toml").unwrap_err().to_string();
        assert!(e.starts_with("job.toml: "), "{e}");
        assert!(e.contains(want), "want {want:?} in {e}");
    }
}

#[test]
fn raster_max_slope_is_degrees_in_the_file() {
    let text = GOOD
        .replace("iso-scallop", "raster")
        .replace("scallop = 0.15", "scallop = 0.15\nmax_slope = 60");
    let job = Job::parse(&text, "job.toml").unwrap();
    let Strategy::Raster(params) = &job.strategy else {
        panic!("{:?}", job.strategy)
    };
    assert_eq!(params.max_slope, Some(60f64.to_radians()));
    // The stepover it gives: a ball's 2 cos(60) sqrt(2Rh - h^2), half the level one.
    let mesh = swarf_io::builtin_mesh("v-grooves").unwrap();
    let plan = crate::plan::plan(&job, crate::plan::PlanInput::Mesh(&mesh)).unwrap();
    let spacing = plan.report.side_step_range.unwrap()[1];
    let level = 2.0 * (0.15f64 * (8.0 - 0.15)).sqrt();
    assert!(
        spacing <= 0.5 * level + 1e-12 && spacing > 0.45 * level,
        "{spacing}"
    );
    let h = plan.report.predicted_max_scallop.unwrap();
    assert!(h <= 0.15 + 1e-12 && h > 0.12, "{h}");
    for bad in ["0", "90", "-5", "nan"] {
        let text = text.replace("max_slope = 60", &format!("max_slope = {bad}"));
        let e = Job::parse(&text, "job.toml").unwrap_err().to_string();
        assert!(e.contains("strategy.max_slope"), "{bad}: {e}");
        assert!(e.contains("degrees"), "{bad}: {e}");
    }
}

/// Roughing's `adaptive` and `corner_radius` reach the kernel: plain offset rings
/// step over `R (1 - cos 60)` = 2.5 mm everywhere; adaptive ones step less, by the
/// rounding of their corners, and a larger corner radius steps over more.
#[test]
fn roughing_adaptive_and_corner_radius_reach_the_rings() {
    let shipped = include_str!("../../../../jobs/fillet-pocket-roughing.toml");
    let mesh = swarf_io::builtin_mesh("fillet-pocket").unwrap();
    let steps = |extra: &str| {
        let text = shipped.replace("tolerance = 0.01", &format!("tolerance = 0.01\n{extra}"));
        let job = Job::parse(&text, "job.toml").unwrap();
        let plan = crate::plan::plan(&job, crate::plan::PlanInput::Mesh(&mesh)).unwrap();
        plan.report.side_step_range.unwrap()
    };
    let plain = steps("adaptive = false");
    assert!(
        (plain[0] - 2.5).abs() < 1e-9 && (plain[1] - 2.5).abs() < 1e-9,
        "{plain:?}"
    );
    let adaptive = steps("");
    assert!(
        adaptive[1] < 2.5 && adaptive[0] < adaptive[1],
        "{adaptive:?}"
    );
    let rounder = steps("corner_radius = 20");
    assert!(rounder[1] > adaptive[1], "{rounder:?} against {adaptive:?}");
}

mod five_axis {
    use super::*;
    use swarf_fiveaxis::positioning::Positioning;

    const FIVE: &str = r#"
part = "builtin:die"
tool = "bull:d=38.1,r=6.35"
positioning = { method = "inclined", alpha = 3 }
[strategy]
kind = "iso-planar"
stepover = 3.5
angle = 60
[output]
machine = "builtin:xyzac-trunnion"
gcode = "die.ngc"
cl = "die.cl"
"#;

    #[test]
    fn positioning_tables_parse() {
        let job = Job::parse(FIVE, "die.toml").unwrap();
        assert_eq!(
            job.positioning,
            Some(Positioning::Inclined {
                alpha: 3.0,
                tilt: 0.0,
                sections: 1.0
            })
        );
        let Strategy::IsoPlanar(planar) = &job.strategy else {
            panic!("{:?}", job.strategy)
        };
        assert_eq!(planar.stepover, Some(3.5));
        assert_eq!(
            job.output.machine.as_deref(),
            Some("builtin:xyzac-trunnion")
        );
        assert_eq!(job.output.feed_mode, FeedMode::InverseTime);
        let auto = FIVE.replace(
            r#"{ method = "inclined", alpha = 3 }"#,
            r#"{ method = "gouge-free", max_alpha = 15, sections = 0.5 }"#,
        );
        let job = Job::parse(&auto, "die.toml").unwrap();
        assert_eq!(
            job.positioning,
            Some(Positioning::GougeFree {
                max_alpha: 15.0,
                sections: 0.5,
                tilt: 0.0,
                max_rate: 0.5,
                tolerance: None
            })
        );
        assert_eq!(job.positioning.map(|p| p.method()), Some("gouge-free"));
        let g94 = FIVE.replace(
            "gcode = ",
            "feed_mode = \"units-per-minute\"\ntool_length = 120\ngcode = ",
        );
        let job = Job::parse(&g94, "die.toml").unwrap();
        assert_eq!(job.output.feed_mode, FeedMode::UnitsPerMinute);
        assert_eq!(job.output.tool_length, Some(120.0));
        // A machine without positioning (a vertical tool in five-axis words), and a
        // positioning with CL output only: both fine.
        let vertical = FIVE.replace("positioning = { method = \"inclined\", alpha = 3 }", "");
        assert!(
            Job::parse(&vertical, "die.toml")
                .unwrap()
                .positioning
                .is_none()
        );
        let cl_only = FIVE
            .replace("machine = \"builtin:xyzac-trunnion\"", "")
            .replace("gcode = \"die.ngc\"", "");
        assert!(Job::parse(&cl_only, "die.toml").is_ok());
    }

    #[test]
    fn bad_five_axis_jobs_name_the_field() {
        let inclined = r#"{ method = "inclined", alpha = 3 }"#;
        let cases = [
            (FIVE.replace("alpha = 3", "alpha = 95"), "positioning.alpha"),
            (FIVE.replace("alpha = 3", "alpha = -1"), "positioning.alpha"),
            (
                FIVE.replace("alpha = 3", "alpha = 3, tilt = 91"),
                "positioning.tilt",
            ),
            (
                FIVE.replace("alpha = 3", "alpha = 3, sections = 0"),
                "positioning.sections",
            ),
            (
                FIVE.replace(inclined, r#"{ method = "gouge-free", max_alpha = 0 }"#),
                "positioning.max_alpha",
            ),
            (
                FIVE.replace(
                    inclined,
                    r#"{ method = "gouge-free", max_alpha = 15, max_rate = -1 }"#,
                ),
                "positioning.max_rate",
            ),
            (
                FIVE.replace(
                    inclined,
                    r#"{ method = "gouge-free", max_alpha = 15, tolerance = -0.1 }"#,
                ),
                "positioning.tolerance",
            ),
            // Unknown method, unknown key, missing field: the TOML line.
            (FIVE.replace("\"inclined\"", "\"tilted\""), "line 4"),
            (FIVE.replace("alpha = 3", "alpha = 3, beta = 2"), "beta"),
            (
                FIVE.replace(inclined, r#"{ method = "gouge-free" }"#),
                "max_alpha",
            ),
            (
                FIVE.replace("machine = \"builtin:xyzac-trunnion\"", ""),
                "output.machine: a tilted tool path needs a machine file for G-code",
            ),
            (
                FIVE.replace("machine = \"builtin:xyzac-trunnion\"", "machine = \"\""),
                "output.machine",
            ),
            (
                FIVE.replace("gcode = ", "feed_mode = \"g93\"\ngcode = "),
                "line 11: unknown variant `g93`, expected `inverse-time`",
            ),
            (
                FIVE.replace("gcode = \"die.ngc\"", "gcode = \"\""),
                "output.gcode: expected a file name inside the output folder",
            ),
            (
                FIVE.replace("cl = \"die.cl\"", "cl = \"../up.cl\""),
                "output.cl: expected a file name",
            ),
            (
                FIVE.replace("gcode = ", "tool_length = -5\ngcode = "),
                "output.tool_length",
            ),
            (
                FIVE.replace("stepover = 3.5", "stepover = 40"),
                "strategy.stepover",
            ),
            (
                FIVE.replace("stepover = 3.5", "stepover = 3.5\nscallop = 0.1"),
                "strategy.stepover",
            ),
            (
                FIVE.replace("iso-planar", "iso-scallop"),
                "strategy.stepover",
            ),
        ];
        for (text, want) in cases {
            let e = Job::parse(&text, "die.toml").unwrap_err().to_string();
            assert!(e.starts_with("die.toml: "), "{e}");
            assert!(e.contains(want), "want {want:?} in {e}");
        }
    }
}

#[test]
fn drop_spin_jobs_name_the_field() {
    let good = include_str!("../../../../jobs/edge-concave-drop-spin.toml");
    let job = Job::parse(good, "ds.toml").unwrap();
    let Strategy::DropSpin(ds) = &job.strategy else {
        panic!("{:?}", job.strategy)
    };
    assert_eq!(ds.faces, [0, 1]);
    assert_eq!((ds.spin, ds.zone), (SpinChoice::Leading, ZoneChoice::Full));
    assert_eq!(ds.bands, BandChoice::Both);
    assert_eq!(BandChoice::default().faces(), vec![0, 1]);
    let cases = [
        (good.replace("step = 5 ", "step = 0 "), "strategy.step"),
        (
            good.replace("bands = \"both\"", "bands = \"all\""),
            "unknown variant `all`, expected one of `first`, `second`, `both`",
        ),
        (good.replace("passes = 4", "passes = 0"), "strategy.passes"),
        (good.replace("passes = 4", "passes = 5000"), "at most 1000"),
        (
            good.replace("faces = [0, 1]", "faces = [1, 1]"),
            "strategy.faces",
        ),
        (
            good.replace("machine = \"builtin:xyzac-trunnion\"", ""),
            "output.machine",
        ),
        (
            good.replace("spin = \"leading\"", "spin = \"up\""),
            "`leading`",
        ),
        (
            good.replace(
                "[strategy]",
                "positioning = { method = \"inclined\", alpha = 3 }\n[strategy]",
            ),
            "positioning",
        ),
    ];
    for (text, want) in cases {
        let e = Job::parse(&text, "ds.toml").unwrap_err().to_string();
        assert!(e.contains(want), "{want}: {e}");
    }
    // Snug needs no pass count.
    let snug = good
        .replace("passes = 4", "passes = 0")
        .replace("zone = \"full\"", "zone = \"snug\"");
    assert!(Job::parse(&snug, "ds.toml").is_ok());
}

#[test]
fn faces_and_import_options_parse_and_are_checked() {
    let text = GOOD.replace(
        "tool = \"ball:d=8\"",
        "faces = [3, \"floor\"]\ntool = \"ball:d=8\"\n[import]\nunsupported = \"refuse\"\ntrim_chord = 0.001",
    );
    let job = Job::parse(&text, "job.toml").unwrap();
    assert_eq!(
        job.faces,
        Some(vec![FaceRef::Index(3), FaceRef::Name("floor".into())])
    );
    let opts = job.load_options();
    assert_eq!(opts.cad.unsupported, swarf_io::Unsupported::Refuse);
    assert_eq!(opts.cad.trim_chord, 0.001);
    let plain = Job::parse(GOOD, "job.toml").unwrap().load_options();
    assert_eq!(plain.cad, swarf_io::CadOptions::default());
    assert!(plain.faces.is_none());
    for (bad, field) in [
        (
            "trim_chord = 0",
            "import.trim_chord: 0: expected a chordal tolerance",
        ),
        ("trim_chord = 2", "import.trim_chord: 2: expected"),
        (
            "unsupported = \"maybe\"",
            "line 6: unknown variant `maybe`, expected `warn` or `refuse`",
        ),
        ("chord = 0.1", "chord"),
    ] {
        let t = text.replace("unsupported = \"refuse\"\ntrim_chord = 0.001", bad);
        let e = Job::parse(&t, "job.toml").unwrap_err().to_string();
        assert!(e.contains(field), "{bad}: {e}");
    }
}

#[test]
fn the_post_is_chosen_by_post_or_its_older_name_dialect() {
    let job = Job::parse(GOOD, "job.toml").unwrap();
    assert_eq!(job.output.post_spec(), "linuxcnc");
    let with =
        |line: &str| GOOD.replace("gcode = \"a.ngc\"", &format!("gcode = \"a.ngc\"\n{line}"));
    let job = Job::parse(&with("dialect = \"fanuc\""), "job.toml").unwrap();
    assert_eq!(job.output.post_spec(), "fanuc");
    let job = Job::parse(&with("post = \"shop.toml\""), "job.toml").unwrap();
    assert_eq!(job.output.post_spec(), "shop.toml");
    let e = Job::parse(&with("post = \"grbl\"\ndialect = \"fanuc\""), "job.toml")
        .unwrap_err()
        .to_string();
    assert!(e.contains("output.dialect: give output.post"), "{e}");
    for (name, _) in swarf_nc::post::BUILTIN_POSTS {
        let job = Job::parse(&with(&format!("post = \"{name}\"")), "job.toml").unwrap();
        let post = swarf_nc::Post::load(job.output.post_spec(), std::path::Path::new(".")).unwrap();
        assert_eq!(post.name(), name);
    }
}

#[test]
fn arcs_are_asked_for_with_a_checked_tolerance() {
    let job = Job::parse(GOOD, "job.toml").unwrap();
    assert_eq!(job.output.arc_tolerance_mm(), None);
    let with =
        |line: &str| GOOD.replace("gcode = \"a.ngc\"", &format!("gcode = \"a.ngc\"\n{line}"));
    let job = Job::parse(&with("arcs = true"), "job.toml").unwrap();
    assert_eq!(
        job.output.arc_tolerance_mm(),
        Some(swarf_nc::DEFAULT_ARC_TOLERANCE_MM)
    );
    let job = Job::parse(&with("arcs = true\narc_tolerance = 0.002"), "job.toml").unwrap();
    assert_eq!(job.output.arc_tolerance_mm(), Some(0.002));
    for (bad, message) in [
        (
            "arc_tolerance = 0.002",
            "output.arc_tolerance: given without arcs",
        ),
        (
            "arcs = true\narc_tolerance = 0",
            "output.arc_tolerance: expected",
        ),
        (
            "arcs = true\narc_tolerance = 5",
            "output.arc_tolerance: expected",
        ),
        (
            "arcs = true\nmachine = \"builtin:xyzac-trunnion\"",
            "output.arcs: five-axis",
        ),
    ] {
        let e = Job::parse(&with(bad), "job.toml").unwrap_err().to_string();
        assert!(e.contains(message), "{bad}: {e}");
    }
}

#[test]
fn misplaced_fields_and_bad_choices_name_field_place_and_domain() {
    let e = Job::parse(
        &GOOD.replace("tolerance = 0.01", "tolerance = 0.01\noverlap = 2"),
        "job.toml",
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with("job.toml: line 8: strategy.overlap: unknown field `overlap` for kind `iso-scallop` (it is a field of `steep-shallow`, `cleanup`)"),
        "{e}"
    );
    let e = Job::parse(
        &GOOD.replace(
            "tolerance = 0.01",
            "tolerance = 0.01\ndirection = \"climb\"",
        ),
        "job.toml",
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("line 8: strategy.direction: \"climb\" is a milling direction")
            && e.contains("takes \"u\" or \"v\""),
        "{e}"
    );
    // A dict (Python's) names the path instead of the line.
    let mut value: toml::Value = toml::from_str(GOOD).unwrap();
    value["strategy"]
        .as_table_mut()
        .unwrap()
        .insert("scallop".into(), toml::Value::String("fine".into()));
    let e = Job::from_value(value, "job dict", std::path::Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("job dict: strategy.scallop: invalid type: string \"fine\", expected f64"),
        "{e}"
    );
}

#[test]
fn a_five_axis_job_without_a_stock_is_cut_from_near_net() {
    let five = GOOD
        .replace(
            "[strategy]",
            "positioning = { method = \"inclined\", alpha = 3 }\n[strategy]",
        )
        .replace("gcode = \"a.ngc\"", "cl = \"a.cl\"");
    let job = Job::parse(&five, "job.toml").unwrap();
    assert_eq!(job.stock, crate::stock::Stock::near_net());
    assert_eq!(job.stock.kind, crate::stock::StockKind::Offset);
    assert_eq!(job.stock.allowance, 1.0);
    let boxed = Job::parse(&format!("{five}[stock]\nkind = \"box\"\n"), "job.toml").unwrap();
    assert_eq!(boxed.stock.kind, crate::stock::StockKind::Box);
    let three = Job::parse(GOOD, "job.toml").unwrap();
    assert_eq!(three.stock, crate::stock::Stock::default());
}
