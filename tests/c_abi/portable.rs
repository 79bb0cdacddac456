//! `include/scatterkit_portable.h` against `scatterkit::portable`: the
//! cases of `tests/c/portable_cases.h`, written again below in Rust, over
//! their 2²⁴ indices each, hashed per block of 2¹⁶ (FNV-1a over the output
//! bits, NaN canonical), compared block by block with
//! - `tests/c/portable.c` built at `-O3 -march=native -ffp-contract=fast`
//!   (GCC, and Clang where present): every index;
//! - the same built as C89, C99, C11, C++11, C++17 and C++20 with
//!   `-pedantic -Wall -Wextra -Werror -O2`: every 257th index (the same
//!   source as the two builds above, whose contraction and vectorisation
//!   are the riskier rounding; C99 at every index took 52 s of CI's CPU
//!   and never told anything the native builds did not);
//! - `tests/c/portable_opencl.c`, the cases compiled into an OpenCL kernel
//!   and run by the platform's runtime (pocl in CI): every index;
//!
//! the header compiled as CUDA device code to PTX and as HIP device code
//! for amdgcn by Clang, so that a qualifier or syntax error fails; and
//! `sk_phase_sample_cos_n_portable`, the library's batch (the build chosen
//! at load time), against the header inline (`tests/c/portable_batch.c`).

use crate::common;
use common::cbuild::{build_program_with, root, run};
use scatterkit::portable as p;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

const N: u32 = 1 << 24;
const CASES: i32 = 35;
const NAN: u32 = 0x7fc0_0000;

fn u_of(k: u32) -> f32 {
    if k >= N - 16 {
        return [
            1.0,
            1.000_000_1,
            -0.0,
            -1e-30,
            2.0,
            f32::from_bits(NAN),
            f32::INFINITY,
            f32::NEG_INFINITY,
            0.999_999_94,
            5.960_464_5e-8,
            1e-45,
            0.5,
            0.25,
            0.75,
            0.499_999_97,
            0.500_000_06,
        ][(k - (N - 16)) as usize];
    }
    k as f32 * 5.960_464_5e-8
}

fn u2_of(k: u32) -> f32 {
    (k.wrapping_mul(2_654_435_761) >> 8) as f32 * 5.960_464_5e-8
}

fn dir_of(k: u32) -> [f32; 3] {
    [
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        [1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.6, 0.0, 0.8],
        [0.0, 0.8, -0.6],
        [0.48, 0.6, 0.64],
        [-0.36, 0.48, -0.8],
    ][(k & 7) as usize]
}

fn g_of(c: i32) -> f32 {
    match c {
        2 => 0.0,
        3 => 0.3,
        4 => -0.7,
        5 => 0.9,
        6 => 0.999,
        _ => -0.999_999,
    }
}

fn hg(g: f32) -> p::Hg {
    p::Hg::new(g).unwrap()
}

