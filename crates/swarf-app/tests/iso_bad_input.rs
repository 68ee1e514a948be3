//! Bad iso job files: a clear error naming the field, never a panic.

use swarf_app::Job;

fn job(kind: &str, body: &str) -> String {
    format!("part = \"builtin:wave\"\ntool = \"ball:d=8\"\n[strategy]\nkind = \"{kind}\"\n{body}\n")
}

const KINDS: [&str; 3] = ["iso-parametric", "iso-planar", "iso-scallop"];

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
fn meshes_are_refused_by_the_iso_strategies() {
    let mesh = swarf_io::builtin_part("wave")
        .unwrap()
        .tessellate(0.1)
        .unwrap();
    for kind in KINDS {
        let j = Job::parse(&job(kind, "scallop = 0.3"), "job").unwrap();
        let e = swarf_app::plan(&j, swarf_app::PlanInput::Mesh(&mesh)).unwrap_err();
        assert!(
            matches!(e, swarf_path::PathError::NoPath(_)),
            "{kind}: {e:?}"
        );
    }
}
