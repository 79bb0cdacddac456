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
        (1e-9, 10.0),
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

/// Whether a point times one element of a batch (4096 uniforms through a
/// batch call, or a loop of the same): drawn, but off the frontier, which
/// compares single calls with single calls.
pub(crate) fn is_batch(e: &Entry) -> bool {
    e.name.contains("(4096")
        || e.name.contains(" loop, inline C")
        || e.name.contains(" loop inline")
}

/// The Pareto frontier of a panel's single calls (batch points left out,
/// [`is_batch`]): sorted by time, each point more accurate than every
/// faster one.
pub(crate) fn frontier<'a>(pts: &[&'a Entry]) -> Vec<&'a Entry> {
    let mut sorted: Vec<&Entry> = pts.iter().copied().filter(|e| !is_batch(e)).collect();
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

/// A label short enough for the chart (the tables keep the full names);
/// calls timed from C say so, so that no two labels of a panel read alike.
pub(crate) fn short(e: &Entry) -> String {
    let native = e.name.starts_with("C ABI native: ");
    let name = e
        .name
        .replace("C ABI native: ", "")
        .replace("C ABI: ", "")
        .replace(", sk_phase_sample_cos_n (4096)", ", batch")
        .replace(" (renderers' stand-in)", "")
        .replace(
            ", sk_phase_sample_cos_by_lobe (paper's lobe choice)",
            ", lobe choice",
        )
        .replace(", sk_phase_sample_cos (monotone inverse)", ", inverse")
        .replace(
            ", sk_phase_cos_inline_sample (scatterkit_inline.h)",
            ", header inline",
        )
        .replace(", sk_phase_sample_cos", "")
        .replace(" cos θ loop, inline C", ", loop")
        .replace(" cos θ, inline C", "")
        .replace(", inline C", "")
        .replace("peer: ", "");
    if native {
        format!("{name} (C, native)")
    } else if e.c_abi {
        format!("{name} (C)")
    } else {
        name
    }
}

/// Whether a point is a peer's formula rather than this library's code.
pub(crate) fn is_peer(e: &Entry) -> bool {
    e.name.contains("peer:")
}

/// This library's points and the peers' points: two colours.
const OURS: &str = "#1f5fbf";
const PEER: &str = "#d95f02";

fn color(e: &Entry) -> &'static str {
    if is_peer(e) { PEER } else { OURS }
}

/// Label text size (px).
const FONT: f64 = 9.0;
/// The farthest a label's box may be from its point (px); the chart test
/// holds every label to it.
pub(crate) const MAX_LABEL_DISTANCE: f64 = 200.0;

/// Points closer than this (px) share one label site, a line each.
const GROUP: f64 = 14.0;

/// The height of a label's line (px).
const LINE: f64 = 1.1 * FONT;

/// A label farther than this from its point (px) gets a leader line.
const LEADER: f64 = 10.0;

/// The width of `text` at `FONT` px in DejaVu Sans (the advance widths, in
/// em, of the character classes); the SVG fixes each label to this width
/// with `textLength`, so the box the placer used is the box drawn.
fn text_width(text: &str) -> f64 {
    let em: f64 = text
        .chars()
        .map(|c| match c {
            'i' | 'j' | 'l' | 'I' | '\'' | '|' => 0.28,
            ' ' | '.' | ',' | ':' | ';' | '·' => 0.32,
            'f' | 't' | 'r' | '(' | ')' | '[' | ']' | '/' | '-' => 0.4,
            'm' | 'w' | 'M' | 'W' | '…' | '—' => 0.9,
            '=' | '×' | '+' | '<' | '>' | '≤' | '−' => 0.84,
            '0'..='9' => 0.64,
            'A'..='Z' => 0.72,
            _ => 0.62,
        })
        .sum();
    em * FONT
}