fn case(c: i32, k: u32) -> [f32; 4] {
    let (u, u2) = (u_of(k), u2_of(k));
    let with_pdf = |r: p::DirSample| [r.dir[0], r.dir[1], r.dir[2], r.pdf];
    match c {
        0 => {
            let (s, co) = p::sin_cos_2pi(u);
            [s, co, 0.0, 0.0]
        }
        1 => with_pdf(p::isotropic_sample_dir(u, u2)),
        2..=7 => {
            let h = hg(g_of(c));
            let (mu, s, pdf) = p::hg_sample_cos_sin(&h, u);
            [p::hg_sample_cos(&h, u), mu, s, pdf]
        }
        8 | 9 => {
            let h = hg(if c == 8 { 0.7 } else { -0.2 });
            with_pdf(p::hg_sample_dir(&h, dir_of(k), u, u2))
        }
        10 => [
            p::hg_pdf(&hg(0.9), 2.0 * u - 1.0),
            p::hg_pdf(&hg(-0.5), 2.0 * u - 1.0),
            0.0,
            0.0,
        ],
        11 => {
            let mu = p::rayleigh_sample_cos(u);
            [mu, p::rayleigh_pdf(mu), 0.0, 0.0]
        }
        12 => with_pdf(p::rayleigh_sample_dir(dir_of(k), u, u2)),
        13 => [p::ln(f32::from_bits(k << 7)), p::ln(u), 0.0, 0.0],
        14 => [p::free_path(2.5, u), p::free_path(1e-3, u), 0.0, 0.0],
        16 | 17 => match p::Hg::new(2.0 * u - 1.0) {
            Some(h) if c == 16 => [h.c1, h.c2, h.c3, h.c4],
            Some(h) => [h.kd, h.k2, h.kp, h.omg],
            None => [f32::NAN; 4],
        },
        15 => {
            let v = p::direction_about(dir_of(k), 2.0 * u - 1.0, u2, u);
            [v[0], v[1], v[2], 0.0]
        }
        18 | 19 => {
            let d1 = p::Draine::new(
                if c == 18 { 0.5 } else { -0.3 },
                if c == 18 { 1.0 } else { 250.0 },
            )
            .unwrap();
            let d2 = p::Draine::new(
                if c == 18 { 0.9 } else { 0.01 },
                if c == 18 { 10.0 } else { 1000.0 },
            )
            .unwrap();
            let (m1, m2) = (p::draine_sample_cos(&d1, u), p::draine_sample_cos(&d2, u));
            [m1, p::draine_pdf(&d1, m1), m2, p::draine_pdf(&d2, m2)]
        }
        20 => match p::Draine::new(2.0 * u - 1.0, 0.5 + 1e4 * u2) {
            Some(d) => [d.lower.d, d.lower.r, d.upper.d, d.kp],
            None => [f32::NAN; 4],
        },
        21 => {
            let t1 = p::TwoLobe::new(0.8, -0.3, 0.9).unwrap();
            let t2 = p::TwoLobe::new(0.5, 0.99, u2).unwrap();
            let (m1, m2) = (
                p::two_lobe_sample_cos(&t1, u),
                p::two_lobe_sample_cos(&t2, u),
            );
            [m1, p::two_lobe_pdf(&t1, m1), m2, p::two_lobe_pdf(&t2, m2)]
        }
        22 => {
            let t = p::TwoLobe::new(0.8, -0.3, if k & 8 != 0 { 1.0 } else { 0.9 }).unwrap();
            with_pdf(p::two_lobe_sample_dir(&t, dir_of(k), u, u2))
        }
        23 => {
            let f1 = p::Fog::new(0.85, 0.45, 250.0, 0.3).unwrap();
            let f2 = p::Fog::new(0.9, 0.6, 20.0, u2).unwrap();
            let (m1, m2) = (p::fog_sample_cos(&f1, u), p::fog_sample_cos(&f2, u));
            [m1, p::fog_pdf(&f1, m1), m2, p::fog_pdf(&f2, m2)]
        }
        24 => {
            let sigma = [0.5, 2.0, 3.0 * u2];
            let mut r = [0.0; 3];
            let t = p::spectral_free_path(&sigma, (k % 3) as usize, u, 1.5, &mut r);
            [t, r[0], r[1], r[2]]
        }
        25 => {
            let x = f32::from_bits(k << 7);
            [
                p::exp(x),
                p::exp(-x),
                p::exp(200.0 * u - 100.0),
                p::transmittance(2.5, 10.0 * u),
            ]
        }
        26 => walk(k, u, u2, u2_of(k ^ 0x5bd1_e995)),
        27 => {
            let a = p::Schlick::new(0.7).unwrap();
            let b = p::Schlick::new(2.0 * u2 - 1.0);
            let (m1, m2) = (
                p::schlick_sample_cos(&a, u),
                b.map_or(f32::NAN, |b| p::schlick_sample_cos(&b, u)),
            );
            [
                m1,
                p::schlick_pdf(&a, m1),
                m2,
                b.map_or(f32::NAN, |b| p::schlick_pdf(&b, m2)),
            ]
        }
        28 => {
            let sch = p::Schlick::new(if k & 8 != 0 { -0.4 } else { 0.85 }).unwrap();
            with_pdf(p::schlick_sample_dir(&sch, dir_of(k), u, u2))
        }
        29 => {
            let (up, down) = (hg(1.0), hg(-1.0));
            let (mu, s, pdf) = p::hg_sample_cos_sin(&down, u);
            [
                p::hg_sample_cos(&up, u),
                p::hg_pdf(&up, 2.0 * u - 1.0),
                mu,
                p::hg_pdf(&down, 2.0 * u2 - 1.0) + s + pdf,
            ]
        }
        30 => with_pdf(p::hg_sample_dir(
            &hg(if k & 8 != 0 { 1.0 } else { -1.0 }),
            dir_of(k),
            u,
            u2,
        )),
        31 => {
            let t = p::TwoLobe::new(1.0, -0.3, u2).unwrap();
            let f = p::Fog::new(
                if k & 8 != 0 { -1.0 } else { 1.0 },
                0.6,
                20.0,
                if k & 16 != 0 { 1.0 } else { u2 },
            )
            .unwrap();
            let (m1, m2) = (p::two_lobe_sample_cos(&t, u), p::fog_sample_cos(&f, u));
            [m1, p::two_lobe_pdf(&t, m1), m2, p::fog_pdf(&f, m2)]
        }
        32 => {
            let d = if k & 8 != 0 {
                p::Draine::new(0.5, 1.0)
            } else {
                p::Draine::new(-0.3, 250.0)
            };
            with_pdf(p::draine_sample_dir(&d.unwrap(), dir_of(k), u, u2))
        }
        33 => {
            let w = if k & 8 != 0 { 0.3 } else { 1.0 };
            let f = p::Fog::new(0.85, 0.45, 250.0, w).unwrap();
            with_pdf(p::fog_sample_dir(&f, dir_of(k), u, u2))
        }
        34 => {
            let t = p::TwoLobe::new(0.8, -0.3, 0.9).unwrap();
            [
                p::hg_sample_dir(&hg(0.7), dir_of(k), u, u2).cos_theta,
                p::rayleigh_sample_dir(dir_of(k), u, u2).cos_theta,
                p::isotropic_sample_dir(u, u2).cos_theta,
                p::two_lobe_sample_dir(&t, dir_of(k), u, u2).cos_theta,
            ]
        }
        _ => unreachable!("case {c}"),
    }
}

