//! Unit tests of the IGES reader on small files written here: a bilinear 128 in
//! inches trimmed by a 144 to a square with a square hole (outer loop a degree-1
//! 126 in `(u, v)`, hole a 102 of four 110 lines), checked against the closed form
//! `S(u, v) = 25.4 (2u, v, u v)` mm; then one broken file per error.

use super::*;
use swarf_geom::Point3;

/// One entity to write: type, parameters (after the type, with the `;`),
/// transformation matrix DE pointer, subordinate status digits, label.
struct Ent<'a>(i64, &'a str, usize, &'a str, &'a str);

/// A fixed-form IGES file of `ents` (DE pointers 1, 3, 5...), unit flag `unit`.
fn iges(ents: &[Ent], unit: &str) -> String {
    let mut s = format!("{:<72}S{:>7}\n", "swarf test", 1);
    let g = format!(
        "1H,,1H;,4Htest,9Hplate.igs,5Hswarf,3H1.0,32,38,6,308,15,4Htest,1.,{unit},1,0.01,\
         15H20260101.000000,1E-07,100.,,,11,0,;"
    );
    let gl: Vec<String> = g
        .as_bytes()
        .chunks(72)
        .map(|c| String::from_utf8_lossy(c).into_owned())
        .collect();
    for (k, l) in gl.iter().enumerate() {
        s += &format!("{l:<72}G{:>7}\n", k + 1);
    }
    let mut d = String::new();
    let mut p = String::new();
    let mut pline = 1;
    for (k, e) in ents.iter().enumerate() {
        let de = 2 * k + 1;
        let text = format!("{},{}", e.0, e.1);
        let chunks: Vec<String> = text
            .as_bytes()
            .chunks(64)
            .map(|c| String::from_utf8_lossy(c).into_owned())
            .collect();
        let status = format!("00{}0000", e.3);
        let form = if e.0 == 406 { 15 } else { 0 };
        d += &format!(
            "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}D{:>7}\n",
            e.0, pline, 0, 0, 0, 0, e.2, 0, status, de
        );
        d += &format!(
            "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}D{:>7}\n",
            e.0,
            0,
            0,
            chunks.len(),
            form,
            "",
            "",
            e.4,
            0,
            de + 1
        );
        for c in &chunks {
            p += &format!("{c:<64}{de:>8}P{pline:>7}\n");
            pline += 1;
        }
    }
    s += &d;
    s += &p;
    s += &format!(
        "S{:>7}G{:>7}D{:>7}P{:>7}{:>40}T{:>7}\n",
        1,
        gl.len(),
        2 * ents.len(),
        pline - 1,
        "",
        1
    );
    s
}

const BILINEAR: &str = "1,1,1,1,0,0,1,0,0,0.,0.,1.,1.,0.,0.,1.,1.,1.,1.,1.,1.,0.,0.,0.,2.,0.,0.,\
                        0.,1.,0.,2.,1.,1.,0.,1.,0.,1.;";
const OUTER: &str = "4,1,1,0,1,0,0.,0.,1.,2.,3.,4.,4.,1.,1.,1.,1.,1.,0.1,0.1,0.,0.9,0.1,0.,\
                     0.9,0.9,0.,0.1,0.9,0.,0.1,0.1,0.,0.,4.,0.,0.,1.;";

/// The test plate: 128 (DE 1), 126 outer (3), 142 outer (5), 110 x 4 (7-13), 102 (15),
/// 142 hole (17), 144 (19), then `extra`.
fn plate(outer: &str, extra: &[Ent]) -> String {
    let mut ents = vec![
        Ent(128, BILINEAR, 0, "01", ""),
        Ent(126, outer, 0, "01", ""),
        Ent(142, "0,1,3,0,1;", 0, "01", ""),
        Ent(110, "0.4,0.4,0.,0.6,0.4,0.;", 0, "01", ""),
        Ent(110, "0.6,0.4,0.,0.6,0.6,0.;", 0, "01", ""),
        Ent(110, "0.6,0.6,0.,0.4,0.6,0.;", 0, "01", ""),
        Ent(110, "0.4,0.6,0.,0.4,0.4,0.D0;", 0, "01", ""),
        Ent(102, "4,7,9,11,13;", 0, "01", ""),
        Ent(142, "0,1,15,0,1;", 0, "01", ""),
        Ent(144, "1,1,1,5,17;", 0, "00", "TOPFACE"),
    ];
    ents.extend(extra.iter().map(|e| Ent(e.0, e.1, e.2, e.3, e.4)));
    iges(&ents, "1")
}