/// The chart: one log-log panel per family, ns per sample (x) against max
/// error (y). Blue is this library, orange the peers' formulas; circles are
/// calls from Rust, triangles calls from C (through the C ABI for the
/// library, written inline for the peers); hollow markers are exact in
/// distribution and sit in a strip under the error axis; dashed lines join a
/// curve's points (tables by size, cube-root steps); the black line is the
/// Pareto frontier. Every point carries one label, placed so that it covers
/// no other label, point or line (with a leader line where it had to move
/// away); under each panel, the peers still on its frontier.
pub(crate) fn svg(es: &[Entry]) -> String {
    let (pw, ph, gap_x, gap_y) = (600.0, 480.0, 110.0, 130.0);
    let top = 112.0;
    let rows = PANELS.len().div_ceil(2) as f64;
    let (w, h) = (2.0 * pw + gap_x + 100.0, top + rows * (ph + gap_y));
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
         font-family=\"DejaVu Sans, Verdana, sans-serif\" font-size=\"{FONT}\">\n\
         <rect width=\"{w}\" height=\"{h}\" fill=\"white\"/>\n\
         <text x=\"70\" y=\"26\" font-size=\"16\" font-weight=\"bold\">scatterkit against the peers: \
         time per sample against max error (lower left is better)</text>\n"
    );
    legend(&mut s, 70.0, 48.0);
    for (k, (family, title, ylabel, (y_lo, y_hi))) in PANELS.iter().enumerate() {
        let pts = panel_points(es, family);
        if pts.is_empty() {
            continue;
        }
        let x0 = 70.0 + (k % 2) as f64 * (pw + gap_x);
        let y0 = top + 30.0 + (k / 2) as f64 * (ph + gap_y);
        let xl = match *family {
            "cbrt" => "ns per cube root",
            "Mie" => "ns per sample",
            _ => "ns per sample (f32)",
        };
        let axes = Axes::new(&pts, (x0, y0, pw, ph), (*y_lo, *y_hi));
        panel(&mut s, &pts, &axes, title, xl, ylabel);
    }
    s += "</svg>\n";
    s
}

/// The legend above the panels: what the colours and markers mean.
fn legend(s: &mut String, x: f64, y: f64) {
    let items: [(&str, &str, bool, &str); 5] = [
        ("circle", OURS, true, "scatterkit, called from Rust"),
        (
            "triangle",
            OURS,
            true,
            "scatterkit, called from C through the C ABI",
        ),
        (
            "circle",
            PEER,
            true,
            "peer's formula (pbrt-v4, Mitsuba 3, Cycles, papers), in Rust",
        ),
        ("triangle", PEER, true, "peer's formula, inline C"),
        (
            "diamond",
            PEER,
            true,
            "peer's formula, inline C built with -O3 -march=native (\"native\")",
        ),
    ];
    for (i, (shape, col, fill, text)) in items.iter().enumerate() {
        let (mx, my) = (x + (i % 2) as f64 * 520.0, y + (i / 2) as f64 * 16.0);
        marker(s, shape, mx, my, col, *fill, false);
        writeln!(
            s,
            "<text x=\"{}\" y=\"{}\" font-size=\"11\">{}</text>",
            mx + 10.0,
            my + 4.0,
            esc(text)
        )
        .unwrap();
    }
    let y2 = y + 16.0 * items.len().div_ceil(2) as f64;
    marker(s, "circle", x, y2, OURS, false, false);
    writeln!(
        s,
        "<text x=\"{}\" y=\"{}\" font-size=\"11\">hollow: exact in distribution (rejection), in the strip under the error axis</text>\
         <line x1=\"{}\" y1=\"{y2}\" x2=\"{}\" y2=\"{y2}\" stroke=\"black\" stroke-width=\"1.5\" opacity=\"0.6\"/>\
         <text x=\"{}\" y=\"{}\" font-size=\"11\">Pareto frontier</text>\
         <line x1=\"{}\" y1=\"{y2}\" x2=\"{}\" y2=\"{y2}\" stroke=\"#555\" stroke-dasharray=\"4,3\"/>\
         <text x=\"{}\" y=\"{}\" font-size=\"11\">a curve: one method at several table sizes or steps</text>",
        x + 10.0,
        y2 + 4.0,
        x + 520.0 - 6.0,
        x + 520.0 + 14.0,
        x + 520.0 + 20.0,
        y2 + 4.0,
        x + 520.0 + 130.0,
        x + 520.0 + 150.0,
        x + 520.0 + 156.0,
        y2 + 4.0,
    )
    .unwrap();
}

