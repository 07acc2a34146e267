//! Per-episode plots (PNG, drawn with plotters into an RGB buffer): the spec's Figures 3–6
//! redrawn from a real run.
//!
//! - [`plot_reward_terms`]: every reward term per step (r_b, r_n, r_e, r_reach), the penalty
//!   multipliers (m_yaw, m_pitch, m_height), the step reward with the fixed penalties, and the
//!   cumulative reward with the cumulative r_b, r_n (the spec's Figure 4) and r_e.
//! - [`plot_regularizers`] and [`plot_velocity_terms`]: the gait regularisers, and the velocity
//!   task's command, reward and terms, when the records hold them.
//! - [`plot_distance`]: D_n over time, and the §4.3 curve R_e(D_n) (Figures 5–6, from
//!   `hyq_spec::reward::exponential::cumulative_exponential_reward`) with the episode's points
//!   (D_n^t, Σ_{s≤t} r_e^s) on it. r_e is R_e's change per step and D_n^0 = 1 where R_e = 0, so
//!   the points sit on the curve exactly when the environment paid r_e as the spec says: the
//!   plot doubles as a visual check.
//!
//! Text uses the bundled DejaVu Sans (registered with plotters once per process), so plots look
//! the same on every machine.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use hyq_spec::reward::exponential::cumulative_exponential_reward;
use hyq_spec::terms::terms_of;
use hyq_spec::{RewardTerm, TermKind};
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::FontStyle;

use crate::error::PlotError;
use crate::frame::Frame;
use crate::records::{
    EpisodeSeries, PlotRecord, VELOCITY_COMMAND_COLUMNS, cumulative, read_jsonl, split_episodes,
};
use crate::text::{SANS, SANS_BOLD};
use crate::writer::write_png;

/// Size of the reward-terms plot (px).
pub const REWARD_PLOT_SIZE: (u32, u32) = (1280, 900);
/// Size of the distance plot (px).
pub const DISTANCE_PLOT_SIZE: (u32, u32) = (1280, 520);

/// The font family name the bundled fonts are registered under.
const FAMILY: &str = "sans-serif";

const BLUE: RGBColor = RGBColor(0x4e, 0x79, 0xa7);
const ORANGE: RGBColor = RGBColor(0xf2, 0x8e, 0x2b);
const GREEN: RGBColor = RGBColor(0x59, 0xa1, 0x4f);
const RED: RGBColor = RGBColor(0xe1, 0x57, 0x59);
const TEAL: RGBColor = RGBColor(0x76, 0xb7, 0xb2);
const YELLOW: RGBColor = RGBColor(0xed, 0xc9, 0x48);
const PURPLE: RGBColor = RGBColor(0xb0, 0x7a, 0xa1);
const BROWN: RGBColor = RGBColor(0x9c, 0x75, 0x5f);
const INK: RGBColor = RGBColor(0x2b, 0x2f, 0x36);
const GREY: RGBColor = RGBColor(0x9a, 0xa0, 0xa8);

/// What to put on an episode's plots besides its data.
#[derive(Clone, Debug, PartialEq)]
pub struct PlotOptions {
    /// Title above each plot, before what the plot shows, e.g. `"rapier, seed 7, episode 3"`;
    /// empty for none. [`plot_jsonl`] appends the episode's number.
    pub title: String,
    /// k_exp (`exp_rew_scaling`) of the run, for the R_e curve; `None` when r_e was off.
    pub k_exp: Option<f64>,
    /// The env step's duration (s): given, the time axes are in seconds (t · Δt); `None`, they
    /// count env steps.
    pub env_dt_s: Option<f64>,
}

impl PlotOptions {
    /// The x values and the axis label for a series' steps.
    fn time_axis(&self, t: &[f64]) -> (Vec<f64>, &'static str) {
        match self.env_dt_s {
            Some(dt) => (t.iter().map(|t| t * dt).collect(), "time (s)"),
            None => (t.to_vec(), "t (env steps)"),
        }
    }
}

impl Default for PlotOptions {
    fn default() -> Self {
        Self {
            title: String::new(),
            k_exp: Some(5.0),
            env_dt_s: None,
        }
    }
}

/// A plot's title: the caller's title, then what the plot shows.
fn heading(title: &str, what: &str) -> String {
    if title.is_empty() {
        what.to_owned()
    } else {
        format!("{title}: {what}")
    }
}

/// Checks k_exp and Δt.
fn check_options(options: &PlotOptions) -> Result<(), PlotError> {
    if let Some(k) = options.k_exp
        && !(k.is_finite() && k > 0.0)
    {
        return Err(PlotError::KExp { value: k });
    }
    if let Some(dt) = options.env_dt_s
        && !(dt.is_finite() && dt > 0.0)
    {
        return Err(PlotError::EnvDt { value: dt });
    }
    Ok(())
}

