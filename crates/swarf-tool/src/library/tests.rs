use super::*;

const ONE: &str = "[[tool]]
number = 3
name = \"ball6-long\"
cutter = \"ball:d=6\"
flute_length = 12
stick_out = 30
shank = [{ d0 = 5, d1 = 6, length = 8 }, { d = 6, length = 40 }]
holder = [{ d0 = 20, d1 = 32, length = 20 }, { d = 63, length = 30 }]
feed = 1200
spindle = 12000
";

fn err(text: &str) -> String {
    ToolLibrary::parse(text, "lib.toml")
        .unwrap_err()
        .to_string()
}

#[test]
fn a_tool_reads_with_its_segments_and_feeds() {
    let lib = ToolLibrary::parse(ONE, "lib.toml").unwrap();
    let t = lib.get("3").unwrap();
    assert_eq!(lib.get("ball6-long").unwrap(), t);
    assert_eq!(t.assembly.cutter, Cutter::ball(6.0, Some(12.0)).unwrap());
    assert_eq!(t.assembly.stick_out, 30.0);
    assert_eq!(t.assembly.tool_length(), 60.0);
    assert_eq!(
        t.assembly.shank[0],
        StackSegment::Cone {
            d0: 5.0,
            d1: 6.0,
            length: 8.0
        }
    );
    assert_eq!(
        t.assembly.holder[1],
        StackSegment::Cylinder {
            d: 63.0,
            length: 30.0
        }
    );
    assert_eq!(
        (t.feed, t.spindle, t.plunge),
        (Some(1200.0), Some(12000.0), None)
    );
}

#[test]
fn the_shipped_library_reads() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tooling/library.toml");
    let lib = ToolLibrary::read(std::path::Path::new(path)).unwrap();
    assert_eq!(lib.tools().len(), 3);
    assert_eq!(lib.get("bull10r2").unwrap().number, 2);
    assert_eq!(lib.get("1").unwrap().assembly.cutter.length(), 22.0);
}

#[test]
fn a_missing_tool_lists_what_exists() {
    let lib = ToolLibrary::parse(ONE, "lib.toml").unwrap();
    let e = lib.get("7").unwrap_err().to_string();
    assert_eq!(e, "lib.toml: no tool `7`: the library has 3 \"ball6-long\"");
    let e = lib.get("flat10").unwrap_err().to_string();
    assert!(e.contains("no tool `flat10`"), "{e}");
}

#[test]
fn duplicates_are_refused_naming_both() {
    let twice = format!("{ONE}\n{}", ONE.replace("ball6-long", "other"));
    let e = err(&twice);
    assert!(
        e.contains("line 12: tool[1] \"other\": number: 3 is already the number of \"ball6-long\""),
        "{e}"
    );
    let renamed = format!("{ONE}\n{}", ONE.replace("number = 3", "number = 4"));
    let e = err(&renamed);
    assert!(
        e.contains("tool[1] \"ball6-long\": name: another tool"),
        "{e}"
    );
}

#[test]
fn missing_and_bad_fields_are_named() {
    let e = err(&ONE.replace("number = 3\n", ""));
    assert!(
        e.contains("lib.toml: line 1: tool[0] \"ball6-long\": number: missing"),
        "{e}"
    );
    let e = err(&ONE.replace("number = 3", "number = 0"));
    assert!(e.contains("number: must be >= 1"), "{e}");
    let e = err(&ONE.replace("number = 3", "number = -2"));
    assert!(e.contains("lib.toml: TOML: line 2"), "{e}");
    let e = err(&ONE.replace("\"ball6-long\"", "\"42\""));
    assert!(
        e.contains("name: expected a name that is not empty and not a number"),
        "{e}"
    );
    let e = err(&ONE.replace("stick_out = 30", "stick_out = 70"));
    assert!(
        e.contains("stick_out: expected between the flute length 12 and the tool's length 60"),
        "{e}"
    );
    let e = err(&ONE.replace("feed = 1200", "feed = -5"));
    assert!(e.contains("feed:"), "{e}");
    let e = err(&ONE.replace("stick_out = 30\n", ""));
    assert!(e.contains("stick_out: missing"), "{e}");
    let e = err(&ONE.replace("cutter = \"ball:d=6\"", "cutter = \"ball:d=-6\""));
    assert!(e.contains("`d` must be > 0"), "{e}");
    let e = err(&format!("{ONE}colour = \"red\"\n"));
    assert!(e.contains("unknown field `colour`"), "{e}");
}

#[test]
fn bad_segments_are_named() {
    let e = err(&ONE.replace("{ d = 63, length = 30 }", "{ d = 63, d0 = 3, length = 30 }"));
    assert!(
        e.contains("holder[1]: expected `{ d, length }` (a cylinder) or `{ d0, d1, length }`"),
        "{e}"
    );
    let e = err(&ONE.replace("{ d = 63, length = 30 }", "{ d = 63 }"));
    assert!(e.contains("holder[1].length: missing"), "{e}");
    let e = err(&ONE.replace("{ d = 6, length = 40 }", "{ d = 0, length = 40 }"));
    assert!(e.contains("shank[1].d:"), "{e}");
    let e = err(&ONE.replace("{ d = 6, length = 40 }", "{ d = 6, length = 40, r = 1 }"));
    assert!(e.contains("unknown field `r`"), "{e}");
    let e = err(&ONE.replace(
        "holder = [{ d0 = 20, d1 = 32, length = 20 }, { d = 63, length = 30 }]",
        "holder = []",
    ));
    assert!(e.contains("holder: expected at least one"), "{e}");
}

#[test]
fn flute_length_must_agree_with_the_cutters_own() {
    let e = err(&ONE.replace("\"ball:d=6\"", "\"ball:d=6,length=15\""));
    assert!(
        e.contains("flute_length: 12 disagrees with the cutter's own length 15"),
        "{e}"
    );
    let same = ONE.replace("\"ball:d=6\"", "\"ball:d=6,length=12\"");
    assert!(ToolLibrary::parse(&same, "lib.toml").is_ok());
    let own = ONE
        .replace("\"ball:d=6\"", "\"ball:d=6,length=14\"")
        .replace("flute_length = 12\n", "");
    let lib = ToolLibrary::parse(&own, "lib.toml").unwrap();
    assert_eq!(lib.tools()[0].assembly.cutter.length(), 14.0);
    let e = err(&ONE.replace("flute_length = 12", "flute_length = 2"));
    assert!(e.contains("flute_length: `length` = 2 is shorter"), "{e}");
}