/// Majorant `i` of case 26's grid (`pc_maj`).
fn maj(i: u32) -> f32 {
    if i == 17 {
        40.0
    } else {
        ((i * 7) % 5) as f32 * 0.75
    }
}

/// Case 26 (`pc_walk`): three steps of a walk through a 5×3×4 grid.
fn walk(k: u32, u: f32, u2: f32, u3: f32) -> [f32; 4] {
    let grid: [f32; 60] = core::array::from_fn(|i| maj(i as u32));
    let d = dir_of(k);
    let back = if k & 64 != 0 { 0.0 } else { 3.0 };
    let org = [
        0.25 - back * d[0] + (u2 - 0.5) * 2.5,
        0.0 - back * d[1] + (u3 - 0.5) * 1.0,
        1.0 - back * d[2] + (u - 0.5) * 2.0,
    ];
    let mut t_min = if k & 16 != 0 { 0.5 } else { 0.0 };
    let mut t_max = if k & 32 != 0 { 4.0 } else { f32::INFINITY };
    let (mut org, mut d, mut hi, mut nx) = (org, d, [1.5, 0.5, 2.0], 5);
    // One input in 128 is bad, eight ways (pc_walk).
    if k & 127 == 127 {
        match (k >> 7) & 7 {
            0 => nx = 0,
            1 => org[0] = f32::NAN,
            2 => t_min = -1.0,
            3 => t_max = -1.0,
            4 => d = [0.0; 3],
            5 => hi[0] = -1.0,
            6 => org[1] = f32::INFINITY,
            _ => nx = 1 << 24,
        }
    }
    let w = p::Walk::new(org, d, [-1.0, -0.5, 0.0], hi, [nx, 3, 4], t_min, t_max);
    let mut w = match w {
        Ok(Some(w)) => w,
        Ok(None) => return [1.0, 0.0, 0.0, 0.0],
        Err(()) => return [0.0; 4],
    };
    let mut o = [0.0; 4];
    let mut code = 2;
    for (i, (u, scale)) in [(u, 3), (u2, 9), (u3, 27)].into_iter().enumerate() {
        let s = match w.step(&grid, u) {
            p::Step::Collision { t, .. } => {
                o[i + 1] = t;
                1
            }
            p::Step::Exit => {
                o[i + 1] = w.t_end;
                0
            }
            p::Step::BadMajorant => -1,
        };
        code += scale * (s + 1);
    }
    o[0] = code as f32 + (100 * w.cell_index()) as f32;
    o
}

/// Block hashes: `(case, block) → hash`, every `stride`-th index.
type Hashes = BTreeMap<(i32, u32), u32>;

fn rust_hashes(stride: u32) -> Hashes {
    let jobs: Vec<(i32, u32)> = (0..CASES)
        .flat_map(|c| (0..N >> 16).map(move |b| (c, b)))
        .collect();
    let hashes = common::map_parallel(&jobs, |&(c, b)| {
        let mut h: u32 = 2_166_136_261;
        for k in ((b << 16)..((b + 1) << 16)).step_by(stride as usize) {
            for x in case(c, k) {
                let w = if x.is_nan() { NAN } else { x.to_bits() };
                h = (h ^ w).wrapping_mul(16_777_619);
            }
        }
        h
    });
    jobs.into_iter().zip(hashes).collect()
}

fn parse(out: &str) -> Hashes {
    out.lines()
        .filter_map(|l| {
            let mut f = l.split_whitespace();
            let c = f.next()?.parse().ok()?;
            let b = f.next()?.parse().ok()?;
            let h = u32::from_str_radix(f.next()?, 16).ok()?;
            Some(((c, b), h))
        })
        .collect()
}

/// The blocks (of 256 per case) whose hashes differ, per case; fails
/// unless none does.
fn compare(what: &str, got: &Hashes, want: &Hashes) {
    assert_eq!(
        got.len(),
        want.len(),
        "{what}: {} blocks, not {}",
        got.len(),
        want.len()
    );
    let mut bad: BTreeMap<i32, usize> = BTreeMap::new();
    for (key, h) in want {
        if got.get(key) != Some(h) {
            *bad.entry(key.0).or_default() += 1;
        }
    }
    println!(
        "{what}: {} cases × 2²⁴ inputs, mismatched blocks per case {bad:?}",
        CASES
    );
    assert!(bad.is_empty(), "{what}: blocks differ {bad:?}");
}

