//! The crate's import structure, read from the source text: the layers
//! import only to their left in the order the crate docs state, and no two
//! sibling files import from each other.
//!
//! The reading is deliberately simple (no parser): comments are dropped,
//! each file is cut at its first inline `#[cfg(test)] mod NAME {` (test
//! code may reach further, as the crate docs say), and every `use` tree and every inline
//! `crate::…`/`super::…` path is resolved to the file that defines its
//! module, following one level of `pub use` re-exports so that an import
//! through a parent's re-export counts as an import of the file behind it.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The layers, left to right, as `src/lib.rs` lists them; folders on one
/// rank do not import each other.
const LAYERS: [&[&str]; 8] = [
    &["integrate"],
    &["model"],
    &["sim"],
    &["analysis"],
    &["io"],
    &["plot"],
    &["bench", "reproduce"],
    &["cli", "gui"],
];

/// One source file: its module path (`["io", "record", "cosmos"]`) and its
/// non-test code without comments.
struct Source {
    module: Vec<String>,
    code: String,
}

fn sources() -> BTreeMap<PathBuf, Source> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    walk(&src, &mut files);
    files
        .into_iter()
        .map(|path| {
            let module = module_of(&path);
            let text = std::fs::read_to_string(&path).unwrap();
            let code = without_comments(&text);
            let code = match test_module_at(&code) {
                Some(at) => code[..at].to_string(),
                None => code,
            };
            (path, Source { module, code })
        })
        .collect()
}

/// Where the first inline test module (`#[cfg(test)] mod NAME {`) starts:
/// a test module in a file of its own (`mod tests;`) is read whole.
fn test_module_at(code: &str) -> Option<usize> {
    code.match_indices("#[cfg(test)]\nmod ").map(|(at, _)| at).find(|&at| {
        let rest = &code[at + "#[cfg(test)]\nmod ".len()..];
        let name_end = rest
            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
            .unwrap_or(rest.len());
        rest[name_end..].trim_start().starts_with('{')
    })
}

/// `text` without `//` and `/* */` comments (string literals holding `//`
/// lose the rest of their line, which holds no import in this crate).
fn without_comments(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while !rest.is_empty() {
        if let Some(after) = rest.strip_prefix("/*") {
            rest = after.split_once("*/").map_or("", |(_, r)| r);
        } else if rest.starts_with("//") {
            rest = rest.find('\n').map_or("", |i| &rest[i..]);
        } else {
            let c = rest.chars().next().unwrap();
            out.push(c);
            rest = &rest[c.len_utf8()..];
        }
    }
    out
}