/// A marker at `(x, y)`; a data point's (`point`, not the legend's) carries
/// its class and position for the chart test.
fn marker(s: &mut String, shape: &str, x: f64, y: f64, col: &str, fill: bool, point: bool) {
    let fill = if fill { col } else { "none" };
    let class = if point {
        format!(" class=\"marker\" data-point=\"{x:.1},{y:.1}\"")
    } else {
        String::new()
    };
    if shape == "diamond" {
        writeln!(s, "<polygon{class} points=\"{:.1},{:.1} {:.1},{:.1} {:.1},{:.1} {:.1},{:.1}\" fill=\"{fill}\" stroke=\"{col}\" stroke-width=\"1.2\"/>", x, y - 5.0, x + 4.5, y, x, y + 5.0, x - 4.5, y).unwrap();
    } else if shape == "triangle" {
        writeln!(s, "<polygon{class} points=\"{:.1},{:.1} {:.1},{:.1} {:.1},{:.1}\" fill=\"{fill}\" stroke=\"{col}\" stroke-width=\"1.2\"/>", x, y - 5.0, x - 4.5, y + 3.5, x + 4.5, y + 3.5).unwrap();
    } else {
        writeln!(s, "<circle{class} cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"3.8\" fill=\"{fill}\" stroke=\"{col}\" stroke-width=\"1.2\"/>").unwrap();
    }
}

/// Text for SVG.
pub(crate) fn esc(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// An axis-aligned box `(x0, y0, x1, y1)` for the label placer.
pub(crate) type Rect = (f64, f64, f64, f64);

/// A line segment between two points (px).
type Segment = ((f64, f64), (f64, f64));

fn overlaps(r: Rect, t: Rect) -> bool {
    r.0 < t.2 && t.0 < r.2 && r.1 < t.3 && t.1 < r.3
}

/// Whether the segment `a`–`b` meets the box `r` (the segment clipped to the
/// box's slab in x, then tested in y).
fn segment_hits(a: (f64, f64), b: (f64, f64), r: Rect) -> bool {
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, d, lo, hi) in [(a.0, b.0 - a.0, r.0, r.2), (a.1, b.1 - a.1, r.1, r.3)] {
        if d.abs() < 1e-12 {
            if p < lo || p > hi {
                return false;
            }
        } else {
            let (mut ta, mut tb) = ((lo - p) / d, (hi - p) / d);
            if ta > tb {
                std::mem::swap(&mut ta, &mut tb);
            }
            t0 = t0.max(ta);
            t1 = t1.min(tb);
            if t0 > t1 {
                return false;
            }
        }
    }
    true
}

/// The point of the box `r` nearest to `p` (where a leader from `p` ends).
fn nearest_in(p: (f64, f64), r: Rect) -> (f64, f64) {
    (p.0.clamp(r.0, r.2), p.1.clamp(r.1, r.3))
}

/// The distance from a point to a box (0 inside).
fn distance_to(p: (f64, f64), r: Rect) -> f64 {
    let dx = (r.0 - p.0).max(p.0 - r.2).max(0.0);
    let dy = (r.1 - p.1).max(p.1 - r.3).max(0.0);
    dx.hypot(dy)
}

