//! The speed-against-accuracy chart the README shows
//! (`docs/measured/speed_accuracy.svg`, written by the main example with
//! `SK_REFRESH_DOCS=1`) can be read without the README: every label sits
//! within `MAX_DISTANCE` px of its point, and no label covers another label,
//! a point, a data line or another label's leader; every point is labelled
//! (or lies inside a curve, which is labelled at its last point, or in a
//! site of touching points that had to take a numbered tag, its names
//! under the panel).
//!
//! The chart states its geometry: each label is a `<text class="label">` with
//! the point it names (`data-point`), its left edge `x`, its baseline `y` and
//! its width fixed by `textLength`; a line of text is `1.1 × 9` px tall with
//! its baseline `0.25 × 9` px above the bottom. Markers are
//! `class="marker"` (a 10 px box about `data-point`), data lines
//! `class="data …"` polylines, leaders `class="leader"` lines.

use std::path::Path;

/// Labels stay within this distance of their point (px), the chart's own
/// limit (`MAX_LABEL_DISTANCE` in `examples/speed_accuracy/chart.rs`).
const MAX_DISTANCE: f64 = 200.0;
/// Points closer than this (px) share one label site (`GROUP` in the
/// chart's code).
const GROUP: f64 = 14.0;
/// The label font size and line height (px).
const FONT: f64 = 9.0;
const LINE: f64 = 1.1 * FONT;
/// Coordinates are written to 0.1 px: boxes that touch may seem to overlap
/// by that much.
const SLACK: f64 = 0.15;

type Rect = (f64, f64, f64, f64);
type Point = (f64, f64);

fn attr(tag: &str, name: &str) -> Option<String> {
    let key = format!(" {name}=\"");
    let start = tag.find(&key)? + key.len();
    let end = start + tag[start..].find('"')?;
    Some(tag[start..end].to_string())
}

fn num(tag: &str, name: &str) -> f64 {
    attr(tag, name)
        .unwrap_or_else(|| panic!("no {name} in {tag}"))
        .parse()
        .unwrap()
}

fn pair(s: &str) -> Point {
    let (a, b) = s.split_once(',').unwrap();
    (a.trim().parse().unwrap(), b.trim().parse().unwrap())
}

/// Every element of the SVG whose class starts with `class`, as its opening
/// tag (and, for text, its content).
fn elements<'a>(svg: &'a str, class: &str) -> Vec<(&'a str, &'a str)> {
    let mut out = Vec::new();
    for (i, _) in svg.match_indices('<') {
        let tag_end = i + svg[i..].find('>').unwrap();
        let tag = &svg[i..tag_end];
        if attr(tag, "class").is_some_and(|c| c.starts_with(class)) {
            let body_end = svg[tag_end..].find('<').map_or(tag_end, |k| tag_end + k);
            out.push((tag, &svg[tag_end + 1..body_end]));
        }
    }
    out
}

fn overlaps(a: Rect, b: Rect) -> bool {
    a.0 < b.2 - SLACK && b.0 < a.2 - SLACK && a.1 < b.3 - SLACK && b.1 < a.3 - SLACK
}

fn distance_to(p: Point, r: Rect) -> f64 {
    let dx = (r.0 - p.0).max(p.0 - r.2).max(0.0);
    let dy = (r.1 - p.1).max(p.1 - r.3).max(0.0);
    dx.hypot(dy)
}

/// Whether the segment `a`–`b` passes through the inside of `r`.
fn segment_hits(a: Point, b: Point, r: Rect) -> bool {
    let r = (r.0 + SLACK, r.1 + SLACK, r.2 - SLACK, r.3 - SLACK);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, d, lo, hi) in [(a.0, b.0 - a.0, r.0, r.2), (a.1, b.1 - a.1, r.1, r.3)] {
        if d.abs() < 1e-12 {
            if p <= lo || p >= hi {
                return false;
            }
        } else {
            let (ta, tb) = ((lo - p) / d, (hi - p) / d);
            t0 = t0.max(ta.min(tb));
            t1 = t1.min(ta.max(tb));
            if t0 >= t1 {
                return false;
            }
        }
    }
    true
}

struct Chart {
    labels: Vec<(String, Point, Rect)>,
    markers: Vec<Point>,
    curves: Vec<Vec<Point>>,
    segments: Vec<(Point, Point)>,
}