/// Registers the bundled fonts with plotters (once per process).
fn fonts_registered() -> Result<(), PlotError> {
    static REGISTERED: OnceLock<Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            for (style, bytes) in [(FontStyle::Normal, SANS), (FontStyle::Bold, SANS_BOLD)] {
                plotters::style::register_font(FAMILY, style, bytes)
                    .map_err(|_| "the bundled font could not be registered".to_owned())?;
            }
            Ok(())
        })
        .clone()
        .map_err(|message| PlotError::Draw {
            plot: "fonts",
            message,
        })
}

/// Draws into a white `width × height` RGB buffer with `draw`, then writes it as a PNG.
fn render_png(
    path: &Path,
    (width, height): (u32, u32),
    plot: &'static str,
    draw: impl FnOnce(&DrawingArea<BitMapBackend<'_>, Shift>) -> Result<(), String>,
) -> Result<(), PlotError> {
    fonts_registered()?;
    let mut frame = Frame::new(width, height);
    {
        let root = BitMapBackend::with_buffer(&mut frame.rgb, (width, height)).into_drawing_area();
        let result = root
            .fill(&WHITE)
            .map_err(|e| e.to_string())
            .and_then(|()| draw(&root))
            .and_then(|()| root.present().map_err(|e| e.to_string()));
        result.map_err(|message| PlotError::Draw { plot, message })?;
    }
    write_png(path, &frame)?;
    Ok(())
}

/// The largest magnitude an axis end may have: the span of two such ends and its padding stay
/// finite (an axis reaching ±inf makes the plotting library loop forever). Values beyond it are
/// drawn at the edge of the plot.
const AXIS_LIMIT: f64 = f64::MAX / 4.0;

/// The range of the finite `values` (and of `also`), padded by 6 %, never empty, each end
/// within ±[`AXIS_LIMIT`].
fn padded_range<'a>(values: impl IntoIterator<Item = &'a f64>, also: &'a [f64]) -> (f64, f64) {
    let (lo, hi) = values
        .into_iter()
        .chain(also)
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    if lo > hi {
        return (-1.0, 1.0);
    }
    let (lo, hi) = (
        lo.clamp(-AXIS_LIMIT, AXIS_LIMIT),
        hi.clamp(-AXIS_LIMIT, AXIS_LIMIT),
    );
    // At most 2 · AXIS_LIMIT, and so is each padded end: finite.
    let span = hi - lo;
    if span < 1e-9 {
        let d = lo.abs().max(1.0) * 0.1;
        return (lo - d, hi + d);
    }
    (lo - 0.06 * span, hi + 0.06 * span)
}

/// The upper end of an axis that starts near 0: the largest finite value of `values`, at least
/// `at_least`, within [`AXIS_LIMIT`], times `scale` (at most 2, for padding). Every axis of the
/// plots is made by this or [`padded_range`], so no value of any series can make one infinite.
fn axis_end(values: impl IntoIterator<Item = f64>, at_least: f64, scale: f64) -> f64 {
    let max = values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold(at_least, f64::max);
    max.min(AXIS_LIMIT) * scale
}

/// `p` moved onto the chart whose axes span `x` and `y`: a value beyond an axis (a foreign
/// record's, or a sum past [`AXIS_LIMIT`]) is drawn at the edge, where the plotting library's
/// pixel arithmetic cannot overflow. Points inside are unchanged.
fn within(p: (f64, f64), x: (f64, f64), y: (f64, f64)) -> (f64, f64) {
    let clamp = |v: f64, (a, b): (f64, f64)| v.clamp(a.min(b), a.max(b));
    (clamp(p.0, x), clamp(p.1, y))
}

fn t_range(t: &[f64]) -> (f64, f64) {
    let (lo, hi) = (t[0], t[t.len() - 1]);
    if hi - lo < 1e-9 {
        (lo - 0.5, hi + 0.5)
    } else {
        (lo, hi)
    }
}

/// Points drawn as dots, with their legend label and colour.
type Markers<'a> = (String, RGBColor, Vec<(f64, f64)>);

/// One line of a panel.
struct Line<'a> {
    label: String,
    colour: RGBColor,
    ys: &'a [f64],
    width: u32,
}

fn caption_font() -> TextStyle<'static> {
    (FAMILY, 19, FontStyle::Bold).into_font().color(&INK)
}

/// Every panel's chart: f64 axes, drawn into the plot's RGB buffer.
type Chart<'a, 'b> =
    ChartContext<'a, BitMapBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// A panel's chart: `caption` above, the axes over `x` and `y` with their labels and light grid.
