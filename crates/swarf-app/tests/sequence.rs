//! The fillet pocket from a box in one sequence job (jobs/fillet-pocket-sequence.toml):
//! roughing, finishing and cleanup on one in-process stock.

use std::path::Path;
use swarf_app::sequence::{Sequence, plan_sequence};

#[test]
fn fillet_pocket_from_a_box_in_one_job() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../jobs");
    let file = root.join("fillet-pocket-sequence.toml");
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(Sequence::is_sequence(&text));
    let seq = Sequence::parse(&text, "fillet-pocket-sequence.toml").unwrap();
    let dir = std::env::temp_dir().join("swarf-sequence-test");
    let mut out = swarf_app::Outputs::new(&dir);
    let t = std::time::Instant::now();
    let report = plan_sequence(&seq, &root, &mut out).unwrap();
    eprintln!("{:.1} s", t.elapsed().as_secs_f64());
    eprintln!("{}", serde_json::to_string_pretty(&report).unwrap());
}
