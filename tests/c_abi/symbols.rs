//! The shipped library's ABI: every dynamic symbol of `libscatterkit.so`
//! starts with `sk_` and is declared in the header, every header function is
//! exported, and no exported function can reach Rust's panic machinery
//! (walked over the call graph of the disassembly). Also: one phase object
//! shared by several threads gives the same samples as one thread.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Builds the C library (release, panic = "abort") once; its directory.
fn lib_dir() -> PathBuf {
    let target = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .unwrap()
        .to_path_buf();
    let status = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()))
        .args([
            "build",
            "--release",
            "-p",
            "scatterkit-capi",
            "--target-dir",
        ])
        .arg(&target)
        .current_dir(root())
        .status()
        .unwrap();
    assert!(status.success());
    target.join("release")
}

/// Function names declared in the generated header.
fn header_functions() -> BTreeSet<String> {
    let h = std::fs::read_to_string(root().join("include/scatterkit.h")).unwrap();
    h.lines()
        .filter(|l| {
            !l.starts_with(' ') && !l.starts_with('#') && l.contains("sk_") && l.contains('(')
        })
        .filter_map(|l| {
            let before = &l[..l.find('(')?];
            let name = before
                .rsplit(|c: char| !(c.is_alphanumeric() || c == '_'))
                .next()?;
            name.starts_with("sk_").then(|| name.to_string())
        })
        .collect()
}

#[test]
fn exported_symbols_match_the_header() {
    if !crate::common::repository("exported_symbols_match_the_header") {
        return;
    }
    let so = lib_dir().join("libscatterkit.so");
    let out = Command::new("nm")
        .args(["-D", "--defined-only"])
        .arg(&so)
        .output()
        .expect("nm");
    let text = String::from_utf8(out.stdout).unwrap();
    let exported: BTreeSet<String> = text
        .lines()
        .filter_map(|l| {
            let mut it = l.split_whitespace();
            let (_, kind, name) = (it.next()?, it.next()?, it.next()?);
            (kind == "T").then(|| name.to_string())
        })
        .collect();
    let declared = header_functions();
    assert!(
        declared.len() >= 90,
        "header parse found only {}",
        declared.len()
    );
    let foreign: Vec<_> = exported.iter().filter(|s| !s.starts_with("sk_")).collect();
    assert!(
        foreign.is_empty(),
        "exported symbols without the sk_ prefix: {foreign:?}"
    );
    let undeclared: Vec<_> = exported.difference(&declared).collect();
    assert!(
        undeclared.is_empty(),
        "exported but not in the header: {undeclared:?}"
    );
    let missing: Vec<_> = declared.difference(&exported).collect();
    assert!(
        missing.is_empty(),
        "declared in the header but not exported: {missing:?}"
    );
}

/// What a GOT slot holds, from the dynamic relocations (`objdump -R`): a
/// named symbol, or (`R_X86_64_RELATIVE`) an address inside the library.
enum Slot {
    Symbol(String),
    Address(u64),
}

fn got_slots(so: &Path) -> BTreeMap<u64, Slot> {
    let out = Command::new("objdump")
        .arg("-R")
        .arg(so)
        .output()
        .expect("objdump -R");
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| {
            let mut it = l.split_whitespace();
            let (addr, _kind, value) = (it.next()?, it.next()?, it.next()?);
            let addr = u64::from_str_radix(addr, 16).ok()?;
            let slot = match value.strip_prefix("*ABS*+0x") {
                Some(hex) => Slot::Address(u64::from_str_radix(hex, 16).ok()?),
                None => Slot::Symbol(value.split('@').next()?.to_string()),
            };
            Some((addr, slot))
        })
        .collect()
}

