//! The viewer page, embedded in the binary: the committed sources under `viewer/`
//! (`index.html` and the ES modules and style sheet of `viewer/page/`) are the page
//! itself, with no build step and no third-party code, so every view folder gets
//! them as they are. The modules draw with WebGL2 directly (a GLB reader for the
//! files [`swarf_report::gltf`] writes, an orbit camera, picking by ray casting).

use crate::error::Result;
use crate::outputs::Outputs;
use std::path::Path;

/// The page's files: path in a view folder, contents.
pub const FILES: &[(&str, &str)] = &[
    ("index.html", include_str!("../../../../viewer/index.html")),
    (
        "page/viewer.css",
        include_str!("../../../../viewer/page/viewer.css"),
    ),
    (
        "page/camera.js",
        include_str!("../../../../viewer/page/camera.js"),
    ),
    (
        "page/colour.js",
        include_str!("../../../../viewer/page/colour.js"),
    ),
    ("page/gl.js", include_str!("../../../../viewer/page/gl.js")),
    (
        "page/glb.js",
        include_str!("../../../../viewer/page/glb.js"),
    ),
    (
        "page/keys.js",
        include_str!("../../../../viewer/page/keys.js"),
    ),
    (
        "page/main.js",
        include_str!("../../../../viewer/page/main.js"),
    ),
    (
        "page/mat.js",
        include_str!("../../../../viewer/page/mat.js"),
    ),
    (
        "page/motions.js",
        include_str!("../../../../viewer/page/motions.js"),
    ),
    (
        "page/overlay.js",
        include_str!("../../../../viewer/page/overlay.js"),
    ),
    (
        "page/panel.js",
        include_str!("../../../../viewer/page/panel.js"),
    ),
    (
        "page/pick.js",
        include_str!("../../../../viewer/page/pick.js"),
    ),
    (
        "page/scene.js",
        include_str!("../../../../viewer/page/scene.js"),
    ),
];

/// Stages the page's files under `dir` of `out`.
///
/// # Errors
/// An output that cannot be staged.
pub fn write_page(out: &mut Outputs, dir: &Path) -> Result<()> {
    for (name, text) in FILES {
        out.write(dir.join(name), text.as_bytes())?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeSet;

    fn embedded() -> BTreeSet<&'static str> {
        FILES.iter().map(|f| f.0).collect()
    }

    /// The page's source folder.
    fn sources() -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../viewer/page")
    }

    #[test]
    fn every_page_source_is_embedded_as_it_is() {
        let dir = sources();
        let on_disk: BTreeSet<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .map(|n| format!("page/{n}"))
            .collect();
        let listed: BTreeSet<String> = embedded()
            .into_iter()
            .filter(|n| n.starts_with("page/"))
            .map(String::from)
            .collect();
        assert_eq!(on_disk, listed, "viewer/page/ and the embedded list differ");
        for (name, text) in FILES {
            let path = Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../../viewer")
                .join(name);
            assert_eq!(std::fs::read_to_string(path).unwrap(), *text, "{name}");
        }
    }

    #[test]
    fn the_page_names_only_embedded_files() {
        let files = embedded();
        let index = FILES[0].1;
        for r in ["page/main.js", "page/viewer.css"] {
            assert!(index.contains(&format!("\"{r}\"")), "index.html: {r}");
        }
        for (name, text) in FILES.iter().filter(|f| f.0.ends_with(".js")) {
            for line in text.lines().filter(|l| l.starts_with("import ")) {
                let module = line.rsplit("from '").next().unwrap();
                let module = module.trim_end_matches("';").trim_start_matches("./");
                assert!(
                    files.contains(format!("page/{module}").as_str()),
                    "{name} imports {module}, which is not embedded"
                );
            }
        }
    }
}
