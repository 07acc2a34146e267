//! The comparison plot: trunk x and z over time for both backends (two stacked panels), and the
//! trunk position divergence |C_A − C_B| below them, drawn with plotters into an RGB buffer and
//! written as a PNG at the encoder's high compression (the plots are committed to the
//! repository, so they are kept small: about 100 KB).

use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;

use crate::error::CompareError;
use crate::multi::MultiReport;
use crate::policy::PolicyReport;
use crate::report::Report;

/// The plot's size (px).
pub const PLOT_SIZE: (u32, u32) = (900, 780);

/// The family name this crate registers its font under (its own, so that it never replaces a
/// font another crate registered with plotters).
const FAMILY: &str = "hyq-compare-sans";

/// DejaVu Sans, the subset hyq-render bundles (its `assets/fonts/`, with the licence).
const SANS: &[u8] = hyq_render::SANS;

const COLOURS: [RGBColor; 3] = [
    RGBColor(0x4e, 0x79, 0xa7),
    RGBColor(0xe1, 0x57, 0x59),
    RGBColor(0xf2, 0x8e, 0x2b),
];
/// The pairs' divergence lines in a plot of three or more backends.
const PAIR_COLOURS: [RGBColor; 3] = [
    GREEN,
    RGBColor(0xb0, 0x7a, 0xa1),
    RGBColor(0x76, 0xb7, 0xb2),
];
const GREEN: RGBColor = RGBColor(0x59, 0xa1, 0x4f);
const INK: RGBColor = RGBColor(0x2b, 0x2f, 0x36);

fn font_registered() -> Result<(), String> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            plotters::style::register_font(FAMILY, FontStyle::Normal, SANS)
                .map_err(|_| "the bundled font could not be registered".to_owned())
        })
        .clone()
}

fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return (-1.0, 1.0);
    }
    let span = hi - lo;
    let pad = if span < 1e-6 {
        lo.abs().max(0.01) * 0.05
    } else {
        0.06 * span
    };
    (lo - pad, hi + pad)
}

fn panel(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    caption: &str,
    y_desc: &str,
    lines: &[(&str, &[f64], &[f64])],
    colours: &[RGBColor],
) -> Result<(), String> {
    let t_max = lines
        .iter()
        .filter_map(|(_, t, _)| t.last().copied())
        .fold(0.0, f64::max)
        .max(1e-3);
    let y = range(lines.iter().flat_map(|(_, _, v)| v.iter().copied()));
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FAMILY, 18).into_font().color(&INK))
        .margin(14)
        .x_label_area_size(36)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..t_max, y.0..y.1)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc(y_desc)
        .label_style((FAMILY, 13).into_font().color(&INK))
        .axis_desc_style((FAMILY, 14).into_font().color(&INK))
        .light_line_style(RGBColor(0xf1, 0xf2, 0xf4))
        .bold_line_style(RGBColor(0xdc, 0xde, 0xe2))
        .draw()
        .map_err(|e| e.to_string())?;
    for (k, (label, t, v)) in lines.iter().enumerate() {
        let colour = colours[k % colours.len()];
        chart
            .draw_series(LineSeries::new(
                t.iter().copied().zip(v.iter().copied()),
                colour.stroke_width(2),
            ))
            .map_err(|e| e.to_string())?
            .label(*label)
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 22, y)], colour.stroke_width(3)));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .label_font((FAMILY, 13).into_font().color(&INK))
        .background_style(WHITE.mix(0.88))
        .border_style(RGBColor(0xc8, 0xcc, 0xd2))
        .draw()
        .map_err(|e| e.to_string())
}

/// Draws the report's plot into `path` (PNG, [`PLOT_SIZE`]).
pub fn plot_trunk_x_z(report: &Report, path: &Path) -> Result<(), CompareError> {
    let s = &report.series;
    let [a, b] = &report.sides;
    let title = format!(
        "{} vs {}: scenario {}, seed {}",
        a.label, b.label, report.scenario, report.seed
    );
    let x = [
        (
            a.label.as_str(),
            s.time_s[0].as_slice(),
            s.x_m[0].as_slice(),
        ),
        (
            b.label.as_str(),
            s.time_s[1].as_slice(),
            s.x_m[1].as_slice(),
        ),
    ];
    let z = [
        (
            a.label.as_str(),
            s.time_s[0].as_slice(),
            s.z_m[0].as_slice(),
        ),
        (
            b.label.as_str(),
            s.time_s[1].as_slice(),
            s.z_m[1].as_slice(),
        ),
    ];
    let d = [(
        "divergence",
        s.divergence_time_s.as_slice(),
        s.trunk_position_m.as_slice(),
    )];
    plot_panels(
        path,
        &title,
        [
            Panel::new("trunk x", "x (m)", &x, &COLOURS),
            Panel::new("trunk z", "z (m)", &z, &COLOURS),
            Panel::new("trunk position divergence |C_A − C_B|", "m", &d, &[GREEN]),
        ],
    )
}