/// `function → callees` from `objdump -d` of the shared library: direct
/// calls and jumps by their symbol, indirect ones through the GOT by its
/// relocations (a relative slot resolved to the function containing its
/// address).
fn call_graph(so: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let slots = got_slots(so);
    let out = Command::new("objdump")
        .args(["-d", "--no-show-raw-insn"])
        .arg(so)
        .output()
        .expect("objdump");
    let text = String::from_utf8_lossy(&out.stdout);
    // Function start addresses, to resolve relative slots.
    let starts: BTreeMap<u64, String> = text
        .lines()
        .filter_map(|l| {
            let (addr, rest) = l.split_once(" <")?;
            let name = rest.strip_suffix(">:")?;
            Some((u64::from_str_radix(addr, 16).ok()?, name.to_string()))
        })
        .collect();
    let containing = |a: u64| starts.range(..=a).next_back().map(|(_, n)| n.clone());
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut current = String::new();
    for line in text.lines() {
        if let Some(name) = line
            .strip_suffix(">:")
            .and_then(|l| l.split_once(" <"))
            .map(|(_, n)| n)
        {
            current = name.to_string();
            graph.entry(current.clone()).or_default();
            continue;
        }
        if !(line.contains("call") || line.contains("jmp")) {
            continue;
        }
        let target = if line.contains("*0x") {
            // Indirect through memory: `call *0x..(%rip)   # 78918 <...>`.
            line.split_once("# ")
                .and_then(|(_, c)| c.split_whitespace().next())
                .and_then(|a| u64::from_str_radix(a, 16).ok())
                .and_then(|a| match slots.get(&a)? {
                    Slot::Symbol(s) => Some(s.clone()),
                    Slot::Address(t) => containing(*t),
                })
        } else {
            line.rsplit_once('<').map(|(_, t)| {
                let t = t.trim_end_matches('>');
                t.split('+')
                    .next()
                    .unwrap_or(t)
                    .trim_end_matches("@plt")
                    .to_string()
            })
        };
        if let Some(t) = target.filter(|t| *t != current) {
            graph.entry(current.clone()).or_default().insert(t);
        }
    }
    graph
}

#[test]
fn no_exported_function_can_reach_a_panic() {
    if !crate::common::repository("no_exported_function_can_reach_a_panic") {
        return;
    }
    let so = lib_dir().join("libscatterkit.so");
    let graph = call_graph(&so);
    let panicky =
        |f: &str| f.contains("panic") || f.contains("unwrap_failed") || f.contains("expect_failed");
    let mut reaching = Vec::new();
    for root_fn in graph.keys().filter(|f| f.starts_with("sk_")) {
        let mut seen = BTreeSet::new();
        let mut stack = vec![root_fn.clone()];
        while let Some(f) = stack.pop() {
            if !seen.insert(f.clone()) {
                continue;
            }
            if panicky(&f) {
                reaching.push((root_fn.clone(), f.clone()));
                break;
            }
            if let Some(callees) = graph.get(&f) {
                stack.extend(callees.iter().cloned());
            }
        }
    }
    let roots = graph.keys().filter(|f| f.starts_with("sk_")).count();
    println!(
        "{roots} exported functions checked; {} reach a panic",
        reaching.len()
    );
    assert!(roots >= 90, "only {roots} sk_ functions in the disassembly");
    assert!(
        reaching.is_empty(),
        "exported functions that can reach panic machinery: {reaching:?}"
    );
}

#[test]
fn threads_share_one_phase_and_agree_with_one_thread() {
    use rand_xoshiro::Xoshiro256PlusPlus;
    use rand_xoshiro::rand_core::SeedableRng;
    use scatterkit::{Phase, PhaseFunction, Real, Vec3};
    let phase = Phase::<f32>::fog_diameter(2.0).unwrap();
    let w_in = Vec3::new(0.0f32, 0.6, 0.8);
    let run = |seed: u64| -> Vec<(Vec3<f32>, f32)> {
        let mut r = Xoshiro256PlusPlus::seed_from_u64(seed);
        (0..20_000)
            .map(|_| phase.sample_dir(w_in, f32::uniform(&mut r), f32::uniform(&mut r)))
            .collect()
    };
    let sequential: Vec<_> = (0..4).map(run).collect();
    let parallel: Vec<_> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..4).map(|seed| s.spawn(move || run(seed))).collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert_eq!(sequential, parallel);
}