fn out_dir() -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join("portable");
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Builds `tests/c/<src>` with `compiler` and `flags`; the executable.
fn build(compiler: &str, src: &str, flags: &[&str], name: &str, libs: &[&str]) -> PathBuf {
    let exe = out_dir().join(name);
    let out = Command::new(compiler)
        .args(flags)
        .arg("-I")
        .arg(root().join("include"))
        .arg("-I")
        .arg(root().join("tests/c"))
        .arg(root().join("tests/c").join(src))
        .arg("-o")
        .arg(&exe)
        .args(libs)
        .output()
        .unwrap_or_else(|e| panic!("{compiler} did not start: {e}"));
    assert!(
        out.status.success(),
        "{compiler} {flags:?} {src} failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    exe
}

fn have(tool: &str) -> bool {
    Command::new(tool)
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success())
}

const STRICT: [&str; 5] = ["-O2", "-Wall", "-Wextra", "-Werror", "-pedantic"];

/// The Rust module's hashes of every index, computed once for the tests
/// that compare against them.
fn full_hashes() -> &'static Hashes {
    static FULL: std::sync::OnceLock<Hashes> = std::sync::OnceLock::new();
    FULL.get_or_init(|| rust_hashes(1))
}

#[test]
fn the_header_returns_the_librarys_bits_on_the_cpu() {
    if !common::repository("the_header_returns_the_librarys_bits_on_the_cpu") {
        return;
    }
    // Every build first, then the programs run side by side (each is one
    // thread), each compared with the Rust module's hashes.
    let mut runs: Vec<(String, PathBuf, Vec<&str>)> = Vec::new();
    let native = ["-O3", "-march=native", "-ffp-contract=fast"];
    let mut compilers = vec!["cc"];
    if have("clang") {
        compilers.push("clang");
    } else {
        common::skip("portable header under Clang -ffp-contract=fast: clang not found");
    }
    for cc in compilers {
        let exe = build(cc, "portable.c", &native, &format!("native-{cc}"), &["-lm"]);
        runs.push((format!("{cc} {}", native.join(" ")), exe, vec![]));
    }
    for (cc, std) in [
        ("cc", "-std=c89"),
        ("cc", "-std=c99"),
        ("cc", "-std=c11"),
        ("c++", "-std=c++11"),
        ("c++", "-std=c++17"),
        ("c++", "-std=c++20"),
    ] {
        let lang: &[&str] = if cc == "c++" { &["-x", "c++"] } else { &[] };
        let flags = [lang, &STRICT[..], &[std]].concat();
        let exe = build(cc, "portable.c", &flags, &std[5..], &["-lm"]);
        runs.push((format!("{std} (every 257th)"), exe, vec!["257"]));
    }
    let children: Vec<_> = runs
        .iter()
        .map(|(_, exe, args)| {
            Command::new(exe)
                .args(args)
                .stdout(std::process::Stdio::piped())
                .spawn()
                .expect("program did not start")
        })
        .collect();
    let sparse = rust_hashes(257);
    let full = full_hashes();
    for ((what, _, args), child) in runs.iter().zip(children) {
        let out = child.wait_with_output().expect("program did not finish");
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{what}: {text}");
        let want = if args.is_empty() { full } else { &sparse };
        compare(what, &parse(&text), want);
    }
}

#[test]
fn the_header_returns_the_librarys_bits_in_opencl() {
    if !common::repository("the_header_returns_the_librarys_bits_in_opencl") {
        return;
    }
    let exe = out_dir().join("opencl");
    let out = Command::new("cc")
        .args(["-std=c99", "-O2", "-I"])
        .arg(root().join("include"))
        .arg("-I")
        .arg(root().join("tests/c"))
        .arg(root().join("tests/c/portable_opencl.c"))
        .arg("-o")
        .arg(&exe)
        .arg("-lOpenCL")
        .output()
        .expect("cc did not start");
    if !out.status.success() {
        common::skip(&format!(
            "OpenCL (headers and libOpenCL: Debian's ocl-icd-opencl-dev, opencl-headers, pocl-opencl-icd): {}",
            String::from_utf8_lossy(&out.stderr)
                .lines()
                .next()
                .unwrap_or("")
        ));
        return;
    }
    let inc = root().join("include");
    let cases = root().join("tests/c");
    let (code, text) = {
        let o = Command::new(&exe).arg(&inc).arg(&cases).output().unwrap();
        (
            o.status.code(),
            String::from_utf8_lossy(&o.stdout).into_owned(),
        )
    };
    if let Some(line) = text.lines().find(|l| l.starts_with("SKIPPED")) {
        common::skip(&format!("OpenCL runtime: {line}"));
        return;
    }
    assert_eq!(code, Some(0), "{text}");
    println!("{}", text.lines().next().unwrap_or(""));
    compare("OpenCL", &parse(&text), full_hashes());
}

