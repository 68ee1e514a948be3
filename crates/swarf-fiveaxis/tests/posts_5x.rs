//! Five-axis programs for every built-in post with rotary axes (LinuxCNC, Fanuc and
//! Mach3 with G93 inverse-time feeds, Heidenhain with feeds per minute), written by
//! `post_5x` for the table-table machine and read back by swarf's reader in the post's
//! language through the machine's forward kinematics: every pose of the tool path
//! (the oracle: the poses as given) comes back in order, the tip to the printed
//! precision and the axis to 1e-4 rad, each from the line the post says it ends
//! on. And the refusals: grbl has no rotary axes,
//! Heidenhain no inverse time; the errors name the post and the field.

use swarf_fiveaxis::machine::Machine;
use swarf_fiveaxis::machine::reader::MachineKinematics;
use swarf_fiveaxis::post::{FeedMode, PostOptions, post_5x};
use swarf_geom::{Point3, Vec3};
use swarf_nc::Post;
use swarf_nc::read::{GcodeReadOptions, parse_gcode};
use swarf_testkit::machines::MACHINES;
use swarf_tool::Pose;
use swarf_toolpath::{Feeds, Linking, Pass, PathPoint, Toolpath};

/// Tip tolerance, mm: 5e-4 mm printed `X Y Z` (Heidenhain's 3 decimals) plus the
/// rotary words' rounding (5e-5 degrees) at up to 100 mm from the rotary axes.
const TIP_TOL: f64 = 1e-3;

/// Axis tolerance, rad (rotary words printed to 1e-4 degree).
const AXIS_TOL: f64 = 1e-4;

/// Two passes with the tool tilted up to about 12 degrees, turning around Z.
fn toolpath() -> Toolpath {
    let passes = (0..2)
        .map(|k| Pass {
            points: (0..5)
                .map(|i| {
                    let t = f64::from(i) * 0.35 + f64::from(k);
                    let axis = Vec3::new(0.2 * t.cos(), 0.2 * t.sin(), 1.0).normalize();
                    let cl = Point3::new(f64::from(i) * 3.1, f64::from(k) * 4.2, -0.3 * t.sin());
                    PathPoint::new(Pose { cl, axis })
                })
                .collect(),
            ..Pass::default()
        })
        .collect();
    Toolpath {
        passes,
        feeds: Feeds::default(),
        linking: Linking {
            clearance: 20.0,
            approach: 2.0,
            ..Linking::default()
        },
    }
}

fn close(a: &Pose, b: &Pose) -> bool {
    (a.cl - b.cl).norm() <= TIP_TOL && (a.axis - b.axis).norm() <= AXIS_TOL
}

#[test]
fn five_axis_posts_read_back_to_the_poses() {
    let (name, text) = MACHINES[0];
    let m = Machine::parse(text, name).unwrap();
    let k = MachineKinematics::new(m.clone(), 0.0).unwrap();
    let tp = toolpath();
    let moves = tp.moves();
    for (post, mode) in [
        ("linuxcnc", FeedMode::InverseTime),
        ("fanuc", FeedMode::InverseTime),
        ("mach3", FeedMode::InverseTime),
        ("heidenhain", FeedMode::UnitsPerMinute),
    ] {
        let post = Post::builtin(post).unwrap();
        let opts = PostOptions {
            post: post.clone(),
            feed_mode: mode,
            ..PostOptions::default()
        };
        let posted = post_5x(&m, &tp, &opts).unwrap();
        let program = posted.gcode;
        let read = GcodeReadOptions {
            language: post.reader(),
            kinematics: Some(&k),
            kinematics_tol: 1e-3,
            ..GcodeReadOptions::default()
        };
        let p = parse_gcode(&program, "p.nc", &read).unwrap();
        let what = post.name();
        if std::env::var_os("SWARF_SHOW_POSTS").is_some() {
            eprintln!("{what}:\n{program}");
        }
        assert!(p.stopped.is_none(), "{what}: {:?}\n{program}", p.stopped);
        let ends: Vec<Pose> = p.motions.iter().map(|m| m.end).collect();
        let mut at: usize = 0;
        for (i, mv) in moves.iter().enumerate() {
            let from = at.saturating_sub(1);
            let Some(found) = (from..ends.len()).find(|&j| close(&ends[j], &mv.to)) else {
                panic!("{what}: move {i} {:?} not read back\n{program}", mv.to);
            };
            // The line the post says the move ends on is the one it is read from.
            assert_eq!(
                p.motions[found].line, posted.move_lines[i],
                "{what}: move {i}"
            );
            at = found + 1;
        }
        assert_eq!(at, ends.len(), "{what}: motions past the last move");
    }
}

#[test]
fn posts_without_rotary_axes_or_inverse_time_are_refused() {
    let (name, text) = MACHINES[0];
    let m = Machine::parse(text, name).unwrap();
    let tp = toolpath();
    let cases = [
        (
            "grbl",
            FeedMode::UnitsPerMinute,
            "post grbl: rotary_axes: five-axis program",
        ),
        (
            "heidenhain",
            FeedMode::InverseTime,
            "post heidenhain: inverse_time: five-axis program",
        ),
    ];
    for (post, mode, want) in cases {
        let opts = PostOptions {
            post: Post::builtin(post).unwrap(),
            feed_mode: mode,
            ..PostOptions::default()
        };
        let e = post_5x(&m, &tp, &opts).unwrap_err().to_string();
        assert!(e.contains(want), "{post}: {e}");
    }
}
