//! The layering of `src/`: no import circle among its files, each folder
//! importing only from the layers below it (`LAYERS`), the core knowing
//! nothing of the C layer outside `math/arch.rs`, the shared numerics below
//! every model, and tables above the phase functions, never the reverse. Reads the `crate::…` and `super::…` paths of every file
//! (comments stripped), resolves each to the deepest file it names, and
//! looks for cycles. A module's own `mod.rs` declaring and re-exporting its
//! children is not an import of them.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Every `.rs` file under `dir`.
fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The module path of a file: `src/phase/draine.rs` → `phase::draine`,
/// `src/phase/mod.rs` → `phase`, `src/lib.rs` → `` (the root).
fn module_of(src: &Path, file: &Path) -> String {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = rel
        .iter()
        .map(|c| c.to_string_lossy().into_owned())
        .collect();
    if parts.last().is_some_and(|l| l == "mod" || l == "lib") {
        parts.pop();
    }
    parts.join("::")
}

/// The identifiers after `prefix` at each of its occurrences in `code`.
fn paths_after(code: &str, prefix: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(i) = rest.find(prefix) {
        let before = rest[..i].chars().next_back();
        rest = &rest[i + prefix.len()..];
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == '$') {
            continue;
        }
        let mut segs = Vec::new();
        let mut s = rest;
        loop {
            let end = s
                .find(|c: char| !(c.is_alphanumeric() || c == '_'))
                .unwrap_or(s.len());
            if end == 0 {
                break;
            }
            segs.push(s[..end].to_string());
            s = &s[end..];
            match s.strip_prefix("::") {
                Some(t) => s = t,
                None => break,
            }
        }
        out.push(segs);
    }
    out
}

/// The deepest known module that `segs` (from the crate root) names.
fn resolve(modules: &BTreeSet<String>, segs: &[String]) -> Option<String> {
    (1..=segs.len())
        .rev()
        .map(|k| segs[..k].join("::"))
        .find(|m| modules.contains(m))
}

/// `module → modules it imports`.
fn graph() -> BTreeMap<String, BTreeSet<String>> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut all = Vec::new();
    files(&src, &mut all);
    let modules: BTreeSet<String> = all.iter().map(|f| module_of(&src, f)).collect();
    let mut g = BTreeMap::new();
    for f in &all {
        let me = module_of(&src, f);
        let code: String = std::fs::read_to_string(f)
            .unwrap()
            .lines()
            .map(|l| l.split("//").next().unwrap_or(""))
            .collect::<Vec<_>>()
            .join("\n");
        // `super` names the enclosing module: `phase` for `phase::hg` and
        // the root for `phase` (its mod.rs). Inside a file's own `mod tests`
        // it names the file itself; taking the parent there only adds an
        // edge to the parent, which a cycle through children never uses.
        let mut parent: Vec<String> = me
            .split("::")
            .filter(|s| !s.is_empty())
            .map(String::from)
            .collect();
        parent.pop();
        let mut deps = BTreeSet::new();
        for segs in paths_after(&code, "crate::") {
            match resolve(&modules, &segs) {
                Some(m) => {
                    deps.insert(m);
                }
                // A path into the root's own items (`crate::Error`, a
                // re-export) names no file; one that names a module the
                // tree lacks is a stale path the compiler would reject.
                None => assert!(
                    segs.len() <= 1 || segs[0].starts_with(char::is_uppercase),
                    "{me}: crate::{} names no module of src/",
                    segs.join("::")
                ),
            }
        }
        for segs in paths_after(&code, "super::") {
            let full: Vec<String> = parent.iter().cloned().chain(segs).collect();
            deps.extend(resolve(&modules, &full).or_else(|| Some(parent.join("::"))));
        }
        // A module's mod.rs re-exporting its children is not an import.
        deps.retain(|d| {
            d != &me && !(d.starts_with(&me) && !me.is_empty() && d[me.len()..].starts_with("::"))
        });
        if me.is_empty() {
            deps.clear();
        }
        g.insert(me, deps);
    }
    g
}