/// The paths of a `use` tree (`a::{b, c::{d as e}}` gives `a::b`, `a::c::d`).
fn expand(tree: &str) -> Vec<Vec<String>> {
    let tree = tree.trim();
    let Some(open) = tree.find('{') else {
        let path = tree.split(" as ").next().unwrap();
        return vec![
            path.split("::")
                .map(str::trim)
                .filter(|s| !s.is_empty() && *s != "*")
                .map(String::from)
                .collect(),
        ];
    };
    let close = tree.rfind('}').unwrap();
    let prefix: Vec<String> = tree[..open]
        .split("::")
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(String::from)
        .collect();
    let (mut parts, mut depth, mut start) = (Vec::new(), 0, open + 1);
    for (i, c) in tree[..close].char_indices().skip_while(|&(i, _)| i <= open) {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&tree[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push(&tree[start..close]);
    parts
        .into_iter()
        .filter(|p| !p.trim().is_empty())
        .flat_map(expand)
        .map(|tail| prefix.iter().cloned().chain(tail).collect())
        .collect()
}

/// Every path `code` names: its `use` trees (`pub use` ones separately
/// too) and its inline `crate::…`/`super::…` paths.
fn paths(code: &str) -> (Vec<Vec<String>>, Vec<Vec<String>>) {
    let (mut all, mut reexports) = (Vec::new(), Vec::new());
    let is_ident = |c: char| c.is_alphanumeric() || c == '_';
    for (at, _) in code.match_indices("use ") {
        if code[..at].chars().next_back().is_some_and(is_ident) {
            continue;
        }
        // A `use` item starts its line (after `pub` or `pub(…)`): the word
        // in a string or a comment ("use --batch …") is not one.
        let line = &code[code[..at].rfind('\n').map_or(0, |i| i + 1)..at];
        let before = line.trim();
        if !(before.is_empty() || before == "pub" || (before.starts_with("pub(") && before.ends_with(')'))) {
            continue;
        }
        let Some(end) = code[at..].find(';') else { continue };
        let trees = expand(&code[at + 4..at + end]);
        let head = code[..at].trim_end();
        if head.ends_with("pub") || head.ends_with(')') && head.contains("pub(") {
            reexports.extend(trees.iter().cloned());
        }
        all.extend(trees);
    }
    for root in ["crate::", "super::"] {
        for (at, _) in code.match_indices(root) {
            if code[..at]
                .chars()
                .next_back()
                .is_some_and(|c| is_ident(c) || c == ':' || c == '$')
            {
                continue;
            }
            let len = code[at..]
                .find(|c: char| !(is_ident(c) || c == ':'))
                .unwrap_or(code.len() - at);
            all.push(
                code[at..at + len]
                    .split("::")
                    .filter(|s| !s.is_empty())
                    .map(String::from)
                    .collect(),
            );
        }
    }
    (all, reexports)
}

/// The absolute module path of `path` as named in the module `module`
/// (`None` for a path outside the crate).
fn absolute(path: &[String], module: &[String], modules: &BTreeSet<Vec<String>>) -> Option<Vec<String>> {
    let first = path.first()?;
    let mut abs: Vec<String> = match first.as_str() {
        "crate" => path[1..].to_vec(),
        "super" => {
            let ups = path.iter().take_while(|s| *s == "super").count();
            let base = module.get(..module.len().checked_sub(ups)?)?;
            base.iter().chain(&path[ups..]).cloned().collect()
        }
        "self" => module.iter().chain(&path[1..]).cloned().collect(),
        name => {
            let child: Vec<String> = module.iter().cloned().chain([name.to_string()]).collect();
            if !modules.contains(&child) {
                return None;
            }
            module.iter().chain(path).cloned().collect()
        }
    };
    abs.retain(|s| s != "self");
    Some(abs)
}

/// Which files import from which (the key file imports from each file of
/// its set).
fn imports() -> BTreeMap<PathBuf, BTreeSet<PathBuf>> {
    let sources = sources();
    let by_module: BTreeMap<Vec<String>, PathBuf> = sources
        .iter()
        .map(|(path, s)| (s.module.clone(), path.clone()))
        .collect();
    let modules: BTreeSet<Vec<String>> = by_module.keys().cloned().collect();
    let file_of = |abs: &[String]| {
        (0..=abs.len())
            .rev()
            .find_map(|k| by_module.get(&abs[..k]).map(|f| (f.clone(), k)))
    };
    // (file, name) -> the file a `pub use` there takes `name` from.
    let mut reexported: BTreeMap<(PathBuf, String), PathBuf> = BTreeMap::new();
    for (path, s) in &sources {
        for p in paths(&s.code).1 {
            if let Some(abs) = absolute(&p, &s.module, &modules)
                && let (Some((target, _)), Some(name)) = (file_of(&abs), abs.last())
                && &target != path
            {
                reexported.insert((path.clone(), name.clone()), target);
            }
        }
    }
    sources
        .iter()
        .map(|(path, s)| {
            let targets = paths(&s.code)
                .0
                .iter()
                .filter_map(|p| absolute(p, &s.module, &modules))
                .filter_map(|abs| {
                    let (file, k) = file_of(&abs)?;
                    let behind = abs
                        .get(k)
                        .and_then(|name| reexported.get(&(file.clone(), name.clone())));
                    Some(behind.cloned().unwrap_or(file))
                })
                .filter(|f| f != path)
                .collect();
            (path.clone(), targets)
        })
        .collect()
}

/// The module path of a file under `src` (`src/io/record/mod.rs` is
/// `["io", "record"]`, `src/lib.rs` the empty path).
fn module_of(path: &Path) -> Vec<String> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut m: Vec<String> = path
        .strip_prefix(&src)
        .unwrap()
        .with_extension("")
        .iter()
        .map(|s| s.to_string_lossy().into_owned())
        .collect();
    if matches!(m.last().map(String::as_str), Some("mod" | "lib" | "main")) {
        m.pop();
    }
    m
}

#[test]
fn no_two_sibling_files_import_from_each_other() {
    let imports = imports();
    // A parent module and its own submodule are one module split in files
    // (the child sees the parent's items by `super::`): not a circle.
    let parent_and_child = |a: &Path, b: &Path| {
        let (ma, mb) = (module_of(a), module_of(b));
        mb.len() == ma.len() + 1 && mb.starts_with(&ma) || ma.len() == mb.len() + 1 && ma.starts_with(&mb)
    };
    let mut circles = Vec::new();
    for (a, targets) in &imports {
        for b in targets {
            if a < b && imports[b].contains(a) && !parent_and_child(a, b) {
                circles.push(format!("{} <-> {}", a.display(), b.display()));
            }
        }
    }
    assert!(
        circles.is_empty(),
        "files importing from each other:\n{}",
        circles.join("\n")
    );
}

#[test]
fn each_layer_imports_only_layers_to_its_left() {
    let rank = |folder: &str| LAYERS.iter().position(|r| r.contains(&folder));
    let mut wrong = Vec::new();
    for (from, targets) in imports() {
        let Some(r_from) = module_of(&from).first().and_then(|f| rank(f)) else {
            continue;
        };
        for to in targets {
            let to_module = module_of(&to);
            let Some(r_to) = to_module.first().and_then(|f| rank(f)) else {
                continue;
            };
            if r_to > r_from || r_to == r_from && module_of(&from)[0] != to_module[0] {
                wrong.push(format!("{} -> {}", from.display(), to.display()));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "imports against the layer order:\n{}",
        wrong.join("\n")
    );
}

/// The checks above read the source correctly: they find a circle and an
/// upward import that are put in front of them.
#[test]
fn the_reading_finds_imports_through_braces_re_exports_and_inline_paths() {
    assert_eq!(
        expand("super::{a::B, c::{D as E, self}}"),
        vec![
            vec!["super", "a", "B"],
            vec!["super", "c", "D"],
            vec!["super", "c", "self"]
        ]
    );
    let (all, reexports) = paths("pub use run::{Method};\nfn f() { crate::io::load(); x::super_y(); }");
    assert_eq!(reexports, vec![vec!["run", "Method"]]);
    assert_eq!(all, vec![vec!["run", "Method"], vec!["crate", "io", "load"]]);
    assert_eq!(without_comments("a // b\n/* c */d"), "a \nd");
    assert_eq!(
        test_module_at("x\n#[cfg(test)]\nmod files;\ny\n#[cfg(test)]\nmod tests {"),
        Some(28)
    );
    // The sim folder imports its own `method` and `run` files: both are found.
    let imports = imports();
    let sim = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/sim");
    assert!(imports[&sim.join("run.rs")].contains(&sim.join("method.rs")));
    // ... and `scenario.rs` takes `Method` from `method.rs`, not through `mod.rs`.
    assert!(imports[&sim.join("scenario.rs")].contains(&sim.join("method.rs")));
    // An import through a parent's `pub use` counts as one of the file behind
    // it: `sim::Scenario` from the app's thread is `sim/scenario.rs`.
    let runner = sim.join("runner.rs");
    assert!(
        imports[&runner].contains(&sim.join("scenario.rs")),
        "{:?}",
        imports[&runner]
    );
}