#[test]
fn the_header_compiles_as_cuda_and_hip_device_code() {
    if !common::repository("the_header_compiles_as_cuda_and_hip_device_code") {
        return;
    }
    if !have("clang") {
        common::skip("CUDA and HIP device compiles: clang not found");
        return;
    }
    let src = out_dir().join("portable_device.cu");
    // The cases, and the media table read from __constant__ and from
    // device memory as a kernel keeps it (tests/c/portable_media.h).
    std::fs::write(
        &src,
        "#include \"portable_media.h\"\n\
         #if defined(__NVPTX__)\n\
         #define TID() __nvvm_read_ptx_sreg_tid_x()\n\
         #else\n\
         #define TID() __builtin_amdgcn_workitem_id_x()\n\
         #endif\n\
         __attribute__((global)) void run(int c, unsigned k0, float *out, const float *maj) {\n\
             float o[4];\n\
             pc_case(c, k0, maj, o);\n\
             out[0] = o[0]; out[1] = o[1]; out[2] = o[2]; out[3] = o[3];\n\
         }\n\
         __attribute__((constant)) pm_medium media_c[PM_MEDIA];\n\
         __attribute__((global)) void from_constant(unsigned *out) {\n\
             unsigned k = TID(), h;\n\
             PM_HASH(media_c, k, h);\n\
             out[k] = h;\n\
         }\n\
         __attribute__((global)) void from_device(const pm_medium *media, unsigned *out) {\n\
             unsigned k = TID(), h;\n\
             PM_HASH(media, k, h);\n\
             out[k] = h;\n\
         }\n",
    )
    .unwrap();
    // The instructions a contraction would leave: none may appear in the
    // PTX, since the tier has no fused multiply-add. (On AMD GCN the
    // correctly rounded division and square root are themselves sequences
    // of fused multiply-adds, so there the compile alone is checked.)
    let targets: [(&str, &[&str], &[&str]); 2] = [
        (
            "cuda",
            &["--cuda-gpu-arch=sm_70", "-nocudainc", "-nocudalib"],
            &["fma.rn.f32", "mad.f32"],
        ),
        (
            "hip",
            &["--cuda-gpu-arch=gfx90a", "-nogpuinc", "-nogpulib"],
            &[],
        ),
    ];
    for (lang, flags, fused) in targets {
        let asm = out_dir().join(format!("portable.{lang}.s"));
        let out = Command::new("clang")
            .args([
                "-x",
                lang,
                "--cuda-device-only",
                "-S",
                "-O2",
                "-Wall",
                "-Werror",
            ])
            .args(flags)
            .arg("-I")
            .arg(root().join("include"))
            .arg("-I")
            .arg(root().join("tests/c"))
            .arg(&src)
            .arg("-o")
            .arg(&asm)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "clang -x {lang}:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let code = std::fs::read_to_string(&asm).unwrap();
        for f in fused {
            assert!(!code.contains(f), "{lang}: the device code fuses ({f})");
        }
        println!(
            "{lang}: device code compiled, {} lines",
            code.lines().count()
        );
    }
}

#[test]
fn the_librarys_batch_returns_the_headers_bits() {
    if !common::repository("the_librarys_batch_returns_the_headers_bits") {
        return;
    }
    let exe = build_program_with(&root().join("tests/c/portable_batch.c"), false, &[], "");
    let (code, out) = run(&exe);
    println!("{out}");
    assert_eq!(code, 0, "{out}");
    assert!(out.contains(" 0 mismatched"), "{out}");
}

/// The generated block of the header: the Rayleigh table's 512 values,
/// each printed so that it parses back to the same float.
fn table_block() -> String {
    let mut b = String::from(
        "/* BEGIN GENERATED by tests/c_abi/portable.rs from scatterkit::portable::RAYLEIGH_TABLE\n   \
         (SK_BLESS=1 cargo test --release --test c_abi portable rewrites it) */\n\
         #define SKP_RAYLEIGH_TABLE_DATA",
    );
    for (i, row) in p::RAYLEIGH_TABLE.chunks(4).enumerate() {
        let vals: Vec<String> = row.iter().map(|v| format!("{v:?}f")).collect();
        let sep = if i + 1 == p::RAYLEIGH_TABLE.len() / 4 {
            ""
        } else {
            ","
        };
        b.push_str(&format!(" \\\n    {}{sep}", vals.join(", ")));
    }
    b.push_str("\n/* END GENERATED */");
    b
}

#[test]
fn the_headers_rayleigh_table_is_the_librarys() {
    let path = root().join("include/scatterkit_portable.h");
    let text = std::fs::read_to_string(&path).unwrap();
    let (start, end) = (
        text.find("/* BEGIN GENERATED").expect("no generated block"),
        text.find("/* END GENERATED */")
            .expect("no end of the generated block")
            + "/* END GENERATED */".len(),
    );
    let want = table_block();
    if std::env::var_os("SK_BLESS").is_some() {
        std::fs::write(&path, format!("{}{want}{}", &text[..start], &text[end..])).unwrap();
        return;
    }
    assert_eq!(
        &text[start..end],
        want,
        "the header's Rayleigh table is stale: SK_BLESS=1 cargo test --release --test c_abi portable"
    );
}

