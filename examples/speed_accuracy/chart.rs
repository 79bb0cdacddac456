//! The CSV and the SVG chart: one log-log panel per family, Pareto
//! frontier drawn, labels placed without overlap.

use crate::*;
use std::fmt::Write as _;

pub(crate) fn csv(es: &[Entry]) -> String {
    let mut s = String::from(
        "family,method,ns_per_cos,ns_per_dir_fast_rng,ns_per_dir_slow_rng,max_abs_error,max_cdf_error,exact_by_rejection,curve\n",
    );
    for e in es {
        let (df, ds) = e.dir_ns.map_or((String::new(), String::new()), |(f, s)| {
            (format!("{f:.3}"), format!("{s:.3}"))
        });
        let err = if e.rejection {
            String::new()
        } else {
            format!("{:.3e}", e.err)
        };
        let cdf = if e.rejection || e.cdf_err.is_nan() {
            String::new()
        } else {
            format!("{:.3e}", e.cdf_err)
        };
        writeln!(
            s,
            "{},\"{}\",{:.3},{df},{ds},{err},{cdf},{},\"{}\"",
            e.family,
            e.name,
            e.ns,
            e.rejection,
            e.curve.unwrap_or("")
        )
        .unwrap();
    }
    s
}

/// The families, one chart panel each: `(family, title, y-axis label, y range)`.
pub(crate) const PANELS: [(&str, &str, &str, (f64, f64)); 7] = [
    ("Rayleigh", "Rayleigh", "max |cos θ − exact|", (1e-9, 1.0)),
    (
        "HG",
        "Henyey–Greenstein",
        "max |cos θ − exact|",
        (1e-8, 1e-2),
    ),
    (
        "Draine",
        "Draine and Cornette–Shanks",
        "max |cos θ − exact|",
        (1e-8, 10.0),
    ),
    (
        "fog",
        "fog (Jendersie & d'Eon), 2 µm",
        "max |cos θ − exact|",
        (1e-8, 1e-1),
    ),
    ("cbrt", "cube root (f32)", "max error in ULP", (0.1, 1e10)),
    (
        "Mie",
        "Mie, water droplet 10 µm at 550 nm",
        "max |F_Mie(μ(u)) − u|",
        (1e-7, 1.0),
    ),
    (
        "FF",
        "Fournier–Forand (through the C ABI)",
        "max |cos θ − exact|",
        (1e-9, 1e-2),
    ),
];

/// The points of one panel: the family's entries with a finite positive error.
pub(crate) fn panel_points<'a>(es: &'a [Entry], family: &str) -> Vec<&'a Entry> {
    es.iter()
        .filter(|e| e.family == family && e.err > 0.0 && e.err.is_finite())
        .collect()
}

/// The Pareto frontier of a panel: sorted by time, each point more accurate
/// than every faster one.
pub(crate) fn frontier<'a>(pts: &[&'a Entry]) -> Vec<&'a Entry> {
    let mut sorted = pts.to_vec();
    sorted.sort_by(|a, b| a.ns.total_cmp(&b.ns));
    let mut best = f64::INFINITY;
    sorted
        .into_iter()
        .filter(|e| {
            let keep = e.err < best;
            best = best.min(e.err);
            keep
        })
        .collect()
}

/// A label short enough for the chart (the tables keep the full names).
pub(crate) fn short(name: &str) -> String {
    name.replace("C ABI: ", "")
        .replace(", sk_phase_sample_cos_n (4096)", ", batch")
        .replace(
            ", sk_phase_sample_cos_lobe (paper's lobe choice)",
            ", lobe choice",
        )
        .replace(", sk_phase_sample_cos (monotone inverse)", ", inverse")
        .replace(", sk_phase_sample_cos", "")
        .replace(" cos θ loop, inline C", ", loop")
        .replace(" cos θ, inline C", "")
        .replace(", inline C", "")
        .replace("peer: ", "")
}

/// The chart: one log-log panel per family, ns per sample (x) against max
/// error (y); circles are Rust calls, triangles calls through the C ABI from
/// C, squares (hollow triangles) exact-in-distribution samplers plotted at
/// f32's rounding floor; dashed lines are curves (tables by n, cube-root
/// steps); the black line is the Pareto frontier. Labels are placed so that
/// none covers another label or a point; one that finds no free place is
/// numbered and named under its panel.
pub(crate) fn svg(es: &[Entry]) -> String {
    let (pw, ph, gap_x, gap_y) = (470.0, 330.0, 110.0, 150.0);
    let rows = PANELS.len().div_ceil(2) as f64;
    let (w, h) = (2.0 * pw + gap_x + 90.0, rows * (ph + gap_y) + 20.0);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"9\">\n\
         <rect width=\"{w}\" height=\"{h}\" fill=\"white\"/>\n"
    );
    for (k, (family, title, ylabel, (y_lo, y_hi))) in PANELS.iter().enumerate() {
        let pts = panel_points(es, family);
        if pts.is_empty() {
            continue;
        }
        let x0 = 70.0 + (k % 2) as f64 * (pw + gap_x);
        let y0 = 40.0 + (k / 2) as f64 * (ph + gap_y);
        let xl = match *family {
            "cbrt" => "ns per cube root",
            "Mie" => "ns per sample",
            _ => "ns per sample (f32)",
        };
        panel(
            &mut s,
            &pts,
            (x0, y0, pw, ph),
            title,
            xl,
            ylabel,
            *y_lo,
            *y_hi,
        );
    }
    s += "</svg>\n";
    s
}

