//! The shape of the source, checked: no module imports another that imports it back (directly or
//! around a loop), no source file over 700 lines, and no function over 100 lines unless a
//! `// Long:` comment above it says why. (Issue 15: a reader follows the code in minutes.)

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

const MAX_FILE_LINES: usize = 700;
const MAX_FN_LINES: usize = 100;

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("source directory") {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every Rust source of the crate and of tools/plot (tests excluded: they are leaves).
fn sources() -> Vec<PathBuf> {
    let mut files = Vec::new();
    rust_files(&root().join("src"), &mut files);
    rust_files(&root().join("tools/plot/src"), &mut files);
    files.sort();
    files
}

/// `src/render/passes/mod.rs` → ["render", "passes"]; lib.rs and main.rs → [].
fn module_path(file: &Path, src: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).expect("under src");
    let mut parts: Vec<String> = rel
        .iter()
        .map(|p| p.to_string_lossy().trim_end_matches(".rs").to_string())
        .collect();
    if matches!(
        parts.last().map(String::as_str),
        Some("mod" | "lib" | "main")
    ) {
        parts.pop();
    }
    parts
}

/// The crate paths (`crate::a::b`, `super::c`) a file names, resolved to absolute segments.
fn referenced_paths(text: &str, module: &[String], is_mod_file: bool) -> Vec<Vec<String>> {
    // For `a/b.rs` (module a::b) `super` is `a`; for `a/mod.rs` (module a) it is the parent of a.
    let own = module.to_vec();
    let mut out = Vec::new();
    let code: String = text
        .lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n");
    let bytes = code.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        if !code.is_char_boundary(i) {
            i += 1;
            continue;
        }
        let rest = &code[i..];
        let start_ok = i == 0
            || !(bytes[i - 1].is_ascii_alphanumeric()
                || bytes[i - 1] == b'_'
                || bytes[i - 1] == b':');
        if start_ok && (rest.starts_with("crate::") || rest.starts_with("super::")) {
            // Read the path up to whatever ends it; expand one level of `{a, b::c}`.
            let end = rest
                .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                .unwrap_or(rest.len());
            let head = &rest[..end];
            let mut segments: Vec<String> = head
                .split("::")
                .filter(|s| !s.is_empty())
                .map(str::to_string)
                .collect();
            let mut base: Vec<String> = Vec::new();
            let mut k = 0;
            if segments.first().map(String::as_str) == Some("crate") {
                k = 1;
            } else {
                base = own.clone();
                if !is_mod_file {
                    base.pop();
                }
                while segments.get(k).map(String::as_str) == Some("super") {
                    if k > 0 {
                        base.pop();
                    }
                    k += 1;
                }
                // The first `super` of a mod.rs file is the parent module.
                if is_mod_file {
                    base.pop();
                }
            }
            segments.drain(..k);
            let prefix: Vec<String> = base.into_iter().chain(segments).collect();
            if rest[end..].starts_with('{') {
                let close = rest[end..].find('}').map_or(rest.len(), |c| end + c);
                for item in rest[end + 1..close].split(',') {
                    let first = item.trim().split("::").next().unwrap_or("").trim();
                    if !first.is_empty() {
                        let mut p = prefix.clone();
                        p.push(first.to_string());
                        out.push(p);
                    }
                }
            }
            out.push(prefix);
            i += end.max(1);
        } else {
            i += 1;
        }
    }
    out
}

/// Module → the modules it uses (the longest module prefix of each path; children and
/// parents of a module are not edges: a parent declares its children).
fn module_graph(src: &Path, files: &[PathBuf]) -> BTreeMap<Vec<String>, BTreeSet<Vec<String>>> {
    let modules: BTreeSet<Vec<String>> = files.iter().map(|f| module_path(f, src)).collect();
    let mut graph = BTreeMap::new();
    for file in files {
        let module = module_path(file, src);
        let is_mod = matches!(
            file.file_name().and_then(|n| n.to_str()),
            Some("mod.rs" | "lib.rs" | "main.rs")
        );
        let text = std::fs::read_to_string(file).expect("readable source");
        let mut deps = BTreeSet::new();
        for path in referenced_paths(&text, &module, is_mod) {
            let target = (0..=path.len())
                .rev()
                .map(|n| path[..n].to_vec())
                .find(|p| modules.contains(p))
                .unwrap_or_default();
            let related = target.starts_with(&module) || module.starts_with(&target);
            if !related {
                deps.insert(target);
            }
        }
        graph.insert(module, deps);
    }
    graph
}

