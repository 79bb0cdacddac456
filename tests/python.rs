//! The Python package as a user gets it: `pip install ./python` into a
//! fresh virtual environment (maturin builds the extension from source,
//! pip fetches maturin, numpy and pytest from PyPI), then the package's own tests
//! (`python/tests` under pytest, run from outside the source tree so that the installed
//! package is the one imported), the README's Python block, the guide's
//! Python blocks (`docs/guides/python.md`) and `help()` on the package.
//! Without a Python 3.9 or later with `venv`, or without PyPI, it says
//! SKIPPED (and fails under `SK_REQUIRE_ALL`).

mod common;

use common::cbuild::root;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn run(cmd: &mut Command) -> Output {
    cmd.output()
        .unwrap_or_else(|e| panic!("{cmd:?} did not start: {e}"))
}

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// A virtual environment with the package installed from this tree, or
/// `None` (having said SKIPPED) where Python or PyPI is missing.
fn environment(dir: &Path) -> Option<PathBuf> {
    let version = Command::new("python3")
        .args(["-c", "import sys; assert sys.version_info >= (3, 9)"])
        .output();
    if !version.is_ok_and(|o| o.status.success()) {
        common::skip("the Python package: no python3 of version 3.9 or later");
        return None;
    }
    let venv = dir.join("venv");
    if !venv.join("bin/python").exists() {
        let o = run(Command::new("python3").arg("-m").arg("venv").arg(&venv));
        if !o.status.success() {
            common::skip(&format!(
                "the Python package: python3 -m venv failed: {}",
                text(&o)
            ));
            return None;
        }
    }
    let py = venv.join("bin/python");
    let pip = |args: &[&str]| {
        run(Command::new(&py)
            .args(["-m", "pip", "install", "-q", "--disable-pip-version-check"])
            .args(args)
            // maturin's cargo build beside the tests' (not in python/).
            .env("CARGO_TARGET_DIR", dir.join("target")))
    };
    let o = pip(&["numpy", "pytest"]);
    if !o.status.success() {
        common::skip(&format!(
            "the Python package: numpy and pytest from PyPI: {}",
            text(&o)
        ));
        return None;
    }
    // pyopencl for the kernel test (python/tests/test_opencl.py), which
    // says SKIPPED without it and fails then under SK_REQUIRE_ALL.
    let o = pip(&["pyopencl"]);
    if !o.status.success() {
        println!("pyopencl did not install: {}", text(&o));
    }
    // Mitsuba 3 and nanobind's headers (which Mitsuba's headers include)
    // for the render tests (python/tests/test_mitsuba.py), which say
    // SKIPPED without them and fail then under SK_REQUIRE_ALL.
    let o = pip(&["mitsuba", "nanobind"]);
    if !o.status.success() {
        println!("mitsuba and nanobind did not install: {}", text(&o));
    }
    // Dask for the cluster test (python/tests/test_dask.py), likewise.
    let o = pip(&["dask[distributed]"]);
    if !o.status.success() {
        println!("dask[distributed] did not install: {}", text(&o));
    }
    let src = root().join("python");
    let o = pip(&["--no-deps", "--force-reinstall", src.to_str().unwrap()]);
    assert!(
        o.status.success(),
        "pip install ./python failed:\n{}",
        text(&o)
    );
    Some(py)
}

/// Runs `code` with the environment's Python in `dir` (outside the tree).
fn python(py: &Path, dir: &Path, what: &str, code: &str) -> String {
    let o = run(Command::new(py).arg("-c").arg(code).current_dir(dir));
    assert!(o.status.success(), "{what} failed:\n{code}\n{}", text(&o));
    text(&o)
}

/// The Python blocks of a Markdown file.
fn python_blocks(file: &str) -> Vec<String> {
    let md = std::fs::read_to_string(root().join(file)).unwrap();
    md.split("```python\n")
        .skip(1)
        .filter_map(|b| b.split("```").next())
        .map(str::to_string)
        .collect()
}

