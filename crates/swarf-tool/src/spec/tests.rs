//! Spec parsing, canonical writing and every error.

use crate::cutter::Cutter;
use crate::error::ToolError;

fn err(spec: &str) -> ToolError {
    match spec.parse::<Cutter>() {
        Ok(c) => panic!("`{spec}` parsed as {c:?}"),
        Err(e) => e,
    }
}

#[test]
fn named_shapes_parse_to_kernel_units() {
    let c: Cutter = "ball:d=8".parse().unwrap();
    assert_eq!(
        c,
        Cutter::Ball {
            radius: 4.0,
            length: 32.0
        }
    );
    let c: Cutter = "flat:d=6".parse().unwrap();
    assert_eq!(
        c,
        Cutter::Flat {
            radius: 3.0,
            length: 24.0
        }
    );
    let c: Cutter = " Bull : D = 10 , R = 2 ".parse().unwrap();
    assert_eq!(
        c,
        Cutter::Bull {
            radius: 5.0,
            corner: 2.0,
            length: 40.0
        }
    );
    let c: Cutter = "cone:d=10,angle=90".parse().unwrap();
    let Cutter::Cone {
        radius,
        half_angle,
        length,
    } = c
    else {
        panic!("{c:?}")
    };
    assert_eq!((radius, length), (5.0, 40.0));
    assert!((half_angle - std::f64::consts::FRAC_PI_4).abs() < 1e-15);
    let c: Cutter = "taperball:d=6,angle=10,tip=1".parse().unwrap();
    let Cutter::TaperBall {
        tip_radius,
        half_angle,
        radius,
        length,
    } = c
    else {
        panic!()
    };
    assert_eq!((tip_radius, radius), (1.0, 3.0));
    assert!((half_angle - 10f64.to_radians()).abs() < 1e-15);
    // The flutes end where the taper reaches d/2.
    let (s, co) = half_angle.sin_cos();
    assert!((length - ((1.0 - s) + (3.0 - co) / half_angle.tan())).abs() < 1e-12);
    assert!((c.radius() - 3.0).abs() < 1e-12);
    let c: Cutter = "apt:d=10,r=2,alpha=0,beta=0,h=30".parse().unwrap();
    assert_eq!(c.to_apt().e, 3.0);
    assert_eq!(c.length(), 30.0);
}

#[test]
fn default_lengths_cover_the_profile() {
    // A narrow cone reaches full radius above 4 d.
    let c: Cutter = "cone:d=10,angle=10".parse().unwrap();
    assert!((c.length() - 5.0 / 5f64.to_radians().tan()).abs() < 1e-12);
    let c: Cutter = "apt:d=10,r=1,alpha=0,beta=-10".parse().unwrap();
    assert!(c.length() < 40.0 && (c.profile().top().rho).abs() < 1e-9);
}

#[test]
fn display_is_canonical_and_reads_back() {
    for (spec, canonical) in [
        ("ball:d=8", "ball:d=8"),
        ("BALL:d=8,length=32", "ball:d=8"),
        ("ball:d=8,length=20", "ball:d=8,length=20"),
        ("flat:d=6", "flat:d=6"),
        ("flat:d=0.3,length=1.1", "flat:d=0.3,length=1.1"),
        ("bull:r=2,d=10", "bull:d=10,r=2"),
        ("cone:d=10,angle=90", "cone:d=10,angle=90"),
        (
            "cone:d=3.175,angle=60,length=12.5",
            "cone:d=3.175,angle=60,length=12.5",
        ),
        (
            "taperball:d=6,angle=10,tip=1",
            "taperball:d=6,angle=10,tip=1",
        ),
        (
            "taperball:d=6,angle=3.5,tip=0.25,length=9",
            "taperball:d=6,angle=3.5,tip=0.25,length=9",
        ),
        (
            "apt:d=10,r=2,e=3,f=2,alpha=0,beta=0,h=30",
            "apt:d=10,r=2,e=3,f=2,alpha=0,beta=0,h=30",
        ),
    ] {
        let c: Cutter = spec.parse().unwrap();
        assert_eq!(c.to_string(), canonical, "{spec}");
        assert_eq!(canonical.parse::<Cutter>().unwrap(), c, "{spec}");
    }
    for spec in [
        "apt:d=10,r=1.5,alpha=10,beta=5",
        "apt:d=12,r=3,alpha=30,beta=-20,length=15",
    ] {
        let c: Cutter = spec.parse().unwrap();
        let text = c.to_string();
        assert!(text.contains("alpha=") && text.contains(",e=") && text.contains(",h="));
        assert_eq!(text.parse::<Cutter>().unwrap(), c, "{text}");
    }
}

