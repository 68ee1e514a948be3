//! The example machine files of `machines/` and the repository root.

use std::path::PathBuf;

/// The three example machines: short name and the text of their TOML file.
pub const MACHINES: [(&str, &str); 3] = [
    (
        "trunnion",
        include_str!("../../../machines/xyzac-trunnion.toml"),
    ),
    ("head", include_str!("../../../machines/xyzbc-head.toml")),
    (
        "table-head",
        include_str!("../../../machines/xyzbc-table-head.toml"),
    ),
];

/// The A/C trunnion table (`machines/xyzac-trunnion.toml`).
pub const TRUNNION: &str = MACHINES[0].1;

/// The root of the repository (where `jobs/` and `machines/` are).
pub fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Path of the machine file `machines/<file>`.
pub fn machine_path(file: &str) -> PathBuf {
    repo_root().join("machines").join(file)
}