/// The table lookups: `tests/c/portable_tables.c` builds tables of every
/// kind with the library, looks them up with the header on the CPU and in
/// an OpenCL kernel (data copied into device buffers) and compares: cos θ
/// with the library's lookups, the kernel's cos θ and density with the
/// CPU's, over 2²⁴ + 1 inputs per table. Here the Rust module looks up the
/// same data (written by the program) and must hash to the header's bits.
#[test]
fn tables_built_on_the_host_are_looked_up_with_the_same_bits() {
    if !common::repository("tables_built_on_the_host_are_looked_up_with_the_same_bits") {
        return;
    }
    let exe = out_dir().join("tables");
    let out = Command::new("cc")
        .args([
            "-std=c99",
            "-O2",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-pedantic",
            "-I",
        ])
        .arg(root().join("include"))
        .arg(root().join("tests/c/portable_tables.c"))
        .arg("-o")
        .arg(&exe)
        .arg("-lm")
        .arg(common::cbuild::static_lib())
        .args(["-lOpenCL", "-lpthread", "-ldl", "-lm"])
        .output()
        .expect("cc did not start");
    if !out.status.success() {
        common::skip(&format!(
            "table lookups in OpenCL (Debian's ocl-icd-opencl-dev, opencl-headers, pocl-opencl-icd): {}",
            String::from_utf8_lossy(&out.stderr)
                .lines()
                .next()
                .unwrap_or("")
        ));
        return;
    }
    let data = out_dir().join("tables.bin");
    let run = Command::new(&exe)
        .arg(root().join("include"))
        .arg(&data)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&run.stdout).into_owned();
    println!("{text}");
    assert_eq!(run.status.code(), Some(0), "{text}");
    let compared: Vec<&str> = text.lines().filter(|l| l.contains(" compared, ")).collect();
    assert!(
        compared.iter().all(|l| l.ends_with(" 0 mismatched")),
        "{text}"
    );
    if let Some(line) = text.lines().find(|l| l.starts_with("SKIPPED")) {
        common::skip(&format!("OpenCL runtime for the table lookups: {line}"));
        assert_eq!(compared.len(), 5, "{text}");
    } else {
        assert_eq!(compared.len(), 10, "{text}");
    }
    // The Rust module on the same data and inputs.
    let bytes = std::fs::read(&data).unwrap();
    let word = |i: usize| u32::from_le_bytes(bytes[4 * i..4 * i + 4].try_into().unwrap());
    let mut at = 0;
    for kind in 0..5u32 {
        let (n, k, len) = (
            word(at) as usize,
            word(at + 1) as usize,
            word(at + 2) as usize,
        );
        let vals: Vec<f32> = (0..len).map(|i| f32::from_bits(word(at + 3 + i))).collect();
        at += 3 + len;
        let mut h: u32 = 2_166_136_261;
        let mut mix = |(mu, pdf): (f32, f32)| {
            h = (h ^ mu.to_bits()).wrapping_mul(16_777_619);
            h = (h ^ pdf.to_bits()).wrapping_mul(16_777_619);
        };
        if kind == 4 {
            for i in 0..4097u32 * 4097 {
                let u = (i % 4097) as f32 / 4096.0;
                let x = 0.35 + 0.4 * (i / 4097) as f32 / 4096.0;
                mix(p::table2d_sample_cos_pdf(&vals, n, k, 0.4, 0.1, x, u));
            }
        } else {
            for i in 0..(1u32 << 24) + 1 {
                let u = i as f32 * 5.960_464_5e-8;
                mix(if kind == 3 {
                    p::table_cdf_sample_cos_pdf(&vals, n, u)
                } else {
                    p::table_sample_cos_pdf(&vals, n, u)
                });
            }
        }
        let want = format!("hash {kind} {h:08x}");
        assert!(
            text.lines().any(|l| l == want),
            "table {kind}: Rust {want}\n{text}"
        );
    }
}

