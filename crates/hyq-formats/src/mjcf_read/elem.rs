//! The MJCF text as a tree of elements, with `<include>` files spliced in: every file read
//! through the project's size-capped reader, its nesting depth checked before the XML parser
//! runs, include cycles and too many files refused, and every element keeping its file and
//! line for messages.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use hyq_physics::input::{self, FileKind};

/// An MJCF file: 8 MiB, a hundred times a Menagerie quadruped's.
pub const MJCF: FileKind = FileKind {
    what: "MJCF",
    max_bytes: 8 << 20,
    max_line_bytes: 8 << 20,
};

/// The most files one model reads (itself and its includes): Menagerie's scenes use two.
pub const MAX_FILES: usize = 64;

/// The most elements in one model, all files together: a hundred times a quadruped's.
pub const MAX_ELEMENTS: usize = 100_000;

/// Why an MJCF file could not be read: one line, naming the file, the line, the element and
/// the attribute where there is one.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct MjcfReadError(pub String);

/// One XML element of the model: its tag, attributes in file order, child elements, and where
/// it was written.
#[derive(Debug, Clone)]
pub(crate) struct Elem {
    pub(crate) tag: String,
    pub(crate) attrs: Vec<(String, String)>,
    pub(crate) children: Vec<Elem>,
    pub(crate) file: Arc<str>,
    pub(crate) line: u32,
}

impl Elem {
    /// The attribute `name`, if written.
    pub(crate) fn get(&self, name: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    /// `FILE:LINE: <tag>`, the start of every message about this element.
    pub(crate) fn at(&self) -> String {
        format!("{}:{}: <{}>", self.file, self.line, self.tag)
    }

    /// An error about this element.
    pub(crate) fn error(&self, message: impl std::fmt::Display) -> MjcfReadError {
        MjcfReadError(hyq_physics::one_line(&format!("{}: {message}", self.at())))
    }
}

/// What the reading of one model has seen so far: the include chain (for cycles) and counts.
struct Reading {
    chain: Vec<PathBuf>,
    files: usize,
    elements: usize,
}

/// Reads the MJCF file at `path` and every file it includes into one `<mujoco>` tree.
pub(crate) fn load_file(path: &Path) -> Result<Elem, MjcfReadError> {
    let mut reading = Reading {
        chain: Vec::new(),
        files: 0,
        elements: 0,
    };
    read_file(path, &mut reading, 0)
}

/// Reads MJCF text (`origin` names it in messages); `dir` is where its `<include>` files are
/// (`None`: includes are refused, as for compiled-in text).
pub(crate) fn load_str(
    text: &str,
    origin: &str,
    dir: Option<&Path>,
) -> Result<Elem, MjcfReadError> {
    let mut reading = Reading {
        chain: Vec::new(),
        files: 1,
        elements: 0,
    };
    parse(text, origin, dir, &mut reading, 0)
}

fn read_file(path: &Path, reading: &mut Reading, depth: usize) -> Result<Elem, MjcfReadError> {
    let shown = path.display().to_string();
    let key = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_owned());
    if reading.chain.contains(&key) {
        return Err(MjcfReadError(format!(
            "{shown}: <include> cycle: the file includes itself through {}",
            reading
                .chain
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(" -> ")
        )));
    }
    reading.files += 1;
    if reading.files > MAX_FILES {
        return Err(MjcfReadError(format!(
            "{shown}: more than {MAX_FILES} files included, which no robot needs"
        )));
    }
    let text = input::read_text(path, &MJCF)
        .map_err(|e| MjcfReadError(format!("cannot read MJCF file {shown}: {e}")))?;
    reading.chain.push(key);
    let dir = path.parent().unwrap_or_else(|| Path::new("."));
    let root = parse(&text, &shown, Some(dir), reading, depth);
    reading.chain.pop();
    root
}

