//! Cases for command-line option values: every numeric, pair, stock, faces and word
//! option of every command (`--cell`, `--tol`, `--scallop`, `--rapid`,
//! `--sample-tol`, `--max-memory`, `--threads`, `--stock`, `--uv`, `--faces` ...)
//! given a hostile value, one or two at a time, on a command line that is otherwise
//! good and fast.

use crate::exec::Case;
use crate::mesh;
use crate::mutate::number;
use crate::seeds;
use proptest::prelude::*;

/// What an option takes.
#[derive(Debug, Clone, Copy)]
enum Kind {
    /// A real number.
    Num,
    /// A count or index.
    Int,
    /// `U,V`.
    Pair,
    /// `box`, `box:TOP`, `offset:A` or a mesh file.
    Stock,
    /// Two patch indices, `A,B`.
    Faces,
    /// One of these words.
    Word(&'static [&'static str]),
}

/// A command line that works, and the options of it to fuzz.
struct Base {
    command: &'static str,
    /// Words before the options.
    head: &'static [&'static str],
    /// Options with their good values (a fuzzed one replaces its good value).
    options: &'static [(&'static str, &'static str)],
    /// The options to fuzz.
    fuzz: &'static [(&'static str, Kind)],
}

const WORDS: &[&str] = &["linuxcnc", "fanuc", "mm", "inch", "vertical", "normal"];

const SIM: &[(&str, Kind)] = &[
    ("--stock", Kind::Stock),
    ("--cell", Kind::Num),
    ("--tol", Kind::Num),
    ("--scallop", Kind::Num),
    ("--rapid", Kind::Num),
    ("--sample-tol", Kind::Num),
    ("--max-memory", Kind::Int),
    ("--deviation", Kind::Word(&["vertical", "normal"])),
];

const BASES: &[Base] = &[
    Base {
        command: "eval",
        head: &["eval", "die"],
        options: &[("--patch", "0"), ("--uv", "0.3,0.7")],
        fuzz: &[("--patch", Kind::Int), ("--uv", Kind::Pair)],
    },
    Base {
        command: "tessellate",
        head: &["tessellate", "wave", "-o", "out.stl"],
        options: &[("--tol", "0.1")],
        fuzz: &[("--tol", Kind::Num)],
    },
    Base {
        command: "classify",
        head: &["classify", "wave", "-o", "out"],
        options: &[("--cell", "2")],
        fuzz: &[
            ("--steep-angle", Kind::Num),
            ("--flat-angle", Kind::Num),
            ("--cell", Kind::Num),
            ("--tol", Kind::Num),
        ],
    },
    Base {
        command: "drop",
        head: &["drop", "--mesh", "mesh.stl", "--points", "points.csv"],
        options: &[("--tool", "ball:d=4")],
        fuzz: &[
            ("--threads", Kind::Int),
            (
                "--tool",
                Kind::Word(&["ball:d=", "bull:d=10,r=", "cone:d=10,angle="]),
            ),
        ],
    },
    Base {
        command: "verify",
        head: &[
            "verify",
            "--part",
            "plate.toml",
            "--program",
            "pass.ngc",
            "-o",
            "out",
        ],
        options: &[
            ("--tool", "ball:d=6"),
            ("--cell", "0.5"),
            ("--max-memory", "1024"),
        ],
        fuzz: SIM,
    },
    Base {
        command: "verify",
        head: &[
            "verify",
            "--part",
            "floor.toml",
            "--program",
            "cycles.ngc",
            "-o",
            "out",
        ],
        options: &[
            ("--tool", "ball:d=6"),
            ("--cell", "1"),
            ("--max-memory", "1024"),
        ],
        fuzz: &[
            ("--dialect", Kind::Word(WORDS)),
            ("--machine-units", Kind::Word(WORDS)),
            ("--sample-tol", Kind::Num),
        ],
    },
    Base {
        command: "verify",
        head: &[
            "verify",
            "--part",
            "die",
            "--program",
            "die-xyzbc-head.ngc",
            "-o",
            "out",
            "--tool=bull:d=38.1,r=6.35",
        ],
        options: &[
            ("--machine", "builtin:xyzbc-head"),
            ("--tool-length", "150"),
            ("--cell", "2"),
            ("--max-memory", "1024"),
        ],
        fuzz: &[("--tool-length", Kind::Num), ("--cell", Kind::Num)],
    },
    Base {
        command: "compare",
        head: &["compare", "wave-iso-planar.toml", "-o", "out"],
        options: &[("--cell", "2"), ("--max-memory", "1024")],
        fuzz: SIM,
    },
    Base {
        command: "rest",
        head: &[
            "rest",
            "--part",
            "v-grooves",
            "--reference",
            "ball:d=12",
            "-o",
            "out",
        ],
        options: &[],
        fuzz: &[
            ("--threshold", Kind::Num),
            ("--merge", Kind::Num),
            ("--overlap", Kind::Num),
            ("--min-area", Kind::Num),
            ("--smoothness", Kind::Num),
            ("--tol", Kind::Num),
        ],
    },
    Base {
        command: "dsm",
        head: &["dsm", "wedge-30-45", "--tool", "bull:d=12,r=2"],
        options: &[("--station", "50"), ("--offset", "1")],
        fuzz: &[
            ("--station", Kind::Num),
            ("--offset", Kind::Num),
            ("--along", Kind::Num),
            ("--footprints", Kind::Int),
            ("--faces", Kind::Faces),
        ],
    },
];

