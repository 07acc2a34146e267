//! The comparison plots' frame: a title over three stacked panels of lines over time (each
//! report module fills them: trunk x and z per backend and the trunk position divergence
//! |C_A − C_B|, or a policy's closed-loop and replayed runs), drawn with plotters into an RGB buffer and
//! written as a PNG at the encoder's high compression (the plots are committed to the
//! repository, so they are kept small: about 100 KB).

use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontStyle;

use crate::error::CompareError;

/// The plot's size (px).
pub const PLOT_SIZE: (u32, u32) = (900, 780);

/// The family name this crate registers its font under (its own, so that it never replaces a
/// font another crate registered with plotters).
const FAMILY: &str = "hyq-compare-sans";

/// DejaVu Sans, the subset hyq-render bundles (its `assets/fonts/`, with the licence).
const SANS: &[u8] = hyq_render::SANS;

pub(crate) const COLOURS: [RGBColor; 3] = [
    RGBColor(0x4e, 0x79, 0xa7),
    RGBColor(0xe1, 0x57, 0x59),
    RGBColor(0xf2, 0x8e, 0x2b),
];
/// The pairs' divergence lines in a plot of three or more backends.
pub(crate) const PAIR_COLOURS: [RGBColor; 3] = [
    GREEN,
    RGBColor(0xb0, 0x7a, 0xa1),
    RGBColor(0x76, 0xb7, 0xb2),
];
pub(crate) const GREEN: RGBColor = RGBColor(0x59, 0xa1, 0x4f);
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

/// One of a plot's three stacked panels: its caption, y-axis label, lines (label, times,
/// values) and their colours.
pub(crate) struct Panel<'a> {
    caption: &'a str,
    y_desc: &'a str,
    lines: &'a [(&'a str, &'a [f64], &'a [f64])],
    colours: &'a [RGBColor],
}

impl<'a> Panel<'a> {
    pub(crate) fn new(
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
pub(crate) fn plot_panels(
    path: &Path,
    title: &str,
    panels: [Panel<'_>; 3],
) -> Result<(), CompareError> {
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
