use super::*;

/// Elements that have no closing tag.
const VOID: [&str; 4] = ["meta", "img", "br", "hr"];

/// Checks that `html` is well formed: every tag closed in order (but the void ones),
/// every attribute value quoted, no `<` or `>` outside a tag, no `&` that starts no
/// entity. Returns the element names in document order.
pub(crate) fn well_formed(html: &str) -> Result<Vec<String>, String> {
    let body = html.strip_prefix("<!DOCTYPE html>").ok_or("no doctype")?;
    let (mut stack, mut names) = (Vec::<String>::new(), Vec::new());
    let mut rest = body;
    while let Some(open) = rest.find('<') {
        text_ok(&rest[..open])?;
        let close = rest[open..].find('>').ok_or("unclosed tag")? + open;
        let tag = &rest[open + 1..close];
        rest = &rest[close + 1..];
        if tag.contains('<') {
            return Err(format!("'<' inside tag {tag}"));
        }
        if let Some(name) = tag.strip_prefix('/') {
            match stack.pop() {
                Some(top) if top == name => {}
                top => return Err(format!("</{name}> closes {top:?}")),
            }
            continue;
        }
        let name: String = tag
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric())
            .collect();
        attributes_ok(&tag[name.len()..])?;
        if name == "style" {
            let end = rest.find("</style>").ok_or("unclosed style")?;
            rest = &rest[end + "</style>".len()..];
        } else if !VOID.contains(&name.as_str()) {
            stack.push(name.clone());
        }
        names.push(name);
    }
    text_ok(rest)?;
    if stack.is_empty() {
        Ok(names)
    } else {
        Err(format!("left open: {stack:?}"))
    }
}

/// Text between tags: no `>`, every `&` an entity.
fn text_ok(text: &str) -> Result<(), String> {
    if text.contains('>') {
        return Err(format!("'>' in text {text:?}"));
    }
    for (k, _) in text.match_indices('&') {
        let entity = &text[k..];
        if !["&amp;", "&lt;", "&gt;", "&quot;"]
            .iter()
            .any(|e| entity.starts_with(e))
        {
            return Err(format!("bare '&' in {text:?}"));
        }
    }
    Ok(())
}

/// ` a="x" b="y"`: names and double-quoted values without `"` inside.
fn attributes_ok(mut s: &str) -> Result<(), String> {
    loop {
        s = s.trim_start();
        if s.is_empty() {
            return Ok(());
        }
        let eq = s.find('=').ok_or(format!("attribute without value: {s}"))?;
        let name = &s[..eq];
        if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '-') {
            return Err(format!("attribute name {name:?}"));
        }
        let value = s[eq + 1..]
            .strip_prefix('"')
            .ok_or(format!("unquoted {name}"))?;
        let end = value.find('"').ok_or(format!("unterminated {name}"))?;
        text_ok(&value[..end])?;
        s = &value[end + 1..];
    }
}

fn fixture() -> Page {
    Page {
        title: "swarf demo <test> & co".into(),
        intro: vec!["All files \"here\".".into()],
        sections: vec![
            Section {
                title: "verification".into(),
                seconds: 12.34,
                blocks: vec![
                    Block::Text(
                        "a line\n| job | time |\n|---|---|\n| wave <1> | 3'04\" |\n\npoints are cells\n"
                            .into(),
                    ),
                    Block::Note("iso-parametric = iso-planar here".into()),
                    Block::Figures(vec![Figure {
                        src: "compare/finish+cleanup.deviation.png".into(),
                        caption: "deviation, gouge < 0".into(),
                    }]),
                    Block::Links(vec![
                        ("compare/a b.view/index.html".into(), "3D view".into()),
                        ("compare/x#1.json".into(), "report".into()),
                    ]),
                ],
            },
            Section {
                title: "parts".into(),
                seconds: 0.5,
                blocks: vec![Block::Text(String::new())],
            },
        ],
    }
}

#[test]
fn the_page_is_well_formed_and_holds_every_table_figure_and_time() {
    let h = render(&fixture());
    let names = well_formed(&h).unwrap();
    assert_eq!(names.iter().filter(|n| *n == "table").count(), 2);
    assert_eq!(names.iter().filter(|n| *n == "img").count(), 1);
    assert!(
        h.contains("<td>wave &lt;1&gt;</td><td>3'04&quot;</td>"),
        "{h}"
    );
    assert!(!h.contains("|---|"), "{h}");
    assert!(h.contains("<pre>a line</pre>") && h.contains("<pre>points are cells</pre>"));
    assert!(h.contains("12.3 s") && h.contains("<th>12.8 s</th>"), "{h}");
    assert!(h.contains("class=\"note\""));
    assert!(!h.contains("<script") && !h.contains("http"), "{h}");
    let long = Page {
        sections: vec![Section {
            blocks: vec![Block::Text("x\n".repeat(FOLD_LINES + 1))],
            ..Section::default()
        }],
        ..Page::default()
    };
    let h = render(&long);
    well_formed(&h).unwrap();
    assert!(
        h.contains("<details><summary>console output, 13 lines</summary><pre>x\nx"),
        "{h}"
    );
}

#[test]
fn links_are_listed_back_decoded() {
    let h = render(&fixture());
    assert_eq!(
        relative_links(&h),
        [
            "compare/finish+cleanup.deviation.png",
            "compare/a b.view/index.html",
            "compare/x#1.json",
            "compare/finish+cleanup.deviation.png",
        ]
    );
    assert!(h.contains("href=\"compare/a%20b.view/index.html\""), "{h}");
    assert!(h.contains("href=\"compare/x%231.json\""), "{h}");
}

#[test]
fn the_checker_refuses_broken_pages() {
    for bad in [
        "<html><p></html>",
        "<!DOCTYPE html><p>a > b</p>",
        "<!DOCTYPE html><p>a & b</p>",
        "<!DOCTYPE html><a href=x>y</a>",
        "<!DOCTYPE html><div>",
    ] {
        assert!(well_formed(bad).is_err(), "{bad}");
    }
    assert!(well_formed("<!DOCTYPE html><p>a<br>b &amp; c</p>").is_ok());
}
