//! Jobs naming the tools of a library: the one resolution of a job's or an
//! operation's `tool` (a T number, or a name that is not a cutter spec) and the
//! library tool's default feeds, shared by single-operation jobs ([`crate::job`])
//! and sequence jobs ([`crate::sequence`]).

use swarf_tool::library::{LibraryTool, ToolLibrary};
use swarf_toolpath::Feeds;

/// The library key a `tool` value names: a number, or text that is not a cutter
/// spec (a spec has a `:`); `None` for a cutter spec or table.
pub fn library_key(tool: Option<&toml::Value>) -> Option<String> {
    match tool {
        Some(toml::Value::Integer(n)) => Some(n.to_string()),
        Some(toml::Value::String(s)) if !s.contains(':') => Some(s.clone()),
        _ => None,
    }
}

/// The library tool a `tool` value names ([`library_key`]); `None` for a cutter
/// spec or table.
///
/// # Errors
/// A library key without a library (`tool: ... no `tools` library`), or a key the
/// library lacks (its error lists the library's tools), as `tool: ...`.
pub fn named_tool<'l>(
    library: Option<&'l ToolLibrary>,
    tool: Option<&toml::Value>,
) -> Result<Option<&'l LibraryTool>, String> {
    let Some(key) = library_key(tool) else {
        return Ok(None);
    };
    let Some(library) = library else {
        return Err(format!(
            "tool: {key:?} names a library tool, but no `tools` library is given (add \
             tools = \"library.toml\", or give a cutter spec such as \"ball:d=6\")"
        ));
    };
    library
        .get(&key)
        .map(Some)
        .map_err(|e| format!("tool: {e}"))
}

/// `feeds` with the library tool's default feed, spindle speed and plunge feed
/// wherever the job's `feeds` table (`given`, absent when the job has none) does not
/// set them.
///
/// # Units
/// mm/min, rev/min.
pub fn default_feeds(tool: &LibraryTool, given: Option<&toml::Value>, feeds: &mut Feeds) {
    let set = |key: &str| given.and_then(|g| g.get(key)).is_some();
    for (key, value, field) in [
        ("feed", tool.feed, &mut feeds.feed),
        ("spindle", tool.spindle, &mut feeds.spindle),
        ("plunge", tool.plunge, &mut feeds.plunge),
    ] {
        if let (false, Some(v)) = (set(key), value) {
            *field = v;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIBRARY: &str = "[[tool]]\nnumber = 3\nname = \"ball6-long\"\ncutter = \"ball:d=6\"\n\
        flute_length = 12\nstick_out = 30\nshank = [{ d = 6, length = 40 }]\n\
        holder = [{ d = 20, length = 20 }]\nfeed = 1200\nspindle = 12000\n";

    #[test]
    fn keys_numbers_and_names_resolve_and_specs_do_not() {
        let lib = ToolLibrary::parse(LIBRARY, "lib.toml").unwrap();
        let n = toml::Value::Integer(3);
        let name = toml::Value::String("ball6-long".into());
        let spec = toml::Value::String("ball:d=6".into());
        assert_eq!(named_tool(Some(&lib), Some(&n)).unwrap().unwrap().number, 3);
        assert_eq!(
            named_tool(Some(&lib), Some(&name)).unwrap().unwrap().number,
            3
        );
        assert!(named_tool(Some(&lib), Some(&spec)).unwrap().is_none());
        let e = named_tool(None, Some(&n)).unwrap_err();
        assert!(e.contains("no `tools` library"), "{e}");
        let e = named_tool(Some(&lib), Some(&toml::Value::Integer(7))).unwrap_err();
        assert!(e.starts_with("tool: ") && e.contains("ball6-long"), "{e}");
        let mut feeds = Feeds::default();
        let given: toml::Value = toml::from_str("feed = 500").unwrap();
        default_feeds(lib.get("3").unwrap(), Some(&given), &mut feeds);
        assert_eq!(
            (feeds.feed, feeds.spindle, feeds.plunge),
            (300.0, 12000.0, 100.0)
        );
    }
}
