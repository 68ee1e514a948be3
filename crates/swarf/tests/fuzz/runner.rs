//! The fuzz loop: settings from the environment, one proptest value per case drawn
//! from its own generator (so that any case can be rerun alone), the run, a bounded
//! shrink of each new kind of failure, and the report.

use crate::check::{Failure, judge};
use crate::exec::{Case, Limits, Outcome, reproducer, run};
use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use std::collections::BTreeMap;
use std::fmt::Debug;
use std::path::PathBuf;
use std::sync::Mutex;
use std::time::Duration;

/// Settings read from `SWARF_FUZZ_*` variables (see the suite's module doc).
#[derive(Debug, Clone)]
pub struct Settings {
    /// Cases per input type (`SWARF_FUZZ_CASES`).
    pub cases: usize,
    /// Seed of every generator (`SWARF_FUZZ_SEED`).
    pub seed: u64,
    /// Only this case (`SWARF_FUZZ_CASE`), to reproduce it.
    pub only: Option<usize>,
    /// Time and memory limits (`SWARF_FUZZ_TIMEOUT` s, `SWARF_FUZZ_MEMORY_MB`).
    pub limits: Limits,
    /// Runs spent shrinking each new kind of failure (`SWARF_FUZZ_SHRINK`).
    pub shrink: usize,
    /// Where case folders go (`SWARF_FUZZ_DIR`).
    pub dir: PathBuf,
}

/// Cases per input type when `SWARF_FUZZ_CASES` is not set.
pub const DEFAULT_CASES: usize = 32;

fn var<T: std::str::FromStr>(name: &str) -> Option<T> {
    let v = std::env::var(name).ok()?;
    Some(
        v.trim()
            .parse()
            .unwrap_or_else(|_| panic!("{name}={v:?} is not a valid value")),
    )
}

impl Settings {
    /// The settings from the environment.
    pub fn from_env() -> Settings {
        let seed = var("SWARF_FUZZ_SEED").unwrap_or(1);
        Settings {
            cases: var("SWARF_FUZZ_CASES").unwrap_or(DEFAULT_CASES),
            seed,
            only: var("SWARF_FUZZ_CASE"),
            limits: Limits {
                timeout: Duration::from_secs(var("SWARF_FUZZ_TIMEOUT").unwrap_or(60)),
                memory_kib: var::<u64>("SWARF_FUZZ_MEMORY_MB").unwrap_or(3000) * 1024,
            },
            shrink: var("SWARF_FUZZ_SHRINK").unwrap_or(8),
            dir: var::<String>("SWARF_FUZZ_DIR").map_or_else(
                || std::env::temp_dir().join(format!("swarf-fuzz-{seed}")),
                PathBuf::from,
            ),
        }
    }
}

/// One run at a time: swarf uses every core, and timings must mean something.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

/// The generator of case `index` of `input` under `seed`.
fn case_rng(seed: u64, input: &str, index: usize) -> TestRng {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in input.bytes() {
        h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
    }
    let mut x = seed ^ h ^ (index as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    let mut bytes = [0u8; 32];
    for chunk in bytes.chunks_mut(8) {
        x = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = x;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        chunk.copy_from_slice(&(z ^ (z >> 31)).to_le_bytes());
    }
    TestRng::from_seed(RngAlgorithm::ChaCha, &bytes)
}

/// A failing case and how it failed.
struct Found {
    case: Case,
    index: usize,
    dir: PathBuf,
    failure: Failure,
    count: usize,
}

/// Runs `cases` cases of `input`, each made by `make` from a value of `strategy`;
/// prints the count, the time and every distinct failure with its reproducer, and
/// panics if any case failed.
pub fn fuzz<S, F>(input: &str, strategy: S, make: F)
where
    S: Strategy,
    S::Value: Debug,
    F: Fn(&S::Value) -> Case,
{
    let s = Settings::from_env();
    let dir = s.dir.join(input);
    let mut found: BTreeMap<String, Found> = BTreeMap::new();
    let (mut ran, mut busy, mut slowest) = (0, Duration::ZERO, Duration::ZERO);
    let indices: Vec<usize> = match s.only {
        Some(i) => vec![i],
        None => (0..s.cases).collect(),
    };
    for index in indices {
        let mut runner =
            TestRunner::new_with_rng(Config::default(), case_rng(s.seed, input, index));
        let mut tree = strategy.new_tree(&mut runner).expect("a value");
        let case = make(&tree.current());
        let case_dir = dir.join(format!("case-{index}"));
        let (outcome, failure) = run_one(&case, &case_dir, &s);
        ran += 1;
        busy += outcome.elapsed;
        slowest = slowest.max(outcome.elapsed);
        let Some(failure) = failure else {
            let _ = std::fs::remove_dir_all(&case_dir);
            continue;
        };
        let key = format!("{} | {input} | {}", case.command, failure.symptom);
        eprintln!("fuzz {input}: case {index} fails: {key}");
        if let Some(f) = found.get_mut(&key) {
            f.count += 1;
            if case.size() < f.case.size() {
                let _ = std::fs::remove_dir_all(&f.dir);
                (f.case, f.index, f.dir, f.failure) = (case, index, case_dir, failure);
            } else {
                let _ = std::fs::remove_dir_all(&case_dir);
            }
            continue;
        }
        let timeout = outcome.status.is_none();
        let mut best = (case, case_dir, failure);
        if !timeout {
            shrink(&mut tree, &make, &key, input, &s, &mut best);
        }
        let (case, dir, failure) = best;
        found.insert(
            key,
            Found {
                case,
                index,
                dir,
                failure,
                count: 1,
            },
        );
    }
    report(input, &s, ran, busy, slowest, &found);
}

/// Runs `cases` as they are (no generation, no shrinking) and reports like
/// [`fuzz`].
pub fn run_cases(input: &str, cases: Vec<Case>) {
    let s = Settings::from_env();
    let dir = s.dir.join(input);
    let mut found: BTreeMap<String, Found> = BTreeMap::new();
    let (mut ran, mut busy, mut slowest) = (0, Duration::ZERO, Duration::ZERO);
    for (index, case) in cases.into_iter().enumerate() {
        let case_dir = dir.join(format!("case-{index}"));
        let (outcome, failure) = run_one(&case, &case_dir, &s);
        ran += 1;
        busy += outcome.elapsed;
        slowest = slowest.max(outcome.elapsed);
        match failure {
            None => {
                let _ = std::fs::remove_dir_all(&case_dir);
            }
            Some(failure) => {
                let key = format!("{} | {input} #{index} | {}", case.command, failure.symptom);
                eprintln!("{input}: case {index} fails: {key}");
                let f = Found {
                    case,
                    index,
                    dir: case_dir,
                    failure,
                    count: 1,
                };
                found.insert(key, f);
            }
        }
    }
    report(input, &s, ran, busy, slowest, &found);
}

/// Runs one case alone on the machine and judges it.
fn run_one(case: &Case, dir: &std::path::Path, s: &Settings) -> (Outcome, Option<Failure>) {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|p| p.into_inner());
    let outcome = run(case, dir, &s.limits);
    let failure = judge(case, &outcome, s.limits.timeout.as_secs());
    (outcome, failure)
}