fn styled_chart<'a, 'b>(
    area: &'a DrawingArea<BitMapBackend<'b>, Shift>,
    caption: impl AsRef<str>,
    x: std::ops::Range<f64>,
    y: std::ops::Range<f64>,
    (x_desc, y_desc): (&str, &str),
) -> Result<Chart<'a, 'b>, String> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption, caption_font())
        .margin(14)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(x, y)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .label_style((FAMILY, 14).into_font().color(&INK))
        .axis_desc_style((FAMILY, 15).into_font().color(&INK))
        .light_line_style(RGBColor(0xf1, 0xf2, 0xf4))
        .max_light_lines(2)
        .bold_line_style(RGBColor(0xdc, 0xde, 0xe2))
        .draw()
        .map_err(|e| e.to_string())?;
    Ok(chart)
}

/// Draws the legend of the series labelled so far at `position`.
fn draw_legend<'a, 'b: 'a>(
    chart: &mut Chart<'a, 'b>,
    position: SeriesLabelPosition,
) -> Result<(), String> {
    chart
        .configure_series_labels()
        .position(position)
        .label_font((FAMILY, 14).into_font().color(&INK))
        .background_style(WHITE.mix(0.88))
        .border_style(RGBColor(0xc8, 0xcc, 0xd2))
        .draw()
        .map_err(|e| e.to_string())
}

/// A panel of lines over time, with a legend.
fn line_panel(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    caption: &str,
    (t, x_desc): (&[f64], &str),
    lines: &[Line<'_>],
    y_desc: &str,
    y_range: (f64, f64),
    markers: &[Markers<'_>],
) -> Result<(), String> {
    let (t0, t1) = t_range(t);
    let mut chart = styled_chart(
        area,
        caption,
        t0..t1,
        y_range.0..y_range.1,
        (x_desc, y_desc),
    )?;
    if y_range.0 < 0.0 && y_range.1 > 0.0 {
        chart
            .draw_series(LineSeries::new(
                [(t0, 0.0), (t1, 0.0)],
                GREY.stroke_width(1),
            ))
            .map_err(|e| e.to_string())?;
    }
    for line in lines {
        let colour = line.colour;
        chart
            .draw_series(LineSeries::new(
                t.iter()
                    .copied()
                    .zip(line.ys.iter().copied())
                    .map(|p| within(p, (t0, t1), y_range)),
                colour.stroke_width(line.width),
            ))
            .map_err(|e| e.to_string())?
            .label(line.label.as_str())
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 22, y)], colour.stroke_width(3)));
    }
    for (label, colour, points) in markers {
        let colour = *colour;
        chart
            .draw_series(
                points
                    .iter()
                    .map(|&p| Circle::new(within(p, (t0, t1), y_range), 5, colour.filled())),
            )
            .map_err(|e| e.to_string())?
            .label(label.as_str())
            .legend(move |(x, y)| Circle::new((x + 11, y), 5, colour.filled()));
    }
    draw_legend(&mut chart, SeriesLabelPosition::UpperLeft)
}

/// The colours of a kind's lines, given in the table's order (cycled past the last).
const REWARD_COLOURS: [RGBColor; 4] = [BLUE, ORANGE, GREEN, RED];
const MULTIPLIER_COLOURS: [RGBColor; 3] = [TEAL, YELLOW, PURPLE];
const PENALTY_COLOURS: [RGBColor; 2] = [PURPLE, BROWN];

/// The terms of `kind` with a colour each, from `palette` in the table's order.
fn coloured(
    kind: TermKind,
    palette: &'static [RGBColor],
) -> impl Iterator<Item = (&'static RewardTerm, RGBColor)> {
    terms_of(kind)
        .enumerate()
        .map(move |(i, t)| (t, palette[i % palette.len()]))
}

/// One panel of the reward-terms plot: what it draws, before any drawing.
struct Panel<'a> {
    caption: &'static str,
    lines: Vec<Line<'a>>,
    y_desc: &'static str,
    /// Fixed y range, or `None` for the padded range of the lines, the markers and 0.
    y_range: Option<(f64, f64)>,
    markers: Vec<Markers<'a>>,
}

/// The four panels of the reward-terms plot, every term of `hyq_spec::REWARD_TERMS` in the
/// panel of its kind: rewards per step; multipliers; the step reward with each penalty's
/// steps as markers; the cumulative reward with each reward's sum (`cumulative` holds Σ r, then
/// Σ of each reward term in the table's order).
fn reward_panels<'a>(
    series: &'a EpisodeSeries,
    t: &[f64],
    cumulative: &'a [Vec<f64>],
) -> [Panel<'a>; 4] {
    [
        rewards_panel(series),
        multipliers_panel(series),
        step_reward_panel(series, t),
        cumulative_panel(cumulative),
    ]
}

/// The column of `term` in `series` (empty if the series lacks it).
fn column<'a>(series: &'a EpisodeSeries, term: &RewardTerm) -> &'a [f64] {
    series.term(term.name).unwrap_or_default()
}