/// A panel's frame and its log-log scales.
/// The height of the strip at the foot of a panel where samplers exact in
/// distribution sit, below the error axis (their error is not a number on
/// it: rejection draws another sample for the same u).
const EXACT_STRIP: f64 = 40.0;

pub(crate) struct Axes {
    frame: Rect,
    lx: (f64, f64),
    ly: (f64, f64),
    y_range: (f64, f64),
}

impl Axes {
    fn new(pts: &[&Entry], (x0, y0, pw, ph): (f64, f64, f64, f64), y_range: (f64, f64)) -> Axes {
        let (xmin, xmax) = pts.iter().fold((f64::INFINITY, 0.0f64), |(a, b), e| {
            (a.min(e.ns), b.max(e.ns))
        });
        Axes {
            frame: (x0, y0, x0 + pw, y0 + ph),
            lx: ((xmin * 0.8).log10().floor(), (xmax * 1.25).log10().ceil()),
            ly: (y_range.0.log10(), y_range.1.log10()),
            y_range,
        }
    }
    fn px(&self, ns: f64) -> f64 {
        let (x0, _, x1, _) = self.frame;
        x0 + (ns.log10() - self.lx.0) / (self.lx.1 - self.lx.0) * (x1 - x0)
    }
    /// The error axis, above the strip of exact samplers.
    fn py(&self, e: f64) -> f64 {
        let (_, y0, _, y1) = self.frame;
        let y1 = y1 - EXACT_STRIP;
        let e = e.clamp(self.y_range.0, self.y_range.1);
        y1 - (e.log10() - self.ly.0) / (self.ly.1 - self.ly.0) * (y1 - y0)
    }
    /// A point's place: on the error axis, or, for a sampler exact in
    /// distribution (which has no per-u error to plot), in the strip
    /// under it.
    fn at(&self, e: &Entry) -> (f64, f64) {
        let y = if e.rejection {
            self.frame.3 - EXACT_STRIP / 2.0
        } else {
            self.py(e.err)
        };
        (self.px(e.ns), y)
    }
}