pub(crate) const COLORS: [(&str, &str); 8] = [
    ("Rayleigh", "#1f77b4"),
    ("HG", "#2ca02c"),
    ("Draine", "#d62728"),
    ("fog", "#9467bd"),
    ("isotropic", "#7f7f7f"),
    ("cbrt", "#ff7f0e"),
    ("Mie", "#17becf"),
    ("FF", "#8c564b"),
];

pub(crate) fn color(family: &str) -> &'static str {
    COLORS
        .iter()
        .find(|c| c.0 == family)
        .map_or("black", |c| c.1)
}

/// Text for SVG.
pub(crate) fn esc(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// An axis-aligned box `(x0, y0, x1, y1)` for the label placer.
pub(crate) type Rect = (f64, f64, f64, f64);

pub(crate) fn overlaps_any(r: Rect, taken: &[Rect]) -> bool {
    taken
        .iter()
        .any(|t| r.0 < t.2 && t.0 < r.2 && r.1 < t.3 && t.1 < r.3)
}

/// One log-log panel at `(x0, y0, pw, ph)`; x from the data, y over `[y_lo, y_hi]`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn panel(
    s: &mut String,
    pts: &[&Entry],
    (x0, y0, pw, ph): (f64, f64, f64, f64),
    title: &str,
    xl: &str,
    yl: &str,
    y_lo: f64,
    y_hi: f64,
) {
    let (xmin, xmax) = pts.iter().fold((f64::INFINITY, 0.0f64), |(a, b), e| {
        (a.min(e.ns), b.max(e.ns))
    });
    let (lx0, lx1) = ((xmin * 0.8).log10().floor(), (xmax * 1.25).log10().ceil());
    let (ly0, ly1) = (y_lo.log10(), y_hi.log10());
    let px = |ns: f64| x0 + (ns.log10() - lx0) / (lx1 - lx0) * pw;
    let py = |e: f64| y0 + ph - (e.clamp(y_lo, y_hi).log10() - ly0) / (ly1 - ly0) * ph;
    writeln!(
        s,
        "<rect x=\"{x0}\" y=\"{y0}\" width=\"{pw}\" height=\"{ph}\" fill=\"none\" stroke=\"#444\"/>\
         <text x=\"{x0}\" y=\"{}\" font-size=\"13\" font-weight=\"bold\">{}</text>",
        y0 - 22.0,
        esc(title)
    )
    .unwrap();
    for d in (lx0 as i32)..=(lx1 as i32) {
        let x = px(10f64.powi(d));
        writeln!(s, "<line x1=\"{x}\" y1=\"{y0}\" x2=\"{x}\" y2=\"{}\" stroke=\"#ddd\"/><text x=\"{x}\" y=\"{}\" text-anchor=\"middle\">1e{d}</text>", y0 + ph, y0 + ph + 13.0).unwrap();
    }
    for d in (ly0 as i32)..=(ly1 as i32) {
        let y = py(10f64.powi(d));
        writeln!(s, "<line x1=\"{x0}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\" stroke=\"#ddd\"/><text x=\"{}\" y=\"{}\" text-anchor=\"end\">1e{d}</text>", x0 + pw, x0 - 4.0, y + 3.0).unwrap();
    }
    writeln!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"11\">{xl}</text>\
         <text x=\"{}\" y=\"{}\" font-size=\"11\">{yl}</text>",
        x0 + pw / 2.0,
        y0 + ph + 28.0,
        x0 + pw - 120.0,
        y0 - 6.0
    )
    .unwrap();
    let col_of = |e: &Entry| color(e.family);
    // Curves (tables by n, step counts).
    let mut curves: Vec<&str> = Vec::new();
    for c in pts.iter().filter_map(|e| e.curve) {
        if !curves.contains(&c) {
            curves.push(c);
        }
    }
    for c in &curves {
        let line: Vec<String> = pts
            .iter()
            .filter(|e| e.curve == Some(c))
            .map(|e| format!("{:.1},{:.1}", px(e.ns), py(e.err)))
            .collect();
        writeln!(
            s,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-dasharray=\"4,3\"/>",
            line.join(" "),
            pts.iter()
                .find(|e| e.curve == Some(c))
                .map_or("black", |e| col_of(e))
        )
        .unwrap();
    }
    let front: Vec<String> = frontier(pts)
        .iter()
        .map(|e| format!("{:.1},{:.1}", px(e.ns), py(e.err)))
        .collect();
    writeln!(s, "<polyline points=\"{}\" fill=\"none\" stroke=\"black\" stroke-width=\"1.5\" opacity=\"0.6\"/>", front.join(" ")).unwrap();
    // Markers; every marker's box is taken before any label is placed.
    let mut taken: Vec<Rect> = Vec::new();
    for e in pts {
        let (x, y, col) = (px(e.ns), py(e.err), col_of(e));
        taken.push((x - 5.0, y - 5.0, x + 5.0, y + 5.0));
        if e.c_abi {
            let fill = if e.rejection { "none" } else { col };
            writeln!(s, "<polygon points=\"{:.1},{:.1} {:.1},{:.1} {:.1},{:.1}\" fill=\"{fill}\" stroke=\"{col}\"/>", x, y - 5.0, x - 4.5, y + 3.5, x + 4.5, y + 3.5).unwrap();
        } else if e.rejection {
            writeln!(s, "<rect x=\"{:.1}\" y=\"{:.1}\" width=\"7\" height=\"7\" fill=\"none\" stroke=\"{col}\"/>", x - 3.5, y - 3.5).unwrap();
        } else {
            writeln!(
                s,
                "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"3.5\" fill=\"{col}\" opacity=\"0.8\"/>"
            )
            .unwrap();
        }
    }
    // The legend box is taken too.
    let (lx, ly) = (x0 + pw - 190.0, y0 + 6.0);
    taken.push((lx - 4.0, ly - 2.0, x0 + pw, ly + 52.0));
    let legend = [
        "● Rust call   ▲ through the C ABI, from C",
        "□ / △ exact in distribution (at f32 floor)",
        "– – curve (tables by n, steps)",
        "—— Pareto frontier",
    ];
    for (i, t) in legend.iter().enumerate() {
        writeln!(
            s,
            "<text x=\"{lx}\" y=\"{}\" fill=\"#333\">{t}</text>",
            ly + 10.0 + 12.0 * i as f64
        )
        .unwrap();
    }
    // Labels: curves at their last point, other entries at their own; the
    // first free place among right, left, above and below, at growing
    // distances; a numbered tag otherwise.
    let mut labelled: Vec<(String, f64, f64, &str)> = Vec::new();
    for c in &curves {
        if let Some(last) = pts.iter().rev().find(|e| e.curve == Some(c)) {
            labelled.push((c.to_string(), px(last.ns), py(last.err), col_of(last)));
        }
    }
    for e in pts.iter().filter(|e| e.curve.is_none()) {
        labelled.push((short(&e.name), px(e.ns), py(e.err), col_of(e)));
    }
    let mut footnotes = Vec::new();
    for (text, x, y, col) in labelled {
        let tw = 4.9 * text.chars().count() as f64;
        let inside = |r: Rect| {
            r.0 >= x0 + 2.0 && r.2 <= x0 + pw - 2.0 && r.1 >= y0 + 2.0 && r.3 <= y0 + ph - 2.0
        };
        let mut spot = None;
        'search: for k in 0..8 {
            let dy = 11.0 * k as f64;
            for (bx, by) in [
                (x + 6.0, y - 4.0 - dy),
                (x + 6.0, y - 4.0 + dy),
                (x - 6.0 - tw, y - 4.0 - dy),
                (x - 6.0 - tw, y - 4.0 + dy),
            ] {
                let r = (bx, by - 6.0, bx + tw, by + 4.0);
                if inside(r) && !overlaps_any(r, &taken) {
                    spot = Some(r);
                    break 'search;
                }
            }
        }
        let (r, shown) = match spot {
            Some(r) => (Some(r), text.clone()),
            None => {
                footnotes.push(text.clone());
                let tag = format!("[{}]", footnotes.len());
                let tw = 5.5 * tag.len() as f64;
                let cands = [
                    (x + 5.0, y - 6.0),
                    (x - 5.0 - tw, y - 6.0),
                    (x - tw / 2.0, y - 10.0),
                    (x - tw / 2.0, y + 14.0),
                ];
                let r = cands
                    .iter()
                    .map(|&(bx, by)| (bx, by - 6.0, bx + tw, by + 4.0))
                    .find(|&r| !overlaps_any(r, &taken));
                (r, tag)
            }
        };
        if let Some(r) = r {
            taken.push(r);
            writeln!(
                s,
                "<text x=\"{:.1}\" y=\"{:.1}\" fill=\"{col}\">{}</text>",
                r.0,
                r.3 - 1.0,
                esc(&shown)
            )
            .unwrap();
        }
    }
    for (i, f) in footnotes.iter().enumerate() {
        writeln!(
            s,
            "<text x=\"{x0}\" y=\"{}\" fill=\"#333\">[{}] {}</text>",
            y0 + ph + 44.0 + 11.0 * i as f64,
            i + 1,
            esc(f)
        )
        .unwrap();
    }
}