/// The first panel: each reward term per step.
fn rewards_panel(series: &EpisodeSeries) -> Panel<'_> {
    let rewards = coloured(TermKind::Reward, &REWARD_COLOURS)
        .map(|(term, colour)| Line {
            label: term.name.to_owned(),
            colour,
            ys: column(series, term),
            width: 2,
        })
        .collect();
    Panel {
        caption: "Reward terms per step (§4)",
        lines: rewards,
        y_desc: "reward",
        y_range: None,
        markers: Vec::new(),
    }
}

/// The second panel: each multiplier per step.
fn multipliers_panel(series: &EpisodeSeries) -> Panel<'_> {
    // The multipliers are often all 1 at once: the first is drawn widest, so that the lines
    // drawn over it leave it visible.
    let multipliers = coloured(TermKind::Multiplier, &MULTIPLIER_COLOURS)
        .enumerate()
        .map(|(i, (term, colour))| Line {
            label: term.name.to_owned(),
            colour,
            ys: column(series, term),
            width: if i == 0 { 3 } else { 2 },
        })
        .collect();
    Panel {
        caption: "Penalty multipliers (§5.1, §5.2)",
        lines: multipliers,
        y_desc: "multiplier",
        y_range: Some((-0.05, 1.12)),
        markers: Vec::new(),
    }
}

/// The third panel: the step reward, and each penalty as markers at the steps (times `t`)
/// where it was paid.
fn step_reward_panel<'a>(series: &'a EpisodeSeries, t: &[f64]) -> Panel<'a> {
    let penalties = coloured(TermKind::Penalty, &PENALTY_COLOURS)
        .map(|(term, colour)| {
            let points = t
                .iter()
                .zip(column(series, term))
                .filter(|(_, p)| **p != 0.0)
                .map(|(&x, &p)| (x, -p))
                .collect();
            (format!("− {}", term.name), colour, points)
        })
        .collect();
    Panel {
        caption: "Step reward and fixed penalties (§5.3, §5.4)",
        lines: vec![Line {
            label: "r (step reward)".to_owned(),
            colour: INK,
            ys: &series.reward,
            width: 2,
        }],
        y_desc: "reward",
        y_range: None,
        markers: penalties,
    }
}

/// The fourth panel: the return so far and each reward term's sum (`cumulative` as
/// [`reward_panels`] takes it).
fn cumulative_panel(cumulative: &[Vec<f64>]) -> Panel<'_> {
    let (sum_of_rewards, sums_of_terms) = cumulative.split_first().unzip();
    let sums = std::iter::once(Line {
        label: "Σ r (return)".to_owned(),
        colour: INK,
        ys: sum_of_rewards.map_or(&[][..], Vec::as_slice),
        width: 3,
    })
    .chain(
        coloured(TermKind::Reward, &REWARD_COLOURS)
            .zip(sums_of_terms.unwrap_or_default())
            .map(|((term, colour), ys)| Line {
                label: match term.sum_name {
                    Some(sum) => format!("Σ {} = {sum}", term.name),
                    None => format!("Σ {}", term.name),
                },
                colour,
                ys,
                width: 2,
            }),
    )
    .collect();
    Panel {
        caption: "Cumulative reward",
        lines: sums,
        y_desc: "cumulative reward",
        y_range: None,
        markers: Vec::new(),
    }
}

/// Σ r, then Σ of each reward term, per step (the cumulative panel's lines).
fn cumulative_rewards(series: &EpisodeSeries) -> Vec<Vec<f64>> {
    std::iter::once(cumulative(&series.reward))
        .chain(
            terms_of(TermKind::Reward).map(|t| cumulative(series.term(t.name).unwrap_or_default())),
        )
        .collect()
}

/// The legend labels of the reward-terms plot of `series`, panel by panel, as
/// [`plot_reward_terms`] draws them.
pub fn reward_plot_legend(series: &EpisodeSeries) -> Vec<String> {
    let cumulative = cumulative_rewards(series);
    reward_panels(series, &series.t, &cumulative)
        .into_iter()
        .flat_map(|p| {
            p.lines
                .into_iter()
                .map(|l| l.label)
                .chain(p.markers.into_iter().map(|m| m.0))
        })
        .collect()
}

