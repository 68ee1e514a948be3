use super::*;

fn row(job: &str, strategy: &str, passes: usize) -> Row {
    Row {
        job: job.into(),
        strategy: strategy.into(),
        time_s: 1463.0,
        scallop_mm: [Some(0.131), Some(0.149), Some(0.152)],
        predicted_scallop_mm: Some(0.15),
        remaining_points: 21,
        gouge_points: 0,
        gouge_regions: 0,
        deepest_gouge_mm: 0.0,
        passes,
        cutting_length_mm: 9876.4,
        cell_mm: 0.05,
        incomplete: false,
    }
}

#[test]
fn identical_figures_of_two_strategies_are_explained() {
    // Figures that differ below the table's precision print the same.
    let mut planar = row("wave, iso-planar", "iso-planar", 48);
    planar.time_s += 0.001;
    planar.cutting_length_mm += 0.004;
    planar.scallop_mm[0] = Some(0.1309);
    let rows = [
        row("wave, iso-parametric", "iso-parametric", 48),
        planar,
        row("wave, iso-scallop", "iso-scallop", 40),
    ];
    let notes = coinciding(&rows, "wave");
    assert_eq!(notes.len(), 1, "{notes:?}");
    assert!(notes[0].contains("y depends only on v"), "{}", notes[0]);
    assert!(notes[0].starts_with("wave, iso-parametric (iso-parametric) and wave, iso-planar"));
    assert!(coinciding(&rows[1..], "wave").is_empty());
    let other = coinciding(&rows[..2], "die");
    assert!(
        other[0].ends_with("their passes coincide on this part."),
        "{other:?}"
    );
    assert!(row_summary(&rows[0]).starts_with("no gouge; scallop 0.131-0.149 mm"));
}

/// A demo-like output set: two programs' files under `compare/`, one without its
/// pictures; the page links only what is staged, and after the commit every link it
/// holds is a file in the folder.
#[test]
fn the_page_links_only_files_of_the_output_set() {
    let dir = std::env::temp_dir().join(format!("swarf-demo-page-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let mut out = Outputs::new(&dir);
    for f in [
        "compare/a.deviation.png",
        "compare/a.toolpath.png",
        "compare/a.report.json",
        "compare/a.view/index.html",
        "compare/b.report.json",
        "compare/compare.md",
    ] {
        out.write(f, b"x").unwrap();
    }
    let mut console = Vec::new();
    let mut s = Sections {
        text: &mut console,
        done: Vec::new(),
    };
    s.run("verification", |t| {
        writeln!(t, "| job | passes |\n|---|---|\n| a | 48 |")?;
        let mut b = program_blocks(&out, "compare", "a", "no gouge");
        b.extend(program_blocks(&out, "compare", "b", "no gouge"));
        b.push(Block::Links(vec![(
            "compare/compare.md".into(),
            "md".into(),
        )]));
        Ok(b)
    })
    .unwrap();
    let sections = s.done;
    let printed = String::from_utf8(console).unwrap();
    assert!(
        printed.contains("== verification\n| job | passes |"),
        "{printed}"
    );
    assert!(printed.contains("(section: "), "{printed}");
    let broken = Section {
        title: "broken".into(),
        seconds: 0.0,
        blocks: vec![Block::Links(vec![("compare/none.png".into(), "x".into())])],
    };
    let mut with_broken = sections.clone();
    with_broken.push(broken);
    let e = stage_page(&mut out, with_broken, 1.0).unwrap_err();
    assert!(e.to_string().contains("compare/none.png"), "{e}");
    stage_page(&mut out, sections, 1.0).unwrap();
    out.commit().unwrap();
    let html = std::fs::read_to_string(dir.join("index.html")).unwrap();
    let links = swarf_report::html::relative_links(&html);
    assert!(
        links.contains(&"compare/a.view/index.html".to_string()),
        "{links:?}"
    );
    assert!(
        links.contains(&"compare/a.deviation.png".to_string()),
        "{links:?}"
    );
    assert!(
        !links
            .iter()
            .any(|l| l.starts_with("compare/b.") && l.ends_with(".png"))
    );
    for l in &links {
        assert!(dir.join(l).is_file(), "{l} is not in the output set");
    }
    assert!(html.contains("<td>a</td><td>48</td>"), "{html}");
    let _ = std::fs::remove_dir_all(&dir);
}
