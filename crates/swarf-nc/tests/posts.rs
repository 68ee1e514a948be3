//! Every built-in post, written and read back: a 3-axis program with rapids, feed
//! moves and a tool change, in mm and in inches, read by swarf's reader in the post's
//! language, gives back the input moves rounded to the post's output precision (the
//! oracle: the moves as given, rounded here by the decimals each control is known to
//! take, not by the writer). The LinuxCNC, Mach3 and grbl programs are accepted by
//! LinuxCNC's `rs274` (skipped when it is absent, unless
//! `SWARF_REQUIRE_REFERENCES=1`). And the refusals: a post that cannot express a
//! program says which post and which field; a bad post file names its field.

use swarf_geom::Point3;
use swarf_nc::read::{GcodeReadOptions, MotionKind, Program, parse_gcode};
use swarf_nc::{GcodeOptions, NcError, Post, Units, write_gcode};
use swarf_testkit::rs274::run_rs274;
use swarf_tool::Pose;
use swarf_toolpath::{Feeds, Linking, Move, MoveKind, Pass, PathPoint, Toolpath};

/// The posts and the decimals of their length words in mm and in inches.
const POSTS: [(&str, [i32; 2]); 5] = [
    ("linuxcnc", [4, 5]),
    ("fanuc", [4, 5]),
    ("mach3", [4, 5]),
    ("grbl", [4, 5]),
    ("heidenhain", [3, 4]),
];

/// Three passes over a wavy surface, with values that do not round evenly.
fn toolpath() -> Toolpath {
    let passes = (0..3)
        .map(|k| Pass {
            points: (0..6)
                .map(|i| {
                    let (x, y) = (f64::from(i) * 1.234_567, f64::from(k) * 2.345_678);
                    PathPoint::new(Pose::vertical(Point3::new(
                        x,
                        y,
                        -0.5 - 0.123_456_7 * (x + y).sin(),
                    )))
                })
                .collect(),
            ..Pass::default()
        })
        .collect();
    Toolpath {
        passes,
        feeds: Feeds {
            feed: 1234.5678,
            ..Feeds::default()
        },
        linking: Linking::default(),
    }
}

fn round(v: f64, decimals: i32) -> f64 {
    let s = 10f64.powi(decimals);
    (v * s).round() / s
}

/// The moves' end points as the control receives them (rounded in the output units),
/// dropping those that repeat the previous point.
fn oracle(moves: &[Move], decimals: i32, scale: f64) -> Vec<([f64; 3], MoveKind, f64)> {
    let mut out: Vec<([f64; 3], MoveKind, f64)> = Vec::new();
    for m in moves {
        let p = m.to.cl;
        let p = [p.x, p.y, p.z].map(|v| round(v / scale, decimals) * scale);
        if out.last().is_none_or(|(q, _, _)| *q != p) {
            out.push((p, m.kind, round(m.feed / scale, 3) * scale));
        }
    }
    out
}

fn read(post: &Post, text: &str) -> Program {
    let opts = GcodeReadOptions {
        language: post.reader(),
        ..GcodeReadOptions::default()
    };
    parse_gcode(text, &format!("{}.nc", post.name()), &opts).unwrap()
}

fn write(post: &Post, units: Units, tp: &Toolpath) -> String {
    let opts = GcodeOptions {
        post: post.clone(),
        units,
        tool_number: 3,
        comments: vec!["part wave (test)".into()],
        ..GcodeOptions::default()
    };
    write_gcode(&tp.moves(), &tp.feeds, &opts).unwrap()
}

#[test]
fn every_post_reads_back_to_its_precision() {
    let tp = toolpath();
    let moves = tp.moves();
    for (name, decimals) in POSTS {
        let post = Post::builtin(name).unwrap();
        for (units, decimals, scale) in [
            (Units::Mm, decimals[0], 1.0),
            (Units::Inch, decimals[1], 25.4),
        ] {
            let text = write(&post, units, &tp);
            let p = read(&post, &text);
            let what = format!("{name} {units:?}");
            assert!(p.stopped.is_none(), "{what}: {:?}\n{text}", p.stopped);
            assert!(p.warnings.is_empty(), "{what}: {:?}", p.warnings);
            let want = oracle(&moves, decimals, scale);
            assert_eq!(p.motions.len(), want.len(), "{what}\n{text}");
            let tol = 1e-9 * scale;
            for (m, (p, kind, feed)) in p.motions.iter().zip(&want) {
                let e = m.end.cl;
                let d = (e - Point3::from(*p)).abs().max();
                assert!(d <= tol, "{what}: line {}: {e:?} vs {p:?}", m.line);
                let read_kind = match m.kind {
                    MotionKind::Rapid => MoveKind::Rapid,
                    _ => MoveKind::Feed,
                };
                assert_eq!(read_kind, *kind, "{what}: line {}", m.line);
                if *kind == MoveKind::Feed {
                    assert!((m.feed - feed).abs() <= tol, "{what}: {} vs {feed}", m.feed);
                }
            }
        }
    }
}

