//! The velocity-command task's display ([`VelocityHud`]): arrows on the ground under the trunk
//! and three rows of the text overlay.
//!
//! Both arrows start under the trunk frame's origin and lie in its heading frame (the trunk's
//! forward axis turned level): the command's is wide and green, the measured velocity's narrow
//! and purple over it, so a robot that follows its command shows one arrow inside the other.
//! A yaw rate is an arc around the same point starting straight ahead, a quarter turn per
//! rad/s, counter-clockwise seen from above for a positive rate, with a head at its end. They
//! are drawn after the robot, so that the robot never hides them.

use std::f64::consts::{FRAC_PI_2, PI};
use std::fmt::Write as _;

use hyq_physics::na::{Point3, Vector3};
use tiny_skia::{LineCap, Paint, PathBuilder, Shader, Stroke};

use super::{Renderer, Rgb, TEXT_PX, fill_solid, paint, push_world_polyline, shown, stroke_solid};
use crate::camera::Camera;
use crate::scene::VelocityHud;
use crate::terrain::LIFT_M;

/// The command's colour on the ground and its lighter shade in the text panel.
const COMMAND: Rgb = Rgb::hex(0x2ca25f);
const COMMAND_TEXT: Rgb = Rgb::hex(0x7fdca6);
/// The measured velocity's colour on the ground and in the text panel.
const MEASURED: Rgb = Rgb::hex(0x7b3fa0);
const MEASURED_TEXT: Rgb = Rgb::hex(0xd2a8f0);

/// Arrow length (m) per m/s, for a robot of the reference size, and the longest arrow (m).
const ARROW_M_PER_MPS: f64 = 2.0;
const ARROW_MAX_M: f64 = 4.0;
/// Half widths (m) of the command's and the measured arrow's shafts.
const COMMAND_HALF_WIDTH_M: f64 = 0.08;
const MEASURED_HALF_WIDTH_M: f64 = 0.035;
/// The yaw arcs' radii (m): the command's, and the measured one's inside it.
const COMMAND_ARC_M: f64 = 0.95;
const MEASURED_ARC_M: f64 = 0.8;
/// Arc sweep (rad) per rad/s of yaw rate, and the largest sweep.
const ARC_RAD_PER_RADPS: f64 = FRAC_PI_2;
const ARC_MAX_RAD: f64 = 1.8 * PI;
/// Arrows shorter than this (m) or arcs of less sweep (rad) are not drawn: the value is zero.
const SMALLEST: f64 = 1e-3;

/// The labels of the overlay's rows, in the order of `VelocityHud`'s values.
pub(super) const ROW_LABELS: [&str; 3] = ["forward", "sideways", "yaw rate"];
const UNITS: [&str; 3] = [" m/s", " m/s", " rad/s"];
/// The widest number a column holds; wider values spill to the left.
const WIDE_NUMBER: &str = "-00.00";
const COLUMN_GAP_PX: f32 = 8.0;

impl Renderer {
    /// The command's and the measured velocity's arrows and yaw arcs, on the ground.
    pub(super) fn draw_velocity_arrows(&mut self, cam: &Camera, hud: &VelocityHud) {
        let trunk = &self.poses[0];
        let origin = [trunk.translation.vector.x, trunk.translation.vector.y];
        let forward = trunk.rotation * Vector3::x();
        // A trunk pointing straight up or down has no heading; world x stands in.
        let heading = if forward.x.hypot(forward.y) > 1e-9 {
            forward.y.atan2(forward.x)
        } else {
            0.0
        };
        let s = self.scale;
        for (v, half_width, arc_r, colour) in [
            (&hud.command, COMMAND_HALF_WIDTH_M, COMMAND_ARC_M, COMMAND),
            (
                &hud.measured,
                MEASURED_HALF_WIDTH_M,
                MEASURED_ARC_M,
                MEASURED,
            ),
        ] {
            let speed = v[0].hypot(v[1]);
            let length = (speed * ARROW_M_PER_MPS * s).min(ARROW_MAX_M * s);
            if length > SMALLEST {
                let angle = heading + v[1].atan2(v[0]);
                let outline = arrow_outline(origin, angle, length, half_width * s);
                self.fill_ground_polygon(cam, &outline, colour.alpha(0.85));
            }
            let sweep = (v[2] * ARC_RAD_PER_RADPS).clamp(-ARC_MAX_RAD, ARC_MAX_RAD);
            if sweep.abs() > SMALLEST {
                self.draw_yaw_arc(cam, origin, heading, sweep, arc_r * s, colour);
            }
        }
    }