/// The guide's three code blocks (`docs/guides/portable.md`), compiled:
/// the renderer's function as C99 (`-pedantic -Wall -Wextra -Werror`), the
/// CUDA kernel as device code (with a two-line stand-in for the CUDA
/// headers, which CI does not have), the OpenCL kernel as OpenCL C 1.2.
#[test]
fn the_guides_code_compiles() {
    if !common::repository("the_guides_code_compiles") {
        return;
    }
    let guide = std::fs::read_to_string(root().join("docs/guides/portable.md")).unwrap();
    let blocks: Vec<&str> = guide
        .split("```c\n")
        .skip(1)
        .map(|b| b.split("```").next().unwrap())
        .collect();
    assert_eq!(blocks.len(), 4, "the guide's two C, CUDA and OpenCL blocks");
    let dir = out_dir();
    let compile = |tool: &str, name: &str, prelude: &str, code: &str, flags: &[&str]| {
        let src = dir.join(name);
        std::fs::write(&src, format!("{prelude}{code}")).unwrap();
        let out = Command::new(tool)
            .args(flags)
            .arg("-I")
            .arg(root().join("include"))
            .arg(&src)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{name}:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    let obj = dir.join("guide.o");
    let obj = obj.to_str().unwrap();
    for (i, block) in blocks[..2].iter().enumerate() {
        compile(
            "cc",
            &format!("guide_renderer{i}.c"),
            "",
            block,
            &[
                "-std=c99",
                "-pedantic",
                "-Wall",
                "-Wextra",
                "-Werror",
                "-c",
                "-o",
                obj,
            ],
        );
    }
    if !have("clang") {
        common::skip("the guide's CUDA and OpenCL blocks: clang not found");
        return;
    }
    let cuda_stand_in = "#define __global__ __attribute__((global))\n\
        #define __constant__ __attribute__((constant))\n\
        struct guide_dim { int x; };\n\
        #define blockIdx (guide_dim{__nvvm_read_ptx_sreg_ctaid_x()})\n\
        #define blockDim (guide_dim{__nvvm_read_ptx_sreg_ntid_x()})\n\
        #define threadIdx (guide_dim{__nvvm_read_ptx_sreg_tid_x()})\n";
    compile(
        "clang",
        "guide_kernel.cu",
        cuda_stand_in,
        blocks[2],
        &[
            "-x",
            "cuda",
            "--cuda-device-only",
            "-nocudainc",
            "-nocudalib",
            "--cuda-gpu-arch=sm_70",
            "-fsyntax-only",
            "-Wall",
            "-Werror",
        ],
    );
    compile(
        "clang",
        "guide_kernel.cl",
        "",
        blocks[3],
        &[
            "-x",
            "cl",
            "-cl-std=CL1.2",
            "-Xclang",
            "-finclude-default-header",
            "-fsyntax-only",
            "-Wall",
            "-Werror",
        ],
    );
}

/// One medium of `tests/c/portable_media.h` (`pm_medium`).
struct Medium {
    hg: p::Hg,
    two: p::TwoLobe,
    fog: p::Fog,
    draine: p::Draine,
    schlick: p::Schlick,
}

/// `pm_medium_new`.
fn medium(m: u32) -> Medium {
    let (hg, two, fog, draine, schlick) = match m {
        0 => (
            0.85,
            (0.8, -0.3, 0.9),
            (0.85, 0.45, 250.0, 0.3),
            (0.5, 1.0),
            0.7,
        ),
        1 => (
            -0.4,
            (1.0, -0.3, 0.25),
            (0.9, 0.6, 20.0, 0.1),
            (-0.3, 250.0),
            -0.4,
        ),
        2 => (
            1.0,
            (0.5, 0.99, 0.5),
            (-1.0, 0.6, 20.0, 0.4),
            (0.9, 10.0),
            0.0,
        ),
        _ => (
            0.0,
            (0.2, -1.0, 1.0),
            (0.85, 0.45, 250.0, 1.0),
            (0.01, 1000.0),
            0.95,
        ),
    };
    Medium {
        hg: p::Hg::new(hg).unwrap(),
        two: p::TwoLobe::new(two.0, two.1, two.2).unwrap(),
        fog: p::Fog::new(fog.0, fog.1, fog.2, fog.3).unwrap(),
        draine: p::Draine::new(draine.0, draine.1).unwrap(),
        schlick: p::Schlick::new(schlick).unwrap(),
    }
}

const PM_N: u32 = 1 << 20;

/// `PM_HASH` at index `k`.
fn media_hash(media: &[Medium], k: u32) -> u32 {
    let t = &media[(k % 4) as usize];
    let u = if k >= PM_N - 16 {
        u_of(N - PM_N + k)
    } else {
        u2_of(k ^ 0x9e37_79b9)
    };
    let (v, w) = (u2_of(k), dir_of(k));
    let c = 2.0 * v - 1.0;
    let mut h: u32 = 2_166_136_261;
    let mut mix = |x: f32| {
        let b = if x.is_nan() { NAN } else { x.to_bits() };
        h = (h ^ b).wrapping_mul(16_777_619);
    };
    for r in [
        p::hg_sample_dir(&t.hg, w, u, v),
        p::two_lobe_sample_dir(&t.two, w, u, v),
        p::fog_sample_dir(&t.fog, w, u, v),
        p::draine_sample_dir(&t.draine, w, u, v),
        p::schlick_sample_dir(&t.schlick, w, u, v),
        p::rayleigh_sample_dir(w, u, v),
    ] {
        for x in [r.dir[0], r.dir[1], r.dir[2], r.cos_theta, r.pdf] {
            mix(x);
        }
    }
    for x in [
        p::hg_sample_cos(&t.hg, u),
        p::hg_pdf(&t.hg, c),
        p::two_lobe_sample_cos(&t.two, u),
        p::two_lobe_pdf(&t.two, c),
        p::fog_sample_cos(&t.fog, u),
        p::fog_pdf(&t.fog, c),
        p::draine_sample_cos(&t.draine, u),
        p::draine_pdf(&t.draine, c),
        p::schlick_sample_cos(&t.schlick, u),
        p::schlick_pdf(&t.schlick, c),
    ] {
        mix(x);
    }
    h
}

/// Model constants wherever a kernel keeps them: `tests/c/portable_spaces.c`
/// builds the table of `tests/c/portable_media.h` on the host, hashes
/// 2²⁰ indices there, and has OpenCL kernels read the same table from a
/// `__constant` and from a `__global` buffer, in OpenCL C 1.2, 2.0 and
/// 3.0; every hash must be the Rust module's. The same program links two
/// OpenCL programs that each include the header (`clLinkProgram`).
#[test]
fn model_constants_from_any_memory_space_and_linked_programs() {
    if !common::repository("model_constants_from_any_memory_space_and_linked_programs") {
        return;
    }
    let media: Vec<Medium> = (0..4).map(medium).collect();
    let want = (0..PM_N).fold(2_166_136_261u32, |acc, k| {
        (acc ^ media_hash(&media, k)).wrapping_mul(16_777_619)
    });
    let want = format!("{want:08x}");
    let exe = out_dir().join("spaces");
    let out = Command::new("cc")
        .args(["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror", "-I"])
        .arg(root().join("include"))
        .arg("-I")
        .arg(root().join("tests/c"))
        .arg(root().join("tests/c/portable_spaces.c"))
        .arg("-o")
        .arg(&exe)
        .args(["-lOpenCL", "-lm"])
        .output()
        .expect("cc did not start");
    if !out.status.success() {
        common::skip(&format!(
            "memory spaces in OpenCL (Debian's ocl-icd-opencl-dev, opencl-headers, pocl-opencl-icd): {}",
            String::from_utf8_lossy(&out.stderr)
                .lines()
                .next()
                .unwrap_or("")
        ));
        return;
    }
    let run = Command::new(&exe)
        .arg(root().join("include"))
        .arg(root().join("tests/c"))
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&run.stdout).into_owned();
    println!("{text}");
    assert_eq!(run.status.code(), Some(0), "{text}");
    assert!(
        text.contains(&format!("host {want}")),
        "Rust {want}\n{text}"
    );
    if let Some(line) = text.lines().find(|l| l.starts_with("SKIPPED")) {
        common::skip(&format!("OpenCL runtime for the memory spaces: {line}"));
        return;
    }
    for space in ["__constant", "__global"] {
        for version in ["CL1.2", "CL2.0", "CL3.0"] {
            let line = format!("{space} {version} {want}");
            assert!(text.lines().any(|l| l == line), "{line}\n{text}");
        }
    }
    assert!(text.contains("link: ok"), "{text}");
}