#[test]
fn each_post_writes_its_own_conventions() {
    let tp = toolpath();
    let expect: [(&str, &[&str]); 5] = [
        (
            "linuxcnc",
            &["%\n(part wave  test )\nG17 G21 G40 G49 G80 G90 G94\nT3 M6\nG43 H3\nS"],
        ),
        (
            "fanuc",
            &["%\nO1000\n(PART WAVE  TEST )\n", "T3 M06\nG43 H3\nS"],
        ),
        ("mach3", &["(part wave  test )\n", "T3 M6\nG43 H3\nS"]),
        (
            "grbl",
            &["(part wave  test )\nG17 G21 G40 G49 G80 G90 G94\nS"],
        ),
        (
            "heidenhain",
            &[
                "0 BEGIN PGM 1000 MM\n1 ; part wave  test \n2 TOOL CALL 3 Z S",
                " FMAX\n",
                " END PGM 1000 MM\n",
            ],
        ),
    ];
    for (name, parts) in expect {
        let text = write(&Post::builtin(name).unwrap(), Units::Mm, &tp);
        for part in parts {
            assert!(text.contains(part), "{name}: {part:?} not in\n{text}");
        }
        assert_eq!(
            text.contains('%'),
            !matches!(name, "grbl" | "heidenhain"),
            "{name}"
        );
    }
}

#[test]
fn gcode_posts_are_accepted_by_rs274() {
    let tp = toolpath();
    for name in ["linuxcnc", "mach3", "grbl"] {
        let post = Post::builtin(name).unwrap();
        for units in [Units::Mm, Units::Inch] {
            let text = write(&post, units, &tp);
            let Some(out) = run_rs274(&text, name) else {
                return;
            };
            let all = out.text("");
            assert!(
                out.success,
                "{name} {units:?}: rs274 refused:\n{all}\n{text}"
            );
            let feeds = all.matches("STRAIGHT_FEED").count();
            let read = read(&post, &text);
            let want = read
                .motions
                .iter()
                .filter(|m| m.kind == MotionKind::Linear)
                .count();
            assert_eq!(feeds, want, "{name} {units:?}:\n{all}");
        }
    }
}

#[test]
fn a_user_post_file_is_read_from_its_folder() {
    let dir = std::env::temp_dir().join(format!("swarf-posts-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let text = swarf_nc::post::BUILTIN_POSTS[0]
        .1
        .replace("name = \"linuxcnc\"", "name = \"shop\"")
        .replace(
            "[words]",
            "[numbers]\nprefix = \"N\"\nstart = 10\nstep = 10\n\n[words]",
        );
    std::fs::write(dir.join("shop.toml"), text).unwrap();
    let post = Post::load("shop.toml", &dir).unwrap();
    let program = write(&post, Units::Mm, &toolpath());
    assert!(
        program.starts_with("%\nN10 (part wave  test )\nN20 G17"),
        "{program}"
    );
    let p = read(&post, &program);
    assert!(
        p.stopped.is_none() && !p.motions.is_empty(),
        "{:?}",
        p.stopped
    );
    let e = Post::load("missing.toml", &dir).unwrap_err().to_string();
    assert!(
        e.contains("missing.toml: post: cannot read the post file"),
        "{e}"
    );
    std::fs::write(dir.join("bad.toml"), "name = 3\n").unwrap();
    let e = Post::load("bad.toml", &dir).unwrap_err().to_string();
    assert!(e.contains("bad.toml: toml: line 1"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn refusals_name_the_post_and_the_field() {
    let tp = toolpath();
    let fanuc = Post::builtin("fanuc").unwrap();
    let opts = GcodeOptions {
        post: fanuc,
        program_number: 12_345,
        ..GcodeOptions::default()
    };
    let e = write_gcode(&tp.moves(), &tp.feeds, &opts).unwrap_err();
    assert!(matches!(
        e,
        NcError::InvalidOption {
            field: "program_number",
            ..
        }
    ));
    assert!(
        e.to_string().contains("post fanuc: expected 1..=9999"),
        "{e}"
    );
    let grbl = Post::builtin("grbl").unwrap();
    let per_minute = swarf_nc::FeedMode::UnitsPerMinute;
    let e = grbl
        .check("five-axis program", 1, per_minute, true)
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "post grbl: rotary_axes: five-axis program: the control has no rotary axes (A/B/C)"
    );
    let heidenhain = Post::builtin("heidenhain").unwrap();
    let inverse = swarf_nc::FeedMode::InverseTime;
    let e = heidenhain
        .check("five-axis program", 1, inverse, true)
        .unwrap_err();
    assert!(
        e.to_string()
            .starts_with("post heidenhain: inverse_time: five-axis program"),
        "{e}"
    );
}
