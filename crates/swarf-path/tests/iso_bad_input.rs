//! Bad input to the iso strategies: a clear error naming the field, never a panic.

mod iso_support;

use iso_support::{Iso, iso_job};
use swarf_path::PathError;
use swarf_testkit::parts::groove;

const KINDS: [&str; 3] = ["iso-parametric", "iso-planar", "iso-scallop"];

/// Makes a good strategy bad.
type Spoil = fn(&mut Iso);

#[test]
fn jobs_built_in_code_are_checked_by_the_planners_too() {
    let part = swarf_io::builtin_part("wave").unwrap();
    for kind in KINDS {
        let good = iso_job(kind, "ball:d=8", "scallop = 0.3");
        let cases: [(Spoil, &str); 5] = [
            (|j| *j.scallop_mut() = None, "scallop"),
            (|j| *j.scallop_mut() = Some(f64::NAN), "scallop"),
            (|j| *j.scallop_mut() = Some(4.0), "scallop"),
            (|j| j.finish_mut().tolerance = 0.0, "tolerance"),
            (|j| j.finish_mut().tolerance = f64::INFINITY, "tolerance"),
        ];
        for (spoil, field) in cases {
            let mut j = good.clone();
            spoil(&mut j.iso);
            let e = j.plan(&part).unwrap_err();
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
        let table = if kind == "iso-planar" {
            "scallop = 0.2\nangle = 90\n"
        } else {
            "scallop = 0.2\ndirection = \"v\"\n"
        };
        let big = iso_job(kind, "ball:d=8", table);
        let e = big.plan(&part).unwrap_err();
        assert!(matches!(e, PathError::NoPath(_)), "{kind}: {e:?}");
        assert!(e.to_string().contains("too large"), "{kind}: {e}");
        // A ball that fits plans, unlifted.
        let small = iso_job(kind, "ball:d=4", table);
        let plan = small.plan(&part).unwrap();
        assert_eq!(plan.report.lifted_points, 0, "{kind}");
    }
}