/// Writes the reward-terms plot of one episode ([`REWARD_PLOT_SIZE`]) to `path`.
pub fn plot_reward_terms(
    series: &EpisodeSeries,
    options: &PlotOptions,
    path: impl AsRef<Path>,
) -> Result<(), PlotError> {
    series.validate()?;
    check_options(options)?;
    let (t, x_desc) = options.time_axis(&series.t);
    let t = &t;
    let total: f64 = series.reward.iter().sum();
    let duration = match options.env_dt_s {
        Some(_) => format!(", {:.2} s", t[t.len() - 1]),
        None => String::new(),
    };
    let title = heading(
        &options.title,
        &format!(
            "reward terms ({} steps{duration}, return {total:.2})",
            series.len()
        ),
    );
    let cumulative = cumulative_rewards(series);
    let panels = reward_panels(series, t, &cumulative);

    render_png(path.as_ref(), REWARD_PLOT_SIZE, "reward terms", |root| {
        let body = root
            .titled(
                &title,
                (FAMILY, 24, FontStyle::Bold).into_font().color(&INK),
            )
            .map_err(|e| e.to_string())?;
        for (area, panel) in body.split_evenly((2, 2)).iter().zip(&panels) {
            let y_range = panel.y_range.unwrap_or_else(|| {
                padded_range(
                    panel.lines.iter().flat_map(|l| l.ys).chain(
                        panel
                            .markers
                            .iter()
                            .flat_map(|m| m.2.iter().map(|(_, y)| y)),
                    ),
                    &[0.0],
                )
            });
            line_panel(
                area,
                panel.caption,
                (t, x_desc),
                &panel.lines,
                panel.y_desc,
                y_range,
                &panel.markers,
            )?;
        }
        Ok(())
    })
}

/// The width of the regularisers' plot and the height of each of its rows of two panels.
pub const REGULARIZER_PLOT_CELL: (u32, u32) = (1280, 300);

/// Writes the gait regularisers' plot of one episode to `path`: each term the records hold,
/// unscaled, in a panel of its own (two to a row of [`REGULARIZER_PLOT_CELL`]'s height). An
/// episode without regularisers is an error.
pub fn plot_regularizers(
    series: &EpisodeSeries,
    options: &PlotOptions,
    path: impl AsRef<Path>,
) -> Result<(), PlotError> {
    series.validate()?;
    check_options(options)?;
    if series.regularizers.is_empty() {
        return Err(PlotError::Empty {
            what: "the episode's gait regularisers".into(),
        });
    }
    let (t, x_desc) = options.time_axis(&series.t);
    let t = &t;
    let rows = series.regularizers.len().div_ceil(2);
    let (width, row_height) = REGULARIZER_PLOT_CELL;
    let height = 60 + row_height * u32::try_from(rows).unwrap_or(u32::MAX / row_height / 2);
    let title = heading(
        &options.title,
        &format!("gait regularisers, unscaled ({} steps)", series.len()),
    );
    render_png(path.as_ref(), (width, height), "regularizers", |root| {
        let body = root
            .titled(
                &title,
                (FAMILY, 24, FontStyle::Bold).into_font().color(&INK),
            )
            .map_err(|e| e.to_string())?;
        let areas = body.split_evenly((rows, 2));
        term_panels(&areas, &series.regularizers, (t, x_desc))
    })
}

/// The colours of one-term panels, in turn.
const TERM_COLOURS: [RGBColor; 7] = [BLUE, ORANGE, GREEN, RED, TEAL, PURPLE, BROWN];

