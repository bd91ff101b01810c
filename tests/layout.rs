//! The shape of the source, checked: no module imports another that imports it back (directly or
//! around a loop), every `crate::` / `super::` path points down the layers (`LAYERS`), no source
//! file over 700 lines, and no function over 100 lines unless a `// Long:` comment above it says
//! why. (Issue 15: a reader follows the code in minutes; issue 31: arrows only run down.)

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

const MAX_FILE_LINES: usize = 700;
const MAX_FN_LINES: usize = 100;

/// The crate's top-level modules, bottom layer first (README, Code layout). A module may use
/// modules of lower layers only: not its own layer's others, not a higher one. The crate root
/// (lib.rs, main.rs and the `shaders` lib.rs includes) is above and below everything: lib.rs
/// declares the modules, main.rs is the top, `crate::shaders` and the `outln!` macro are the
/// root's and free to use. A new top-level module must be given a layer here.
const LAYERS: &[&[&str]] = &[
    // Leaves: no crate imports. The frame's pass names, GLSL-shared constants, defensive input
    // files, the OS differences.
    &["pass_names", "shared", "input", "platform"],
    // Vulkan (with the platform's loader advice); the stop flag (with its signal handlers).
    &["gpu", "interrupt"],
    // The simulation (on gpu); statistics and the profile JSON (gpu's timings); output files
    // (checked against the stop flag).
    &["ocean", "profile", "output"],
    // The passes that record the frame.
    &["render"],
    // What a running sample can change, and the presets that fill it (ocean's and render's
    // enums): below the frontend whose overlay edits it.
    &["tuning"],
    // Window or headless, the overlay, the session.
    &["frontend"],
    // bench fft / frames / gerstner (run sessions of the frontend).
    &["bench"],
    // The command line: parses, resolves presets, builds settings for frontend and bench.
    &["cli"],
];

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
    let texts: Vec<(PathBuf, String)> = files
        .iter()
        .map(|f| {
            (
                f.clone(),
                std::fs::read_to_string(f).expect("readable source"),
            )
        })
        .collect();
    module_graph_of(src, &texts)
}

/// [`module_graph`] of (path, source text) pairs (the layer checker's test feeds it made-up
/// files).
fn module_graph_of(
    src: &Path,
    files: &[(PathBuf, String)],
) -> BTreeMap<Vec<String>, BTreeSet<Vec<String>>> {
    let modules: BTreeSet<Vec<String>> = files.iter().map(|(f, _)| module_path(f, src)).collect();
    let mut graph = BTreeMap::new();
    for (file, text) in files {
        let module = module_path(file, src);
        let is_mod = matches!(
            file.file_name().and_then(|n| n.to_str()),
            Some("mod.rs" | "lib.rs" | "main.rs")
        );
        let mut deps = BTreeSet::new();
        for path in referenced_paths(text, &module, is_mod) {
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

/// The layer of top-level module `name` (an index into `LAYERS`), `None` if it has none.
fn layer_of(name: &str) -> Option<usize> {
    LAYERS.iter().position(|layer| layer.contains(&name))
}

/// Every import that does not point down the layers, as "a::b uses c::d (layer i → j)", and
/// every top-level module without a layer. The crate root (module path []) is exempt.
fn layer_violations(graph: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>) -> Vec<String> {
    let mut found = BTreeSet::new();
    for (module, deps) in graph {
        let Some(top) = module.first() else {
            continue; // lib.rs, main.rs
        };
        let Some(from) = layer_of(top) else {
            found.insert(format!("module `{top}` has no layer in LAYERS"));
            continue;
        };
        for dep in deps {
            let Some(target) = dep.first() else {
                continue; // the root's `shaders`, `outln!`
            };
            if target == top {
                continue; // inside one top-level module
            }
            match layer_of(target) {
                Some(to) if to < from => {}
                Some(to) => {
                    found.insert(format!(
                        "{} uses {} (layer {from} `{top}` → layer {to} `{target}`: not below)",
                        module.join("::"),
                        dep.join("::")
                    ));
                }
                None => {
                    found.insert(format!("module `{target}` has no layer in LAYERS"));
                }
            }
        }
    }
    found.into_iter().collect()
}

#[test]
fn every_import_points_down_the_layers() {
    let src = root().join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let graph = module_graph(&src, &files);
    let violations = layer_violations(&graph);
    assert!(
        violations.is_empty(),
        "imports against the layer order {LAYERS:?}:\n{}",
        violations.join("\n")
    );
    // Every layer's modules exist (a renamed module must be renamed here too).
    for name in LAYERS.iter().flat_map(|l| l.iter()) {
        assert!(
            graph
                .keys()
                .any(|m| m.first().map(String::as_str) == Some(*name)),
            "LAYERS names `{name}`, which is not a module of src/"
        );
    }
}

#[test]
fn the_layer_checker_finds_an_upward_import() {
    // Made-up files: the frontend importing the command line (issue 31's arrow up the
    // layers), through `crate::` and through `super::`, and one import down, which is fine.
    let src = PathBuf::from("/made-up/src");
    let file = |path: &str, text: &str| (src.join(path), text.to_string());
    let files = [
        file("lib.rs", "pub mod cli;\npub mod frontend;\npub mod gpu;\n"),
        file("gpu/mod.rs", "pub struct Context;\n"),
        file(
            "cli/mod.rs",
            "pub mod tuning;\nuse crate::frontend::RunSettings;\n",
        ),
        file("cli/tuning.rs", "pub struct Tunables;\n"),
        file(
            "frontend/mod.rs",
            "pub mod overlay;\nuse crate::gpu::Context;\npub struct RunSettings;\n",
        ),
        file(
            "frontend/overlay.rs",
            "use crate::cli::tuning::Tunables;\nuse super::super::cli::{tuning};\n",
        ),
    ];
    let graph = module_graph_of(&src, &files);
    let violations = layer_violations(&graph);
    // Only the overlay's imports (`cli` from `super::super::cli`, `cli::tuning` from both);
    // cli → frontend and frontend → gpu point down.
    assert!(
        violations
            .iter()
            .any(|v| v.starts_with("frontend::overlay uses cli::tuning")),
        "{violations:?}"
    );
    assert!(
        violations
            .iter()
            .all(|v| v.starts_with("frontend::overlay uses cli")),
        "{violations:?}"
    );
    // A module outside the order is reported too.
    let stray = [
        file("lib.rs", ""),
        file("newthing.rs", "use crate::gpu::Context;\n"),
    ];
    let stray = [stray[0].clone(), stray[1].clone(), files[1].clone()];
    let violations = layer_violations(&module_graph_of(&src, &stray));
    assert_eq!(
        violations,
        vec!["module `newthing` has no layer in LAYERS".to_string()]
    );
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