/// Draws a several-backend report's plot into `path` (PNG, [`PLOT_SIZE`]): every backend's
/// trunk x and z, and every pair's trunk position divergence.
pub fn plot_many(report: &MultiReport, path: &Path) -> Result<(), CompareError> {
    let labels: Vec<&str> = report.sides.iter().map(|s| s.label.as_str()).collect();
    let title = format!(
        "{}: scenario {}, seed {}",
        labels.join(" vs "),
        report.scenario,
        report.seed
    );
    let x: Vec<(&str, &[f64], &[f64])> = labels
        .iter()
        .zip(&report.traces)
        .map(|(l, t)| (*l, t[0].as_slice(), t[1].as_slice()))
        .collect();
    let z: Vec<(&str, &[f64], &[f64])> = labels
        .iter()
        .zip(&report.traces)
        .map(|(l, t)| (*l, t[0].as_slice(), t[2].as_slice()))
        .collect();
    let names: Vec<String> = report
        .pairs
        .iter()
        .map(|p| format!("{} vs {}", p.labels[0], p.labels[1]))
        .collect();
    let d: Vec<(&str, &[f64], &[f64])> = names
        .iter()
        .zip(&report.reports)
        .map(|(n, r)| {
            (
                n.as_str(),
                r.series.divergence_time_s.as_slice(),
                r.series.trunk_position_m.as_slice(),
            )
        })
        .collect();
    plot_panels(
        path,
        &title,
        [
            Panel::new("trunk x", "x (m)", &x, &COLOURS),
            Panel::new("trunk z", "z (m)", &z, &COLOURS),
            Panel::new("trunk position divergence per pair", "m", &d, &PAIR_COLOURS),
        ],
    )
}

/// Draws a policy comparison's plot into `path` (PNG, [`PLOT_SIZE`]): every engine's
/// first-episode trunk x closed loop, the same under the replayed actions, and every pair's
/// trunk position divergence over the first episodes.
pub fn plot_policy(report: &PolicyReport, path: &Path) -> Result<(), CompareError> {
    let labels: Vec<&str> = report.sides.iter().map(|s| s.label.as_str()).collect();
    let title = format!(
        "{}: policy, closed loop, seed {}",
        labels.join(" vs "),
        report.seed
    );
    let xs: Vec<Vec<f64>> = report
        .traces
        .iter()
        .map(|t| t.position_m.iter().map(|p| p[0]).collect())
        .collect();
    let lines: Vec<(&str, &[f64], &[f64])> = report
        .traces
        .iter()
        .zip(&xs)
        .map(|(t, x)| (t.label.as_str(), t.time_s.as_slice(), x.as_slice()))
        .collect();
    let (closed, replayed) = lines.split_at(report.sides.len().min(lines.len()));
    let source = report
        .replay
        .as_ref()
        .map_or(String::new(), |r| format!(" ({}'s actions)", r.source));
    let names: Vec<String> = report
        .pairs
        .iter()
        .map(|p| format!("{} vs {}", p.labels[0], p.labels[1]))
        .collect();
    let times: Vec<Vec<f64>> = report
        .pairs
        .iter()
        .map(|p| {
            (0..p.divergence_m.len())
                .map(|k| k as f64 * report.env_dt_s)
                .collect()
        })
        .collect();
    let d: Vec<(&str, &[f64], &[f64])> = names
        .iter()
        .zip(&times)
        .zip(&report.pairs)
        .map(|((n, t), p)| (n.as_str(), t.as_slice(), p.divergence_m.as_slice()))
        .collect();
    let open_loop = format!("trunk x, open loop{source}");
    plot_panels(
        path,
        &title,
        [
            Panel::new(
                "trunk x, closed loop (first episode)",
                "x (m)",
                closed,
                &COLOURS,
            ),
            Panel::new(&open_loop, "x (m)", replayed, &COLOURS),
            Panel::new(
                "trunk position divergence per pair, closed loop",
                "m",
                &d,
                &PAIR_COLOURS,
            ),
        ],
    )
}

/// One of a plot's three stacked panels: its caption, y-axis label, lines (label, times,
/// values) and their colours.
struct Panel<'a> {
    caption: &'a str,
    y_desc: &'a str,
    lines: &'a [(&'a str, &'a [f64], &'a [f64])],
    colours: &'a [RGBColor],
}

impl<'a> Panel<'a> {
    fn new(
        caption: &'a str,
        y_desc: &'a str,
        lines: &'a [(&'a str, &'a [f64], &'a [f64])],
        colours: &'a [RGBColor],
    ) -> Self {
        Self {
            caption,
            y_desc,
            lines,
            colours,
        }
    }
}

/// Draws `title` over three stacked panels into `path` (PNG, [`PLOT_SIZE`]): every
/// comparison plot's frame.
fn plot_panels(path: &Path, title: &str, panels: [Panel<'_>; 3]) -> Result<(), CompareError> {
    let fail = |message: String| CompareError::Plot {
        path: path.to_owned(),
        message,
    };
    font_registered().map_err(fail)?;
    let (width, height) = PLOT_SIZE;
    let mut rgb = vec![0u8; width as usize * height as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (width, height)).into_drawing_area();
        let drawn =
            root.fill(&WHITE)
                .map_err(|e| e.to_string())
                .and_then(|()| {
                    root.titled(title, (FAMILY, 22).into_font().color(&INK))
                        .map_err(|e| e.to_string())
                })
                .and_then(|body| {
                    let areas = body.split_evenly((3, 1));
                    areas.iter().zip(&panels).try_for_each(|(area, p)| {
                        panel(area, p.caption, p.y_desc, p.lines, p.colours)
                    })
                })
                .and_then(|()| root.present().map_err(|e| e.to_string()));
        drawn.map_err(fail)?;
    }
    write_png(path, &rgb, (width, height)).map_err(|e| fail(e.to_string()))
}

fn write_png(
    path: &Path,
    rgb: &[u8],
    (width, height): (u32, u32),
) -> Result<(), png::EncodingError> {
    let file = std::fs::File::create(path)?;
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::High);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(rgb)?;
    writer.finish()
}
