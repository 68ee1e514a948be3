//! Hand-written files: units, errors, cyclic references.

use super::*;

const HEAD: &str = "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\n";
const TAIL: &str = "ENDSEC;\nEND-ISO-10303-21;\n";

/// A square plane face of side 10 (file units), hole-free, with unit entity `unit`.
fn square(unit: &str) -> String {
    format!(
        "{HEAD}#1 = CLOSED_SHELL('',(#2));
#2 = ADVANCED_FACE('top',(#3),#30,.T.);
#3 = FACE_OUTER_BOUND('',#4,.T.);
#4 = EDGE_LOOP('',(#5,#6,#7,#8));
#5 = ORIENTED_EDGE('',*,*,#11,.T.);
#6 = ORIENTED_EDGE('',*,*,#12,.T.);
#7 = ORIENTED_EDGE('',*,*,#13,.T.);
#8 = ORIENTED_EDGE('',*,*,#14,.F.);
#11 = EDGE_CURVE('',#21,#22,#40,.T.);
#12 = EDGE_CURVE('',#22,#23,#40,.T.);
#13 = EDGE_CURVE('',#23,#24,#40,.T.);
#14 = EDGE_CURVE('',#21,#24,#40,.T.);
#21 = VERTEX_POINT('',#51);
#22 = VERTEX_POINT('',#52);
#23 = VERTEX_POINT('',#53);
#24 = VERTEX_POINT('',#54);
#30 = PLANE('',#31);
#31 = AXIS2_PLACEMENT_3D('',#50,#32,#33);
#32 = DIRECTION('',(0.,0.,1.));
#33 = DIRECTION('',(1.,0.,0.));
#40 = LINE('',#50,#41);
#41 = VECTOR('',#32,1.);
#50 = CARTESIAN_POINT('',(0.,0.,0.));
#51 = CARTESIAN_POINT('',(0.,0.,0.));
#52 = CARTESIAN_POINT('',(10.,0.,0.));
#53 = CARTESIAN_POINT('',(10.,10.,0.));
#54 = CARTESIAN_POINT('',(0.,10.,0.));
#60 = ( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#61,#62)) REPRESENTATION_CONTEXT('',''));
{unit}
#62 = ( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) );
{TAIL}"
    )
}

const MM: &str = "#61 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );";
const INCH: &str = "#61 = ( CONVERSION_BASED_UNIT('INCH',#63) LENGTH_UNIT() NAMED_UNIT(#64) );
#63 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#65);
#64 = DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.);
#65 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );";

fn read(text: &str) -> Result<CadPart, IoError> {
    parse_step(text, "t.step", &CadOptions::default())
}

#[test]
fn a_plane_square_in_mm_and_in_inch() {
    let p = read(&square(MM)).unwrap();
    assert_eq!(p.unit, "mm");
    assert_eq!(p.part.patches.len(), 1);
    assert_eq!(p.part.face_name(0), Some("top"));
    let pr = p.part.patches[0].project(&swarf_geom::Point3::new(5.0, 5.0, 0.0));
    assert!(pr.distance < 1e-12 && p.part.face_contains(0, pr.u, pr.v));
    let pr = p.part.patches[0].project(&swarf_geom::Point3::new(10.1, 5.0, 0.0));
    assert!(pr.distance < 1e-12 && !p.part.face_contains(0, pr.u, pr.v));
    let q = read(&square(INCH)).unwrap();
    assert_eq!(q.unit, "inch");
    let b = q.part.control_box();
    assert!((b.size().x - 254.0 * 1.04).abs() < 1.0, "{:?}", b.size());
    let pr = q.part.patches[0].project(&swarf_geom::Point3::new(250.0, 250.0, 0.0));
    assert!(q.part.face_contains(0, pr.u, pr.v));
}

#[test]
fn bad_input_names_file_line_entity_and_argument() {
    let e = |t: &str| read(t).unwrap_err().to_string();
    assert!(e("solid x").contains("not a STEP file"));
    let s = square(MM);
    let m = e(&s.replace("#53 = CARTESIAN_POINT('',(10.,10.,0.));", ""));
    assert!(m.contains("#53") && m.contains("not define"), "{m}");
    let m = e(&s.replace("#30 = PLANE('',#31);", "#30 = PLANE('',5.);"));
    assert!(
        m.contains("line 22") && m.contains("#30 PLANE") && m.contains("argument 2"),
        "{m}"
    );
    let m = e(&s.replace("#13 = EDGE_CURVE('',#23,", "#13 = EDGE_CURVE('',#21,"));
    assert!(m.contains("open loop"), "{m}");
    let m = e(&s.replace(
        "PLANE('',#31)",
        "DEGENERATE_TOROIDAL_SURFACE('',#31,1.,2.,.T.)",
    ));
    assert!(
        m.contains("no faces") && m.contains("#30 DEGENERATE_TOROIDAL_SURFACE"),
        "{m}"
    );
    let refuse = CadOptions {
        unsupported: Unsupported::Refuse,
        ..CadOptions::default()
    };
    let m = parse_step(
        &s.replace("PLANE('',#31)", "FOO('',#31)"),
        "t.step",
        &refuse,
    )
    .unwrap_err()
    .to_string();
    assert!(
        m.starts_with("t.step: line 22: #30 FOO: unsupported"),
        "{m}"
    );
    // Cyclic references are walked by type: an error, no hang.
    let m = e(&s.replace(
        "#31 = AXIS2_PLACEMENT_3D('',#50,#32,#33);",
        "#31 = AXIS2_PLACEMENT_3D('',#31,#32,#33);",
    ));
    assert!(m.contains("#31") && m.contains("CARTESIAN_POINT"), "{m}");
    let m = e(&s.replace(
        "#2 = ADVANCED_FACE('top',(#3),#30,.T.);",
        "#2 = ADVANCED_FACE('top',(#2),#30,.T.);",
    ));
    assert!(m.contains("FACE_OUTER_BOUND"), "{m}");
}

