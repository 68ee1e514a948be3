//! Drop-and-spin passes on a machine's rotary limits (issue 13): with the C table
//! limited to one half turn a pass is cut with the side that half turn reaches (the
//! spin sign the machine allows), the other half turn gives the other side, and a
//! machine that reaches neither is refused with the reason; one thread or two give
//! the same passes.

use swarf_app::drop_spin::plan_drop_spin;
use swarf_fiveaxis::dsm::Side;
use swarf_fiveaxis::machine::Machine;
use swarf_testkit::machines::TRUNNION;

/// One pass at the zone's limit in one band, ten stations.
const JOB: &str = r#"part = "builtin:edge-concave"
tool = "bull:d=12,r=2,length=30"
[strategy]
kind = "drop-spin"
step = 10
passes = 1
bands = "first"
spin = "leading"
[output]
machine = "m.toml"
"#;

fn machine(rotary: &str) -> Machine {
    let text = TRUNNION.replace("continuous = true", rotary);
    Machine::parse(&text, "m.toml").unwrap()
}

/// The sides the passes cut with, their axes' signs along the edge, and the issues.
fn plan(rotary: &str) -> Result<(Vec<Side>, Vec<f64>, String), String> {
    let job = swarf_app::Job::parse(JOB, "job.toml").unwrap();
    let part = swarf_io::builtin_part("edge-concave").unwrap();
    let m = machine(rotary);
    let ds = plan_drop_spin(&job, &part, Some(&m)).map_err(|e| e.to_string())?;
    let poses: Vec<_> = ds.passes.poses.iter().flatten().collect();
    Ok((
        poses.iter().map(|e| e.side).collect(),
        poses.iter().map(|e| e.spin.pose.axis.x.signum()).collect(),
        format!("{:?}", ds.passes.issues),
    ))
}

#[test]
fn the_pass_takes_the_side_the_rotary_limits_allow() {
    let (a, a_axis, a_issues) = plan("limits = [0, 180]").unwrap();
    let (b, b_axis, b_issues) = plan("limits = [-180, 0]").unwrap();
    eprintln!("C in [0, 180]: {:?} {a_issues}", a[0]);
    eprintln!("C in [-180, 0]: {:?} {b_issues}", b[0]);
    assert_eq!(a.len(), 10);
    assert_eq!(b.len(), 10);
    assert!(a.iter().all(|s| *s == a[0]) && b.iter().all(|s| *s == b[0]));
    assert_ne!(a[0], b[0], "both half turns cut with the same side");
    assert!(a_axis.iter().all(|s| *s == a_axis[0]) && b_axis.iter().all(|s| *s == b_axis[0]));
    assert_ne!(
        a_axis[0], b_axis[0],
        "both half turns tilt the axis the same way"
    );
    let (switched, kept) = if a[0] == Side::Trailing {
        (a_issues, b_issues)
    } else {
        (b_issues, a_issues)
    };
    assert!(
        switched.contains("the leading spin is out of the machine's reach")
            && switched.contains("cuts with the trailing side"),
        "{switched}"
    );
    assert_eq!(kept, "[]");
}

#[test]
fn a_machine_that_reaches_neither_side_is_refused() {
    let text = TRUNNION.replace("limits = [-30, 120]", "limits = [-1, 1]");
    let m = Machine::parse(&text, "m.toml").unwrap();
    let job = swarf_app::Job::parse(JOB, "job.toml").unwrap();
    let part = swarf_io::builtin_part("edge-concave").unwrap();
    let e = plan_drop_spin(&job, &part, Some(&m))
        .unwrap_err()
        .to_string();
    eprintln!("{e}");
    assert!(
        e.contains("no drop-spin pass") && e.contains("out of the machine's reach"),
        "{e}"
    );
    assert!(
        e.contains("A:") && e.contains("so is the trailing spin"),
        "{e}"
    );
}

/// The same job in one thread and in two: identical contacts (the zones are found
/// in parallel).
#[test]
fn one_thread_or_two_give_the_same_passes() {
    let job = swarf_app::Job::parse(
        &JOB.replace("bands = \"first\"", "bands = \"both\""),
        "job.toml",
    )
    .unwrap();
    let part = swarf_io::builtin_part("edge-concave").unwrap();
    let csv: Vec<String> = [1, 2]
        .into_iter()
        .map(|threads| {
            swarf_testkit::threads::on_threads(threads, || {
                let ds = plan_drop_spin(&job, &part, None).unwrap();
                swarf_app::drop_spin::contacts_csv(&ds.passes.poses, [0, 1])
            })
        })
        .collect();
    assert_eq!(csv[0].lines().count(), 21);
    assert_eq!(csv[0], csv[1]);
}
