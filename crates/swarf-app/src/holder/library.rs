//! Jobs naming the tools of a library: the one resolution of a library key (a T
//! number, or a name that is not a cutter spec: [`crate::job::ToolRef`]), shared by
//! single-operation jobs ([`crate::job`]) and sequence jobs ([`crate::sequence`]).

use swarf_tool::library::{LibraryTool, ToolLibrary};

/// The library tool `key` (a T number or a name) names.
///
/// # Errors
/// A key without a library (`tool: ... no `tools` library`), or a key the library
/// lacks (its error lists the library's tools), as `tool: ...`.
pub fn named_tool<'l>(
    library: Option<&'l ToolLibrary>,
    key: &str,
) -> Result<&'l LibraryTool, String> {
    let Some(library) = library else {
        return Err(format!(
            "tool: {key:?} names a library tool, but no `tools` library is given (add \
             tools = \"library.toml\", or give a cutter spec such as \"ball:d=6\")"
        ));
    };
    library.get(key).map_err(|e| format!("tool: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    const LIBRARY: &str = "[[tool]]\nnumber = 3\nname = \"ball6-long\"\ncutter = \"ball:d=6\"\n\
        flute_length = 12\nstick_out = 30\nshank = [{ d = 6, length = 40 }]\n\
        holder = [{ d = 20, length = 20 }]\nfeed = 1200\nspindle = 12000\n";

    #[test]
    fn keys_numbers_and_names_resolve_and_specs_do_not() {
        use crate::job::{FeedsSpec, ToolRef};
        let lib = ToolLibrary::parse(LIBRARY, "lib.toml").unwrap();
        let tool = |v: toml::Value| toml::Value::try_into::<ToolRef>(v).unwrap();
        let n = tool(toml::Value::Integer(3));
        let name = tool(toml::Value::String("ball6-long".into()));
        let spec = tool(toml::Value::String("ball:d=6".into()));
        assert_eq!(n.resolve(Some(&lib)).unwrap().1.unwrap().number, 3);
        assert_eq!(name.resolve(Some(&lib)).unwrap().1.unwrap().number, 3);
        assert!(spec.resolve(Some(&lib)).unwrap().1.is_none());
        let e = n.resolve(None).unwrap_err();
        assert!(e.contains("no `tools` library"), "{e}");
        let e = named_tool(Some(&lib), "7").unwrap_err();
        assert!(e.starts_with("tool: ") && e.contains("ball6-long"), "{e}");
        let given: FeedsSpec = toml::from_str("feed = 500").unwrap();
        let feeds = given.resolve(Some(lib.get("3").unwrap()));
        assert_eq!(
            (feeds.feed, feeds.spindle, feeds.plunge),
            (500.0, 12000.0, 100.0)
        );
    }
}
