//! Help texts written from the code's own lists, so that `--help` names what the
//! commands read: the design formats ([`swarf_io::ModelFormat`]) and the built-in
//! parts ([`swarf_app::model::builtin_names`]); and the notes a command adds to a
//! flag it shares with others ([`note`]).

use swarf_io::ModelFormat;

/// What a part argument may be.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Reads {
    /// Any design: patches (part file, STEP, IGES) or a mesh (STL, OBJ).
    Model,
    /// Parametric patches only (a part file, STEP or IGES; no mesh).
    Patches,
}

/// The formats `reads` takes, as a help text lists them: `a part file (.toml), STEP
/// (.step, .stp), IGES (.igs, .iges), STL (.stl), OBJ (.obj)`.
pub fn formats(reads: Reads) -> String {
    let named: Vec<String> = ModelFormat::ALL
        .into_iter()
        .filter(|f| reads == Reads::Model || !f.is_mesh())
        .map(|f| {
            let exts: Vec<String> = f.extensions().iter().map(|e| format!(".{e}")).collect();
            let article = if f == ModelFormat::Part { "a " } else { "" };
            format!("{article}{} ({})", f.name(), exts.join(", "))
        })
        .collect();
    named.join(", ")
}

/// The built-in part names `reads` takes, in the code's order.
pub fn builtin_names(reads: Reads) -> Vec<&'static str> {
    match reads {
        Reads::Model => swarf_app::model::builtin_names(),
        Reads::Patches => swarf_app::model::builtin_part_names(),
    }
}

/// The help of a part argument: `what`, then the formats and built-in names it
/// takes (`The part: a part file (.toml), STEP (.step, .stp), ... or a built-in part
/// (die, wave, ...)`).
pub fn part(what: &str, reads: Reads) -> String {
    format!(
        "{what}: {}, or a built-in part ({}; builtin:NAME when a file has that name)",
        formats(reads),
        builtin_names(reads).join(", ")
    )
}

/// `arg` with `note` added to its help: a command's own defaults for a flag it
/// shares with others (`--tol` in `verify`, `compare` and `view`).
pub fn note(arg: clap::Arg, note: &str) -> clap::Arg {
    let help = arg.get_help().map(ToString::to_string).unwrap_or_default();
    let help = help.strip_suffix('.').unwrap_or(&help).to_string();
    arg.help(format!("{help} {note}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_name_step_and_iges_and_meshes_only_where_read() {
        let all = formats(Reads::Model);
        assert!(all.starts_with("a part file (.toml), STEP (.step, .stp), IGES (.igs, .iges)"));
        assert!(all.ends_with("STL (.stl), OBJ (.obj)"), "{all}");
        assert!(!formats(Reads::Patches).contains("STL"));
    }

    #[test]
    fn the_help_lists_every_built_in_part() {
        let text = part("Design part", Reads::Model);
        for name in swarf_app::model::builtin_names() {
            assert!(text.contains(name), "{name} missing from {text}");
        }
        assert!(!part("Part", Reads::Patches).contains("fillet-pocket"));
    }
}