fn read(text: &str, opts: &CadOptions) -> Result<CadPart, IoError> {
    parse_iges(text, "plate.igs", opts)
}

#[test]
fn inch_plate_with_hole() {
    let cad = read(&plate(OUTER, &[]), &CadOptions::default()).unwrap();
    assert_eq!(cad.unit, "inch");
    assert!(cad.warnings.is_empty());
    let part = &cad.part;
    assert_eq!(part.patches.len(), 1);
    assert_eq!(part.face_name(0), Some("TOPFACE"));
    assert_eq!(
        part.faces[0].surface.as_deref(),
        Some("DE 1 type 128 (rational B-spline surface)")
    );
    for (u, v) in [(0.3, 0.7), (0.0, 0.0), (1.0, 0.25), (0.55, 0.95)] {
        let want = Point3::new(2.0 * u, v, u * v) * 25.4;
        assert!(
            (part.patches[0].eval(u, v) - want).norm() < 1e-12,
            "({u}, {v})"
        );
    }
    assert!(part.face_contains(0, 0.2, 0.2) && part.face_contains(0, 0.7, 0.5));
    assert!(!part.face_contains(0, 0.5, 0.5), "the hole");
    assert!(!part.face_contains(0, 0.05, 0.5) && !part.face_contains(0, 0.5, 0.95));
    let t = part.trim(0).unwrap();
    assert_eq!(t.loops().len(), 2);
}

/// A bare 128 declaring a parameter range smaller than its knots is trimmed to it.
#[test]
fn declared_range_trims_a_bare_surface() {
    let smaller = BILINEAR.replace("0.,1.,0.,1.;", "0.2,1.,0.,0.5;");
    let cad = read(
        &iges(&[Ent(128, &smaller, 0, "00", "")], "2"),
        &CadOptions::default(),
    )
    .unwrap();
    let part = &cad.part;
    assert!(part.face_contains(0, 0.5, 0.3));
    assert!(!part.face_contains(0, 0.1, 0.3) && !part.face_contains(0, 0.5, 0.7));
}

/// Delimiters from the Global section: `/` between parameters, `#` ending records.
#[test]
fn custom_delimiters() {
    let text = plate(OUTER, &[]).replace(',', "/").replace(';', "#");
    assert!(text.contains("1H//1H#/4Htest/"));
    let cad = read(&text, &CadOptions::default()).unwrap();
    assert!(cad.part.face_contains(0, 0.2, 0.2) && !cad.part.face_contains(0, 0.5, 0.5));
}

#[test]
fn transform_and_bare_surface() {
    let ents = [
        Ent(128, BILINEAR, 3, "00", "SKIN"),
        Ent(124, "1.,0.,0.,10.,0.,1.,0.,0.,0.,0.,1.,-1.;", 0, "01", ""),
    ];
    let cad = read(&iges(&ents, "2"), &CadOptions::default()).unwrap();
    assert_eq!(cad.unit, "mm");
    let p = &cad.part.patches[0];
    assert!((p.eval(0.5, 0.5) - Point3::new(11.0, 0.5, -0.75)).norm() < 1e-12);
    assert_eq!(cad.part.face_name(0), Some("SKIN"));
    assert!(cad.part.trim(0).is_none());
}

/// A writer that marks every entity independent: the trimmed 128 is not read
/// again as a whole face. An unsupported surface under a 144 names both.
#[test]
fn all_independent_and_unsupported_surface() {
    let text = plate(OUTER, &[]).replace("000010000D", "000000000D");
    let cad = read(&text, &CadOptions::default()).unwrap();
    assert_eq!(cad.part.patches.len(), 1);
    let text = plate(
        OUTER,
        &[
            Ent(120, "1,3,0.,6.28;", 0, "01", ""),
            Ent(144, "21,0,0,0;", 0, "00", ""),
        ],
    );
    let cad = read(&text, &CadOptions::default()).unwrap();
    assert_eq!(cad.part.patches.len(), 1);
    assert_eq!(
        cad.warnings,
        vec![
            "DE 23 type 144: surface DE 21 of type 120 (expected 128 or a bounded 108)".to_string()
        ]
    );
}