#[test]
fn structural_errors() {
    assert_eq!(err(""), ToolError::Empty);
    assert_eq!(err("  "), ToolError::Empty);
    let e = err("drill:d=5");
    assert!(
        e.to_string()
            .contains("`drill`: expected one of flat, ball, bull, cone, taperball, apt")
    );
    assert!(matches!(err("ball"), ToolError::Missing { field: "d", .. }));
    assert!(
        err("ball:length=5")
            .to_string()
            .contains("missing `d` (diameter, mm)")
    );
    assert!(matches!(
        err("bull:d=10"),
        ToolError::Missing { field: "r", .. }
    ));
    assert!(matches!(
        err("cone:d=10"),
        ToolError::Missing { field: "angle", .. }
    ));
    assert!(matches!(
        err("taperball:d=6,angle=3"),
        ToolError::Missing { field: "tip", .. }
    ));
    assert!(matches!(
        err("apt:d=6,r=1,alpha=0"),
        ToolError::Missing { field: "beta", .. }
    ));
    let e = err("ball:d=8,r=1");
    assert_eq!(
        e.to_string(),
        "ball tool: unknown key `r`, expected one of d, length"
    );
    assert_eq!(err("ball:d=8,d=9").to_string(), "duplicate key `d`");
    assert!(matches!(
        err("apt:d=8,r=1,alpha=0,beta=0,h=40,length=40"),
        ToolError::DuplicateKey { .. }
    ));
    assert_eq!(err("ball:d").to_string(), "expected `key=value`, got `d`");
    assert!(matches!(err("ball:d=8,"), ToolError::Malformed { .. }));
    assert_eq!(
        err("ball:d=eight").to_string(),
        "`d`: expected a number, got `eight`"
    );
    assert_eq!(
        err("ball:d=NaN").to_string(),
        "`d`: expected a finite number, got NaN"
    );
    assert!(matches!(
        err("ball:d=inf"),
        ToolError::NotFinite { field: "d", .. }
    ));
}

#[test]
fn value_errors() {
    assert_eq!(err("ball:d=0").to_string(), "`d` must be > 0, got 0");
    assert!(matches!(
        err("flat:d=-3"),
        ToolError::NotPositive { field: "d", .. }
    ));
    assert_eq!(
        err("bull:d=10,r=6").to_string(),
        "`r` must be <= 5 (d/2), got 6"
    );
    assert_eq!(
        err("bull:d=10,r=-1").to_string(),
        "`r` must be >= 0, got -1"
    );
    assert_eq!(
        err("taperball:d=6,angle=5,tip=4").to_string(),
        "`tip` must be <= 3 (d/2), got 4"
    );
    assert!(matches!(
        err("taperball:d=6,angle=5,tip=0"),
        ToolError::NotPositive { field: "tip", .. }
    ));
    let e = err("cone:d=10,angle=180");
    assert_eq!(
        e.to_string(),
        "`angle` must be in (0, 180) degrees, got 180"
    );
    assert!(matches!(
        err("cone:d=10,angle=0"),
        ToolError::AngleOutOfRange { .. }
    ));
    assert!(matches!(
        err("taperball:d=6,angle=90,tip=1"),
        ToolError::AngleOutOfRange { .. }
    ));
    assert!(matches!(
        err("taperball:d=6,angle=-1,tip=1"),
        ToolError::AngleOutOfRange { .. }
    ));
    let e = err("apt:d=10,r=1,alpha=90,beta=0");
    assert_eq!(e.to_string(), "`alpha` must be in [0, 90) degrees, got 90");
    assert!(matches!(
        err("apt:d=10,r=1,alpha=-5,beta=0"),
        ToolError::AngleOutOfRange { field: "alpha", .. }
    ));
    assert!(matches!(
        err("apt:d=10,r=1,alpha=0,beta=-90"),
        ToolError::AngleOutOfRange { field: "beta", .. }
    ));
    assert!(matches!(
        err("apt:d=10,r=1,alpha=50,beta=40"),
        ToolError::AnglesTooSteep { .. }
    ));
    assert!(matches!(
        err("apt:d=10,r=6,alpha=0,beta=0"),
        ToolError::CornerPastAxis { .. }
    ));
    let e = err("apt:d=10,r=2,e=2.5,alpha=0,beta=0");
    assert_eq!(
        e.to_string(),
        "`e` = 2.5 is inconsistent with `d`, `r`, `alpha`, `beta`: expected 3"
    );
    assert!(matches!(
        err("apt:d=10,r=2,f=2.5,alpha=0,beta=0"),
        ToolError::Inconsistent { field: "f", .. }
    ));
}

