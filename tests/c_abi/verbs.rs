//! The handle × verb table of `docs/guides/c_api.md` against the header: a
//! ✓ is a function of the header in float and in double, a — is none, and
//! every header function named for a handle and a verb of the table has
//! its ✓.

use crate::common;

use common::cbuild::root;

#[test]
fn the_handle_verb_table_is_the_header() {
    let guide = std::fs::read_to_string(root().join("docs/guides/c_api.md")).unwrap();
    let header = std::fs::read_to_string(root().join("include/scatterkit.h")).unwrap();
    // A declaration starts its line (comments in the header are indented).
    let declared = |f: &str| {
        let call = format!(" {f}(");
        header
            .lines()
            .any(|l| !l.starts_with([' ', '#', '*']) && l.contains(&call))
    };
    let rows: Vec<Vec<String>> = guide
        .split_once("## Handles and verbs")
        .expect("the guide has the section")
        .1
        .lines()
        .skip_while(|l| !l.starts_with("| handle"))
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            l.trim_matches('|')
                .split('|')
                .map(|c| c.trim().trim_matches('`').to_string())
                .collect()
        })
        .collect();
    let verbs = &rows[0][1..];
    assert!(verbs.len() >= 9, "{verbs:?}");
    let mut checked = 0;
    for row in &rows[2..] {
        let handle = &row[0];
        for (verb, cell) in verbs.iter().zip(&row[1..]) {
            let f = format!("{handle}_{verb}");
            match cell.as_str() {
                "✓" => {
                    assert!(declared(&f), "{f} is ✓ in the guide but not in the header");
                    assert!(declared(&format!("{f}_f64")), "{f}_f64 is missing");
                }
                "—" => assert!(!declared(&f), "{f} is — in the guide but in the header"),
                other => panic!("cell {other:?} for {f}"),
            }
            checked += 1;
        }
    }
    assert!(checked >= 45, "{checked} cells");
    // No handle of the table has a verb of the table that the table omits
    // (the cells above cover every pair, so a ✓ missing is a — that fails).
    for row in &rows[2..] {
        for verb in verbs {
            let f = format!("{}_{verb}", row[0]);
            let cell = &row[1 + verbs.iter().position(|v| v == verb).unwrap()];
            assert_eq!(declared(&f), cell == "✓", "{f}");
        }
    }
}

/// Every model of the library's registry has its `SK_PHASE_` constant in
/// the header, with its tag: the C enum line a new model adds.
#[test]
fn every_registered_model_has_its_c_constant() {
    let header = std::fs::read_to_string(root().join("include/scatterkit.h")).unwrap();
    let values: std::collections::BTreeSet<u32> = header
        .lines()
        .map(str::trim)
        .filter(|l| l.starts_with("SK_PHASE_"))
        .filter_map(|l| l.split('=').nth(1))
        .filter_map(|v| v.trim().trim_end_matches(',').parse().ok())
        .collect();
    let tags: std::collections::BTreeSet<u32> = (1..=scatterkit::Phase::<f32>::LAST_TAG).collect();
    assert_eq!(
        values, tags,
        "the header's sk_phase_model against the registry"
    );
}
