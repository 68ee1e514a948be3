//! Every `swarf` command the README and the docs name exists, with every flag they
//! give it: the commands in their shell and text code blocks and in inline code spans
//! are read, and each subcommand and flag is looked up in `swarf SUBCOMMAND --help` of
//! the built binary.
//!
//! A command is a line (or, in a block, a line continued by `\`; in a text block, by
//! the indented lines after it) whose first word is `swarf`, or `cargo run ... -p
//! swarf -- ...`. Its second word is the subcommand when it is lower case (`swarf
//! SUBCOMMAND --help` is a placeholder and is skipped); every later word that starts
//! with `--NAME` or is `-X` is a flag, once brackets, bars, `=VALUE` and punctuation
//! are stripped.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Code block languages whose lines are read for commands.
const SHELL: &[&str] = &["sh", "bash", "console", "shell"];
/// Code block languages read as a command summary (continuation by indentation).
const TEXT: &[&str] = &["text", ""];

/// A command named in a document: where, its subcommand (`None`: `swarf` alone) and
/// its flags.
#[derive(Debug, Clone, PartialEq)]
struct Named {
    line: usize,
    sub: Option<String>,
    flags: Vec<String>,
}

/// The commands a Markdown document names, in its code blocks and inline code spans.
fn commands(doc: &str) -> Vec<Named> {
    let mut out = Vec::new();
    let mut block: Option<String> = None;
    let mut logical: Vec<(usize, String)> = Vec::new();
    let mut prose: Vec<(usize, String)> = Vec::new();
    for (k, raw) in doc.lines().enumerate() {
        let line_no = k + 1;
        let trimmed = raw.trim_start();
        if let Some(lang) = trimmed.strip_prefix("```") {
            match block.take() {
                Some(lang_open) => flush_block(&lang_open, &mut logical, &mut out),
                None => {
                    flush_prose(&mut prose, &mut out);
                    block = Some(lang.trim().to_string());
                }
            }
            continue;
        }
        match &block {
            Some(lang) if SHELL.contains(&lang.as_str()) => {
                let continues = logical.last().is_some_and(|(_, l)| l.ends_with('\\'));
                if continues {
                    let last = logical.last_mut().unwrap();
                    last.1.pop();
                    last.1.push(' ');
                    last.1.push_str(trimmed);
                } else {
                    logical.push((line_no, raw.to_string()));
                }
            }
            Some(lang) if TEXT.contains(&lang.as_str()) => {
                let indented = raw.starts_with(' ') || raw.starts_with('\t');
                match logical.last_mut() {
                    Some(last) if indented && !trimmed.is_empty() => {
                        last.1.push(' ');
                        last.1.push_str(trimmed);
                    }
                    _ => logical.push((line_no, raw.to_string())),
                }
            }
            Some(_) => {}
            None if trimmed.is_empty() => flush_prose(&mut prose, &mut out),
            None => prose.push((line_no, raw.to_string())),
        }
    }
    flush_prose(&mut prose, &mut out);
    out
}

/// Reads the commands of a finished code block's logical lines.
fn flush_block(lang: &str, logical: &mut Vec<(usize, String)>, out: &mut Vec<Named>) {
    let shell = SHELL.contains(&lang);
    for (line, text) in logical.drain(..) {
        let text = text.trim();
        let text = text.strip_prefix("$ ").unwrap_or(text);
        let text = if shell { strip_comment(text) } else { text };
        out.extend(segments(text, shell).filter_map(|s| parse(line, s)));
    }
}

/// Reads the commands of a paragraph's inline code spans (a span may run over a
/// line break; it is placed at the line where it starts).
fn flush_prose(prose: &mut Vec<(usize, String)>, out: &mut Vec<Named>) {
    let Some(&(first, _)) = prose.first() else {
        return;
    };
    let text: Vec<String> = prose.drain(..).map(|(_, l)| l).collect();
    let text = text.join("\n");
    let pieces: Vec<&str> = text.split('`').collect();
    if pieces.len().is_multiple_of(2) {
        return; // unbalanced backticks: no spans to trust
    }
    let mut line = first;
    for (k, piece) in pieces.iter().enumerate() {
        if k % 2 == 1 {
            let span = piece.replace('\n', " ");
            out.extend(segments(&span, true).filter_map(|s| parse(line, s)));
        }
        line += piece.matches('\n').count();
    }
}

