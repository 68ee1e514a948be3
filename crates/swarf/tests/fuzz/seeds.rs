//! Seed inputs: the repository's own files (parts, jobs, machines, the G-code
//! reference corpus with its tool table, parameter file and subroutines), small
//! programs swarf wrote (`seeds/`: the heads of what `swarf plan` writes for
//! `jobs/wave-raster.toml`, G-code, APT CL and pose CSV, and for
//! `jobs/die-inclined-3.toml` posted to each machine in `machines/`), hand-written
//! RS274 and Fanuc macro programs and a five-axis pose CSV, and fixtures the cases
//! run against.

use std::path::{Path, PathBuf};

/// One seed file.
#[derive(Debug, Clone)]
pub struct Seed {
    /// Where it came from (repository path), for reports.
    pub origin: String,
    /// Its file name.
    pub name: String,
    /// Its content.
    pub bytes: Vec<u8>,
}

/// The workspace root.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Every file in `dir` (relative to the root) whose name ends with `ext`, sorted.
pub fn dir_seeds(dir: &str, ext: &str) -> Vec<Seed> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(root().join(dir))
        .unwrap_or_else(|e| panic!("{dir}: {e}"))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.to_string_lossy().ends_with(ext))
        .collect();
    paths.sort();
    paths.iter().map(|p| seed_at(dir, p)).collect()
}

fn seed_at(dir: &str, p: &Path) -> Seed {
    let name = p.file_name().unwrap().to_string_lossy().into_owned();
    Seed {
        origin: format!("{dir}/{name}"),
        bytes: std::fs::read(p).unwrap_or_else(|e| panic!("{}: {e}", p.display())),
        name,
    }
}

/// One file of the repository.
pub fn file_seed(path: &str) -> Seed {
    let (dir, _) = path.rsplit_once('/').unwrap_or((".", path));
    seed_at(dir, &root().join(path))
}

/// A seed from text written here.
pub fn text_seed(name: &str, text: &str) -> Seed {
    Seed {
        origin: format!("(written in the fuzz suite) {name}"),
        name: name.into(),
        bytes: text.as_bytes().to_vec(),
    }
}

/// The folder of the suite's own seed files.
pub const OWN: &str = "crates/swarf/tests/fuzz/seeds";

/// The G-code reference corpus.
pub const CORPUS: &str = "crates/swarf-nc/tests/corpus";

/// Part files: the project's parts (byte-identical copies of ../shared/parts plus
/// its own), B-spline and NURBS patches, and the STEP and IGES parts of `parts/cad`.
pub fn parts() -> Vec<Seed> {
    let mut s = dir_seeds("parts", ".toml");
    s.push(text_seed("bspline.toml", BSPLINE));
    s.push(text_seed("nurbs.toml", NURBS));
    s.push(text_seed("plate.toml", PLATE));
    s.extend(dir_seeds("parts/cad", ".step"));
    s.extend(dir_seeds("parts/cad", ".igs"));
    s
}

/// A bi-quadratic B-spline patch with an inner knot in u, in inches.
const BSPLINE: &str = r#"name = "bspline"
units = "inch"

[[patch]]
degree = [2, 1]
knots_u = [0, 0, 0, 0.4, 1, 1, 1]
knots_v = [0, 0, 1, 1]
points = [
  [0, 0, 0.2], [0, 2, 0.2],
  [0.5, 0, 0.6], [0.5, 2, 0.5],
  [1.5, 0, 0.1], [1.5, 2, 0.3],
  [2, 0, 0.4], [2, 2, 0.4],
]
"#;

/// A quarter cylinder of radius 10 along y, exact as a rational patch.
const NURBS: &str = r#"name = "quarter cylinder"
units = "mm"

[[patch]]
degree = [2, 1]
knots_u = [0, 0, 0, 1, 1, 1]
knots_v = [0, 0, 1, 1]
points = [
  [10, 0, 0], [10, 30, 0],
  [10, 0, 10], [10, 30, 10],
  [0, 0, 10], [0, 30, 10],
]
weights = [1, 1, 0.7071067811865476, 0.7071067811865476, 1, 1]
"#;

/// The plane z = 0 over [0, 20] x [0, 10].
pub const PLATE: &str = "name = \"plate\"\nunits = \"mm\"\n[[patch]]\ndegree = [1, 1]\n\
                         points = [[0, 0, 0], [0, 10, 0], [20, 0, 0], [20, 10, 0]]\n";

/// The plane z = -2 over [-60, 60]², under the corpus programs.
pub const FLOOR: &str = "name = \"floor\"\nunits = \"mm\"\n[[patch]]\ndegree = [1, 1]\n\
    points = [[-60, -60, -2], [-60, 60, -2], [60, -60, -2], [60, 60, -2]]\n";

/// Two passes of a ball across the plate, cutting 0.2 mm into it.
pub const PLATE_PROGRAM: &str = "G21 G90 G17\nG0 Z5\nG0 X-4 Y2\nG1 Z-0.2 F300\nG1 X24\n\
                                 G0 Z5\nG0 X-4 Y7\nG1 Z-0.2\nG1 X24\nG0 Z5\nM2\n";