/// A hole whose parameter-space curve is unsupported (104 conic) but whose
/// model-space curve (four 110 lines in inches along the bilinear patch's rulings)
/// is given: the model-space curve is projected.
#[test]
fn model_space_fallback() {
    let extra = [
        Ent(104, "1,0,1,0,0,0,-1,0.,1.,0.,1.,0.;", 0, "01", ""),
        Ent(102, "4,25,27,29,31;", 0, "01", ""),
        Ent(110, "0.8,0.4,0.16,1.2,0.4,0.24;", 0, "01", ""),
        Ent(110, "1.2,0.4,0.24,1.2,0.6,0.36;", 0, "01", ""),
        Ent(110, "1.2,0.6,0.36,0.8,0.6,0.24;", 0, "01", ""),
        Ent(110, "0.8,0.6,0.24,0.8,0.4,0.16;", 0, "01", ""),
    ];
    let text = plate(OUTER, &extra).replace("142,0,1,15,0,1; ", "142,0,1,21,23,1;");
    let cad = read(&text, &CadOptions::default()).unwrap();
    let part = &cad.part;
    assert!(!part.face_contains(0, 0.5, 0.5) && !part.face_contains(0, 0.41, 0.59));
    assert!(part.face_contains(0, 0.39, 0.5) && part.face_contains(0, 0.5, 0.61));
    let hole = &part.trim(0).unwrap().loops()[1];
    for p in hole {
        let on_edge = [p[0] - 0.4, p[0] - 0.6, p[1] - 0.4, p[1] - 0.6]
            .iter()
            .any(|d| d.abs() < 1e-9);
        assert!(on_edge, "{p:?}");
    }
}

/// An unsupported trimming curve skips its face, naming the curve and the face.
#[test]
fn unsupported_curve_skips_the_face() {
    let text = plate(
        OUTER,
        &[Ent(104, "1,0,1,0,0,0,-1,0.,1.,0.,1.,0.;", 0, "01", "")],
    )
    .replace("142,0,1,15,0,1;", "142,0,1,21,0,1;");
    let m = message(&text, &CadOptions::default());
    assert!(
        m.ends_with(
            "no faces: expected at least one supported entity 144 (trimmed surface) or 128 \
             (B-spline surface); skipped: DE 21 type 104: curve type 104 in a trimming loop \
             (expected 100, 102, 110 or 126); face DE 19 skipped"
        ),
        "{m}"
    );
}

#[test]
fn names_from_406_properties() {
    let text = plate(OUTER, &[Ent(406, "1,8HTop face;", 0, "01", "")])
        .replace("144,1,1,1,5,17;       ", "144,1,1,1,5,17,0,1,21;");
    let cad = read(&text, &CadOptions::default()).unwrap();
    assert_eq!(cad.part.face_name(0), Some("Top face"));
}

fn message(text: &str, opts: &CadOptions) -> String {
    read(text, opts).unwrap_err().to_string()
}

#[test]
fn not_iges() {
    let m = message("\nsolid cube\nendsolid\n", &CadOptions::default());
    assert_eq!(
        m,
        "plate.igs: line 2: not an IGES file: expected 80-column records with S, G, D, P or T \
         in column 73 (fixed ASCII form)"
    );
    let cut: String = plate(OUTER, &[])
        .lines()
        .filter(|l| !l.contains('D') || l.len() < 73 || &l[72..73] != "D")
        .map(|l| format!("{l}\n"))
        .collect();
    assert!(message(&cut, &CadOptions::default()).contains("expected Global (G), Directory (D)"));
}

#[test]
fn unsupported_entity_warns_or_refuses() {
    let extra = [Ent(120, "1,3,0.,6.28;", 0, "00", "")];
    let text = plate(OUTER, &extra);
    let cad = read(&text, &CadOptions::default()).unwrap();
    assert_eq!(cad.part.patches.len(), 1);
    assert_eq!(cad.warnings.len(), 1);
    assert!(
        cad.warnings[0].starts_with("DE 21 type 120: not a supported face entity"),
        "{:?}",
        cad.warnings
    );
    let refuse = CadOptions {
        unsupported: Unsupported::Refuse,
        ..CadOptions::default()
    };
    let m = message(&text, &refuse);
    assert!(
        m.starts_with("plate.igs: line 38: DE 21 type 120: unsupported: not a supported face"),
        "{m}"
    );
}

