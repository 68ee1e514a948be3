use super::*;
use crate::testutil::scratch_dir;
use proptest::prelude::*;
use swarf_geom::Point3;

/// A binary STL of `tris` with the given 80-byte header start.
fn binary(header: &[u8], tris: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut b = vec![0u8; 80];
    b[..header.len()].copy_from_slice(header);
    b.extend_from_slice(&(tris.len() as u32).to_le_bytes());
    for t in tris {
        b.extend_from_slice(&[0u8; 12]);
        for v in t {
            for c in v {
                b.extend_from_slice(&c.to_le_bytes());
            }
        }
        b.extend_from_slice(&[0u8; 2]);
    }
    b
}

/// The same triangles as ASCII STL text.
fn ascii(tris: &[[[f32; 3]; 3]]) -> String {
    let mut s = String::from("solid test part\n");
    for t in tris {
        s += "  facet normal 0 0 0\n    outer loop\n";
        for v in t {
            s += &format!("      vertex {:e} {:e} {:e}\n", v[0], v[1], v[2]);
        }
        s += "    endloop\n  endfacet\n";
    }
    s + "endsolid test part\n"
}

/// A strip of `n` triangles over a wavy grid row pair, f32-exact.
fn strip(n: usize) -> Vec<[[f32; 3]; 3]> {
    let p = |i: usize, j: usize| {
        [
            i as f32 * 0.5,
            j as f32 * 0.5,
            ((i * 7 + j * 3) % 5) as f32 * 0.25,
        ]
    };
    (0..n)
        .map(|k| {
            let i = k / 2;
            if k % 2 == 0 {
                [p(i, 0), p(i + 1, 0), p(i + 1, 1)]
            } else {
                [p(i, 0), p(i + 1, 1), p(i, 1)]
            }
        })
        .collect()
}

fn as_points(t: &[[f32; 3]; 3]) -> [Point3; 3] {
    t.map(|v| Point3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2])))
}

fn err(bytes: &[u8]) -> String {
    parse_stl(bytes, "part.stl").unwrap_err().to_string()
}

#[test]
fn binary_and_ascii_read_the_same_welded_mesh() {
    let tris = strip(12);
    let from_binary = parse_stl(&binary(b"solid but binary", &tris), "b.stl").unwrap();
    let from_ascii = parse_stl(ascii(&tris).as_bytes(), "a.stl").unwrap();
    assert_eq!(from_binary, from_ascii);
    assert_eq!(from_binary.len(), 12);
    assert_eq!(from_binary.vertices.len(), 14);
    for (i, t) in tris.iter().enumerate() {
        assert_eq!(from_binary.triangle(i), as_points(t));
    }
}

/// Float32 coordinates are read as the exact f64 of the stored bits, not through the
/// shortest decimal of the float (issue 14: a stored -0.319627195596695 read as
/// -0.3196272 moved drop heights by up to 1.6e-4 mm). (ASCII coordinates are the
/// decimals as written, read as f64.)
#[test]
fn float32_coordinates_are_read_exactly() {
    let c = [
        -0.319_627_2_f32,
        1.0e-7,
        123.456_79,
        -98.765_43,
        0.1,
        7.3e-3,
    ];
    let tris = [[[c[0], c[1], c[2]], [c[3], c[4], c[5]], [c[2], c[0], c[4]]]];
    let exact = |v: f32| f64::from(v);
    assert!((exact(c[0]) - -0.319_627_195_596_695).abs() < 1e-16);
    let mesh = parse_stl(&binary(b"", &tris), "f32.stl").unwrap();
    let t = mesh.triangle(0);
    for (k, v) in tris[0].iter().enumerate() {
        assert_eq!(
            [t[k].x, t[k].y, t[k].z].map(f64::to_bits),
            v.map(|x| exact(x).to_bits())
        );
    }
}

#[test]
fn write_then_read_round_trips() {
    let dir = scratch_dir("stl");
    let mesh = TriMesh::from_triangles(&strip(100_000).iter().map(as_points).collect::<Vec<_>>());
    let path = dir.join("round.stl");
    let mut out = OutputSet::new();
    write_stl(&mut out, &path, &mesh, "round trip").unwrap();
    out.commit().unwrap();
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(bytes.len(), 84 + 50 * 100_000);
    assert!(bytes.starts_with(b"binary STL by swarf: round trip"));
    assert_eq!(read_stl(&path).unwrap(), mesh);
    let normal = f32::from_le_bytes(bytes[84 + 8..84 + 12].try_into().unwrap());
    assert_eq!(f64::from(normal), mesh.normal(0).unwrap().z as f32 as f64);
    let bad = TriMesh {
        vertices: vec![Point3::origin()],
        triangles: vec![[0, 0, 1]],
    };
    let e = write_stl(&mut OutputSet::new(), &path, &bad, "bad")
        .unwrap_err()
        .to_string();
    assert!(
        e.ends_with("round.stl: cannot write triangle 0: vertex index out of range"),
        "{e}"
    );
    assert_eq!(read_stl(&path).unwrap(), mesh);
}