#[test]
fn an_unsupported_edge_curve_skips_its_face_or_refuses() {
    let s = square(MM).replace("#40 = LINE('',#50,#41);", "#40 = POLYLINE('',(#51,#52));");
    let m = read(&s).unwrap_err().to_string();
    assert!(
        m.contains("no faces") && m.contains("#40 POLYLINE: unsupported curve type"),
        "{m}"
    );
    let refuse = CadOptions {
        unsupported: Unsupported::Refuse,
        ..CadOptions::default()
    };
    let m = parse_step(&s, "t.step", &refuse).unwrap_err().to_string();
    assert!(
        m.starts_with("t.step: line 26: #40 POLYLINE: unsupported"),
        "{m}"
    );
}

#[test]
fn a_cone_semi_angle_in_degrees() {
    let deg = "#62 = ( CONVERSION_BASED_UNIT('DEGREE',#66) NAMED_UNIT(#64) PLANE_ANGLE_UNIT() );
#64 = DIMENSIONAL_EXPONENTS(0.,0.,0.,0.,0.,0.,0.);
#66 = PLANE_ANGLE_MEASURE_WITH_UNIT(PLANE_ANGLE_MEASURE(0.0174532925199433),#67);
#67 = ( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) );";
    // The square's plane swapped for a 45-degree cone whose apex is far away: read
    // in degrees the face exists; read as 45 radians it is refused.
    let s = square(MM)
        .replace(
            "#62 = ( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) );",
            deg,
        )
        .replace(
            "#30 = PLANE('',#31);",
            "#30 = CONICAL_SURFACE('',#31,100.,45.);",
        );
    let g = graph::Graph {
        ex: &parser::parse(&s).unwrap(),
        file: "t.step",
    };
    let u = units::units(&g).unwrap();
    assert!((u.rad - std::f64::consts::PI / 180.0).abs() < 1e-15);
    let rad = square(MM).replace(
        "#30 = PLANE('',#31);",
        "#30 = CONICAL_SURFACE('',#31,100.,45.);",
    );
    let m = read(&rad).unwrap_err().to_string();
    assert!(
        m.contains("#30 CONICAL_SURFACE") && m.contains("semi-angle"),
        "{m}"
    );
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]
    #[test]
    fn damaged_files_never_panic(cut in 0usize..2000, at in 0usize..2000, byte in 32u8..127) {
        let s = square(MM);
        let mut b = s.into_bytes();
        let i = at % b.len();
        b[i] = byte;
        b.truncate(b.len() - cut % b.len());
        let t = String::from_utf8_lossy(&b);
        let _ = read(&t);
    }
}

#[test]
fn a_crossing_loop_and_a_bad_chord_are_refused() {
    // Swapping two corners makes the square's loop a bow tie.
    let s = square(MM)
        .replace("(10.,10.,0.)", "(9.,9.,9.)")
        .replace("(0.,10.,0.)", "(10.,10.,0.)")
        .replace("(9.,9.,9.)", "(0.,10.,0.)");
    let m = read(&s).unwrap_err().to_string();
    assert!(
        m.starts_with("t.step: line 7: #2 ADVANCED_FACE: trimming loops") && m.contains("cross"),
        "{m}"
    );
    let bad = CadOptions {
        trim_chord: 0.0,
        ..CadOptions::default()
    };
    let m = parse_step(&square(MM), "t.step", &bad)
        .unwrap_err()
        .to_string();
    assert!(m.contains("trim_chord"), "{m}");
}

#[test]
fn a_circle_of_zero_radius_is_named() {
    let s = square(MM).replace("#40 = LINE('',#50,#41);", "#40 = CIRCLE('',#31,0.);");
    let m = read(&s).unwrap_err().to_string();
    assert!(
        m.contains("#40 CIRCLE: argument 3: expected a positive radius, found 0"),
        "{m}"
    );
}
