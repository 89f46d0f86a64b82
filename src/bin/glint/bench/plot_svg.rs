//! A small hand-written SVG plotter for `glint bench --sweep`: side-by-side log-log
//! panels of error against time, one polyline per (setting family, scene). Colour names
//! the family and the marker the scene, so the legend stays two short lists however
//! many series there are. No plotting crate: this is all the sweep needs, and it keeps
//! font and system-library dependencies out of the build.

use std::fmt::Write as _;
use std::path::Path;

/// One line of the plot: a family of settings on one scene, points (x, y) in the order
/// the family's cost grows.
#[derive(Clone, Debug)]
pub struct Series {
    pub family: String,
    pub scene: String,
    pub points: Vec<(f64, f64)>,
}

/// One log-log panel.
#[derive(Clone, Debug)]
pub struct Panel {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
}

const PANEL_W: f64 = 420.0;
const PANEL_H: f64 = 320.0;
const MARGIN_L: f64 = 70.0;
const MARGIN_T: f64 = 50.0;
const MARGIN_B: f64 = 55.0;
const GAP: f64 = 40.0;
const LEGEND_W: f64 = 300.0;
/// Distinguishable on white, colour-blind-safe (Okabe–Ito).
const COLOURS: [&str; 7] = [
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000",
];
const MARKERS: [&str; 4] = ["circle", "square", "triangle", "diamond"];

/// The decades [10^lo, 10^hi] spanning every positive value of `values`.
fn decades(values: impl Iterator<Item = f64>) -> (i32, i32) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| *v > 0.0 && v.is_finite()) {
        lo = lo.min(v.log10());
        hi = hi.max(v.log10());
    }
    if !lo.is_finite() {
        return (0, 1);
    }
    let (lo, hi) = (lo.floor() as i32, hi.ceil() as i32);
    (lo, hi.max(lo + 1))
}