/// A cycle through `start`, if any.
fn cycle_from(g: &BTreeMap<String, BTreeSet<String>>, start: &str) -> Option<Vec<String>> {
    fn dfs(
        g: &BTreeMap<String, BTreeSet<String>>,
        node: &str,
        start: &str,
        path: &mut Vec<String>,
        seen: &mut BTreeSet<String>,
    ) -> bool {
        for next in g.get(node).into_iter().flatten() {
            if next == start {
                return true;
            }
            if seen.insert(next.clone()) {
                path.push(next.clone());
                if dfs(g, next, start, path, seen) {
                    return true;
                }
                path.pop();
            }
        }
        false
    }
    let mut path = vec![start.to_string()];
    let mut seen = BTreeSet::new();
    dfs(g, start, start, &mut path, &mut seen).then_some(path)
}

#[test]
fn no_import_circle_in_src() {
    let g = graph();
    assert!(g.len() > 20, "read only {} modules", g.len());
    let cycles: Vec<_> = g.keys().filter_map(|m| cycle_from(&g, m)).collect();
    assert!(cycles.is_empty(), "import circles: {cycles:?}");
}

#[test]
fn numerics_sit_below_the_models_and_tables_above_the_phases() {
    let g = graph();
    let numeric = &g["math::numeric"];
    assert!(
        numeric.iter().all(|d| d == "math::real"),
        "math::numeric imports {numeric:?}; it may import only math::real"
    );
    for (m, deps) in &g {
        if m.starts_with("phase") {
            assert!(
                !deps.contains("table"),
                "{m} imports table: tables sit above the phases"
            );
        }
    }
    // The cubic root is numeric's: no other model borrows it from Rayleigh.
    for (m, deps) in &g {
        let allowed = m == "ffi::rayleigh";
        assert!(
            allowed || !deps.contains("phase::rayleigh"),
            "{m} imports phase::rayleigh (the cubic root lives in numeric)"
        );
    }
}

/// The folders of `src/` (and its two top-level model files) from the
/// bottom up: a module may import from its own folder (without a circle) and
/// from folders of a lower rank, never from a higher or an equal one.
const LAYERS: [(&str, u32); 13] = [
    ("error", 0),
    ("math", 1),
    ("stokes", 2),
    ("surface", 2),
    ("mie", 2),
    ("medium", 2),
    ("phase", 3),
    ("portable", 2),
    ("table", 4),
    ("transport", 4),
    ("mixture", 5),
    ("choose", 6),
    ("ffi", 7),
];

fn rank(module: &str) -> u32 {
    let top = module.split("::").next().unwrap_or("");
    LAYERS
        .iter()
        .find(|(name, _)| *name == top)
        .unwrap_or_else(|| panic!("{module}: its folder is not in LAYERS"))
        .1
}

#[test]
fn every_folder_imports_only_downward() {
    let g = graph();
    let mut wrong = Vec::new();
    for (m, deps) in g.iter().filter(|(m, _)| !m.is_empty()) {
        let top = m.split("::").next().unwrap();
        for d in deps.iter().filter(|d| !d.is_empty()) {
            let same = d.split("::").next() == Some(top);
            if !same && rank(d) >= rank(m) {
                wrong.push(format!("{m} -> {d}"));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "imports that run up or sideways: {wrong:?}"
    );
}

/// The core (everything outside `ffi/`) names no `ffi` path, no `sk_`
/// symbol and no `ffi` feature, except `math/arch.rs`, which defines the
/// load-time choice of builds and names its symbols `sk__…`.
#[test]
fn the_core_knows_nothing_of_the_c_layer() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut all = Vec::new();
    files(&src, &mut all);
    let mut found = Vec::new();
    for f in &all {
        let rel = f
            .strip_prefix(&src)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        if rel.starts_with("ffi/") || rel == "math/arch.rs" || rel == "lib.rs" {
            continue;
        }
        let text = std::fs::read_to_string(f).unwrap();
        for (n, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap_or("");
            let sk = code
                .match_indices("sk_")
                .any(|(i, _)| !code[..i].ends_with(|c: char| c.is_alphanumeric() || c == '_'));
            if sk || code.contains("crate::ffi") || code.contains("feature = \"ffi\"") {
                found.push(format!("src/{rel}:{}: {}", n + 1, line.trim()));
            }
        }
    }
    assert!(found.is_empty(), "the core names the C layer: {found:#?}");
}