/// One panel per named column, in `areas` order, each its term per step over time.
fn term_panels(
    areas: &[DrawingArea<BitMapBackend<'_>, Shift>],
    columns: &Columns,
    (t, x_desc): (&[f64], &str),
) -> Result<(), String> {
    for (k, (area, (name, column))) in areas.iter().zip(columns).enumerate() {
        let lines = [Line {
            label: (*name).to_owned(),
            colour: TERM_COLOURS[k % TERM_COLOURS.len()],
            ys: column,
            width: 2,
        }];
        let y_range = padded_range(column.iter(), &[0.0]);
        line_panel(area, name, (t, x_desc), &lines, "per step", y_range, &[])?;
    }
    Ok(())
}

/// Named columns of a series.
type Columns = [(&'static str, Vec<f64>)];

/// The velocity task's columns of `series`: the command's, then the terms'; an error when the
/// series holds none.
fn velocity_columns(series: &EpisodeSeries) -> Result<(&Columns, &Columns), PlotError> {
    let n = VELOCITY_COMMAND_COLUMNS.len();
    let holds_command = series.velocity.len() > n
        && series.velocity[..n]
            .iter()
            .zip(VELOCITY_COMMAND_COLUMNS)
            .all(|((a, _), b)| *a == b);
    if !holds_command {
        return Err(PlotError::Empty {
            what: "the episode's velocity-task columns".into(),
        });
    }
    Ok(series.velocity.split_at(n))
}

/// The velocity plot's first panel: the command in thick lines and the trunk's measured
/// velocity (when recorded) in thin ones of the same colour, so a follower's thin line runs
/// along its thick one; with their y range and the panel's caption.
fn command_and_measured<'a>(
    command: &'a Columns,
    series: &'a EpisodeSeries,
) -> (Vec<Line<'a>>, (f64, f64), &'static str) {
    let labels = ["v_x (m/s)", "v_y (m/s)", "ω_z (rad/s)"];
    let colours = [BLUE, ORANGE, GREEN];
    let measured = &series.velocity_measured;
    let lines = |columns: &'a Columns, width: u32, suffix: &'static str| {
        columns
            .iter()
            .zip(labels)
            .zip(colours)
            .map(move |((column, label), colour)| Line {
                label: format!("{label}{suffix}"),
                colour,
                ys: &column.1,
                width,
            })
    };
    let lines = lines(command, 2, "")
        .chain(lines(measured, 1, ", measured"))
        .collect();
    let y_range = padded_range(command.iter().chain(measured).flat_map(|c| &c.1), &[0.0]);
    let panel = if measured.is_empty() {
        "command"
    } else {
        "command (thick) and measured (thin)"
    };
    (lines, y_range, panel)
}

/// Writes the velocity task's plot of one episode to `path`: the command over time (with the
/// trunk's measured velocity when the records hold it), the
/// step's reward (the task's), and every task term unscaled, each in a panel of its own (two to
/// a row of [`REGULARIZER_PLOT_CELL`]'s height). An episode without the task's columns is an
/// error.
pub fn plot_velocity_terms(
    series: &EpisodeSeries,
    options: &PlotOptions,
    path: impl AsRef<Path>,
) -> Result<(), PlotError> {
    series.validate()?;
    check_options(options)?;
    let (command, terms) = velocity_columns(series)?;
    let (t, x_desc) = options.time_axis(&series.t);
    let t = &t;
    let rows = (terms.len() + 2).div_ceil(2);
    let (width, row_height) = REGULARIZER_PLOT_CELL;
    let height = 60 + row_height * u32::try_from(rows).unwrap_or(u32::MAX / row_height / 2);
    let title = heading(
        &options.title,
        &format!(
            "velocity task: command and terms, unscaled ({} steps)",
            series.len()
        ),
    );
    render_png(path.as_ref(), (width, height), "velocity", |root| {
        let body = root
            .titled(
                &title,
                (FAMILY, 24, FontStyle::Bold).into_font().color(&INK),
            )
            .map_err(|e| e.to_string())?;
        let areas = body.split_evenly((rows, 2));
        let (command_lines, y_range, panel) = command_and_measured(command, series);
        line_panel(
            &areas[0],
            panel,
            (t, x_desc),
            &command_lines,
            "",
            y_range,
            &[],
        )?;
        let reward = [Line {
            label: "reward".to_owned(),
            colour: INK,
            ys: &series.reward,
            width: 2,
        }];
        let y_range = padded_range(series.reward.iter(), &[0.0]);
        line_panel(
            &areas[1],
            "step reward",
            (t, x_desc),
            &reward,
            "per step",
            y_range,
            &[],
        )?;
        term_panels(&areas[2..], terms, (t, x_desc))
    })
}

/// Writes the distance plot of one episode ([`DISTANCE_PLOT_SIZE`]) to `path`: D_n over time,
/// and R_e(D_n) with the episode's points.
pub fn plot_distance(
    series: &EpisodeSeries,
    options: &PlotOptions,
    path: impl AsRef<Path>,
) -> Result<(), PlotError> {
    series.validate()?;
    check_options(options)?;
    let (t, x_desc) = options.time_axis(&series.t);
    let t = &t;
    let d_n: Vec<(f64, f64)> = t
        .iter()
        .zip(&series.d_n)
        .filter_map(|(&x, d)| d.map(|d| (x, d)))
        .collect();
    // K = D^t / D_n^t, the same for every step; shown so that D_n can be read in metres.
    let k_m = series
        .d_n
        .iter()
        .zip(&series.distance_to_goal)
        .find_map(|(d, &dist)| d.filter(|d| *d > 1e-9).map(|d| dist / d))
        // Only a K the environment could have had is shown (a foreign record may hold any).
        .filter(|k| k.is_finite() && k.abs() < 1e6);
    // The exponential reward against its §4.3 curve: Σ r_e is R_e(D_n).
    let cum_e = cumulative(series.term("r_e").unwrap_or_default());
    let points: Vec<(f64, f64)> = series
        .d_n
        .iter()
        .zip(&cum_e)
        .filter_map(|(d, &r)| d.map(|d| (d, r)))
        .collect();
    let title = match k_m {
        Some(k) => heading(&options.title, &format!("distance to goal (K = {k:.2} m)")),
        None => heading(&options.title, "distance to goal"),
    };

    render_png(path.as_ref(), DISTANCE_PLOT_SIZE, "distance", |root| {
        let body = root
            .titled(
                &title,
                (FAMILY, 24, FontStyle::Bold).into_font().color(&INK),
            )
            .map_err(|e| e.to_string())?;
        let (left, right) = body.split_horizontally(body.dim_in_pixel().0 / 2);

        draw_distance_over_time(&left, t, x_desc, &d_n)?;
        draw_exponential_curve(&right, &points, options.k_exp)
    })
}

/// The left panel of the distance plot: D_n over time (`t`, described by `x_desc`), with the
/// start (1) and the goal (0).
fn draw_distance_over_time(
    left: &DrawingArea<BitMapBackend<'_>, Shift>,
    t: &[f64],
    x_desc: &str,
    d_n: &[(f64, f64)],
) -> Result<(), String> {
    let (t0, t1) = t_range(t);
    let y_hi = axis_end(d_n.iter().map(|p| p.1), 1.0, 1.08);
    let mut chart = styled_chart(
        left,
        "Normalised distance D_n = D / K (§4.2)",
        t0..t1,
        -0.04..y_hi,
        (x_desc, "D_n"),
    )?;
    for (y, label, colour) in [
        (1.0, "start (D_n = 1)", GREY),
        (0.0, "goal (D_n = 0)", GREEN),
    ] {
        chart
            .draw_series(DashedLineSeries::new(
                [(t0, y), (t1, y)],
                8,
                6,
                colour.stroke_width(2),
            ))
            .map_err(|e| e.to_string())?
            .label(label)
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 22, y)], colour.stroke_width(2)));
    }
    chart
        .draw_series(LineSeries::new(
            d_n.iter().map(|&p| within(p, (t0, t1), (-0.04, y_hi))),
            BLUE.stroke_width(3),
        ))
        .map_err(|e| e.to_string())?
        .label("D_n")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 22, y)], BLUE.stroke_width(3)));
    draw_legend(&mut chart, SeriesLabelPosition::UpperRight)?;
    Ok(())
}