#[test]
fn the_python_package_installs_and_passes_its_tests() {
    if !common::repository("the_python_package_installs_and_passes_its_tests") {
        return;
    }
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("python");
    std::fs::create_dir_all(&dir).unwrap();
    let Some(py) = environment(&dir) else {
        return;
    };
    let tests = root().join("python/tests");
    let o = run(Command::new(&py)
        .args(["-m", "pytest", "-q", "-p", "no:cacheprovider"])
        .arg(&tests)
        .current_dir(&dir));
    println!("{}", text(&o));
    assert!(
        o.status.success(),
        "the package's tests failed:\n{}",
        text(&o)
    );

    let readme = python_blocks("README.md");
    assert_eq!(readme.len(), 1, "the README holds one Python block");
    let out = python(&py, &dir, "the README's Python block", &readme[0]);
    println!("README block: {out}");

    let has_mitsuba = run(Command::new(&py).args(["-c", "import mitsuba, nanobind"]))
        .status
        .success();
    let guide = python_blocks("docs/guides/python.md");
    assert!(guide.len() >= 3, "the guide's Python blocks");
    for (i, block) in guide.iter().enumerate() {
        if block.contains("import mitsuba") && !has_mitsuba {
            // python/tests/test_mitsuba.py has said SKIPPED (or failed
            // under SK_REQUIRE_ALL) already.
            println!("SKIPPED: the guide's block {i} (Mitsuba 3 or nanobind is not installed)");
            continue;
        }
        python(&py, &dir, &format!("the guide's block {i}"), block);
    }

    // The examples: every one compiles; the fitting example runs, and the
    // figure runs where matplotlib is installed (it is not a dependency).
    let examples = root().join("python/examples");
    // Compiled in memory: nothing is written beside the sources.
    let compile = format!(
        "import pathlib\nfor f in sorted(pathlib.Path({:?}).glob('*.py')):\n    compile(f.read_text(), str(f), 'exec')",
        examples.to_str().unwrap()
    );
    python(&py, &dir, "compiling the examples", &compile);
    let o = run(Command::new(&py)
        .arg(examples.join("fit_measured.py"))
        .current_dir(&dir));
    assert!(
        o.status.success(),
        "examples/fit_measured.py:\n{}",
        text(&o)
    );
    assert!(text(&o).contains("within: True"), "{}", text(&o));
    // The README's Mitsuba picture, at 4 samples per pixel.
    if has_mitsuba {
        let o = run(Command::new(&py)
            .arg(examples.join("fog_picture.py"))
            .arg(dir.join("fog_hg_fit_mie.png"))
            .arg("4")
            .env("SCATTERKIT_CACHE", dir.join("mitsuba_plugin"))
            .current_dir(&dir));
        assert!(o.status.success(), "examples/fog_picture.py:\n{}", text(&o));
    }
    let has_mpl = run(Command::new(&py).args(["-c", "import matplotlib"]))
        .status
        .success();
    if has_mpl {
        let o = run(Command::new(&py)
            .arg(examples.join("phase_vs_mie.py"))
            .arg(dir.join("phase_vs_mie.png"))
            .current_dir(&dir));
        assert!(
            o.status.success(),
            "examples/phase_vs_mie.py:\n{}",
            text(&o)
        );
    } else {
        println!("examples/phase_vs_mie.py compiled, not run: matplotlib is not installed");
    }

    let help = python(
        &py,
        &dir,
        "help()",
        "import pydoc, scatterkit\nprint(pydoc.render_doc(scatterkit, renderer=pydoc.plaintext))",
    );
    for name in [
        "class Phase",
        "class Mie",
        "class AlbedoCurve",
        "class Medium",
        "class RayleighPolarized",
        "fit_mie",
        "class Table2d",
        "class SpectralPhase",
        "spectral_track",
        "polydisperse",
        "sample_cos",
        "water_index",
    ] {
        assert!(help.contains(name), "help(scatterkit) lacks {name}");
    }
}