    /// An arc of radius `r` around `origin` from angle `from` over `sweep` (rad), stroked, with
    /// a head at its end pointing the way it turns.
    fn draw_yaw_arc(
        &mut self,
        cam: &Camera,
        origin: [f64; 2],
        from: f64,
        sweep: f64,
        r: f64,
        colour: Rgb,
    ) {
        let head = 0.16 * self.scale;
        // The stroke stops where the head begins.
        let body = sweep - sweep.signum() * (head / r).min(sweep.abs());
        let n = ((body.abs() / 0.05).ceil() as usize).max(1);
        let mut points = std::mem::take(&mut self.line_pts);
        points.clear();
        points.extend((0..=n).map(|i| {
            let a = from + body * i as f64 / n as f64;
            self.on_ground([origin[0] + r * a.cos(), origin[1] + r * a.sin()])
        }));
        let mut pb = PathBuilder::new();
        push_world_polyline(cam, &mut pb, &points);
        self.line_pts = points;
        if let Some(path) = pb.finish() {
            let stroke = Stroke {
                width: 4.0,
                line_cap: LineCap::Butt,
                ..Stroke::default()
            };
            stroke_solid(&mut self.pixmap, &path, colour.alpha(0.85), &stroke);
        }
        // The head: a triangle from the stroke's end to the arc's end, along the tangent.
        let (a0, a1) = (from + body, from + sweep);
        let base = [origin[0] + r * a0.cos(), origin[1] + r * a0.sin()];
        let tip = [origin[0] + r * a1.cos(), origin[1] + r * a1.sin()];
        let radial = [a0.cos() * head * 0.45, a0.sin() * head * 0.45];
        let triangle = [
            [base[0] + radial[0], base[1] + radial[1]],
            tip,
            [base[0] - radial[0], base[1] - radial[1]],
        ];
        self.fill_ground_polygon(cam, &triangle, colour.alpha(0.85));
    }

    /// The ground point under (x, y): on a height field just above its surface.
    fn on_ground(&self, p: [f64; 2]) -> Point3<f64> {
        let z = self
            .ground
            .as_deref()
            .map_or(0.0, |g| g.height_at(p[0], p[1]) + LIFT_M);
        Point3::new(p[0], p[1], z)
    }

    /// Fills a polygon of ground points (x, y), clipped to the near plane.
    fn fill_ground_polygon(
        &mut self,
        cam: &Camera,
        polygon: &[[f64; 2]],
        colour: tiny_skia::Color,
    ) {
        let corners: Vec<Point3<f64>> = polygon.iter().map(|&p| self.on_ground(p)).collect();
        if let Some(path) = self.world_polygon_path(cam, &corners) {
            fill_solid(&mut self.pixmap, &path, colour);
        }
    }

    /// The width (px) of the velocity rows' value column: two numbers and the widest unit.
    pub(super) fn velocity_value_width(&mut self) -> f32 {
        let number = self.bold.width(WIDE_NUMBER, TEXT_PX);
        let unit = self.text.width(UNITS[2], TEXT_PX);
        2.0 * number + COLUMN_GAP_PX + unit
    }

    /// The overlay's velocity rows from `baseline` on: the label, the command (green), the
    /// measured value (purple) and the unit, right-aligned at `right`.
    pub(super) fn draw_velocity_rows(
        &mut self,
        x0: f32,
        right: f32,
        baseline: f32,
        hud: &VelocityHud,
        label_paint: &Paint<'_>,
    ) {
        let number_w = self.bold.width(WIDE_NUMBER, TEXT_PX);
        let unit_w = self.text.width(UNITS[2], TEXT_PX);
        let measured_right = right - unit_w;
        let command_right = measured_right - number_w - COLUMN_GAP_PX;
        let command_paint = paint(Shader::SolidColor(COMMAND_TEXT.opaque()));
        let measured_paint = paint(Shader::SolidColor(MEASURED_TEXT.opaque()));
        for row in 0..ROW_LABELS.len() {
            let y = baseline + row as f32 * super::LINE_PX;
            self.text.draw(
                &mut self.pixmap,
                ROW_LABELS[row],
                TEXT_PX,
                x0,
                y,
                label_paint,
            );
            for (value, at, value_paint) in [
                (hud.command[row], command_right, &command_paint),
                (hud.measured[row], measured_right, &measured_paint),
            ] {
                self.line.clear();
                // Writing to a String cannot fail.
                let _ = write!(self.line, "{:.2}", shown(value));
                let w = self.bold.width(&self.line, TEXT_PX);
                self.bold.draw(
                    &mut self.pixmap,
                    &self.line,
                    TEXT_PX,
                    at - w,
                    y,
                    value_paint,
                );
            }
            self.text.draw(
                &mut self.pixmap,
                UNITS[row],
                TEXT_PX,
                measured_right,
                y,
                label_paint,
            );
        }
    }
}

/// The outline of an arrow on the ground from `origin` along `angle` (rad, world), `length`
/// long with a shaft `half_width` wide on each side: seven corners, counter-clockwise.
fn arrow_outline(origin: [f64; 2], angle: f64, length: f64, half_width: f64) -> [[f64; 2]; 7] {
    let head_len = (half_width * 3.5).min(length * 0.6);
    let head_half = half_width * 2.4;
    let shaft = length - head_len;
    let (c, s) = (angle.cos(), angle.sin());
    // Local (along, across) to world.
    let at = |u: f64, v: f64| [origin[0] + u * c - v * s, origin[1] + u * s + v * c];
    [
        at(0.0, -half_width),
        at(shaft, -half_width),
        at(shaft, -head_half),
        at(length, 0.0),
        at(shaft, head_half),
        at(shaft, half_width),
        at(0.0, half_width),
    ]
}