#[test]
fn binary_size_errors_give_byte_offsets() {
    let full = binary(b"", &strip(12));
    assert_eq!(
        err(&full[..300]),
        "part.stl: byte 284: file ends inside triangle 5 of 12 (expected 684 bytes for a binary STL with 12 triangles, found 300)"
    );
    let mut long = full.clone();
    long.extend_from_slice(&[0u8; 16]);
    assert_eq!(
        err(&long),
        "part.stl: byte 684: 16 bytes after the last of 12 triangles (expected 684 bytes for a binary STL with 12 triangles, found 700)"
    );
    assert_eq!(
        err(&full[..50]),
        "part.stl: byte 50: file ends inside the 84-byte header of a binary STL (found 50 bytes), and it does not begin with `solid` as an ASCII STL does"
    );
    assert_eq!(
        err(b""),
        "part.stl: empty file; expected an ASCII STL (`solid ...`) or a binary STL"
    );
    let solid = binary(b"solid exported by CAD", &strip(12));
    let e = err(&solid[..300]);
    assert!(
        e.starts_with("part.stl: byte 284: file ends inside triangle 5 of 12 (expected 684 bytes"),
        "{e}"
    );
    assert!(
        e.contains("; it begins with `solid` but is not ASCII STL either (line "),
        "{e}"
    );
}

#[test]
fn ascii_errors_give_lines() {
    let text = ascii(&strip(3));
    let bad = |from: &str, to: &str| err(text.replacen(from, to, 1).as_bytes());
    assert_eq!(
        bad("outer loop", "outer lop"),
        "part.stl: line 3: expected `loop`, found `lop`"
    );
    assert_eq!(
        bad("vertex 0e0", "vertex zero"),
        "part.stl: line 4: expected a number (x), found `zero`"
    );
    assert_eq!(
        bad("facet normal", "facets normal"),
        "part.stl: line 2: expected `facet` or `endsolid`, found `facets`"
    );
    let four = text.replacen("    endloop", "      vertex 1 2 3\n    endloop", 1);
    assert_eq!(
        err(four.as_bytes()),
        "part.stl: line 7: expected `endloop` (facets are triangles: three vertices), found `vertex`"
    );
    let cut = &text[..text.find("vertex 5e-1").unwrap() + 12];
    assert_eq!(
        err(cut.as_bytes()),
        "part.stl: line 5: file ends inside facet 1; expected a number (y)"
    );
    let open = text.replace("endsolid test part\n", "");
    assert_eq!(
        err(open.as_bytes()),
        "part.stl: line 22: file ends; expected `facet` or `endsolid`"
    );
    assert_eq!(
        err(format!("{text}garbage\n").as_bytes()),
        "part.stl: line 24: expected `solid` or the end of the file, found `garbage`"
    );
}

#[test]
fn ascii_variants_read() {
    let text = ascii(&strip(2));
    let upper = text
        .replace("vertex", "VERTEX")
        .replace("facet normal 0 0 0", "FACET");
    let two = format!("{text}{}", ascii(&strip(4)));
    assert_eq!(
        parse_stl(upper.as_bytes(), "u.stl").unwrap(),
        parse_stl(text.as_bytes(), "t.stl").unwrap()
    );
    let m = parse_stl(two.as_bytes(), "two.stl").unwrap();
    assert_eq!((m.len(), m.vertices.len()), (6, 6));
    let one_line = text.replace('\n', " ");
    assert_eq!(parse_stl(one_line.as_bytes(), "l.stl").unwrap().len(), 2);
    assert!(
        parse_stl(b"solid empty\nendsolid empty\n", "e.stl")
            .unwrap()
            .is_empty()
    );
}

#[test]
fn nan_vertices_are_read_and_reported() {
    let mut tris = strip(3);
    tris[1][2][0] = f32::NAN;
    let m = parse_stl(&binary(b"", &tris), "n.stl").unwrap();
    assert_eq!(m.validate().non_finite, vec![1]);
    let text = ascii(&strip(2)).replacen("vertex 5e-1", "vertex nan", 1);
    assert_eq!(
        parse_stl(text.as_bytes(), "n.stl")
            .unwrap()
            .validate()
            .non_finite,
        vec![0]
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        if let Err(e) = parse_stl(&bytes, "r.stl") {
            prop_assert!(e.to_string().starts_with("r.stl"));
        }
    }

    #[test]
    fn random_binary_records_read(values in prop::collection::vec(any::<f32>(), 9..90), header in "[a-z ]{0,20}") {
        let tris: Vec<[[f32; 3]; 3]> = values
            .chunks_exact(9)
            .map(|c| [[c[0], c[1], c[2]], [c[3], c[4], c[5]], [c[6], c[7], c[8]]])
            .collect();
        let m = parse_stl(&binary(header.as_bytes(), &tris), "r.stl").unwrap();
        prop_assert_eq!(m.len(), tris.len());
        for (i, t) in tris.iter().enumerate() {
            for (p, v) in m.triangle(i).iter().zip(t) {
                for k in 0..3 {
                    let (a, b) = (p[k], f64::from(v[k]));
                    prop_assert!(a == b || (a.is_nan() && b.is_nan()));
                }
            }
        }
    }

    #[test]
    fn mutated_ascii_never_panics(at in 0usize..400, len in 0usize..8, insert in "[ -~\n]{0,10}") {
        let base = ascii(&strip(3));
        let start = at.min(base.len());
        let end = (start + len).min(base.len());
        let text = format!("{}{}{}", &base[..start], insert, &base[end..]);
        if let Err(e) = parse_stl(text.as_bytes(), "m.stl") {
            prop_assert!(e.to_string().starts_with("m.stl"));
        }
    }
}