/// A shell line up to its comment (a word starting with `#`).
fn strip_comment(line: &str) -> &str {
    match line.find(" #") {
        Some(k) => &line[..k],
        None if line.starts_with('#') => "",
        None => line,
    }
}

/// The commands of one line: split at `&&`, `||`, `;` and, in a shell line, at a
/// pipe between words (a summary's `[-a | -b]` is one command).
fn segments(line: &str, shell: bool) -> impl Iterator<Item = &str> {
    let mut parts = vec![line];
    for sep in ["&&", "||", ";"] {
        parts = parts.into_iter().flat_map(|p| p.split(sep)).collect();
    }
    if shell {
        parts = parts.into_iter().flat_map(|p| p.split(" | ")).collect();
    }
    parts.into_iter()
}

/// The command a segment names, if it calls swarf.
fn parse(line: usize, segment: &str) -> Option<Named> {
    let words: Vec<&str> = segment.split_whitespace().collect();
    let mut at = words
        .iter()
        .position(|w| !w.contains('=') || w.starts_with('-'))?;
    let args: &[&str] = if words[at] == "swarf" {
        &words[at + 1..]
    } else if words[at] == "cargo" && words.get(at + 1) == Some(&"run") {
        let swarf = words
            .windows(2)
            .any(|w| w == ["-p", "swarf"] || w == ["--bin", "swarf"]);
        let dashes = words.iter().position(|w| *w == "--")?;
        if !swarf {
            return None;
        }
        at = dashes;
        &words[at + 1..]
    } else {
        return None;
    };
    let (sub, rest) = match args.first() {
        Some(w) if w.starts_with('-') => (None, args),
        Some(w) if w.chars().all(|c| c.is_ascii_lowercase() || c == '-') => {
            (Some(w.to_string()), &args[1..])
        }
        Some(_) => return None, // a placeholder (`SUBCOMMAND`) or not a command
        None => (None, args),
    };
    let flags = rest.iter().filter_map(|w| flag(w)).collect();
    Some(Named { line, sub, flags })
}

/// The flag a word names (`[--out`, `--tol=0.01`, `(-o`), if any.
fn flag(word: &str) -> Option<String> {
    let word = word.trim_matches(|c: char| "[](){}|,;:'\"".contains(c));
    let word = word.split('=').next().unwrap_or(word);
    let word = word.split('|').next().unwrap_or(word);
    let word = word.trim_end_matches(|c: char| "[](){},;:.".contains(c));
    let long = word.strip_prefix("--").is_some_and(|n| {
        n.starts_with(|c: char| c.is_ascii_lowercase())
            && n.chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-')
    });
    let short = word.len() == 2
        && word.starts_with('-')
        && word.chars().nth(1).is_some_and(|c| c.is_ascii_alphabetic());
    (long || short).then(|| word.to_string())
}

/// The flags a `--help` text lists: each option line's leading `-X, --name <V>`
/// (indented at most six spaces, where clap puts options; their descriptions are
/// indented further).
fn help_flags(help: &str) -> BTreeSet<String> {
    let mut flags = BTreeSet::new();
    for line in help.lines() {
        let indent = line.len() - line.trim_start().len();
        let line = line.trim_start();
        if !line.starts_with('-') || indent > 6 {
            continue;
        }
        let spec = line.split("  ").next().unwrap_or(line);
        for word in spec.split([',', ' ']) {
            let word = word.split(['=', '[', '<']).next().unwrap_or(word);
            if word.starts_with('-') && word.len() > 1 {
                flags.insert(word.to_string());
            }
        }
    }
    flags
}

/// The built binary's `--help` of a subcommand (`None`: the top level); `None` when
/// it has none (an unknown subcommand).
fn binary_help(sub: Option<&str>) -> Option<String> {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_swarf"));
    cmd.args(sub).arg("--help");
    let out = cmd.output().expect("the swarf binary runs");
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).into_owned())
}

