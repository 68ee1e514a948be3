//! Bad input to the iso strategies: a clear error naming the field, never a panic.

use swarf_app::{Job, PlanInput};
use swarf_path::PathError;
use swarf_testkit::parts::groove;

fn job(kind: &str, body: &str) -> String {
    format!("part = \"builtin:wave\"\ntool = \"ball:d=8\"\n[strategy]\nkind = \"{kind}\"\n{body}\n")
}

const KINDS: [&str; 3] = ["iso-parametric", "iso-planar", "iso-scallop"];

/// Makes a good job bad.
type Spoil = fn(&mut Job);

#[test]
fn job_files_name_the_field() {
    for kind in KINDS {
        for (body, field) in [
            ("scallop = 0", "scallop"),
            ("scallop = -0.1", "scallop"),
            ("scallop = 4", "scallop"),
            ("scallop = 9", "scallop"),
            ("scallop = 0.1\ntolerance = 0", "tolerance"),
            ("scallop = 0.1\ntolerance = -1", "tolerance"),
            ("scallop = 0.1\nangle = nan", "angle"),
            ("scallop = 0.1\ndirection = \"w\"", "line 6"),
        ] {
            let e = Job::parse(&job(kind, body), "job.toml")
                .unwrap_err()
                .to_string();
            assert!(e.starts_with("job.toml: "), "{e}");
            assert!(e.contains(field), "{kind} {body}: want {field} in {e}");
        }
    }
}

#[test]
fn jobs_built_in_code_are_checked_by_the_planners_too() {
    let part = swarf_io::builtin_part("wave").unwrap();
    for kind in KINDS {
        let good = Job::parse(&job(kind, "scallop = 0.3"), "job").unwrap();
        let cases: [(Spoil, &str); 5] = [
            (|j| j.strategy.scallop = None, "scallop"),
            (|j| j.strategy.scallop = Some(f64::NAN), "scallop"),
            (|j| j.strategy.scallop = Some(4.0), "scallop"),
            (|j| j.strategy.tolerance = 0.0, "tolerance"),
            (
                |j| j.strategy.tolerance = f64::INFINITY,
                "tolerance",
            ),
        ];
        for (spoil, field) in cases {
            let mut j = good.clone();
            spoil(&mut j);
            let e = swarf_app::plan(&j, PlanInput::Part(&part)).unwrap_err();
            assert!(matches!(e, PathError::InvalidParameter { .. }), "{e:?}");
            assert!(
                e.to_string().starts_with(field),
                "{kind}: want {field}: {e}"
            );
        }
    }
}

#[test]
fn a_tool_too_large_for_any_position_is_refused() {
    let part = groove();
    for kind in KINDS {
        let text = format!(
            "part = \"x\"\ntool = \"ball:d=8\"\n[strategy]\nkind = \"{kind}\"\nscallop = 0.2\ndirection = \"v\"\nangle = 90\n"
        );
        let big = Job::parse(&text, "job").unwrap();
        let e = swarf_app::plan(&big, PlanInput::Part(&part)).unwrap_err();
        assert!(matches!(e, PathError::NoPath(_)), "{kind}: {e:?}");
        assert!(e.to_string().contains("too large"), "{kind}: {e}");
        // A ball that fits plans, unlifted.
        let small = Job::parse(&text.replace("ball:d=8", "ball:d=4"), "job").unwrap();
        let plan = swarf_app::plan(&small, PlanInput::Part(&part)).unwrap();
        assert_eq!(plan.report.lifted_points, 0, "{kind}");
    }
}

#[test]
fn meshes_are_refused_by_the_iso_strategies() {
    let mesh = swarf_io::builtin_part("wave")
        .unwrap()
        .tessellate(0.1)
        .unwrap();
    for kind in KINDS {
        let j = Job::parse(&job(kind, "scallop = 0.3"), "job").unwrap();
        let e = swarf_app::plan(&j, PlanInput::Mesh(&mesh)).unwrap_err();
        assert!(matches!(e, PathError::NoPath(_)), "{kind}: {e:?}");
    }
}
