//! The machines shipped with swarf (`machines/*.toml` at the repository root), and
//! resolving a machine as a job or a command names it: `builtin:NAME` or a file.

use super::Machine;
use crate::error::FiveAxisError;
use std::path::Path;
use swarf_io::Source;

/// The machine files shipped with swarf (`machines/*.toml`), by built-in name.
pub const BUILTIN_MACHINES: [(&str, &str); 3] = [
    (
        "xyzac-trunnion",
        include_str!("../../../../machines/xyzac-trunnion.toml"),
    ),
    (
        "xyzbc-head",
        include_str!("../../../../machines/xyzbc-head.toml"),
    ),
    (
        "xyzbc-table-head",
        include_str!("../../../../machines/xyzbc-table-head.toml"),
    ),
];

/// The machine `spec` names: `builtin:NAME` (one of [`BUILTIN_MACHINES`]) or a
/// machine file, relative to `job_dir` unless absolute.
///
/// # Errors
/// [`FiveAxisError::Machine`] for an unknown built-in name, a file that cannot be
/// read, or a machine file that does not parse (with its line and field).
pub fn load_machine(spec: &str, job_dir: &Path) -> Result<Machine, FiveAxisError> {
    let path = match Source::parse(spec, job_dir) {
        Source::File(path) => path,
        Source::Builtin(name) => {
            let name = name.strip_suffix(".toml").unwrap_or(name);
            let Some((_, text)) = BUILTIN_MACHINES.iter().find(|(n, _)| *n == name) else {
                let names: Vec<_> = BUILTIN_MACHINES.iter().map(|(n, _)| *n).collect();
                return Err(FiveAxisError::Machine {
                    file: spec.to_string(),
                    message: format!(
                        "no built-in machine of that name (built-in machines: {})",
                        names.join(", ")
                    ),
                });
            };
            return Machine::parse(text, &format!("{name}.toml (built in)"));
        }
    };
    let text = swarf_io::read_input_text(&path).map_err(|e| FiveAxisError::Machine {
        file: path.display().to_string(),
        message: format!("cannot read the machine file (output.machine): {e}"),
    })?;
    Machine::parse(&text, &path.display().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn machines_resolve() {
        let dir = Path::new(".");
        for (name, _) in BUILTIN_MACHINES {
            load_machine(&format!("builtin:{name}"), dir).unwrap();
        }
        let e = load_machine("builtin:hexapod", dir)
            .unwrap_err()
            .to_string();
        assert!(e.contains("xyzac-trunnion"), "{e}");
        let e = load_machine("no/such/machine.toml", dir)
            .unwrap_err()
            .to_string();
        assert!(e.contains("output.machine"), "{e}");
    }
}
