//! `swarf dsm` as a user runs it: the zone and spins on a wedge against the closed
//! forms, and errors that say what is wrong.

use std::process::{Command, Output};

fn swarf(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swarf"))
        .args(args)
        .output()
        .expect("the swarf binary runs")
}

#[test]
fn the_wedge_zone_and_spins() {
    let o = swarf(&[
        "dsm",
        "wedge-30-45",
        "--tool",
        "bull:d=12,r=2,length=30",
        "--station",
        "50",
        "--footprints",
        "3",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    // b = 30, g = 45 degrees, R = 4, r = 2 (parts/README.md).
    let (tb, tg) = (30f64.to_radians().tan(), 1.0);
    let (sb, sg) = (1.0 / 30f64.to_radians().cos(), 2f64.sqrt());
    let t1 = (4.0 * (tb - tg) + 2.0 * (sb - sg)) / (tb + tg);
    let z = &v["zone"];
    assert!((z["t1_mm"].as_f64().unwrap() - t1).abs() < 1e-9, "{z}");
    let line = v["footprints"].as_array().unwrap();
    assert_eq!(line.len(), 3);
    // Inside the zone each spin clears the other face and touches it; at its end
    // (a double root) within the contact tolerance.
    for (k, f) in line.iter().enumerate() {
        let lo = if k + 1 < line.len() { 0.0 } else { -1e-6 };
        for side in ["spin_plus", "spin_minus"] {
            let c = f[side]["clearance_mm"].as_f64().unwrap();
            assert!((lo..1e-6).contains(&c), "{f}");
        }
    }
}

/// A bad request: part, tool, station, extra arguments, what the error must say.
type Case<'a> = (&'a str, &'a str, &'a str, &'a [&'a str], &'a [&'a str]);

#[test]
fn dsm_says_what_is_wrong() {
    let cases: [Case<'_>; 6] = [
        ("die", "bull:d=12,r=2", "50", &[], &["faces", "below 1"]),
        ("boss", "bull:d=12,r=2", "50", &[], &["patch part"]),
        (
            "edge-convex",
            "bull:d=12,r=2",
            "500",
            &[],
            &["station 500", "do not cross"],
        ),
        ("edge-convex", "flat:d=12", "50", &[], &["bull or ball"]),
        (
            "edge-convex",
            "bull:d=80,r=30",
            "50",
            &[],
            &["station 50", "does not lie under"],
        ),
        (
            "edge-convex",
            "bull:d=12,r=2",
            "50",
            &["--faces", "0"],
            &["--faces"],
        ),
    ];
    for (part, tool, station, extra, want) in cases {
        let mut args = vec!["dsm", part, "--tool", tool, "--station", station];
        args.extend_from_slice(extra);
        let o = swarf(&args);
        assert!(!o.status.success(), "{args:?}");
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(want.iter().all(|w| e.contains(w)), "{args:?}: {e}");
    }
}

/// A bull too large for the symmetric wedge's faces (each runs 20 mm past the edge):
/// the ball limit there is `R` (closed form, `g = b`), so the footprint at the limit
/// leaves face 0 for `R > 20`, and the largest bull of the shape d = 100, r = 10
/// that fits is half of it, d = 50, r = 5 (to the bisection's 2^-12).
#[test]
fn a_cutter_too_large_is_told_the_largest_that_fits() {
    let o = swarf(&[
        "dsm",
        "wedge-symmetric",
        "--tool",
        "bull:d=100,r=10",
        "--station",
        "50",
    ]);
    assert!(!o.status.success());
    let e = String::from_utf8_lossy(&o.stderr);
    let fit = e
        .split("the largest cutter of this shape that fits there: ")
        .nth(1)
        .unwrap_or_else(|| panic!("{e}"));
    let d: f64 = fit
        .trim_start_matches("bull:d=")
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!((d - 50.0).abs() <= 100.0 / 4096.0 + 1e-9, "{e}");
}

/// A ridge (two faces meeting at a convex edge, each on its own side) has no valley
/// for the tool: refused at the station with the reason.
#[test]
fn a_ridge_is_refused() {
    let dir = std::env::temp_dir().join(format!("swarf-dsm-ridge-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let roof = dir.join("roof.toml");
    // z = 20 + y / 2 for y in [-40, 0], z = 20 - y / 2 for y in [0, 40].
    std::fs::write(
        &roof,
        "name = \"roof\"\nunits = \"mm\"\n\
         [[patch]]\ndegree = [1, 1]\npoints = [[0, -40, 0], [0, 0, 20], [100, -40, 0], [100, 0, 20]]\n\
         [[patch]]\ndegree = [1, 1]\npoints = [[0, 0, 20], [0, 40, 0], [100, 0, 20], [100, 40, 0]]\n",
    )
    .unwrap();
    let o = swarf(&[
        "dsm",
        roof.to_str().unwrap(),
        "--tool",
        "bull:d=12,r=2",
        "--station",
        "50",
    ]);
    assert!(!o.status.success());
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(e.contains("station 50") && e.contains("ridge"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}