/// What is wrong with the commands of document `name`: an unknown subcommand or a
/// flag its help does not list, one line each, with the document's line.
fn problems(
    name: &str,
    named: &[Named],
    help: impl Fn(Option<&str>) -> Option<String>,
) -> Vec<String> {
    let mut known: BTreeMap<Option<String>, Option<BTreeSet<String>>> = BTreeMap::new();
    let mut found = Vec::new();
    for n in named {
        let flags = known
            .entry(n.sub.clone())
            .or_insert_with(|| help(n.sub.as_deref()).map(|h| help_flags(&h)));
        let shown = n
            .sub
            .as_deref()
            .map_or("swarf".to_string(), |s| format!("swarf {s}"));
        match flags {
            None => found.push(format!("{name}:{}: `{shown}`: no such subcommand", n.line)),
            Some(flags) => {
                for f in n.flags.iter().filter(|f| !flags.contains(*f)) {
                    found.push(format!(
                        "{name}:{}: `{shown}` has no flag {f} (see `{shown} --help`)",
                        n.line
                    ));
                }
            }
        }
    }
    found
}

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Checks one document of the repository, and that it names at least `least`
/// commands (so that a parser that finds none cannot pass).
fn check(path: &str, least: usize) {
    let text = std::fs::read_to_string(repo().join(path)).expect("the document reads");
    let named = commands(&text);
    assert!(
        named.len() >= least,
        "{path}: {} swarf commands found, expected at least {least}",
        named.len()
    );
    let found = problems(path, &named, binary_help);
    assert!(found.is_empty(), "{}", found.join("\n"));
}

#[test]
fn readme_commands_and_flags_exist() {
    check("README.md", 10);
}

#[test]
fn docs_commands_and_flags_exist() {
    check("docs/guide.md", 20);
    let mut docs: Vec<PathBuf> = std::fs::read_dir(repo().join("docs"))
        .expect("docs/ lists")
        .map(|e| e.expect("a docs/ entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    for doc in docs {
        let name = format!("docs/{}", doc.file_name().unwrap().to_string_lossy());
        check(&name, 0);
    }
}

#[test]
fn a_made_up_flag_and_subcommand_are_reported() {
    let doc = "```sh\nswarf plan job.toml --no-such-flag -o out\nswarf frobnicate x\n```\n";
    let found = problems("doc.md", &commands(doc), binary_help);
    assert_eq!(found.len(), 2, "{found:?}");
    assert!(found[0].contains("doc.md:2") && found[0].contains("--no-such-flag"));
    assert!(found[1].contains("doc.md:3") && found[1].contains("frobnicate"));
    let inline = "Run `swarf demo --out\nd` and\n`swarf verify --part wave --bogus 1`.\n";
    let found = problems("doc.md", &commands(inline), binary_help);
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].contains("doc.md:3") && found[0].contains("--bogus"));
}

#[test]
fn commands_are_read_from_blocks_and_spans() {
    let doc = "\
Plan with `swarf plan job.toml -o out | head`.

```sh
cargo install --path crates/swarf && swarf demo
SEED=1 swarf verify --part wave \\
    --program a.ngc --tool=ball:d=6   # --not-a-flag
cargo run --release -p swarf -- demo --out d
$ swarf --help
```

```text
swarf rest (--reference TOOL | --job PARENT.toml) [--part P] -o DIR
                    regions [--source reference|contacts]
swarf SUBCOMMAND --help
```

```toml
swarf = \"--not-read\"
```
";
    let named = commands(doc);
    let got: Vec<(usize, Option<&str>, Vec<&str>)> = named
        .iter()
        .map(|n| {
            (
                n.line,
                n.sub.as_deref(),
                n.flags.iter().map(String::as_str).collect(),
            )
        })
        .collect();
    assert_eq!(
        got,
        vec![
            (1, Some("plan"), vec!["-o"]),
            (4, Some("demo"), vec![]),
            (5, Some("verify"), vec!["--part", "--program", "--tool"]),
            (7, Some("demo"), vec!["--out"]),
            (8, None, vec!["--help"]),
            (
                12,
                Some("rest"),
                vec!["--reference", "--job", "--part", "-o", "--source"]
            ),
        ]
    );
}

#[test]
fn help_flags_read_clap_option_lines() {
    let help = "Usage: swarf plan [OPTIONS] <JOB>\n\nOptions:\n  -o, --out <OUT>  Directory\n      \
                --allow-unsafe   Write it\n      --tool <SPEC>...  Tools, one\n          \
                --per-tool-not-a-flag\n  -h, --help  Print help\n";
    let flags: Vec<String> = help_flags(help).into_iter().collect();
    assert_eq!(
        flags,
        ["--allow-unsafe", "--help", "--out", "--tool", "-h", "-o"]
    );
}
