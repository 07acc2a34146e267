//! The code's shape, checked rather than reviewed: no function body over 80 lines of code, and
//! no import circle inside a crate but the ones ARCHITECTURE.md explains.
//!
//! Both read the workspace's own sources with `syn` (run as tests, so the xtask binary does not
//! compile a Rust parser). A circle is a set of files of one crate that import each other in a
//! loop over `use crate::…`, `use super::…` and `use self::…`; a parent module's `use` of its own
//! child (a `mod.rs` re-exporting what it declares) is the module tree itself, not an import, and
//! is left out. clippy's `too_many_lines` (threshold 80 in `clippy.toml`) says the same of
//! bodies as they are written; the test here counts what rustfmt leaves, blank and comment-only
//! lines excluded, so the two cannot drift apart by formatting.

#[cfg(test)]
mod tests {
    use std::collections::{BTreeMap, BTreeSet};
    use std::path::{Path, PathBuf};

    use syn::visit::Visit;

    use crate::workspace::workspace_root;

    /// The longest body, in lines of code, a non-test function may have.
    const MAX_BODY_LINES: usize = 80;

    /// The circles ARCHITECTURE.md's "Import circles" section explains: crate, then its files.
    const EXPLAINED_CIRCLES: &[(&str, &[&str])] = &[("hyq-spec", &["src/step.rs", "src/terms.rs"])];

    /// Every crate directory of the workspace with a `src/` (crates/*, spec-tests, xtask).
    fn crate_dirs() -> Vec<PathBuf> {
        let root = workspace_root();
        let mut dirs: Vec<PathBuf> = std::fs::read_dir(root.join("crates"))
            .expect("crates/ is readable")
            .map(|e| e.expect("a crates/ entry").path())
            .collect();
        dirs.push(root.join("spec-tests"));
        dirs.push(root.join("xtask"));
        dirs.retain(|d| d.join("src").is_dir());
        dirs.sort();
        dirs
    }

    fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).expect("a source directory is readable") {
            let path = entry.expect("a directory entry").path();
            if path.is_dir() {
                rust_files(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }

    /// A crate's source files under `src/`, keyed by their path relative to the crate.
    fn sources(crate_dir: &Path) -> BTreeMap<String, syn::File> {
        let mut files = Vec::new();
        rust_files(&crate_dir.join("src"), &mut files);
        files
            .into_iter()
            .map(|path| {
                let text = std::fs::read_to_string(&path).expect("a source file is readable");
                let parsed = syn::parse_file(&text)
                    .unwrap_or_else(|e| panic!("{} does not parse: {e}", path.display()));
                let rel = path.strip_prefix(crate_dir).expect("under the crate");
                (rel.to_string_lossy().replace('\\', "/"), parsed)
            })
            .collect()
    }

    fn is_test_attr(attrs: &[syn::Attribute]) -> bool {
        attrs.iter().any(|a| {
            let text = quote_attr(a);
            text == "test" || text.starts_with("cfg(test") || text.contains("proptest")
        })
    }

    fn quote_attr(attr: &syn::Attribute) -> String {
        let path = attr.path().segments.iter().map(|s| s.ident.to_string());
        let path: Vec<String> = path.collect();
        match &attr.meta {
            syn::Meta::List(list) => format!("{}({}", path.join("::"), list.tokens),
            _ => path.join("::"),
        }
    }

    /// Lines of code in `block`: its span's lines minus blank and comment-only ones.
    fn body_lines(block: &syn::Block, text: &[&str]) -> usize {
        let span = block.brace_token.span.join();
        let (first, last) = (span.start().line, span.end().line);
        (first..=last)
            .filter(|&n| {
                let line = text.get(n - 1).map_or("", |l| l.trim());
                !(line.is_empty() || line.starts_with("//"))
            })
            .count()
            .saturating_sub(2)
    }

    struct Bodies<'a> {
        text: Vec<&'a str>,
        file: String,
        long: Vec<String>,
    }

    impl Bodies<'_> {
        fn check(&mut self, name: &syn::Ident, block: &syn::Block) {
            let lines = body_lines(block, &self.text);
            if lines > MAX_BODY_LINES {
                let line = name.span().start().line;
                self.long
                    .push(format!("{}:{line} {name}: {lines} lines", self.file));
            }
        }
    }

    impl<'ast> Visit<'ast> for Bodies<'_> {
        fn visit_item_mod(&mut self, m: &'ast syn::ItemMod) {
            if !is_test_attr(&m.attrs) {
                syn::visit::visit_item_mod(self, m);
            }
        }
        fn visit_item_fn(&mut self, f: &'ast syn::ItemFn) {
            if !is_test_attr(&f.attrs) {
                self.check(&f.sig.ident, &f.block);
                syn::visit::visit_item_fn(self, f);
            }
        }
        fn visit_impl_item_fn(&mut self, f: &'ast syn::ImplItemFn) {
            if !is_test_attr(&f.attrs) {
                self.check(&f.sig.ident, &f.block);
                syn::visit::visit_impl_item_fn(self, f);
            }
        }
        fn visit_trait_item_fn(&mut self, f: &'ast syn::TraitItemFn) {
            if let Some(block) = &f.default {
                self.check(&f.sig.ident, block);
            }
            syn::visit::visit_trait_item_fn(self, f);
        }
    }

    #[test]
    fn no_function_body_is_longer_than_80_lines_of_code() {
        let mut long = Vec::new();
        let mut checked = 0;
        for dir in crate_dirs() {
            let mut files = Vec::new();
            rust_files(&dir.join("src"), &mut files);
            for path in files {
                let text = std::fs::read_to_string(&path).expect("readable");
                let file = syn::parse_file(&text).expect("parses");
                let rel = path
                    .strip_prefix(workspace_root())
                    .expect("in the workspace");
                let mut bodies = Bodies {
                    text: text.lines().collect(),
                    file: rel.display().to_string(),
                    long: Vec::new(),
                };
                bodies.visit_file(&file);
                long.append(&mut bodies.long);
                checked += 1;
            }
        }
        assert!(
            checked > 100,
            "only {checked} files were read: the walk is broken"
        );
        assert!(
            long.is_empty(),
            "bodies over {MAX_BODY_LINES} lines:\n{}",
            long.join("\n")
        );
    }

    #[test]
    fn the_body_count_sees_a_long_body() {
        let body: String = (0..90).map(|i| format!("    let x{i} = {i};\n")).collect();
        let text = format!("fn long() {{\n{body}}}\n");
        let file = syn::parse_file(&text).expect("parses");
        let mut bodies = Bodies {
            text: text.lines().collect(),
            file: "t.rs".into(),
            long: vec![],
        };
        bodies.visit_file(&file);
        assert_eq!(bodies.long, ["t.rs:1 long: 90 lines"]);
    }

    /// The module path of a file under `src/` (`lib.rs`/`main.rs` → root, `a/mod.rs` → `a`).
    fn module_path(file: &str) -> Vec<String> {
        let stem = file.trim_start_matches("src/").trim_end_matches(".rs");
        let mut parts: Vec<String> = stem.split('/').map(String::from).collect();
        if matches!(
            parts.last().map(String::as_str),
            Some("mod" | "lib" | "main")
        ) {
            parts.pop();
        }
        parts
    }

    /// The paths of a file that start at `crate`, `super` or `self`: its `use` trees and the
    /// paths written in its code (`crate::x::f()` imports as surely as `use`), test code left out.
    #[derive(Default)]
    struct Paths(Vec<Vec<String>>);

    impl Paths {
        fn tree(&mut self, tree: &syn::UseTree, prefix: &mut Vec<String>) {
            match tree {
                syn::UseTree::Path(p) => {
                    prefix.push(p.ident.to_string());
                    self.tree(&p.tree, prefix);
                    prefix.pop();
                }
                syn::UseTree::Name(n) => {
                    self.0.push([&prefix[..], &[n.ident.to_string()]].concat())
                }
                syn::UseTree::Rename(r) => {
                    self.0.push([&prefix[..], &[r.ident.to_string()]].concat())
                }
                syn::UseTree::Glob(_) => self.0.push(prefix.clone()),
                syn::UseTree::Group(g) => g.items.iter().for_each(|t| self.tree(t, prefix)),
            }
        }
    }

    impl<'ast> Visit<'ast> for Paths {
        fn visit_item_mod(&mut self, m: &'ast syn::ItemMod) {
            if !is_test_attr(&m.attrs) {
                syn::visit::visit_item_mod(self, m);
            }
        }
        fn visit_item_fn(&mut self, f: &'ast syn::ItemFn) {
            if !is_test_attr(&f.attrs) {
                syn::visit::visit_item_fn(self, f);
            }
        }
        fn visit_item_use(&mut self, u: &'ast syn::ItemUse) {
            self.tree(&u.tree, &mut Vec::new());
        }
        fn visit_path(&mut self, path: &'ast syn::Path) {
            let segments: Vec<String> = path.segments.iter().map(|s| s.ident.to_string()).collect();
            if matches!(
                segments.first().map(String::as_str),
                Some("crate" | "super" | "self")
            ) {
                self.0.push(segments);
            }
            syn::visit::visit_path(self, path);
        }
    }

    /// What a file re-exports by name (`pub use a::b::Name;`): the name → the path as written.
    fn reexports(file: &syn::File) -> BTreeMap<String, Vec<String>> {
        fn walk(
            tree: &syn::UseTree,
            prefix: &mut Vec<String>,
            out: &mut BTreeMap<String, Vec<String>>,
        ) {
            match tree {
                syn::UseTree::Path(p) => {
                    prefix.push(p.ident.to_string());
                    walk(&p.tree, prefix, out);
                    prefix.pop();
                }
                syn::UseTree::Name(n) => {
                    let name = n.ident.to_string();
                    out.insert(name.clone(), [&prefix[..], &[name]].concat());
                }
                syn::UseTree::Rename(r) => {
                    let path = [&prefix[..], &[r.ident.to_string()]].concat();
                    out.insert(r.rename.to_string(), path);
                }
                syn::UseTree::Glob(_) => {}
                syn::UseTree::Group(g) => g.items.iter().for_each(|t| walk(t, prefix, out)),
            }
        }
        let mut out = BTreeMap::new();
        for item in &file.items {
            if let syn::Item::Use(u) = item
                && !matches!(u.vis, syn::Visibility::Inherited)
            {
                walk(&u.tree, &mut Vec::new(), &mut out);
            }
        }
        out
    }

    /// A crate's files: module path → file, and each file's re-exports.
    struct Crate {
        modules: BTreeMap<Vec<String>, String>,
        reexports: BTreeMap<String, BTreeMap<String, Vec<String>>>,
    }

    /// `path` (as written in the module `from`) made absolute, or `None` outside the crate. A
    /// path's first segment that names a child module of `from` is relative to it.
    fn absolute(from: &[String], path: &[String], krate: &Crate) -> Option<Vec<String>> {
        let first = path.first()?.as_str();
        let mut absolute: Vec<String> = match first {
            "crate" => Vec::new(),
            "self" => from.to_vec(),
            "super" => from[..from.len().saturating_sub(1)].to_vec(),
            _ if krate.modules.contains_key(&[from, &path[..1]].concat()) => {
                return Some([from, path].concat());
            }
            _ => return None,
        };
        let mut rest = &path[1..];
        while rest.first().is_some_and(|s| s == "super") {
            absolute.pop();
            rest = &rest[1..];
        }
        absolute.extend(rest.iter().cloned());
        Some(absolute)
    }

    /// The file a path of the module `from` lands in: the longest module prefix that is a file
    /// of the crate, followed through that file's re-exports to where the name is declared;
    /// `None` for paths outside the crate.
    fn resolve(from: &[String], path: &[String], krate: &Crate) -> Option<String> {
        let mut path = absolute(from, path, krate)?;
        for _ in 0..8 {
            let n = (0..=path.len())
                .rev()
                .find(|&n| krate.modules.contains_key(&path[..n]))?;
            let file = &krate.modules[&path[..n]];
            let next = path
                .get(n)
                .and_then(|name| krate.reexports.get(file)?.get(name));
            match next.and_then(|to| absolute(&path[..n], to, krate)) {
                Some(to) => path = [&to[..], &path[n + 1..]].concat(),
                None => return Some(file.clone()),
            }
        }
        krate.modules.get(&path).cloned()
    }

    /// A crate's import graph: file → files it imports (children's re-exports left out).
    fn import_graph(crate_dir: &Path) -> BTreeMap<String, BTreeSet<String>> {
        let files = sources(crate_dir);
        let krate = Crate {
            modules: files.keys().map(|f| (module_path(f), f.clone())).collect(),
            reexports: files
                .iter()
                .map(|(f, parsed)| (f.clone(), reexports(parsed)))
                .collect(),
        };
        let mut graph = BTreeMap::new();
        for (file, parsed) in &files {
            let from = module_path(file);
            let mut paths = Paths::default();
            paths.visit_file(parsed);
            let targets = paths
                .0
                .iter()
                .filter_map(|p| resolve(&from, p, &krate))
                .filter(|t| t != file && !module_path(t).starts_with(&from))
                .collect();
            graph.insert(file.clone(), targets);
        }
        graph
    }

    /// The strongly connected components of more than one file (Tarjan's algorithm).
    fn circles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<BTreeSet<String>> {
        struct Walk<'g> {
            graph: &'g BTreeMap<String, BTreeSet<String>>,
            index: BTreeMap<&'g str, usize>,
            low: BTreeMap<&'g str, usize>,
            stack: Vec<&'g str>,
            found: Vec<BTreeSet<String>>,
        }
        impl<'g> Walk<'g> {
            fn visit(&mut self, v: &'g str) {
                let n = self.index.len();
                self.index.insert(v, n);
                self.low.insert(v, n);
                self.stack.push(v);
                for w in self.graph.get(v).into_iter().flatten() {
                    if !self.index.contains_key(w.as_str()) {
                        self.visit(w);
                        let low = self.low[v].min(self.low[w.as_str()]);
                        self.low.insert(v, low);
                    } else if self.stack.contains(&w.as_str()) {
                        let low = self.low[v].min(self.index[w.as_str()]);
                        self.low.insert(v, low);
                    }
                }
                if self.low[v] == self.index[v] {
                    let mut component = BTreeSet::new();
                    while let Some(w) = self.stack.pop() {
                        component.insert(w.to_string());
                        if w == v {
                            break;
                        }
                    }
                    if component.len() > 1 {
                        self.found.push(component);
                    }
                }
            }
        }
        let mut walk = Walk {
            graph,
            index: BTreeMap::new(),
            low: BTreeMap::new(),
            stack: Vec::new(),
            found: Vec::new(),
        };
        for v in graph.keys() {
            if !walk.index.contains_key(v.as_str()) {
                walk.visit(v);
            }
        }
        walk.found
    }

    #[test]
    fn import_circles_are_the_ones_architecture_md_explains() {
        let architecture =
            std::fs::read_to_string(workspace_root().join("ARCHITECTURE.md")).expect("readable");
        let section = architecture
            .split("## Import circles")
            .nth(1)
            .expect("ARCHITECTURE.md has an \"Import circles\" section");
        let mut found = Vec::new();
        for dir in crate_dirs() {
            let name = dir
                .file_name()
                .expect("a name")
                .to_string_lossy()
                .into_owned();
            for circle in circles(&import_graph(&dir)) {
                let files: Vec<&str> = circle.iter().map(String::as_str).collect();
                found.push((name.clone(), files.join(" ↔ ")));
            }
        }
        let explained: Vec<(String, String)> = EXPLAINED_CIRCLES
            .iter()
            .map(|(name, files)| (name.to_string(), files.join(" ↔ ")))
            .collect();
        assert_eq!(
            found, explained,
            "the workspace's import circles (crate, files)"
        );
        for (name, files) in EXPLAINED_CIRCLES {
            let all_named = files
                .iter()
                .all(|f| section.contains(&format!("{name}/{f}")));
            assert!(
                all_named,
                "ARCHITECTURE.md's section does not explain {name}: {files:?}"
            );
        }
    }

    #[test]
    fn the_circle_search_finds_a_loop_and_leaves_a_chain() {
        let edges = [("a", "b"), ("b", "c"), ("c", "a"), ("c", "d")];
        let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for (from, to) in edges {
            graph.entry(from.into()).or_default().insert(to.into());
            graph.entry(to.into()).or_default();
        }
        let found = circles(&graph);
        let expected: BTreeSet<String> = ["a", "b", "c"].map(String::from).into();
        assert_eq!(found, [expected]);
    }

    #[test]
    fn a_use_path_lands_in_the_file_that_declares_its_name() {
        let files = [
            "src/lib.rs",
            "src/config/mod.rs",
            "src/config/task.rs",
            "src/env.rs",
        ];
        let modules = files.map(|f| (module_path(f), f.to_string())).into();
        let path = |s: &str| s.split("::").map(String::from).collect::<Vec<_>>();
        let config = BTreeMap::from([("TaskConfig".to_string(), path("task::TaskConfig"))]);
        let reexports = BTreeMap::from([("src/config/mod.rs".to_string(), config)]);
        let krate = Crate { modules, reexports };
        let from = module_path("src/env.rs");
        let land = |p: &str| resolve(&from, &path(p), &krate);
        assert_eq!(land("crate::env::Env").as_deref(), Some("src/env.rs"));
        assert_eq!(
            land("crate::config::Other").as_deref(),
            Some("src/config/mod.rs")
        );
        assert_eq!(
            land("crate::config::TaskConfig").as_deref(),
            Some("src/config/task.rs")
        );
        assert_eq!(land("crate::Thing").as_deref(), Some("src/lib.rs"));
        assert_eq!(land("nalgebra::Vector3"), None);
        let from_task = module_path("src/config/task.rs");
        let up = resolve(&from_task, &path("super::Other"), &krate);
        assert_eq!(up.as_deref(), Some("src/config/mod.rs"));
    }
}