/// Four translation units, two C (C99, C89) and two C++ (C++11, C++17),
/// each including the header, link into one program
/// (`tests/c/portable_unit.c`).
#[test]
fn the_header_links_into_programs_of_several_units() {
    if !common::repository("the_header_links_into_programs_of_several_units") {
        return;
    }
    let dir = out_dir().join("units");
    std::fs::create_dir_all(&dir).unwrap();
    let src = root().join("tests/c/portable_unit.c");
    let mut objs = Vec::new();
    for (tool, std, name) in [
        ("cc", "-std=c99", "unit_c1"),
        ("cc", "-std=c89", "unit_c2"),
        ("c++", "-std=c++11", "unit_cpp1"),
        ("c++", "-std=c++17", "unit_cpp2"),
    ] {
        let obj = dir.join(format!("{name}.o"));
        let lang: &[&str] = if tool == "c++" { &["-x", "c++"] } else { &[] };
        let main: &[&str] = if name == "unit_c1" {
            &["-DPORTABLE_UNIT_MAIN"]
        } else {
            &[]
        };
        let out = Command::new(tool)
            .args(lang)
            .args(STRICT)
            .arg(std)
            .args(main)
            .arg(format!("-DUNIT_NAME={name}"))
            .arg("-I")
            .arg(root().join("include"))
            .arg("-c")
            .arg(&src)
            .arg("-o")
            .arg(&obj)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{tool} {std}:\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        objs.push(obj);
    }
    let exe = dir.join("units");
    let out = Command::new("c++")
        .args(&objs)
        .arg("-o")
        .arg(&exe)
        .arg("-lm")
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "link:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (code, text) = run(&exe);
    println!("{text}");
    assert!(code == 0 && text.contains("4 of 4 agree"), "{text}");
}
