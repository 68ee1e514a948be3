//! The four shared test parts, embedded in the binary so that `swarf demo` and the
//! benches need no files. The texts are the project's copies in `parts/`, which a
//! test keeps byte-identical to `../shared/parts` where that folder exists. The
//! project's own patch parts (`parts/README.md`) are embedded beside them.

use crate::part::parse_part;
use swarf_geom::Part;

const DIE: &str = include_str!("../../../parts/die.toml");
const WAVE: &str = include_str!("../../../parts/wave.toml");
const EDGE_CONVEX: &str = include_str!("../../../parts/edge-convex.toml");
const EDGE_CONCAVE: &str = include_str!("../../../parts/edge-concave.toml");
const WEDGE_SYMMETRIC: &str = include_str!("../../../parts/wedge-symmetric.toml");
const WEDGE_30_45: &str = include_str!("../../../parts/wedge-30-45.toml");

/// `(name, part file text)` of the project's own built-in patch parts: the planar
/// wedges of paper 003's closed forms.
pub fn project_parts() -> [(&'static str, &'static str); 2] {
    [
        ("wedge-symmetric", WEDGE_SYMMETRIC),
        ("wedge-30-45", WEDGE_30_45),
    ]
}

/// `(name, part file text)` of the built-in parts: `die`, `wave`, `edge-convex`,
/// `edge-concave`.
pub fn builtin_parts() -> [(&'static str, &'static str); 4] {
    [
        ("die", DIE),
        ("wave", WAVE),
        ("edge-convex", EDGE_CONVEX),
        ("edge-concave", EDGE_CONCAVE),
    ]
}

/// The built-in part called `name` (with or without `.toml`), parsed; `None` for
/// another name.
///
/// # Example
/// ```
/// let die = swarf_io::builtin_part("die.toml").unwrap();
/// assert_eq!((die.name.as_str(), die.patches.len()), ("die", 1));
/// assert!(swarf_io::builtin_part("bracket").is_none());
/// ```
pub fn builtin_part(name: &str) -> Option<Part> {
    let name = name.strip_suffix(".toml").unwrap_or(name);
    let (file, text) = builtin_parts()
        .into_iter()
        .chain(project_parts())
        .find(|(n, _)| *n == name)?;
    parse_part(text, &format!("{file}.toml (built in)")).ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::part::read_part;
    use crate::testutil::scratch_dir;
    use std::path::Path;
    use swarf_geom::Point3;

    fn dir(rel: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join(rel)
    }

    #[test]
    fn embedded_texts_match_project_and_shared_copies() {
        let shared = dir("../../../shared/parts");
        for (name, text) in builtin_parts() {
            let file = format!("{name}.toml");
            let project = std::fs::read_to_string(dir("../../parts").join(&file)).unwrap();
            assert_eq!(project, text, "parts/{file} differs from the embedded text");
            if shared.is_dir() {
                let original = std::fs::read(shared.join(&file)).unwrap();
                assert_eq!(
                    original,
                    project.as_bytes(),
                    "parts/{file} differs from ../shared/parts"
                );
            }
        }
    }

    #[test]
    fn all_four_load() {
        for (name, _) in builtin_parts() {
            let part = builtin_part(name).unwrap_or_else(|| panic!("{name} does not load"));
            assert_eq!(part.name, name);
            assert!(!part.patches.is_empty());
        }
        assert_eq!(builtin_part("edge-convex").unwrap().patches.len(), 2);
        for (name, text) in project_parts() {
            let file = format!("{name}.toml");
            let project = std::fs::read_to_string(dir("../../parts").join(&file)).unwrap();
            assert_eq!(project, text, "parts/{file} differs from the embedded text");
            assert_eq!(builtin_part(name).unwrap().patches.len(), 2);
        }
    }

    /// The control points are the file's, read independently through `toml::Table`.
    #[test]
    fn die_points_are_the_files() {
        let table: toml::Table = DIE.parse().unwrap();
        let points = table["patch"][0]["points"].as_array().unwrap();
        let die = builtin_part("die").unwrap();
        let patch = &die.patches[0];
        assert_eq!(patch.degree(), [2, 2]);
        assert_eq!(patch.points().len(), points.len());
        for (p, q) in patch.points().iter().zip(points) {
            let q: Vec<f64> = q
                .as_array()
                .unwrap()
                .iter()
                .map(|c| c.as_float().or(c.as_integer().map(|i| i as f64)).unwrap())
                .collect();
            assert_eq!(*p, Point3::new(q[0], q[1], q[2]));
        }
    }

    /// The die patch is thesis 000's eq. 6.1: evaluate the Bezier patch by de Casteljau
    /// and compare with the closed form.
    #[test]
    fn die_is_thesis_eq_6_1() {
        let die = builtin_part("die").unwrap();
        let p = &die.patches[0];
        let b2 = |t: f64| [(1.0 - t) * (1.0 - t), 2.0 * t * (1.0 - t), t * t];
        for (u, v) in [(0.0, 0.0), (0.3, 0.7), (1.0, 0.5), (0.8, 1.0), (0.5, 0.25)] {
            let (bu, bv) = (b2(u), b2(v));
            let mut s = Point3::origin();
            for (i, wu) in bu.iter().enumerate() {
                for (j, wv) in bv.iter().enumerate() {
                    s += p.point(i, j).coords * (wu * wv);
                }
            }
            let x = -99.4 + 88.9 * v + 5.6 * v * v;
            let y = -131.3 * u + 28.1 * u * u;
            let z =
                5.9 * (u * u * v * v + u * u * v) - 3.9 * v * v * u + 76.2 * u * u + 6.7 * v * v
                    - 27.3 * u * v
                    - 50.8 * u
                    + 25.0 * v
                    + 12.1;
            assert!(
                (s - Point3::new(x, y, z)).norm() < 1e-9,
                "({u}, {v}): {s} vs {x} {y} {z}"
            );
        }
    }

    #[test]
    fn inch_file_is_scaled() {
        let path = scratch_dir("inch").join("die-inch.toml");
        std::fs::write(&path, DIE.replace("units = \"mm\"", "units = \"inch\"")).unwrap();
        let inch = read_part(&path).unwrap();
        let mm = builtin_part("die").unwrap();
        for (a, b) in inch.patches[0].points().iter().zip(mm.patches[0].points()) {
            assert!((a - b * 25.4).norm() < 1e-12, "{a} vs {b}");
        }
        let missing = read_part(&path.with_file_name("none.toml")).unwrap_err();
        assert!(
            missing.to_string().contains("none.toml: cannot read"),
            "{missing}"
        );
    }
}