/// One panel: frame, grid, axis labels, curves, frontier, markers, labels,
/// and the caption naming the peers on the frontier.
fn panel(s: &mut String, pts: &[&Entry], ax: &Axes, title: &str, xl: &str, yl: &str) {
    let (x0, y0, x1, y1) = ax.frame;
    writeln!(
        s,
        "<rect x=\"{x0}\" y=\"{y0}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#444\"/>\
         <text x=\"{x0}\" y=\"{}\" font-size=\"13\" font-weight=\"bold\">{}</text>",
        x1 - x0,
        y1 - y0,
        y0 - 8.0,
        esc(title)
    )
    .unwrap();
    for d in (ax.lx.0 as i32)..=(ax.lx.1 as i32) {
        let x = ax.px(10f64.powi(d));
        writeln!(s, "<line x1=\"{x}\" y1=\"{y0}\" x2=\"{x}\" y2=\"{y1}\" stroke=\"#e4e4e4\"/><text x=\"{x}\" y=\"{}\" text-anchor=\"middle\">1e{d}</text>", y1 + 13.0).unwrap();
    }
    for d in (ax.ly.0.round() as i32)..=(ax.ly.1.round() as i32) {
        let y = ax.py(10f64.powi(d));
        writeln!(s, "<line x1=\"{x0}\" y1=\"{y}\" x2=\"{x1}\" y2=\"{y}\" stroke=\"#e4e4e4\"/><text x=\"{}\" y=\"{}\" text-anchor=\"end\">1e{d}</text>", x0 - 4.0, y + 3.0).unwrap();
    }
    writeln!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"11\">{xl}</text>\
         <text x=\"{x1}\" y=\"{}\" text-anchor=\"end\" font-size=\"11\">{yl}</text>",
        (x0 + x1) / 2.0,
        y1 + 28.0,
        y0 - 8.0
    )
    .unwrap();
    // Data lines: the curves and the frontier. Labels keep off them.
    let mut segments: Vec<Segment> = Vec::new();
    let mut curves: Vec<&str> = Vec::new();
    for c in pts.iter().filter_map(|e| e.curve) {
        if !curves.contains(&c) {
            curves.push(c);
        }
    }
    for c in &curves {
        let on: Vec<&&Entry> = pts.iter().filter(|e| e.curve == Some(c)).collect();
        polyline(
            s,
            on.iter().map(|e| ax.at(e)),
            &format!(
                "class=\"data curve\" stroke=\"{}\" stroke-dasharray=\"4,3\"",
                color(on[0])
            ),
            &mut segments,
        );
    }
    let front = frontier(pts);
    polyline(
        s,
        front.iter().map(|e| ax.at(e)),
        "class=\"data frontier\" stroke=\"black\" stroke-width=\"1.5\" opacity=\"0.6\"",
        &mut segments,
    );
    // Markers; every marker's box is taken before any label is placed.
    let mut taken: Vec<Rect> = Vec::new();
    if pts.iter().any(|e| e.rejection) {
        let ys = y1 - EXACT_STRIP;
        let note = "exact in distribution";
        writeln!(
            s,
            "<line x1=\"{x0}\" y1=\"{ys}\" x2=\"{x1}\" y2=\"{ys}\" stroke=\"#999\" stroke-dasharray=\"2,3\"/>\
             <text x=\"{}\" y=\"{}\" font-size=\"10\" fill=\"#666\">{note}</text>",
            x0 + 4.0,
            y1 - 4.0
        )
        .unwrap();
        taken.push((
            x0 + 2.0,
            y1 - 14.0,
            x0 + 6.0 + text_width(note) * 10.0 / FONT,
            y1,
        ));
    }
    for e in pts {
        let (x, y) = ax.at(e);
        taken.push((x - 5.0, y - 5.0, x + 5.0, y + 5.0));
        let shape = if e.name.starts_with("C ABI native: ") {
            "diamond"
        } else if e.c_abi || e.name.contains("inline C") {
            "triangle"
        } else {
            "circle"
        };
        marker(s, shape, x, y, color(e), !e.rejection, true);
    }
    // Sites: a curve's label at its last point; every other point's at the
    // point, points whose markers touch (within `GROUP` px) sharing one
    // site, with a line each.
    let mut sites: Vec<Site> = Vec::new();
    for c in &curves {
        if let Some(last) = pts.iter().rev().find(|e| e.curve == Some(c)) {
            sites.push(vec![(c.to_string(), ax.at(last), color(last))]);
        }
    }
    let curve_sites = sites.len();
    let mut rest: Vec<&&Entry> = pts.iter().filter(|e| e.curve.is_none()).collect();
    rest.sort_by(|a, b| a.ns.total_cmp(&b.ns));
    for e in rest {
        let p = ax.at(e);
        let line = (short(e), p, color(e));
        let near = |site: &&mut Site| {
            let q = site[0].1;
            (p.0 - q.0).hypot(p.1 - q.1) < GROUP
        };
        match sites[curve_sites..].iter_mut().find(|site| near(site)) {
            Some(site) => site.push(line),
            None => sites.push(vec![line]),
        }
    }
    // Sites in a crowd choose first (they have the fewest places).
    let crowd = |site: &Site| {
        let p = site[0].1;
        let n = pts
            .iter()
            .filter(|o| {
                let q = ax.at(o);
                (p.0 - q.0).hypot(p.1 - q.1) < 30.0
            })
            .count();
        std::cmp::Reverse(n)
    };
    sites[curve_sites..].sort_by_key(crowd);
    // Any site the best layout leaves gets a numbered tag, its names under
    // the panel.
    let (mut placed, left, (mut taken, mut segments)) =
        best_layout(sites, &taken, &segments, ax.frame);
    let mut footnotes = Vec::new();
    for site in left {
        let names: Vec<&str> = site.iter().map(|l| l.0.as_str()).collect();
        footnotes.push(names.join("; "));
        let tag = vec![(format!("[{}]", footnotes.len()), site[0].1, site[0].2)];
        let tag_line = [(site[0].1, site_size(&tag).0)];
        let at = (site[0].1, &tag_line[..]);
        let spot =
            radii().find_map(|r| place_at(site_size(&tag), at, r, ax.frame, &taken, &segments));
        if let Some(r) = spot {
            keep(tag, r, &mut taken, &mut segments, &mut placed);
        }
    }
    for (lines, spot) in &placed {
        let (anchor, col) = (lines[0].1, lines[0].2);
        if distance_to(anchor, *spot) > LEADER {
            // A leader from the point to the nearest point of the box.
            let q = nearest_in(anchor, *spot);
            writeln!(s, "<line class=\"leader\" x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"{col}\" stroke-width=\"0.7\" opacity=\"0.8\"/>", anchor.0, anchor.1, q.0, q.1).unwrap();
        }
        for (i, (text, p, col)) in lines.iter().enumerate() {
            let bottom = spot.1 + LINE * (i + 1) as f64;
            writeln!(
                s,
                "<text class=\"label\" data-point=\"{:.1},{:.1}\" x=\"{:.1}\" y=\"{:.1}\" textLength=\"{:.1}\" lengthAdjust=\"spacingAndGlyphs\" fill=\"{col}\">{}</text>",
                p.0,
                p.1,
                spot.0,
                bottom - 0.25 * FONT,
                text_width(text),
                esc(text)
            )
            .unwrap();
        }
    }
    let mut y = y1 + 44.0;
    for (i, f) in footnotes.iter().enumerate() {
        // Wrapped to the panel's width.
        let mut line = format!("[{}]", i + 1);
        for word in f.split(' ') {
            if text_width(&line) + text_width(word) > x1 - x0 {
                writeln!(
                    s,
                    "<text x=\"{x0}\" y=\"{y}\" fill=\"#333\">{}</text>",
                    esc(&line)
                )
                .unwrap();
                y += 11.0;
                line = String::from("    ");
            }
            line = format!("{line} {word}");
        }
        writeln!(
            s,
            "<text x=\"{x0}\" y=\"{y}\" fill=\"#333\">{}</text>",
            esc(&line)
        )
        .unwrap();
        y += 11.0;
    }
    let peers: Vec<String> = front
        .iter()
        .filter(|e| is_peer(e))
        .map(|e| short(e))
        .collect();
    let has_peer = pts.iter().any(|e| is_peer(e));
    let batch = if pts.iter().any(|e| is_batch(e)) {
        " Batch points (per element) are off the single-call frontier."
    } else {
        ""
    };
    let caption = if !has_peer {
        format!("This panel has no peer.{batch}")
    } else if peers.is_empty() {
        format!("No peer is on this panel's frontier.{batch}")
    } else {
        format!(
            "Peers on this panel's frontier: {}.{batch}",
            peers.join("; ")
        )
    };
    writeln!(
        s,
        "<text x=\"{x0}\" y=\"{y}\" font-size=\"10\" fill=\"#333\">{}</text>",
        esc(&caption)
    )
    .unwrap();
}