#[test]
fn length_errors() {
    assert_eq!(
        err("flat:d=6,length=0").to_string(),
        "`length` must be > 0, got 0"
    );
    assert!(matches!(
        err("flat:d=6,length=-2"),
        ToolError::NotPositive {
            field: "length",
            ..
        }
    ));
    let e = err("ball:d=8,length=3");
    assert_eq!(
        e.to_string(),
        "`length` = 3 is shorter than the profile needs: expected >= 4"
    );
    assert!(matches!(
        err("cone:d=10,angle=20,length=5"),
        ToolError::LengthTooShort { .. }
    ));
    assert!(matches!(
        err("bull:d=10,r=2,length=1.5"),
        ToolError::LengthTooShort { .. }
    ));
    let e = err("taperball:d=6,angle=10,tip=1,length=30");
    assert!(
        matches!(
            e,
            ToolError::LengthTooLong {
                field: "length",
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("taper reaches d/2"));
    assert!(matches!(
        err("apt:d=10,r=2,alpha=0,beta=0,h=1"),
        ToolError::LengthTooShort { field: "h", .. }
    ));
    assert!(matches!(
        err("apt:d=10,r=2,alpha=0,beta=0,length=1"),
        ToolError::LengthTooShort {
            field: "length",
            ..
        }
    ));
    // Exactly at the need is fine; so is a rounding hair below it.
    assert!("ball:d=8,length=4".parse::<Cutter>().is_ok());
    assert!("cone:d=10,angle=90,length=5".parse::<Cutter>().is_ok());
}

#[test]
fn hand_built_cutters_are_validated() {
    assert!(
        Cutter::Ball {
            radius: 4.0,
            length: 32.0
        }
        .validate()
        .is_ok()
    );
    let bad = Cutter::Bull {
        radius: 5.0,
        corner: 6.0,
        length: 40.0,
    };
    assert!(matches!(
        bad.validate(),
        Err(ToolError::TooLarge { field: "r", .. })
    ));
    let bad = Cutter::Cone {
        radius: 5.0,
        half_angle: 2.0,
        length: 40.0,
    };
    assert!(matches!(
        bad.validate(),
        Err(ToolError::AngleOutOfRange { field: "angle", .. })
    ));
    let bad = Cutter::Flat {
        radius: 3.0,
        length: f64::NAN,
    };
    assert!(matches!(
        bad.validate(),
        Err(ToolError::NotFinite {
            field: "length",
            ..
        })
    ));
    // Methods on invalid cutters do not panic.
    let nan = Cutter::Ball {
        radius: f64::NAN,
        length: f64::NAN,
    };
    let _ = (
        nan.profile(),
        nan.radius(),
        nan.height_at_radius(1.0),
        nan.to_string(),
    );
}