/// The right panel of the distance plot: the §4.3 curve R_e(D_n) for `k_exp` (none when r_e
/// is off) and the episode's points (D_n^t, Σ r_e) on it.
fn draw_exponential_curve(
    right: &DrawingArea<BitMapBackend<'_>, Shift>,
    points: &[(f64, f64)],
    k_exp: Option<f64>,
) -> Result<(), String> {
    let x_hi = axis_end(points.iter().map(|p| p.0), 1.2, 1.06);
    let curve: Vec<(f64, f64)> = match k_exp {
        Some(k) => (0..=600)
            .map(|i| {
                let d = x_hi * f64::from(i) / 600.0;
                (d, cumulative_exponential_reward(d, k))
            })
            .collect(),
        None => Vec::new(),
    };
    let (y_lo, y_hi) = padded_range(curve.iter().chain(points).map(|p| &p.1), &[0.0]);
    let caption = match k_exp {
        Some(k) => format!("R_e(D_n), k_exp = {k} (§4.3), and this episode"),
        None => "Σ r_e against D_n (r_e off: no curve)".to_owned(),
    };
    let mut chart = styled_chart(right, caption, 0.0..x_hi, y_lo..y_hi, ("D_n", "R_e"))?;
    if !curve.is_empty() {
        chart
            .draw_series(LineSeries::new(
                curve.iter().map(|&p| within(p, (0.0, x_hi), (y_lo, y_hi))),
                GREEN.stroke_width(3),
            ))
            .map_err(|e| e.to_string())?
            .label("R_e(D_n), the spec's curve")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 22, y)], GREEN.stroke_width(3)));
    }
    let n = points.len().max(2) - 1;
    chart
        .draw_series(points.iter().enumerate().map(|(i, &p)| {
            // Early steps light, late steps dark.
            let s = i as f64 / n as f64;
            let mix = |a: u8, b: u8| (f64::from(a) + (f64::from(b) - f64::from(a)) * s) as u8;
            let c = RGBColor(mix(0xa6, 0x1f), mix(0xc8, 0x3a), mix(0xe8, 0x6b));
            Circle::new(within(p, (0.0, x_hi), (y_lo, y_hi)), 4, c.filled())
        }))
        .map_err(|e| e.to_string())?
        .label("(D_n^t, Σ r_e), light → dark with time")
        .legend(|(x, y)| Circle::new((x + 11, y), 4, BLUE.filled()));
    chart
        .draw_series(std::iter::once(Circle::new(
            (1.0, 0.0),
            7,
            INK.stroke_width(2),
        )))
        .map_err(|e| e.to_string())?
        .label("start: D_n = 1, R_e = 0")
        .legend(|(x, y)| Circle::new((x + 11, y), 6, INK.stroke_width(2)));
    draw_legend(&mut chart, SeriesLabelPosition::UpperRight)
}