fn read(svg: &str) -> Chart {
    let labels = elements(svg, "label")
        .into_iter()
        .map(|(tag, text)| {
            let (x, y, w) = (num(tag, "x"), num(tag, "y"), num(tag, "textLength"));
            let bottom = y + 0.25 * FONT;
            let point = pair(&attr(tag, "data-point").unwrap());
            (text.to_string(), point, (x, bottom - LINE, x + w, bottom))
        })
        .collect();
    let markers = elements(svg, "marker")
        .into_iter()
        .map(|(tag, _)| pair(&attr(tag, "data-point").unwrap()))
        .collect();
    let mut curves = Vec::new();
    let mut segments = Vec::new();
    for (tag, _) in elements(svg, "data") {
        let pts: Vec<Point> = attr(tag, "points")
            .unwrap()
            .split_whitespace()
            .map(pair)
            .collect();
        segments.extend(pts.windows(2).map(|w| (w[0], w[1])));
        if attr(tag, "class").unwrap().contains("curve") {
            curves.push(pts);
        }
    }
    for (tag, _) in elements(svg, "leader") {
        let a = (num(tag, "x1"), num(tag, "y1"));
        let b = (num(tag, "x2"), num(tag, "y2"));
        segments.push((a, b));
    }
    Chart {
        labels,
        markers,
        curves,
        segments,
    }
}

/// Every rule of the module docs; the list of what broke.
fn problems(c: &Chart) -> Vec<String> {
    let mut bad = Vec::new();
    for (i, (text, p, r)) in c.labels.iter().enumerate() {
        let d = distance_to(*p, *r);
        if d > MAX_DISTANCE {
            bad.push(format!("\"{text}\" is {d:.0} px from its point"));
        }
        for (other, _, r2) in &c.labels[i + 1..] {
            if overlaps(*r, *r2) {
                bad.push(format!("\"{text}\" overlaps \"{other}\""));
            }
        }
        for m in &c.markers {
            if overlaps(*r, (m.0 - 5.0, m.1 - 5.0, m.0 + 5.0, m.1 + 5.0)) {
                bad.push(format!("\"{text}\" covers the point at {m:?}"));
            }
        }
        for &(a, b) in &c.segments {
            if segment_hits(a, b, *r) {
                bad.push(format!("\"{text}\" lies over the line {a:?}–{b:?}"));
            }
        }
    }
    let near = |a: Point, b: Point| (a.0 - b.0).abs() < 0.2 && (a.1 - b.1).abs() < 0.2;
    for m in &c.markers {
        // A label names its own point; a numbered tag (the names under the
        // panel) names a site of touching points, within `GROUP` px.
        let labelled = c.labels.iter().any(|(text, p, _)| {
            near(*p, *m) || (text.starts_with('[') && (p.0 - m.0).hypot(p.1 - m.1) < GROUP)
        });
        let on_curve = c.curves.iter().any(|cv| cv.iter().any(|q| near(*q, *m)));
        if !labelled && !on_curve {
            bad.push(format!("the point at {m:?} has no label"));
        }
    }
    bad
}

#[test]
fn chart_labels_are_readable() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/measured/speed_accuracy.svg");
    let svg = std::fs::read_to_string(&path).unwrap();
    let chart = read(&svg);
    assert!(
        chart.labels.len() >= 40 && chart.markers.len() >= 60,
        "the chart has {} labels and {} points: did its format change?",
        chart.labels.len(),
        chart.markers.len()
    );
    let bad = problems(&chart);
    assert!(bad.is_empty(), "{}:\n{}", path.display(), bad.join("\n"));
}

/// The test can fail: moving one label onto another, or far from its point,
/// is caught.
#[test]
fn chart_test_catches_a_misplaced_label() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/measured/speed_accuracy.svg");
    let mut chart = read(&std::fs::read_to_string(path).unwrap());
    let first = chart.labels[0].2;
    let moved = chart.labels[1].clone();
    chart.labels[1].2 = (
        first.0 + 3.0,
        first.1 + 2.0,
        first.0 + 3.0 + (moved.2.2 - moved.2.0),
        first.3 + 2.0,
    );
    assert!(problems(&chart).iter().any(|p| p.contains("overlaps")));
    let mut chart2 = read(
        &std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/measured/speed_accuracy.svg"),
        )
        .unwrap(),
    );
    let (_, p, r) = chart2.labels[0].clone();
    chart2.labels[0].2 = (p.0 + 300.0, r.1, p.0 + 300.0 + (r.2 - r.0), r.3);
    assert!(
        problems(&chart2)
            .iter()
            .any(|p| p.contains("px from its point"))
    );
}