/// Simplifies the failing value while the failure stays the same, for at most
/// `s.shrink` runs; `best` ends as the simplest failing case seen.
fn shrink<T: ValueTree, F>(
    tree: &mut T,
    make: &F,
    key: &str,
    input: &str,
    s: &Settings,
    best: &mut (Case, PathBuf, Failure),
) where
    T::Value: Debug,
    F: Fn(&T::Value) -> Case,
{
    let mut runs = 0;
    if !tree.simplify() {
        return;
    }
    while runs < s.shrink {
        runs += 1;
        let case = make(&tree.current());
        let dir = best.1.with_extension(format!("s{runs}"));
        let (_, failure) = run_one(&case, &dir, s);
        let same = failure
            .as_ref()
            .is_some_and(|f| format!("{} | {input} | {}", case.command, f.symptom) == key);
        if same {
            let _ = std::fs::remove_dir_all(&best.1);
            *best = (case, dir, failure.unwrap());
            if !tree.simplify() {
                break;
            }
        } else {
            let _ = std::fs::remove_dir_all(&dir);
            if !tree.complicate() {
                break;
            }
        }
    }
}

/// Prints the summary and every distinct failure; panics if there was one.
fn report(
    input: &str,
    s: &Settings,
    ran: usize,
    busy: Duration,
    slowest: Duration,
    found: &BTreeMap<String, Found>,
) {
    let failing: usize = found.values().map(|f| f.count).sum();
    let mut text = format!(
        "fuzz {input}: {ran} cases in {:.1} s (slowest {:.1} s), seed {}, limits {} s / {} MB: \
         {failing} failing, {} distinct\n",
        busy.as_secs_f64(),
        slowest.as_secs_f64(),
        s.seed,
        s.limits.timeout.as_secs(),
        s.limits.memory_kib / 1024,
        found.len()
    );
    for (k, (key, f)) in found.iter().enumerate() {
        text += &format!("\n[{}] {key} ({} case(s))\n", k + 1, f.count);
        text += &format!("  case: {}; {}\n", f.index, f.case.about);
        text += &format!(
            "  rerun: SWARF_FUZZ_SEED={} SWARF_FUZZ_CASE={} cargo test -p swarf --test fuzz \
             -- --exact {}\n",
            s.seed,
            f.index,
            test_name(input)
        );
        text += &format!("  command: {}\n", reproducer(&f.case, &f.dir, &s.limits));
        text += &inputs_text(&f.case, &f.dir);
        text += &format!("  {}\n", f.failure.detail.trim().replace('\n', "\n  | "));
    }
    println!("{text}");
    let _ = std::fs::create_dir_all(&s.dir);
    let summary = match s.only {
        Some(i) => s.dir.join(format!("{input}-case-{i}.txt")),
        None => s.dir.join(format!("{input}.txt")),
    };
    let _ = std::fs::write(&summary, &text);
    assert!(
        found.is_empty(),
        "fuzz {input}: {} distinct failure(s), listed above and in {}",
        found.len(),
        summary.display()
    );
}

/// The test function of `input`.
fn test_name(input: &str) -> String {
    format!("fuzz_{}", input.replace('-', "_"))
}

/// The mutated inputs of `case` (those among its places): shown when short text,
/// else where they are.
fn inputs_text(case: &Case, dir: &std::path::Path) -> String {
    let mut text = String::new();
    let fixtures: Vec<&str> = case
        .files
        .iter()
        .map(|(n, _)| n.as_str())
        .filter(|n| n.starts_with("subs/") || !case.places.iter().any(|p| p == n))
        .collect();
    if !fixtures.is_empty() {
        text += &format!("  unmutated inputs beside it: {}\n", fixtures.join(", "));
    }
    for (name, bytes) in &case.files {
        if fixtures.contains(&name.as_str()) {
            continue;
        }
        let shown = std::str::from_utf8(bytes)
            .ok()
            .filter(|t| t.len() <= 1500 && !t.contains('\0'));
        match shown {
            Some(t) => {
                text += &format!("  {name} ({} bytes):\n", bytes.len());
                for line in t.lines() {
                    text += &format!("  | {line}\n");
                }
            }
            None => {
                let at = dir.join(name);
                text += &format!("  {name}: {} bytes, in {}\n", bytes.len(), at.display());
            }
        }
    }
    text
}