/// A label site: one line per point, `(text, point, colour)`.
type Site<'a> = Vec<(String, (f64, f64), &'a str)>;

/// A label line's point and its width (px).
type Line = ((f64, f64), f64);

/// The label text's size of a site (px).
fn site_size(site: &Site) -> (f64, f64) {
    let w = site.iter().fold(0.0f64, |a, l| a.max(text_width(&l.0)));
    (w, LINE * site.len() as f64)
}

/// The taken boxes and the segments labels keep off.
type Obstacles = (Vec<Rect>, Vec<Segment>);

/// The layout that leaves the fewest sites unplaced: [`layout`] in the
/// given order, then with the sites left over moved to the front (12
/// tries), then in orders shuffled by a fixed-seed generator (a chart drawn
/// twice from the same figures comes out the same), 150 tries in all.
fn best_layout<'a>(
    sites: Vec<Site<'a>>,
    taken: &[Rect],
    segments: &[Segment],
    frame: Rect,
) -> (Vec<(Site<'a>, Rect)>, Vec<Site<'a>>, Obstacles) {
    let mut order = sites;
    let mut best = layout(order.clone(), taken, segments, frame);
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    for attempt in 0..150 {
        if best.1.is_empty() {
            break;
        }
        if attempt < 12 {
            let failed: Vec<String> = best.1.iter().map(|s| s[0].0.clone()).collect();
            let (first, rest): (Vec<Site>, Vec<Site>) =
                order.into_iter().partition(|s| failed.contains(&s[0].0));
            order = first.into_iter().chain(rest).collect();
        } else {
            for i in (1..order.len()).rev() {
                seed = seed
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                order.swap(i, (seed >> 33) as usize % (i + 1));
            }
        }
        let next = layout(order.clone(), taken, segments, frame);
        if next.1.len() < best.1.len() {
            best = next;
        }
    }
    best
}

/// Places `sites` in this order, in rounds of growing radius (every site
/// gets its chance at one radius before any goes farther out): the sites
/// placed with their boxes, the sites left, and the obstacles after.
fn layout<'a>(
    sites: Vec<Site<'a>>,
    taken: &[Rect],
    segments: &[Segment],
    frame: Rect,
) -> (Vec<(Site<'a>, Rect)>, Vec<Site<'a>>, Obstacles) {
    let (mut taken, mut segments) = (taken.to_vec(), segments.to_vec());
    let mut placed = Vec::new();
    let mut left = sites;
    for radius in radii() {
        let mut still = Vec::new();
        for site in left {
            let points: Vec<((f64, f64), f64)> =
                site.iter().map(|l| (l.1, text_width(&l.0))).collect();
            match place_at(
                site_size(&site),
                (site[0].1, &points),
                radius,
                frame,
                &taken,
                &segments,
            ) {
                Some(r) => keep(site, r, &mut taken, &mut segments, &mut placed),
                None => still.push(site),
            }
        }
        left = still;
    }
    (placed, left, (taken, segments))
}

/// A site placed at `r`: its box and its leader are taken.
fn keep<'a>(
    site: Site<'a>,
    r: Rect,
    taken: &mut Vec<Rect>,
    segments: &mut Vec<Segment>,
    placed: &mut Vec<(Site<'a>, Rect)>,
) {
    taken.push(r);
    let anchor = site[0].1;
    if distance_to(anchor, r) > LEADER {
        segments.push((anchor, nearest_in(anchor, r)));
    }
    placed.push((site, r));
}

/// Draws a polyline and adds its segments to `segments`.
fn polyline(
    s: &mut String,
    pts: impl Iterator<Item = (f64, f64)>,
    style: &str,
    segments: &mut Vec<Segment>,
) {
    let pts: Vec<(f64, f64)> = pts.collect();
    segments.extend(pts.windows(2).map(|w| (w[0], w[1])));
    let text: Vec<String> = pts
        .iter()
        .map(|p| format!("{:.1},{:.1}", p.0, p.1))
        .collect();
    writeln!(
        s,
        "<polyline points=\"{}\" fill=\"none\" {style}/>",
        text.join(" ")
    )
    .unwrap();
}

/// The radii (px) at which labels are tried, nearest first: every site
/// gets its chance at one radius before any site goes farther out. (Room is
/// left for a site's other points, within `GROUP` px of the first.)
fn radii() -> impl Iterator<Item = f64> {
    (0..48)
        .map(|k| 6.0 + 4.0 * k as f64)
        .filter(|&r| r < MAX_LABEL_DISTANCE - GROUP)
}

/// A box of size `(w, h)` at distance `radius` from the point `p` that stays
/// inside `frame`, covers no box in `taken` and no segment, whose leader
/// (if it needs one) crosses no taken box, and which lies within
/// [`MAX_LABEL_DISTANCE`] of every point it names (`points`: each with its
/// line's width, the line's own box measured, `p` the first): 32 directions, the box's near edge or corner facing the point,
/// and for the sideways, upward and downward directions the box also slid
/// along its edge (a short line of a site with several points had ended up
/// 213 px from its point).
fn place_at(
    (w, h): (f64, f64),
    (p, points): ((f64, f64), &[Line]),
    radius: f64,
    frame: Rect,
    taken: &[Rect],
    segments: &[Segment],
) -> Option<Rect> {
    let inside = |r: Rect| {
        r.0 >= frame.0 + 2.0 && r.2 <= frame.2 - 2.0 && r.1 >= frame.1 + 2.0 && r.3 <= frame.3 - 2.0
    };
    // Right and left first, then ever steeper directions.
    let order = (0..=8).flat_map(|k| {
        let ks: Vec<i32> = if k == 0 {
            vec![0, 16]
        } else if k == 8 {
            vec![8, 24]
        } else {
            vec![k, 32 - k, 16 - k, 16 + k]
        };
        ks.into_iter()
    });
    for k in order {
        let a = k as f64 * std::f64::consts::PI / 16.0;
        let (dx, dy) = (a.cos(), -a.sin());
        let (ax, ay) = (p.0 + radius * dx, p.1 + radius * dy);
        let bx = if dx > 0.3 {
            ax
        } else if dx < -0.3 {
            ax - w
        } else {
            ax - w / 2.0
        };
        let by = if dy > 0.3 {
            ay
        } else if dy < -0.3 {
            ay - h
        } else {
            ay - h / 2.0
        };
        // Sideways, the box may also slide up or down along its edge; above
        // or below, it starts at the point (reading on from it) before it
        // is centred or ends there.
        let shifts: &[(f64, f64)] = if dy.abs() <= 0.3 {
            &[(0.0, 0.0), (0.0, -0.5), (0.0, 0.5)]
        } else if dx.abs() <= 0.3 {
            &[(0.5, 0.0), (0.0, 0.0), (-0.5, 0.0)]
        } else {
            &[(0.0, 0.0)]
        };
        for &(sx, sy) in shifts {
            let x = bx + sx * (w - 12.0).max(0.0);
            let r = (x, by + sy * h, x + w, by + (1.0 + sy) * h);
            let near = points.iter().enumerate().all(|(i, &(q, lw))| {
                let top = r.1 + LINE * i as f64;
                distance_to(q, (r.0, top, r.0 + lw, top + LINE)) <= MAX_LABEL_DISTANCE
            });
            if near && fits(r, p, &inside, taken, segments) {
                return Some(r);
            }
        }
    }
    None
}

/// Whether the box `r` for the point `p` is free (see [`place_at`]).
fn fits(
    r: Rect,
    p: (f64, f64),
    inside: &impl Fn(Rect) -> bool,
    taken: &[Rect],
    segments: &[Segment],
) -> bool {
    if !inside(r) || taken.iter().any(|&t| overlaps(r, t)) {
        return false;
    }
    if segments.iter().any(|&(a, b)| segment_hits(a, b, r)) {
        return false;
    }
    let d = distance_to(p, r);
    if d <= LEADER {
        return true;
    }
    // The leader, from 6 px out (markers that touch this one's are passed
    // over) to the box.
    let q = nearest_in(p, r);
    let k = 6.0 / d;
    let start = (p.0 + k * (q.0 - p.0), p.1 + k * (q.1 - p.1));
    !taken
        .iter()
        .filter(|&&t| distance_to(p, t) > 0.0)
        .any(|&t| segment_hits(start, q, t))
}