fn parse(
    text: &str,
    origin: &str,
    dir: Option<&Path>,
    reading: &mut Reading,
    depth: usize,
) -> Result<Elem, MjcfReadError> {
    let fail = |m: String| MjcfReadError(hyq_physics::one_line(&format!("{origin}: {m}")));
    if text.len() as u64 > MJCF.max_bytes {
        return Err(fail(format!(
            "larger than {}, which no MJCF robot is",
            input::size_text(MJCF.max_bytes)
        )));
    }
    input::check_xml_depth(text, input::XML_MAX_DEPTH).map_err(fail)?;
    let options = roxmltree::ParsingOptions {
        allow_dtd: false,
        nodes_limit: 4 * MAX_ELEMENTS as u32,
        ..roxmltree::ParsingOptions::default()
    };
    let doc = roxmltree::Document::parse_with_options(text, options)
        .map_err(|e| fail(hyq_physics::printable(&e.to_string())))?;
    let root = doc.root_element();
    if root.tag_name().name() != "mujoco" {
        return Err(fail(format!(
            "the root element is <{}>, not <mujoco>: not an MJCF file",
            hyq_physics::printable(root.tag_name().name())
        )));
    }
    let file: Arc<str> = Arc::from(origin);
    let ctx = Ctx {
        doc: &doc,
        file,
        dir,
    };
    convert(&ctx, root, reading, depth)
}

struct Ctx<'a, 'input> {
    doc: &'a roxmltree::Document<'input>,
    file: Arc<str>,
    dir: Option<&'a Path>,
}

/// The element `node` and its children, `<include>`s replaced by the children of the included
/// file's `<mujoco>`. `depth` counts elements above, across files, held to
/// [`input::XML_MAX_DEPTH`] so that the recursive walks after this one stay shallow.
fn convert(
    ctx: &Ctx<'_, '_>,
    node: roxmltree::Node<'_, '_>,
    reading: &mut Reading,
    depth: usize,
) -> Result<Elem, MjcfReadError> {
    let line = ctx.doc.text_pos_at(node.range().start).row;
    let mut elem = Elem {
        tag: hyq_physics::printable(node.tag_name().name()),
        attrs: node
            .attributes()
            .map(|a| (a.name().to_owned(), a.value().to_owned()))
            .collect(),
        children: Vec::new(),
        file: Arc::clone(&ctx.file),
        line,
    };
    reading.elements += 1;
    if reading.elements > MAX_ELEMENTS {
        return Err(elem.error(format!(
            "more than {MAX_ELEMENTS} elements in the model, which no robot needs"
        )));
    }
    if depth > input::XML_MAX_DEPTH {
        return Err(elem.error(format!(
            "nested more than {} deep (includes counted), which no robot is",
            input::XML_MAX_DEPTH
        )));
    }
    for child in node.children().filter(roxmltree::Node::is_element) {
        let converted = convert(ctx, child, reading, depth + 1)?;
        if converted.tag == "include" {
            elem.children
                .extend(include(ctx, &converted, reading, depth + 1)?);
        } else {
            elem.children.push(converted);
        }
    }
    Ok(elem)
}

/// The children of the `<mujoco>` of the file an `<include file>` names, relative to the
/// including file's directory.
fn include(
    ctx: &Ctx<'_, '_>,
    inc: &Elem,
    reading: &mut Reading,
    depth: usize,
) -> Result<Vec<Elem>, MjcfReadError> {
    let Some(name) = inc.get("file") else {
        return Err(inc.error("no `file` attribute"));
    };
    if let Some((k, _)) = inc.attrs.iter().find(|(k, _)| k != "file") {
        return Err(inc.error(format!("attribute `{k}` is not understood")));
    }
    if !inc.children.is_empty() {
        return Err(inc.error("an <include> has no children"));
    }
    let Some(dir) = ctx.dir else {
        return Err(inc.error(format!(
            "includes {name:?}, but this text has no directory to find it in"
        )));
    };
    let root = read_file(&dir.join(name), reading, depth)
        .map_err(|e| MjcfReadError(format!("{}: {}", inc.at(), e.0)))?;
    Ok(root.children)
}