#[test]
fn open_and_crossing_loops() {
    let open = OUTER.replace("0.1,0.1,0.,0.,4.", "0.2,0.1,0.,0.,4.");
    let m = message(&plate(&open, &[]), &CadOptions::default());
    assert!(
        m.contains("DE 5 type 142: open trimming loop: its end is 1.000e-1"),
        "{m}"
    );
    let bow = OUTER.replace("0.9,0.9,0.,0.1,0.9", "0.1,0.9,0.,0.9,0.9");
    let m = message(&plate(&bow, &[]), &CadOptions::default());
    assert!(
        m.contains("DE 19 type 144: trimming loops (loop[0] = DE 5, loop[1] = DE 17): loop[0]"),
        "{m}"
    );
    assert!(m.contains("cross"), "{m}");
}

#[test]
fn bad_values_and_pointers() {
    let opts = CadOptions::default();
    let text = plate(OUTER, &[]);
    let m = message(
        &text.replace("0.,0.,1.,1.,0.,0.,1.,1.,1.", "0.,0.,1.,1Q,0.,0.,1.,1.,1."),
        &opts,
    );
    assert!(
        m.contains("DE 1 type 128: parameter 13: expected a finite number, found \"1Q\""),
        "{m}"
    );
    let m = message(&text.replace("144,1,1,1,5,17;", "144,1,1,1,5,99;"), &opts);
    assert!(
        m.contains(
            "DE 19 type 144: parameter 5: expected a DE pointer (odd, 1 to 20) or 0, found 99"
        ),
        "{m}"
    );
    let m = message(&text.replace("102,4,7,9,11,13;", "102,4,7,9,11,15;"), &opts);
    assert!(
        m.contains("DE 15 type 102: piece 4 is DE 15, which contains it: expected no cycle"),
        "{m}"
    );
    let m = message(
        &text.replace("0.,0.,1.,1.,0.,0.,1.,1.,1.", "0.,1.,0.,1.,0.,0.,1.,1.,1."),
        &opts,
    );
    assert!(
        m.contains(
            "DE 1 type 128: rational B-spline surface: knots_u: expected finite, non-decreasing"
        ),
        "{m}"
    );
    let m = message(
        &text.replace("0.,0.,1.,1.,0.,0.,1.,1.,1.", "0,0,1D999,1,0.,0.,1.,1.,1."),
        &opts,
    );
    assert!(
        m.contains("DE 1 type 128: parameter 12: expected a finite number, found \"1D999\""),
        "{m}"
    );
    let only_line = iges(&[Ent(110, "0.,0.,0.,1.,0.,0.;", 0, "00", "")], "2");
    assert_eq!(
        message(&only_line, &opts),
        "plate.igs: no faces: expected at least one supported entity 144 (trimmed surface) or 128 (B-spline surface)"
    );
    let t = text.replace("D     20P", "D     22P");
    let m = message(&t, &opts);
    assert!(
        m.contains("terminate record: D count \"D     22\", but the file has 20 D records"),
        "{m}"
    );
}

/// Truncated and mutated files (each byte on a stride replaced by characters that
/// matter to the format) never panic.
#[test]
fn truncations_do_not_panic() {
    let text = plate(OUTER, &[]);
    for cut in (0..text.len()).step_by(37) {
        let _ = read(&text[..cut], &CadOptions::default());
    }
    let mangled: String = text
        .chars()
        .map(|c| if c == '1' { '9' } else { c })
        .collect();
    let _ = read(&mangled, &CadOptions::default());
    let bytes = text.as_bytes();
    for at in (0..bytes.len()).step_by(5) {
        for c in [b',', b';', b'H', b'9', b'-', b' ', b'D', b'.', b'0'] {
            let mut b = bytes.to_vec();
            b[at] = c;
            let _ = read(&String::from_utf8_lossy(&b), &CadOptions::default());
        }
    }
}
