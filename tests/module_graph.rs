//! Every crate's modules import one way: no module reaches, through `crate::`
//! paths in its file or its folder (tests included), a module that reaches it.
//! Cargo keeps the crates acyclic; this keeps the modules inside each so.
//! Comment lines do not count: a doc link is not an import.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The modules each module names through `crate::`, from the texts of its
/// files: `crate::a`, and each path of a group `crate::{a, b::c}`.
fn imports(texts: &[String]) -> Vec<String> {
    let mut names = Vec::new();
    for text in texts {
        let code: String = text.lines().filter(|line| !line.trim_start().starts_with("//")).collect::<Vec<_>>().join("\n");
        for (at, _) in code.match_indices("crate::") {
            let rest = &code[at + "crate::".len()..];
            match rest.strip_prefix('{') {
                Some(group) => {
                    let group = &group[..group.find('}').unwrap_or(group.len())];
                    names.extend(group.split(',').map(|path| first_name(path.trim())));
                }
                None => names.push(first_name(rest)),
            }
        }
    }
    names.retain(|name| !name.is_empty());
    names
}

fn first_name(path: &str) -> String {
    path.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect()
}

/// Each module of `src/` (a file `NAME.rs`, with the files of a folder `NAME/`)
/// and the other modules it imports. The crate's root (`lib.rs`, `main.rs`)
/// is no module of the graph: every module may use what it defines.
fn module_graph(src: &Path) -> BTreeMap<String, Vec<String>> {
    let mut texts: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for entry in std::fs::read_dir(src).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_str().unwrap().to_string();
        let files: Vec<_> = if path.is_dir() {
            rust_files(&path)
        } else if path.extension().is_some_and(|e| e == "rs") && name != "lib" && name != "main" {
            vec![path.clone()]
        } else {
            Vec::new()
        };
        texts.entry(name).or_default().extend(files.iter().map(|f| std::fs::read_to_string(f).unwrap()));
    }
    let modules: Vec<String> = texts.keys().cloned().collect();
    texts
        .into_iter()
        .map(|(name, texts)| {
            let mut imported: Vec<String> = imports(&texts).into_iter().filter(|m| *m != name && modules.contains(m)).collect();
            imported.sort();
            imported.dedup();
            (name, imported)
        })
        .collect()
}

/// The `.rs` files under `dir`, at any depth.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files.extend(rust_files(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            files.push(path);
        }
    }
    files
}

/// A circle of imports in `graph`, if it has one, as the modules along it.
fn circle(graph: &BTreeMap<String, Vec<String>>) -> Option<Vec<String>> {
    fn visit<'a>(module: &'a str, graph: &'a BTreeMap<String, Vec<String>>, path: &mut Vec<&'a str>, done: &mut Vec<&'a str>) -> Option<Vec<String>> {
        if let Some(start) = path.iter().position(|m| *m == module) {
            return Some(path[start..].iter().chain([&module]).map(|m| m.to_string()).collect());
        }
        if done.contains(&module) {
            return None;
        }
        path.push(module);
        for next in &graph[module] {
            if let Some(found) = visit(next, graph, path, done) {
                return Some(found);
            }
        }
        path.pop();
        done.push(module);
        None
    }
    let mut done = Vec::new();
    graph.keys().find_map(|module| visit(module, graph, &mut Vec::new(), &mut done))
}

#[test]
fn every_crates_modules_import_one_way() {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR")).join("crates");
    let mut circles = Vec::new();
    let mut read = Vec::new();
    for entry in std::fs::read_dir(&crates).unwrap() {
        let src = entry.unwrap().path().join("src");
        if !src.is_dir() {
            continue;
        }
        let name = src.parent().unwrap().file_name().unwrap().to_string_lossy().into_owned();
        let graph = module_graph(&src);
        if let Some(circle) = circle(&graph) {
            circles.push(format!("{name}: {}", circle.join(" → ")));
        }
        read.push((name, graph));
    }
    let graph_of = |crate_name: &str| &read.iter().find(|(name, _)| name == crate_name).unwrap_or_else(|| panic!("{crate_name} was read")).1;
    assert!(graph_of("glint-encoding")["gpu_types"].contains(&"gpu_bvh".to_string()), "the graphs were read");
    assert!(graph_of("glint-gpu")["renderer"].contains(&"pipelines".to_string()), "the graphs were read");
    assert!(read.len() >= 10, "every crate: {:?}", read.iter().map(|(name, _)| name).collect::<Vec<_>>());
    assert!(circles.is_empty(), "modules import in a circle:\n{}", circles.join("\n"));
}

#[test]
fn a_circle_is_found_and_named() {
    let texts = |text: &str| vec![text.to_string()];
    assert_eq!(imports(&texts("use crate::a::X;\nuse crate::{b, c::Y};\nlet z = crate::d::f();\n/// [`crate::e`]")), ["a", "b", "c", "d"]);
    let graph: BTreeMap<String, Vec<String>> =
        [("a", vec!["b"]), ("b", vec!["c"]), ("c", vec!["a"]), ("d", vec![])].map(|(m, to)| (m.to_string(), to.into_iter().map(String::from).collect())).into();
    assert_eq!(circle(&graph).unwrap(), ["a", "b", "c", "a"]);
    let one_way: BTreeMap<String, Vec<String>> = [("a", vec!["b".to_string()]), ("b", vec![])].map(|(m, to)| (m.to_string(), to)).into();
    assert_eq!(circle(&one_way), None);
}