/// Raw material for one option value; [`render`] shapes it for the option's kind.
#[derive(Debug, Clone)]
pub struct Raw {
    flag: usize,
    a: String,
    b: String,
    pick: usize,
    garbage: Option<String>,
}

/// Values no option should take quietly.
const GARBAGE: &[&str] = &[
    "", " ", "-", "--", " 1", "1 ", "\u{661}", "0x1p3", "1,2,3", "=", "1e5e5",
];

fn raw() -> impl Strategy<Value = Raw> {
    let garbage = prop_oneof![
        6 => Just(None),
        2 => prop::sample::select(GARBAGE).prop_map(|g| Some(g.to_string())),
        1 => Just(Some("9".repeat(100_000))),
    ];
    (0usize..1000, number(), number(), 0usize..1000, garbage).prop_map(
        |(flag, a, b, pick, garbage)| Raw {
            flag,
            a,
            b,
            pick,
            garbage,
        },
    )
}

/// A command index and one or two option values.
pub fn option_edit() -> impl Strategy<Value = (usize, Vec<Raw>)> {
    (0usize..1000, prop::collection::vec(raw(), 1..=2))
}

/// The option value `r` gives for `kind`.
fn render(kind: Kind, r: &Raw) -> String {
    if let Some(g) = &r.garbage {
        return g.clone();
    }
    let int = |s: &str| s.split(['.', 'e', 'E']).next().unwrap_or("").to_string();
    match kind {
        Kind::Num => r.a.clone(),
        Kind::Int => match r.pick % 3 {
            0 => r.a.clone(),
            _ => int(&r.a),
        },
        Kind::Pair => format!("{},{}", r.a, r.b),
        Kind::Stock => match r.pick % 5 {
            0 => format!("offset:{}", r.a),
            1 => format!("box:{}", r.a),
            2 => "box".into(),
            3 => "stock.stl".into(),
            _ => format!("{}:{}", r.a, r.b),
        },
        Kind::Faces => match r.pick % 3 {
            0 => format!("{},{}", int(&r.a), int(&r.b)),
            1 => int(&r.a),
            _ => format!("0,1,{}", int(&r.a)),
        },
        Kind::Word(words) => match r.pick % 3 {
            0 => words[r.pick / 3 % words.len()].to_uppercase(),
            1 => format!("{}{}", words[r.pick / 3 % words.len()], r.a),
            _ => r.a.clone(),
        },
    }
}

/// The files every base command line reads.
fn fixtures() -> Vec<(String, Vec<u8>)> {
    let text = |n: &str, t: &str| (n.to_string(), t.as_bytes().to_vec());
    let stl = mesh::binary_stl(&mesh::height_field(8));
    let own = |n: &str| {
        (
            n.to_string(),
            seeds::file_seed(&format!("{}/{n}", seeds::OWN)).bytes,
        )
    };
    let job = seeds::file_seed("jobs/wave-iso-planar.toml");
    vec![
        text("plate.toml", seeds::PLATE),
        text("floor.toml", seeds::FLOOR),
        text("pass.ngc", seeds::PLATE_PROGRAM),
        text("points.csv", "x,y\n10,10\n20,25\n"),
        ("mesh.stl".into(), stl.clone()),
        ("stock.stl".into(), stl),
        own("cycles.ngc"),
        own("die-xyzbc-head.ngc"),
        (job.name, job.bytes),
    ]
}

/// A command line with one or two options given hostile values.
pub fn option_case((cmd, raws): &(usize, Vec<Raw>)) -> Case {
    let base = &BASES[cmd % BASES.len()];
    let mut fuzzed: Vec<(&str, String)> = Vec::new();
    for r in raws {
        let (flag, kind) = base.fuzz[r.flag % base.fuzz.len()];
        let value = crate::check::head(&render(kind, r), 100_000);
        fuzzed.retain(|(f, _)| *f != flag);
        fuzzed.push((flag, value));
    }
    let mut args: Vec<String> = base.head.iter().map(|s| (*s).to_string()).collect();
    for (flag, good) in base.options {
        if !fuzzed.iter().any(|(f, _)| f == flag) {
            args.push(format!("{flag}={good}"));
        }
    }
    for (flag, value) in &fuzzed {
        args.push(format!("{flag}={value}"));
    }
    let shown: Vec<String> = fuzzed
        .iter()
        .map(|(f, v)| format!("{f}={}", v.chars().take(60).collect::<String>()))
        .collect();
    Case {
        command: base.command,
        args,
        files: fixtures(),
        places: fuzzed.iter().map(|(f, _)| (*f).to_string()).collect(),
        about: format!("options {}", shown.join(" ")),
    }
}

/// Every base command line with its good values only.
pub fn good_cases() -> Vec<Case> {
    BASES
        .iter()
        .map(|base| {
            let mut args: Vec<String> = base.head.iter().map(|s| (*s).to_string()).collect();
            args.extend(base.options.iter().map(|(f, v)| format!("{f}={v}")));
            Case {
                command: base.command,
                args,
                files: fixtures(),
                places: Vec::new(),
                about: "good options".into(),
            }
        })
        .collect()
}