/// Strongly connected components with more than one module (Tarjan).
fn cycles(graph: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>) -> Vec<Vec<Vec<String>>> {
    struct State<'a> {
        graph: &'a BTreeMap<Vec<String>, BTreeSet<Vec<String>>>,
        index: BTreeMap<&'a Vec<String>, usize>,
        low: BTreeMap<&'a Vec<String>, usize>,
        stack: Vec<&'a Vec<String>>,
        found: Vec<Vec<Vec<String>>>,
    }
    fn visit<'a>(s: &mut State<'a>, v: &'a Vec<String>) {
        let n = s.index.len();
        s.index.insert(v, n);
        s.low.insert(v, n);
        s.stack.push(v);
        for w in s.graph.get(v).into_iter().flatten() {
            let Some((w, _)) = s.graph.get_key_value(w) else {
                continue;
            };
            if !s.index.contains_key(w) {
                visit(s, w);
                let low = s.low[v].min(s.low[w]);
                s.low.insert(v, low);
            } else if s.stack.contains(&w) {
                let low = s.low[v].min(s.index[w]);
                s.low.insert(v, low);
            }
        }
        if s.low[v] == s.index[v] {
            let mut component = Vec::new();
            while let Some(w) = s.stack.pop() {
                component.push(w.clone());
                if w == v {
                    break;
                }
            }
            if component.len() > 1 {
                s.found.push(component);
            }
        }
    }
    let mut s = State {
        graph,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        found: Vec::new(),
    };
    for v in graph.keys() {
        if !s.index.contains_key(v) {
            visit(&mut s, v);
        }
    }
    s.found
}

#[test]
fn no_module_imports_one_that_imports_it_back() {
    for src in [root().join("src"), root().join("tools/plot/src")] {
        let mut files = Vec::new();
        rust_files(&src, &mut files);
        let graph = module_graph(&src, &files);
        assert!(graph.len() >= 3, "{} parsed", src.display());
        let found = cycles(&graph);
        let names: Vec<Vec<String>> = found
            .iter()
            .map(|c| c.iter().map(|m| m.join("::")).collect())
            .collect();
        assert!(
            names.is_empty(),
            "module cycles in {}: {names:?}",
            src.display()
        );
    }
}

#[test]
fn the_cycle_finder_finds_a_cycle() {
    // So that the test above cannot pass by finding nothing.
    let m = |s: &str| vec![s.to_string()];
    let mut graph = BTreeMap::new();
    graph.insert(m("a"), BTreeSet::from([m("b")]));
    graph.insert(m("b"), BTreeSet::from([m("c")]));
    graph.insert(m("c"), BTreeSet::from([m("a")]));
    graph.insert(m("d"), BTreeSet::from([m("a")]));
    assert_eq!(cycles(&graph).len(), 1);
    let resolved = referenced_paths(
        "use super::camera::Camera;\nuse crate::gpu::{Buffer, track::Use};\n",
        &["render".to_string(), "frame".to_string()],
        false,
    );
    assert!(resolved.contains(&vec!["render".into(), "camera".into(), "Camera".into()]));
    assert!(resolved.contains(&vec!["gpu".into(), "track".into()]));
}

#[test]
fn no_source_file_is_over_700_lines() {
    let long: Vec<String> = sources()
        .iter()
        .filter_map(|f| {
            let n = std::fs::read_to_string(f)
                .expect("readable")
                .lines()
                .count();
            (n > MAX_FILE_LINES).then(|| format!("{} ({n} lines)", f.display()))
        })
        .collect();
    assert!(long.is_empty(), "over {MAX_FILE_LINES} lines: {long:?}");
}

#[test]
fn functions_over_100_lines_say_why() {
    let mut unexplained = Vec::new();
    for file in sources() {
        let text = std::fs::read_to_string(&file).expect("readable");
        let lines: Vec<&str> = text.lines().collect();
        for (i, line) in lines.iter().enumerate() {
            let trimmed = line.trim_start();
            let indent = &line[..line.len() - trimmed.len()];
            let is_fn = [
                "fn ",
                "pub fn ",
                "pub(crate) fn ",
                "pub(super) fn ",
                "const fn ",
            ]
            .iter()
            .any(|p| trimmed.starts_with(p));
            if !is_fn || trimmed.ends_with(';') {
                continue;
            }
            let close = format!("{indent}}}");
            let Some(end) = lines[i + 1..].iter().position(|l| *l == close) else {
                continue;
            };
            let length = end + 2;
            // The comment block (and attributes) right above the function.
            let explained = lines[..i]
                .iter()
                .rev()
                .take_while(|l| {
                    let t = l.trim_start();
                    t.starts_with("//") || t.starts_with("#[")
                })
                .any(|l| l.contains("Long:"));
            if length > MAX_FN_LINES && !explained {
                unexplained.push(format!("{}:{} ({length} lines)", file.display(), i + 1));
            }
        }
    }
    assert!(
        unexplained.is_empty(),
        "functions over {MAX_FN_LINES} lines without a `// Long:` comment: {unexplained:?}"
    );
}