/// The two files [`plot_episode`] writes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EpisodePlots {
    /// `<stem>_rewards.png`, from [`plot_reward_terms`].
    pub rewards: PathBuf,
    /// `<stem>_distance.png`, from [`plot_distance`].
    pub distance: PathBuf,
    /// `<stem>_regularizers.png`, from [`plot_regularizers`], when the episode's records hold
    /// gait regularisers.
    pub regularizers: Option<PathBuf>,
    /// `<stem>_velocity.png`, from [`plot_velocity_terms`], when the episode's records hold
    /// the velocity task's command and terms.
    pub velocity: Option<PathBuf>,
}

/// Writes both plots of one episode into `dir` (created if missing) as `<stem>_rewards.png` and
/// `<stem>_distance.png`, `<stem>_regularizers.png` when its records hold gait regularisers,
/// and `<stem>_velocity.png` when they hold the velocity task's.
pub fn plot_episode(
    series: &EpisodeSeries,
    options: &PlotOptions,
    dir: impl AsRef<Path>,
    stem: &str,
) -> Result<EpisodePlots, PlotError> {
    let dir = dir.as_ref();
    std::fs::create_dir_all(dir).map_err(|source| crate::WriteError::Io {
        path: dir.to_owned(),
        source,
    })?;
    let plots = EpisodePlots {
        rewards: dir.join(format!("{stem}_rewards.png")),
        distance: dir.join(format!("{stem}_distance.png")),
        regularizers: (!series.regularizers.is_empty())
            .then(|| dir.join(format!("{stem}_regularizers.png"))),
        velocity: (!series.velocity.is_empty()).then(|| dir.join(format!("{stem}_velocity.png"))),
    };
    plot_reward_terms(series, options, &plots.rewards)?;
    plot_distance(series, options, &plots.distance)?;
    if let Some(path) = &plots.regularizers {
        plot_regularizers(series, options, path)?;
    }
    if let Some(path) = &plots.velocity {
        plot_velocity_terms(series, options, path)?;
    }
    Ok(plots)
}

/// Reads a JSONL file of step records and writes both plots of every episode in it into
/// `dir`, as `episode_001_rewards.png`, `episode_001_distance.png`, … (numbered by their
/// order in the file). `options.title` prefixes each plot's title (`"<title>, episode 1"`);
/// `options.k_exp` is the run's `exp_rew_scaling` and `options.env_dt_s` its env step. A torn
/// last line is left out and reported (see [`crate::parse_jsonl`]).
pub fn plot_jsonl(
    path: impl AsRef<Path>,
    options: &PlotOptions,
    dir: impl AsRef<Path>,
) -> Result<JsonlPlots, PlotError> {
    let path = path.as_ref();
    let read = read_jsonl(path)?;
    plot_records(&read.records, &path.display().to_string(), options, dir).map(|plots| JsonlPlots {
        plots,
        torn_last_line: read.torn_last_line,
    })
}

/// Writes both plots of every episode in `records` into `dir`, as [`plot_jsonl`] does for a
/// file; `origin` names the records in errors.
pub fn plot_records(
    records: &[PlotRecord],
    origin: &str,
    options: &PlotOptions,
    dir: impl AsRef<Path>,
) -> Result<Vec<EpisodePlots>, PlotError> {
    let episodes = split_episodes(records);
    if episodes.is_empty() {
        return Err(PlotError::Empty {
            what: origin.to_owned(),
        });
    }
    episodes
        .iter()
        .enumerate()
        .map(|(i, records)| {
            let title = match (options.title.as_str(), records[0].episode) {
                ("", Some(e)) => format!("episode {e}"),
                ("", None) => format!("episode {}", i + 1),
                (title, Some(e)) => format!("{title}, episode {e}"),
                (title, None) => format!("{title}, episode {}", i + 1),
            };
            let options = PlotOptions {
                title,
                ..options.clone()
            };
            plot_episode(
                &EpisodeSeries::from_records(records),
                &options,
                dir.as_ref(),
                &format!("episode_{:03}", i + 1),
            )
        })
        .collect()
}

/// What [`plot_jsonl`] wrote, and the torn last line it left out, if any.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct JsonlPlots {
    /// Both plots of every episode, in the file's order.
    pub plots: Vec<EpisodePlots>,
    /// The 1-based number of a torn last line that was left out.
    pub torn_last_line: Option<usize>,
}

#[cfg(test)]
mod tests {
    use super::padded_range;

    #[test]
    fn padded_ranges_stay_finite_with_a_finite_span() {
        for values in [
            vec![1e308, -1e308],
            vec![f64::MAX, -f64::MAX, 0.0],
            vec![f64::MAX],
            vec![f64::INFINITY, 2.0, f64::NAN],
            vec![],
        ] {
            let (lo, hi) = padded_range(&values, &[0.0]);
            assert!(
                lo.is_finite() && hi.is_finite() && (hi - lo).is_finite() && lo < hi,
                "{values:?} gave [{lo}, {hi}]"
            );
        }
        assert_eq!(padded_range(&[1.0, 3.0], &[]), (0.88, 3.12));
    }
}
