//! Records the git commit the binary is built from, for `swarf --version`:
//! `SWARF_COMMIT` is `git rev-parse --short HEAD`, or `unknown` where there is no git
//! or no repository (a source tarball).

use std::path::{Path, PathBuf};
use std::process::Command;

fn main() {
    let dir = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").unwrap_or_default());
    let commit = git(&dir, &["rev-parse", "--short", "HEAD"]).unwrap_or_else(|| "unknown".into());
    println!("cargo:rustc-env=SWARF_COMMIT={commit}");
    println!("cargo:rerun-if-changed=build.rs");
    if let Some(git_dir) = git(&dir, &["rev-parse", "--absolute-git-dir"]) {
        let git_dir = Path::new(&git_dir);
        // HEAD moves on a checkout; the branch it names moves on a commit (its ref
        // file, or packed-refs once git has packed it).
        let mut watched = vec![git_dir.join("HEAD"), git_dir.join("packed-refs")];
        if let Ok(head) = std::fs::read_to_string(git_dir.join("HEAD"))
            && let Some(branch) = head.trim().strip_prefix("ref: ")
        {
            watched.push(git_dir.join(branch));
        }
        // A path that does not exist would rerun this script on every build.
        for path in watched.iter().filter(|p| p.exists()) {
            println!("cargo:rerun-if-changed={}", path.display());
        }
    }
}

/// The trimmed output of `git ARGS` run in `dir`, or `None` when git is missing or
/// fails (no repository).
fn git(dir: &Path, args: &[&str]) -> Option<String> {
    let out = Command::new("git")
        .args(args)
        .current_dir(dir)
        .output()
        .ok()?;
    let text = String::from_utf8(out.stdout).ok()?;
    let text = text.trim();
    (out.status.success() && !text.is_empty()).then(|| text.to_string())
}