/// Two passes across the seed meshes (height field up to 15 mm).
pub const MESH_PROGRAM: &str = "G21 G90 G17\nG0 Z30\nG0 X-3 Y10\nG1 Z14 F500\nG1 X43 Z12\n\
                                G0 Z30\nG0 X-3 Y30\nG1 Z11\nG1 X43 Z16\nG0 Z30\nM2\n";

/// G-code programs: swarf's own (three- and five-axis), hand-written RS274 with
/// parameters, O-words and canned cycles, Fanuc macro B, and the reference corpus.
pub fn gcode() -> Vec<Seed> {
    let mut s: Vec<Seed> = [
        "wave-raster.ngc",
        "die-trunnion.ngc",
        "cycles.ngc",
        "fanuc.nc",
    ]
    .iter()
    .map(|n| file_seed(&format!("{OWN}/{n}")))
    .collect();
    s.extend(dir_seeds(CORPUS, ".ngc"));
    s
}

/// The corpus's subroutine files, as `subs/NAME` inputs.
pub fn corpus_subs() -> Vec<(String, Vec<u8>)> {
    dir_seeds(&format!("{CORPUS}/subs"), ".ngc")
        .into_iter()
        .map(|s| (format!("subs/{}", s.name), s.bytes))
        .collect()
}

/// Drop points: with a header, comments and blank lines; bare.
pub fn points() -> Vec<Seed> {
    let mut grid = String::from("x,y\n# a grid over the seed mesh\n");
    for j in 0..5 {
        for i in 0..5 {
            grid += &format!(
                "{},{}\n",
                2.5 + 9.0 * f64::from(i),
                1.0 + 9.5 * f64::from(j)
            );
        }
    }
    grid += "\n-10, -10 # off the mesh\n";
    vec![
        text_seed("points.csv", &grid),
        text_seed("bare.csv", "20,20\n0.5,39.5\n40,0\n"),
    ]
}

/// Tool specs, one of every shape, with and without a flute length.
pub const TOOLS: &[&str] = &[
    "ball:d=8",
    "flat:d=6",
    "bull:d=10,r=2",
    "cone:d=10,angle=90",
    "taperball:d=6,angle=10,tip=1",
    "apt:d=10,r=2,e=3.32180073764544,f=2,alpha=0,beta=10,h=30",
    "ball:d=8,length=20",
    "bull:d=12,r=2,length=30",
];

/// A job for a tool spec: the wave, iso-planar (fast), with `TOOL` to replace.
pub const TOOL_JOB: &str = "name = \"tool fuzz\"\npart = \"builtin:wave\"\ntool = TOOL\n\n\
    [strategy]\nkind = \"iso-planar\"\nscallop = 0.5\ntolerance = 0.05\nangle = 0\n\n\
    [output]\ngcode = \"t.ngc\"\ncl = \"t.cl\"\ncsv = \"t.csv\"\nsummary = \"t.json\"\n";

/// Edits that make the slow example jobs fast enough to fuzz in a debug build (a
/// coarser step: the inputs keep their shape).
pub const CHEAPER: &[(&str, &str, &str)] = &[
    ("die-gouge-free.toml", "stepover = 3.5", "stepover = 15"),
    ("die-inclined-3.toml", "stepover = 3.5", "stepover = 15"),
    ("die-inclined-6.toml", "stepover = 3.5", "stepover = 15"),
    ("edge-concave-drop-spin.toml", "step = 5", "step = 30"),
    (
        "fillet-pocket-cleanup.toml",
        "scallop = 0.01",
        "scallop = 0.1",
    ),
    (
        "fillet-pocket-finish.toml",
        "scallop = 0.01",
        "scallop = 0.1",
    ),
    (
        "fillet-pocket-sequence.toml",
        "scallop = 0.01",
        "scallop = 0.1",
    ),
    ("fillet-pocket-sequence.toml", "cell = 0.25", "cell = 0.5"),
    ("wave-steep-shallow.toml", "scallop = 0.15", "scallop = 0.6"),
];

/// The example jobs, made cheaper.
pub fn jobs() -> Vec<Seed> {
    dir_seeds("jobs", ".toml")
        .into_iter()
        .map(|mut s| {
            for (name, from, to) in CHEAPER {
                if s.name == *name {
                    let text = String::from_utf8(s.bytes).unwrap().replace(from, to);
                    s.bytes = text.into_bytes();
                }
            }
            s
        })
        .collect()
}

/// The job files `job` names as its parent (`job = "..."`), as inputs.
pub fn parents(job: &Seed, all: &[Seed]) -> Vec<(String, Vec<u8>)> {
    let text = String::from_utf8_lossy(&job.bytes);
    all.iter()
        .filter(|s| s.name != job.name && text.contains(&format!("job = \"{}\"", s.name)))
        .map(|s| (s.name.clone(), s.bytes.clone()))
        .collect()
}
