//! `swarf view`: the view folder of a job, of a part with a program and of a
//! sequence job (GLB files, view.json, the verification's report, the page embedded
//! in swarf), written as one set and byte for byte the same on a repeat; a sequence
//! shown per operation; bad input refused with a clear message and no folder (a
//! program with no moves, a program away from the part); `--serve` answering on
//! 127.0.0.1.

use std::io::{BufRead, BufReader, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

fn swarf(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swarf"))
        .args(args)
        .output()
        .expect("the swarf binary runs")
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("swarf-view-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn job(name: &str) -> String {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../../jobs/{name}.toml"));
    p.to_str().unwrap().to_string()
}

/// Asserts that the view folder `out` holds the viewer page as its sources are.
fn has_the_page(out: &Path) {
    let viewer = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../viewer");
    for f in [
        "index.html",
        "page/main.js",
        "page/glb.js",
        "page/viewer.css",
    ] {
        assert_eq!(
            std::fs::read(out.join(f)).unwrap(),
            std::fs::read(viewer.join(f)).unwrap(),
            "{f}"
        );
    }
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn job_view_folder_is_whole_and_repeats() {
    let dir = scratch("job");
    let out = dir.join("view");
    let args = [
        "view",
        "--job",
        &job("wave-iso-scallop"),
        "--cell",
        "0.5",
        "-o",
        out.to_str().unwrap(),
    ];
    let o = swarf(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    has_the_page(&out);
    let files = ["part.glb", "toolpath.glb", "cutter.glb", "stock.glb"];
    let first: Vec<Vec<u8>> = files
        .iter()
        .map(|f| std::fs::read(out.join(f)).unwrap())
        .collect();
    for (f, bytes) in files.iter().zip(&first) {
        assert_eq!(&bytes[..4], b"glTF", "{f}");
        assert_eq!(
            u32::from_le_bytes(bytes[8..12].try_into().unwrap()) as usize,
            bytes.len()
        );
    }
    let view: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("view.json")).unwrap()).unwrap();
    let count = view["motions"]["count"].as_u64().unwrap() as usize;
    assert!(count > 1000);
    assert_eq!(
        view["motions"]["pose"].as_array().unwrap().len(),
        6 * (count + 1)
    );
    let line = view["motions"]["line"][count / 2].as_u64().unwrap() as usize;
    let source = view["source"][line - 1].as_str().unwrap();
    assert!(source.contains(['X', 'Y', 'Z']), "line {line}: {source}");
    assert!(out.join("report.json").is_file() && out.join("deviation.png").is_file());
    assert_eq!(view["operations"].as_array().unwrap().len(), 1);
    assert_eq!(view["operations"][0]["motions"], count);
    let o = swarf(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    for (f, bytes) in files.iter().zip(&first) {
        assert_eq!(
            &std::fs::read(out.join(f)).unwrap(),
            bytes,
            "{f} differs on a repeat"
        );
    }
    // The planned program on its part gives the same stock.
    let ngc = out.join("wave-iso-scallop.ngc");
    let out2 = dir.join("program");
    let o = swarf(&[
        "view",
        "--part",
        "builtin:wave",
        "--program",
        ngc.to_str().unwrap(),
        "--tool",
        "ball:d=8",
        "--cell",
        "0.5",
        "-o",
        out2.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read(out2.join("stock.glb")).unwrap(), first[3]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Runs a view of `program` on wave that must fail with `message`, leaving no folder.
fn refused(name: &str, program: &str, extra: &[&str], message: &str) {
    let dir = scratch(name);
    let prog = dir.join("p.ngc");
    std::fs::write(&prog, program).unwrap();
    let out = dir.join("view");
    let mut args = vec![
        "view",
        "--part",
        "builtin:wave",
        "--program",
        prog.to_str().unwrap(),
        "--tool",
        "ball:d=8",
        "-o",
        out.to_str().unwrap(),
    ];
    args.extend(extra);
    let o = swarf(&args);
    assert!(!o.status.success());
    let err = stderr(&o);
    assert!(err.contains(message), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(!out.exists(), "a folder was left behind");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_program_with_no_moves_is_refused() {
    refused("empty", "G21 G90\nM30\n", &[], "has no moves");
}

#[test]
fn a_program_away_from_the_part_is_refused() {
    refused(
        "apart",
        "G21 G90\nG0 X1000 Y1000 Z50\nG1 X1100 Y1000 Z0 F300\nM30\n",
        &[],
        "do not overlap",
    );
}

#[test]
fn a_sequence_is_shown_per_operation() {
    let dir = scratch("sequence");
    let out = dir.join("view");
    let args = [
        "view",
        "--job",
        &job("fillet-pocket-sequence"),
        "--cell",
        "1",
        "-o",
        out.to_str().unwrap(),
    ];
    let o = swarf(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    has_the_page(&out);
    let view: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("view.json")).unwrap()).unwrap();
    let ops = view["operations"].as_array().unwrap();
    let names: Vec<&str> = ops.iter().map(|o| o["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["rough", "rest-rough", "finish", "cleanup"]);
    let mut first = 0;
    for (k, op) in ops.iter().enumerate() {
        assert_eq!(op["first_motion"], first, "operation {k}");
        first += op["motions"].as_u64().unwrap();
        let stock = op["stock"].as_str().unwrap();
        let cutter = op["cutter"].as_str().unwrap();
        assert_eq!(
            stock,
            if k == 3 {
                "stock.glb".into()
            } else {
                format!("stock-{}.glb", k + 1)
            }
        );
        for f in [stock, cutter] {
            assert_eq!(&std::fs::read(out.join(f)).unwrap()[..4], b"glTF", "{f}");
        }
    }
    assert_eq!(view["motions"]["count"], first);
    // The stock after the roughing is not the final stock.
    let bytes = |f: &str| std::fs::read(out.join(f)).unwrap();
    assert_ne!(bytes("stock-1.glb"), bytes("stock.glb"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn serve_answers_on_localhost_and_refuses_paths_outside() {
    let dir = scratch("serve");
    let out = dir.join("view");
    let mut child = Command::new(env!("CARGO_BIN_EXE_swarf"))
        .args([
            "view",
            "--job",
            &job("wave-iso-scallop"),
            "--cell",
            "1",
            "-o",
            out.to_str().unwrap(),
        ])
        .args(["--serve", "--port", "0", "--serve-for", "20"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
    let url = lines
        .find_map(|l| {
            l.ok()?
                .split("at http://")
                .nth(1)
                .map(|s| s.split('/').next().unwrap().to_string())
        })
        .expect("the server says where it listens");
    let get = |path: &str| {
        let mut s = std::net::TcpStream::connect(&url).unwrap();
        write!(s, "GET {path} HTTP/1.1\r\nHost: x\r\n\r\n").unwrap();
        let mut r = Vec::new();
        s.read_to_end(&mut r).unwrap();
        r
    };
    let index = get("/");
    assert!(index.starts_with(b"HTTP/1.1 200"));
    assert!(index.ends_with(&std::fs::read(out.join("index.html")).unwrap()));
    let glb = get("/stock.glb");
    assert!(glb.ends_with(&std::fs::read(out.join("stock.glb")).unwrap()));
    assert!(get("/../Cargo.toml").starts_with(b"HTTP/1.1 404"));
    let _ = child.kill();
    let _ = child.wait();
    let _ = std::fs::remove_dir_all(&dir);
}