fn marker(shape: &str, x: f64, y: f64, colour: &str) -> String {
    let r = 4.0;
    match shape {
        "square" => format!(
            r#"<rect x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}" fill="{colour}"/>"#,
            x - r,
            y - r,
            2.0 * r,
            2.0 * r
        ),
        "triangle" => format!(
            r#"<polygon points="{:.1},{:.1} {:.1},{:.1} {:.1},{:.1}" fill="{colour}"/>"#,
            x,
            y - r * 1.2,
            x - r * 1.1,
            y + r * 0.8,
            x + r * 1.1,
            y + r * 0.8
        ),
        "diamond" => format!(
            r#"<polygon points="{:.1},{:.1} {:.1},{:.1} {:.1},{:.1} {:.1},{:.1}" fill="{colour}"/>"#,
            x,
            y - r * 1.3,
            x + r,
            y,
            x,
            y + r * 1.3,
            x - r,
            y
        ),
        _ => format!(r#"<circle cx="{x:.1}" cy="{y:.1}" r="{r}" fill="{colour}"/>"#),
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Position in a list, added at the end when new.
fn index_of(list: &mut Vec<String>, name: &str) -> usize {
    match list.iter().position(|n| n == name) {
        Some(i) => i,
        None => {
            list.push(name.to_string());
            list.len() - 1
        }
    }
}

/// The SVG document of `panels` side by side, with a legend at the right.
pub fn loglog_svg(title: &str, panels: &[Panel]) -> String {
    // Colours and markers are handed out in order of first appearance across panels.
    let mut families = Vec::new();
    let mut scenes = Vec::new();
    let width = MARGIN_L + panels.len() as f64 * (PANEL_W + GAP + MARGIN_L) + LEGEND_W;
    let height = MARGIN_T + PANEL_H + MARGIN_B;
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(
        svg,
        r#"<rect width="100%" height="100%" fill="white"/><text x="{:.0}" y="22" font-size="15" font-weight="bold">{}</text>"#,
        MARGIN_L,
        escape(title)
    );
    for (p, panel) in panels.iter().enumerate() {
        let x0 = MARGIN_L + p as f64 * (PANEL_W + GAP + MARGIN_L);
        let axes = PanelAxes::new(panel, x0, MARGIN_T);
        draw_panel_frame(&mut svg, panel, &axes);
        draw_panel_series(&mut svg, panel, &axes, &mut families, &mut scenes);
    }
    draw_legend(&mut svg, panels.len(), &families, &scenes);
    svg.push_str("</svg>\n");
    svg
}

/// A panel's place on the page and its log-log scale (whole decades on both axes).
struct PanelAxes {
    x0: f64,
    y0: f64,
    x_decades: (i32, i32),
    y_decades: (i32, i32),
}

impl PanelAxes {
    fn new(panel: &Panel, x0: f64, y0: f64) -> Self {
        let all = || panel.series.iter().flat_map(|s| s.points.iter());
        let x_decades = decades(all().map(|p| p.0));
        let y_decades = decades(all().map(|p| p.1));
        PanelAxes {
            x0,
            y0,
            x_decades,
            y_decades,
        }
    }

    fn sx(&self, x: f64) -> f64 {
        let (xl, xh) = self.x_decades;
        self.x0 + (x.log10() - xl as f64) / (xh - xl) as f64 * PANEL_W
    }

    fn sy(&self, y: f64) -> f64 {
        let (yl, yh) = self.y_decades;
        self.y0 + PANEL_H - (y.log10() - yl as f64) / (yh - yl) as f64 * PANEL_H
    }
}

/// The panel's box, decade grid lines with labels, title and axis labels.
fn draw_panel_frame(svg: &mut String, panel: &Panel, axes: &PanelAxes) {
    let (x0, y0) = (axes.x0, axes.y0);
    let (xl, xh) = axes.x_decades;
    let (yl, yh) = axes.y_decades;
    let _ = writeln!(
        svg,
        r##"<rect x="{x0:.1}" y="{y0:.1}" width="{PANEL_W}" height="{PANEL_H}" fill="none" stroke="#444"/>"##
    );
    // Grid lines and labels at each decade.
    for k in xl..=xh {
        let x = axes.sx(10f64.powi(k));
        let _ = writeln!(
            svg,
            r##"<line x1="{x:.1}" y1="{y0:.1}" x2="{x:.1}" y2="{:.1}" stroke="#ddd"/><text x="{x:.1}" y="{:.1}" text-anchor="middle">{}</text>"##,
            y0 + PANEL_H,
            y0 + PANEL_H + 16.0,
            10f64.powi(k)
        );
    }
    for k in yl..=yh {
        let y = axes.sy(10f64.powi(k));
        let _ = writeln!(
            svg,
            r##"<line x1="{x0:.1}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="#ddd"/><text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"##,
            x0 + PANEL_W,
            x0 - 6.0,
            y + 4.0,
            10f64.powi(k)
        );
    }
    let _ = writeln!(
        svg,
        r#"<text x="{:.1}" y="{:.1}" text-anchor="middle" font-weight="bold">{}</text>"#,
        x0 + PANEL_W / 2.0,
        y0 - 10.0,
        escape(&panel.title)
    );
    let _ = writeln!(
        svg,
        r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
        x0 + PANEL_W / 2.0,
        y0 + PANEL_H + 38.0,
        escape(&panel.x_label)
    );
    let (lx, ly) = (x0 - 52.0, y0 + PANEL_H / 2.0);
    let _ = writeln!(
        svg,
        r#"<text x="{lx:.1}" y="{ly:.1}" text-anchor="middle" transform="rotate(-90 {lx:.1} {ly:.1})">{}</text>"#,
        escape(&panel.y_label)
    );
}

/// Each series as a polyline with a marker per point (colour: family, marker: scene).
fn draw_panel_series(
    svg: &mut String,
    panel: &Panel,
    axes: &PanelAxes,
    families: &mut Vec<String>,
    scenes: &mut Vec<String>,
) {
    for series in &panel.series {
        let colour = COLOURS[index_of(families, &series.family) % COLOURS.len()];
        let shape = MARKERS[index_of(scenes, &series.scene) % MARKERS.len()];
        let points: Vec<(f64, f64)> = series
            .points
            .iter()
            .filter(|(x, y)| *x > 0.0 && *y > 0.0)
            .map(|&(x, y)| (axes.sx(x), axes.sy(y)))
            .collect();
        let path: Vec<String> = points
            .iter()
            .map(|(x, y)| format!("{x:.1},{y:.1}"))
            .collect();
        let _ = writeln!(
            svg,
            r#"<polyline points="{}" fill="none" stroke="{colour}" stroke-width="1.5"/>"#,
            path.join(" ")
        );
        for (x, y) in points {
            let _ = writeln!(svg, "{}", marker(shape, x, y, colour));
        }
    }
}

/// The legend right of the panels: colours for settings families, markers for scenes.
fn draw_legend(svg: &mut String, panel_count: usize, families: &[String], scenes: &[String]) {
    let lx = MARGIN_L + panel_count as f64 * (PANEL_W + GAP + MARGIN_L) - GAP;
    let mut y = MARGIN_T;
    let _ = writeln!(
        svg,
        r#"<text x="{lx:.1}" y="{y:.1}" font-weight="bold">settings (colour)</text>"#
    );
    for (i, family) in families.iter().enumerate() {
        y += 18.0;
        let colour = COLOURS[i % COLOURS.len()];
        let _ = writeln!(
            svg,
            r#"<line x1="{lx:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{colour}" stroke-width="3"/><text x="{:.1}" y="{y:.1}">{}</text>"#,
            y - 4.0,
            lx + 22.0,
            y - 4.0,
            lx + 28.0,
            escape(family)
        );
    }
    y += 30.0;
    let _ = writeln!(
        svg,
        r#"<text x="{lx:.1}" y="{y:.1}" font-weight="bold">scene (marker)</text>"#
    );
    for (i, scene) in scenes.iter().enumerate() {
        y += 18.0;
        let _ = writeln!(
            svg,
            "{}<text x=\"{:.1}\" y=\"{y:.1}\">{}</text>",
            marker(MARKERS[i % MARKERS.len()], lx + 11.0, y - 4.0, "#333"),
            lx + 28.0,
            escape(scene)
        );
    }
}

/// Writes `text` to `path` atomically (a temp file beside it, then a rename).
pub fn write_atomically(path: &Path, text: &str) -> std::io::Result<()> {
    use std::io::Write;
    glint::image_io::write_via_temp(path, |file| file.write_all(text.as_bytes()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decades_span_the_values() {
        assert_eq!(decades([0.003, 0.2].into_iter()), (-3, 0));
        assert_eq!(decades([1.0].into_iter()), (0, 1));
        assert_eq!(decades(std::iter::empty()), (0, 1));
    }

    #[test]
    fn plot_has_a_line_per_series_and_a_legend() {
        let panel = Panel {
            title: "FLIP".into(),
            x_label: "time (s)".into(),
            y_label: "error".into(),
            series: vec![
                Series {
                    family: "uniform".into(),
                    scene: "a".into(),
                    points: vec![(0.1, 0.05), (1.0, 0.01)],
                },
                Series {
                    family: "adaptive".into(),
                    scene: "b<".into(),
                    points: vec![(0.2, 0.02)],
                },
            ],
        };
        let svg = loglog_svg("t", &[panel]);
        assert!(svg.starts_with("<svg"));
        assert_eq!(svg.matches("<polyline").count(), 2);
        assert!(svg.contains("b&lt;") && svg.contains(">uniform<"));
    }
}
