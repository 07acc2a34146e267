//! The CPU renderer: a perspective view of the robot's collision shapes, drawn back to front
//! (painter's algorithm) with tiny-skia's anti-aliased 2-D filler.
//!
//! Per frame, back to front: a sky gradient; the ground (a large square clipped to the near
//! plane) with a 1 m grid, or over a height field its shaded cells around the camera's target
//! with the grid draped over them (`terrain.rs`); distance fog towards the horizon; the robot's shadows (every shape
//! projected straight down onto the ground, filled as one path so that overlaps do not darken
//! twice); ground discs under feet in contact; the goal's ring and a dashed line to it; then
//! the robot's shapes and the goal's pole, sorted by depth: boxes as their visible faces,
//! flat-shaded by a fixed light; capsules as the hull of their two end circles with a
//! cross-wise gradient; spheres with a radial highlight; last, the text overlay.
//!
//! Only the projection and the scene logic are written here; every pixel is filled by
//! tiny-skia. The renderer reuses its own buffers (poses, projected shapes, the pixmap) from
//! frame to frame; tiny-skia's API makes each frame build its paths and gradient stops anew,
//! a few small allocations per shape, which is not on the physics path.

use std::fmt::Write as _;
use std::sync::Arc;

use hyq_physics::na::{Isometry3, Point3, Vector3};
use hyq_physics::{HeightGrid, RobotModel, Shape};
use tiny_skia::{
    Color, FillRule, GradientStop, LineCap, LineJoin, LinearGradient, Paint, Path, PathBuilder,
    Pixmap, Point, RadialGradient, Rect, Shader, SpreadMode, Stroke, StrokeDash, Transform,
};

use crate::camera::{Camera, CameraConfig, NEAR_PLANE_M, REFERENCE_DISTANCE_M, REFERENCE_HEIGHT_M};
use crate::clip;
use crate::error::RenderError;
use crate::frame::Frame;
use crate::geom::{clip_polygon_near, clip_segment_near, convex_hull, push_circle_points};
use crate::scene::{Overlay, RobotPose, Scene, VelocityHud};
use crate::terrain::{LIFT_M, Quad, TERRAIN_HALF_M, draped, quads};
use crate::text::{SANS, SANS_BOLD, TextPainter, bundled};

mod hud;

/// Image size, camera placement and ground grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderConfig {
    /// Image width in pixels, 16 to 4096 (default: 480).
    pub width: u32,
    /// Image height in pixels, 16 to 4096 (default: 360).
    pub height: u32,
    /// Where the camera sits relative to the trunk (default: [`CameraConfig::default`]).
    pub camera: CameraConfig,
    /// Spacing of the ground grid's lines (m); every fifth line is darker (default: 1.0).
    pub grid_spacing_m: f64,
}

impl Default for RenderConfig {
    fn default() -> Self {
        Self {
            width: DEFAULT_WIDTH_PX,
            height: DEFAULT_HEIGHT_PX,
            camera: CameraConfig::default(),
            grid_spacing_m: 1.0,
        }
    }
}

/// The default image width (pixels), of `hyq render` and Python's `rgb_array` alike.
pub const DEFAULT_WIDTH_PX: u32 = 480;
/// The default image height (pixels), of `hyq render` and Python's `rgb_array` alike.
pub const DEFAULT_HEIGHT_PX: u32 = 360;

/// The largest image side the renderer accepts.
pub const MAX_SIDE_PX: u32 = 4096;
/// The smallest image side the renderer accepts.
pub const MIN_SIDE_PX: u32 = 16;

impl RenderConfig {
    /// Checks every setting; the error names the first one out of range.
    pub fn validate(&self) -> Result<(), RenderError> {
        for (field, v) in [("width", self.width), ("height", self.height)] {
            if !(MIN_SIDE_PX..=MAX_SIDE_PX).contains(&v) {
                return Err(RenderError::InvalidConfig {
                    field,
                    value: f64::from(v),
                    reason: "must be 16 to 4096 pixels",
                });
            }
        }
        if !(self.grid_spacing_m.is_finite() && (0.05..=100.0).contains(&self.grid_spacing_m)) {
            return Err(RenderError::InvalidConfig {
                field: "grid_spacing_m",
                value: self.grid_spacing_m,
                reason: "must be 0.05 to 100 m",
            });
        }
        self.camera.validate()
    }
}

/// A colour with components in 0..1.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Rgb(f32, f32, f32);

impl Rgb {
    const fn hex(v: u32) -> Self {
        Rgb(
            ((v >> 16) & 0xff) as f32 / 255.0,
            ((v >> 8) & 0xff) as f32 / 255.0,
            (v & 0xff) as f32 / 255.0,
        )
    }

    /// Darker (k < 1) or brighter (k > 1), clamped to white.
    fn scale(self, k: f32) -> Self {
        Rgb(
            (self.0 * k).min(1.0),
            (self.1 * k).min(1.0),
            (self.2 * k).min(1.0),
        )
    }

    /// Mixed towards white by `t` (0: unchanged, 1: white).
    fn tint(self, t: f32) -> Self {
        Rgb(
            self.0 + (1.0 - self.0) * t,
            self.1 + (1.0 - self.1) * t,
            self.2 + (1.0 - self.2) * t,
        )
    }

    fn alpha(self, a: f32) -> Color {
        // Components are within 0..1 by construction (`hex`, clamped `scale` and `tint`), which
        // is all `from_rgba` checks.
        Color::from_rgba(self.0, self.1, self.2, a).unwrap_or(Color::BLACK)
    }

    fn opaque(self) -> Color {
        self.alpha(1.0)
    }
}

// The palette: a pale sky, a light neutral ground, a steel-blue trunk, dark thighs, light
// shins, orange feet in contact, a green goal.
const SKY_TOP: Rgb = Rgb::hex(0x9dbad6);
const SKY_HORIZON: Rgb = Rgb::hex(0xe4ebf1);
const GROUND: Rgb = Rgb::hex(0xd8dbd2);
const GRID_MINOR: Rgb = Rgb::hex(0xa9ae9f);
const GRID_MAJOR: Rgb = Rgb::hex(0x7f8676);
const SHADOW: Rgb = Rgb::hex(0x1e2328);
const TRUNK: Rgb = Rgb::hex(0x4f77ad);
const TRUNK_CONTACT: Rgb = Rgb::hex(0xc8463d);
/// Limb colours by kinematic depth below the trunk (1: hip, 2: upper leg, 3 and more: lower
/// leg), so that any robot's legs read the same way.
const LIMBS: [Rgb; 3] = [Rgb::hex(0x56606c), Rgb::hex(0x343c47), Rgb::hex(0x8f9aa6)];
const FOOT_AIR: Rgb = Rgb::hex(0x2e3238);
const FOOT_CONTACT: Rgb = Rgb::hex(0xf28e2b);
const GOAL: Rgb = Rgb::hex(0x2ca25f);
const POLE: Rgb = Rgb::hex(0x5a5f66);
const PANEL: Rgb = Rgb::hex(0x1b1f24);
const TEXT_LABEL: Rgb = Rgb::hex(0xb8c2cc);
const TEXT_VALUE: Rgb = Rgb::hex(0xffffff);

/// Half the side (m) of the ground square drawn around the camera's target.
const GROUND_HALF_M: f64 = 200.0;
/// Half the side (m) of the grid drawn around the camera's target.
const GRID_HALF_M: f64 = 14.0;
/// Fog: clear up to this horizontal distance from the camera (m), thick from the next one on.
const FOG_CLEAR_M: f64 = 5.0;
const FOG_THICK_M: f64 = 16.0;
/// Radius (m) of the disc drawn on the ground under a foot in contact, for a robot of the
/// reference size (HyQ; see [`crate::camera::REFERENCE_HEIGHT_M`]), scaled for others.
const CONTACT_DISC_M: f64 = 0.07;
/// The goal marker: ring radius and ball radius (m) for a robot of the reference size, scaled
/// like [`CONTACT_DISC_M`]; pole radius (m).
const GOAL_RING_M: f64 = 0.3;
const GOAL_BALL_M: f64 = 0.06;
const GOAL_POLE_M: f64 = 0.01;
/// Feet are small (HyQ's are 2 cm spheres): never draw one smaller than this radius (px).
const MIN_FOOT_PX: f32 = 2.5;
/// The largest share of the image's width and of its height the overlay panel may take; a
/// frame too small for it (under about 300 × 190 px for HyQ) is drawn without the overlay.
const OVERLAY_MAX_SHARE: [f32; 2] = [2.0 / 3.0, 1.0 / 2.0];
/// Overlay text size (px per em) and line height (px).
const TEXT_PX: f32 = 13.0;
const LINE_PX: f32 = 18.0;

/// What a collision shape is, for its colour.
#[derive(Clone, Copy, Debug)]
enum Role {
    Trunk,
    Foot(usize),
    Limb(usize),
}

/// One collision shape to draw.
#[derive(Clone, Copy, Debug)]
struct Part {
    link: usize,
    collision: usize,
    role: Role,
}

/// A projected shape, ready to paint.
#[derive(Clone, Copy, Debug)]
enum PrimKind {
    /// Up to three visible faces of a box (a convex box never shows more): four corners each,
    /// and a colour.
    Faces {
        corners: [[[f32; 2]; 4]; 3],
        colours: [Rgb; 3],
        count: usize,
    },
    /// A capsule (or cylinder) between two projected end centres with their pixel radii.
    Capsule {
        a: [f32; 2],
        ra: f32,
        b: [f32; 2],
        rb: f32,
        colour: Rgb,
    },
    /// A sphere.
    Sphere { c: [f32; 2], r: f32, colour: Rgb },
}

#[derive(Clone, Copy, Debug)]
struct Prim {
    /// Distance from the camera (m): the painter's sort key, far first.
    depth: f64,
    kind: PrimKind,
}

/// The corners of each box face, by index bits (bit 0: +x, bit 1: +y, bit 2: +z), in order
/// around the face, and the face's outward normal in the box frame.
const BOX_FACES: [([usize; 4], [f64; 3]); 6] = [
    ([1, 3, 7, 5], [1.0, 0.0, 0.0]),
    ([0, 4, 6, 2], [-1.0, 0.0, 0.0]),
    ([2, 3, 7, 6], [0.0, 1.0, 0.0]),
    ([0, 1, 5, 4], [0.0, -1.0, 0.0]),
    ([4, 5, 7, 6], [0.0, 0.0, 1.0]),
    ([0, 1, 3, 2], [0.0, 0.0, -1.0]),
];

/// Draws frames of one robot model; build once, render many (it keeps its buffers).
pub struct Renderer {
    model: Arc<RobotModel>,
    config: RenderConfig,
    /// The robot's size relative to the reference robot (HyQ: exactly 1).
    scale: f64,
    parts: Vec<Part>,
    foot_names: Vec<String>,
    pixmap: Pixmap,
    poses: Vec<Isometry3<f64>>,
    prims: Vec<Prim>,
    cam_pts: Vec<Vector3<f64>>,
    clipped: Vec<Vector3<f64>>,
    pts: Vec<[f64; 2]>,
    hull: Vec<[f64; 2]>,
    /// The frame's height field, if its ground is one.
    ground: Option<Arc<HeightGrid>>,
    /// The point the frame's camera looks at.
    target: Point3<f64>,
    quads: Vec<Quad>,
    line_pts: Vec<Point3<f64>>,
    text: TextPainter,
    bold: TextPainter,
    line: String,
}

impl std::fmt::Debug for Renderer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Renderer")
            .field("robot", &self.model.name())
            .field("config", &self.config)
            .finish_non_exhaustive()
    }
}

impl Renderer {
    /// A renderer of `model` with `config` (validated here). An unset camera distance becomes
    /// the reference distance scaled to the robot (see [`CameraConfig::distance_m`]), and the
    /// contact discs and the goal marker are scaled alike; [`Renderer::config`] gives the
    /// distance used.
    pub fn new(model: Arc<RobotModel>, mut config: RenderConfig) -> Result<Self, RenderError> {
        config.validate()?;
        // HyQ's standing height is the reference, so its scale is exactly 1 and its frames
        // are those drawn before the scaling existed. The ratio is checked finite and
        // positive: the model's standing height is (the loader refuses other values).
        let scale = model.standing_height() / REFERENCE_HEIGHT_M;
        if config.camera.distance_m.is_none() {
            config.camera.distance_m = Some(REFERENCE_DISTANCE_M * scale);
        }
        // The size was just checked to be 16..=4096 on each side, which a pixmap accepts.
        let pixmap =
            Pixmap::new(config.width, config.height).ok_or(RenderError::InvalidConfig {
                field: "width",
                value: f64::from(config.width),
                reason: "cannot allocate a pixmap of this size",
            })?;
        let parts = classify_parts(&model);
        let foot_names = model.tracked()[..model.num_feet()]
            .iter()
            .map(|t| t.name.to_uppercase())
            .collect();
        let n_links = model.num_links();
        Ok(Self {
            parts,
            foot_names,
            pixmap,
            poses: vec![Isometry3::identity(); n_links],
            prims: Vec::with_capacity(64),
            cam_pts: Vec::with_capacity(16),
            clipped: Vec::with_capacity(16),
            pts: Vec::with_capacity(64),
            hull: Vec::with_capacity(64),
            ground: None,
            target: Point3::origin(),
            quads: Vec::new(),
            line_pts: Vec::new(),
            text: TextPainter::new(bundled(SANS)),
            bold: TextPainter::new(bundled(SANS_BOLD)),
            line: String::with_capacity(64),
            model,
            config,
            scale,
        })
    }

    /// The settings this renderer draws with.
    pub fn config(&self) -> &RenderConfig {
        &self.config
    }

    /// The robot model this renderer draws.
    pub fn model(&self) -> &Arc<RobotModel> {
        &self.model
    }

    /// The camera a scene is seen through: [`Scene::camera_target`], else the trunk frame's
    /// origin taken from `trunk`.
    pub fn camera(&self, trunk: &Isometry3<f64>, camera_target: Option<Point3<f64>>) -> Camera {
        let target = camera_target.unwrap_or_else(|| Point3::from(trunk.translation.vector));
        Camera::looking_at(
            &self.config.camera,
            target,
            self.config.width,
            self.config.height,
        )
    }

    /// Renders `scene` into a new frame.
    pub fn render(&mut self, scene: &Scene<'_>) -> Result<Frame, RenderError> {
        let mut frame = Frame::new(self.config.width, self.config.height);
        self.render_into(scene, &mut frame)?;
        Ok(frame)
    }

    /// Renders `scene` into `frame`, which must have the renderer's size (reuses its buffer).
    pub fn render_into(&mut self, scene: &Scene<'_>, frame: &mut Frame) -> Result<(), RenderError> {
        if frame.width != self.config.width
            || frame.height != self.config.height
            || !frame.is_consistent()
        {
            return Err(RenderError::FrameSize {
                width: self.config.width,
                height: self.config.height,
                got_width: frame.width,
                got_height: frame.height,
            });
        }
        self.load_scene(scene)?;
        self.target = scene
            .camera_target
            .unwrap_or_else(|| Point3::from(self.poses[0].translation.vector));
        let cam = self.camera(&self.poses[0], scene.camera_target);

        self.draw_sky_and_ground(&cam);
        self.draw_shadows(&cam);
        self.draw_contact_discs(&cam, scene.contacts);
        if let Some(goal) = scene.goal {
            self.draw_goal_on_ground(&cam, &goal);
        }
        self.collect_prims(&cam, scene.contacts, scene.goal.as_ref());
        self.draw_prims();
        if let Some(hud) = &scene.velocity {
            self.draw_velocity_arrows(&cam, hud);
        }
        if let Some(overlay) = &scene.overlay {
            self.draw_overlay(overlay, scene.contacts, scene.velocity.as_ref());
        }

        // Every pixel is opaque (the sky covers the whole image first), so premultiplied RGBA
        // is plain RGBA and dropping alpha gives the colour.
        for (dst, src) in frame
            .rgb
            .chunks_exact_mut(3)
            .zip(self.pixmap.data().chunks_exact(4))
        {
            dst.copy_from_slice(&src[..3]);
        }
        Ok(())
    }

    /// Checks the scene against the model and fills `self.poses` and `self.ground`.
    fn load_scene(&mut self, scene: &Scene<'_>) -> Result<(), RenderError> {
        self.ground = match scene.terrain {
            Some(hyq_physics::Terrain::Field(grid)) => Some(Arc::clone(grid)),
            _ => None,
        };
        let tracked = self.model.tracked().len();
        if scene.contacts.len() != tracked {
            return Err(RenderError::WrongLength {
                what: "contact flags (one per tracked body: the feet, then the trunk)",
                expected: tracked,
                got: scene.contacts.len(),
            });
        }
        match scene.pose {
            RobotPose::Links(poses) => {
                if poses.len() != self.poses.len() {
                    return Err(RenderError::WrongLength {
                        what: "link poses (one per body of the model)",
                        expected: self.poses.len(),
                        got: poses.len(),
                    });
                }
                self.poses.copy_from_slice(poses);
            }
            RobotPose::Joints { trunk, q } => {
                if q.len() != self.model.num_joints() {
                    return Err(RenderError::WrongLength {
                        what: "joint angles (one per actuated joint, profile order)",
                        expected: self.model.num_joints(),
                        got: q.len(),
                    });
                }
                if let Some((i, &v)) = q.iter().enumerate().find(|(_, v)| !v.is_finite()) {
                    return Err(RenderError::NonFinite {
                        what: format!("angle of joint {}", self.model.joints()[i].name),
                        value: v,
                    });
                }
                self.model.link_poses(trunk, q, &mut self.poses)?;
            }
        }
        for (pose, link) in self.poses.iter().zip(self.model.links()) {
            let t = pose.translation.vector;
            let r = pose.rotation.coords;
            if let Some(&v) = t.iter().chain(r.iter()).find(|v| !v.is_finite()) {
                return Err(RenderError::NonFinite {
                    what: format!("pose of body {}", link.name),
                    value: v,
                });
            }
        }
        if let Some(hud) = &scene.velocity
            && let Some(&v) = hud
                .command
                .iter()
                .chain(&hud.measured)
                .find(|v| !v.is_finite())
        {
            return Err(RenderError::NonFinite {
                what: "velocity display (command or measured velocity)".to_owned(),
                value: v,
            });
        }
        for (what, p) in [("goal", scene.goal), ("camera target", scene.camera_target)] {
            if let Some(&v) = p.iter().flat_map(|p| p.iter()).find(|v| !v.is_finite()) {
                return Err(RenderError::NonFinite {
                    what: what.to_owned(),
                    value: v,
                });
            }
        }
        Ok(())
    }

    /// Sky gradient, ground square, grid and fog.
    fn draw_sky_and_ground(&mut self, cam: &Camera) {
        let (w, h) = (self.config.width as f32, self.config.height as f32);
        let horizon = cam.horizon_y() as f32;
        let full = Rect::from_xywh(0.0, 0.0, w, h);
        let sky = LinearGradient::new(
            Point::from_xy(0.0, horizon - 0.6 * h),
            Point::from_xy(0.0, horizon),
            vec![
                GradientStop::new(0.0, SKY_TOP.opaque()),
                GradientStop::new(1.0, SKY_HORIZON.opaque()),
            ],
            SpreadMode::Pad,
            Transform::identity(),
        );
        if let (Some(rect), Some(shader)) = (full, sky) {
            self.pixmap
                .fill_rect(rect, &paint(shader), Transform::identity(), None);
        }

        // The ground: a square around the camera, cut at the near plane.
        let (tx, ty) = (cam.eye().x, cam.eye().y);
        let g = GROUND_HALF_M;
        let square = [
            Point3::new(tx - g, ty - g, 0.0),
            Point3::new(tx + g, ty - g, 0.0),
            Point3::new(tx + g, ty + g, 0.0),
            Point3::new(tx - g, ty + g, 0.0),
        ];
        if let Some(path) = self.world_polygon_path(cam, &square) {
            fill_solid(&mut self.pixmap, &path, GROUND.opaque());
        }

        match self.ground.clone() {
            Some(grid) => self.draw_terrain(cam, &grid),
            None => self.draw_flat_grid(cam),
        }

        // Fog: the ground fades into the horizon's colour between FOG_CLEAR_M and the horizon.
        let y_clear = cam
            .project(&ground_point_ahead(cam, FOG_CLEAR_M))
            .map_or(h, |p| p[1] as f32);
        let y_thick = cam
            .project(&ground_point_ahead(cam, FOG_THICK_M))
            .map_or(horizon, |p| p[1] as f32);
        if horizon < h && y_clear > horizon + 1.0 {
            let thick_at = ((y_clear - y_thick) / (y_clear - horizon)).clamp(0.05, 0.95);
            let fog = LinearGradient::new(
                Point::from_xy(0.0, y_clear),
                Point::from_xy(0.0, horizon),
                vec![
                    GradientStop::new(0.0, SKY_HORIZON.alpha(0.0)),
                    GradientStop::new(thick_at, SKY_HORIZON.alpha(0.8)),
                    GradientStop::new(1.0, SKY_HORIZON.alpha(1.0)),
                ],
                SpreadMode::Pad,
                Transform::identity(),
            );
            let top = horizon.max(0.0) - 1.0;
            if let (Some(rect), Some(shader)) =
                (Rect::from_xywh(0.0, top, w, y_clear.min(h) - top), fog)
            {
                self.pixmap
                    .fill_rect(rect, &paint(shader), Transform::identity(), None);
            }
        }
    }

    /// The 1 m grid on flat ground, around the ground point at the image centre.
    fn draw_flat_grid(&mut self, cam: &Camera) {
        // The camera looks down, so its view ray meets the ground.
        let s = self.config.grid_spacing_m;
        let t = -cam.eye().z / cam.forward().z.min(-1e-6);
        let (cx, cy) = (
            cam.eye().x + cam.forward().x * t,
            cam.eye().y + cam.forward().y * t,
        );
        let mut minor = PathBuilder::new();
        let mut major = PathBuilder::new();
        let k0 = ((cx - GRID_HALF_M) / s).floor() as i64;
        let k1 = ((cx + GRID_HALF_M) / s).ceil() as i64;
        for k in k0..=k1 {
            let x = k as f64 * s;
            let pb = if k % 5 == 0 { &mut major } else { &mut minor };
            push_world_segment(
                cam,
                pb,
                &Point3::new(x, cy - GRID_HALF_M, 0.0),
                &Point3::new(x, cy + GRID_HALF_M, 0.0),
            );
        }
        let k0 = ((cy - GRID_HALF_M) / s).floor() as i64;
        let k1 = ((cy + GRID_HALF_M) / s).ceil() as i64;
        for k in k0..=k1 {
            let y = k as f64 * s;
            let pb = if k % 5 == 0 { &mut major } else { &mut minor };
            push_world_segment(
                cam,
                pb,
                &Point3::new(cx - GRID_HALF_M, y, 0.0),
                &Point3::new(cx + GRID_HALF_M, y, 0.0),
            );
        }
        for (pb, colour, width) in [(minor, GRID_MINOR, 1.0), (major, GRID_MAJOR, 1.4)] {
            if let Some(path) = pb.finish() {
                let stroke = Stroke {
                    width,
                    ..Stroke::default()
                };
                stroke_solid(&mut self.pixmap, &path, colour.alpha(0.8), &stroke);
            }
        }
    }

    /// A height field around the camera's target: its shaded quads far first, then the 1 m
    /// grid draped over it.
    fn draw_terrain(&mut self, cam: &Camera, grid: &HeightGrid) {
        let target = self.target;
        let light = light_direction(cam);
        let mut cells = std::mem::take(&mut self.quads);
        quads(grid, cam, &target, &light, &mut cells);
        for q in &cells {
            let Some(path) = self.world_polygon_path(cam, &q.corners) else {
                continue;
            };
            // Cut to the rasteriser's safe range like every other path: a cell of a tall
            // field just past the near plane projects to millions of pixels.
            let (w, h) = (self.pixmap.width(), self.pixmap.height());
            if let Some(path) = clip::for_fill(&path, w, h) {
                let colour = GROUND.scale(0.9 * q.shade).tint(q.tint).opaque();
                self.pixmap.fill_path(
                    &path,
                    &Paint {
                        shader: Shader::SolidColor(colour),
                        anti_alias: false,
                        ..Paint::default()
                    },
                    FillRule::Winding,
                    Transform::identity(),
                    None,
                );
            }
        }
        self.quads = cells;
        let s = self.config.grid_spacing_m;
        let half = TERRAIN_HALF_M.min(GRID_HALF_M);
        let mut minor = PathBuilder::new();
        let mut major = PathBuilder::new();
        for (along_x, centre) in [(true, target.x), (false, target.y)] {
            let k0 = ((centre - half) / s).floor() as i64;
            let k1 = ((centre + half) / s).ceil() as i64;
            for k in k0..=k1 {
                let v = k as f64 * s;
                let (a, b) = if along_x {
                    ([v, target.y - half], [v, target.y + half])
                } else {
                    ([target.x - half, v], [target.x + half, v])
                };
                let mut points = std::mem::take(&mut self.line_pts);
                draped(grid, a, b, 0.1, &mut points);
                let pb = if k % 5 == 0 { &mut major } else { &mut minor };
                for pair in points.windows(2) {
                    push_world_segment(cam, pb, &pair[0], &pair[1]);
                }
                self.line_pts = points;
            }
        }
        for (pb, colour, width) in [(minor, GRID_MINOR, 1.0), (major, GRID_MAJOR, 1.4)] {
            if let Some(path) = pb.finish() {
                let stroke = Stroke {
                    width,
                    ..Stroke::default()
                };
                stroke_solid(&mut self.pixmap, &path, colour.alpha(0.6), &stroke);
            }
        }
    }

    /// The robot's shadows: every shape projected straight down, as one path.
    fn draw_shadows(&mut self, cam: &Camera) {
        let mut pb = PathBuilder::new();
        for i in 0..self.parts.len() {
            let part = self.parts[i];
            let link = &self.model.links()[part.link];
            let c = &link.collisions[part.collision];
            let pose = self.poses[part.link] * c.origin;
            self.pts.clear();
            match c.shape {
                Shape::Box { half_extents: e } => {
                    for k in 0..8 {
                        let p = pose * box_corner(&e, k);
                        self.pts.push([p.x, p.y]);
                    }
                }
                Shape::Sphere { radius } => {
                    let p = pose.translation.vector;
                    push_circle_points([p.x, p.y], radius, 16, &mut self.pts);
                }
                Shape::Capsule {
                    radius,
                    half_length,
                }
                | Shape::Cylinder {
                    radius,
                    half_length,
                } => {
                    for z in [-half_length, half_length] {
                        let p = pose * Point3::new(0.0, 0.0, z);
                        push_circle_points([p.x, p.y], radius, 12, &mut self.pts);
                    }
                }
                // A shape kind this renderer does not know casts no shadow.
                _ => continue,
            }
            convex_hull(&mut self.pts, &mut self.hull);
            self.push_ground_polygon(cam, &mut pb);
        }
        if let Some(path) = pb.finish() {
            fill_solid(&mut self.pixmap, &path, SHADOW.alpha(0.22));
        }
    }

    /// Orange discs on the ground under the feet in contact.
    fn draw_contact_discs(&mut self, cam: &Camera, contacts: &[bool]) {
        let mut pb = PathBuilder::new();
        let model = Arc::clone(&self.model);
        for (f, tracked) in model.tracked()[..model.num_feet()].iter().enumerate() {
            if !contacts[f] {
                continue;
            }
            let link = &model.links()[tracked.link];
            for &s in &tracked.shapes {
                let p = (self.poses[tracked.link] * link.collisions[s].origin)
                    .translation
                    .vector;
                self.hull.clear();
                push_circle_points([p.x, p.y], CONTACT_DISC_M * self.scale, 20, &mut self.hull);
                self.push_ground_polygon(cam, &mut pb);
            }
        }
        if let Some(path) = pb.finish() {
            fill_solid(&mut self.pixmap, &path, FOOT_CONTACT.alpha(0.55));
        }
    }

    /// The goal's ring on the ground and a dashed line to it from under the trunk.
    fn draw_goal_on_ground(&mut self, cam: &Camera, goal: &Point3<f64>) {
        let trunk = self.poses[0].translation.vector;
        let mut line = PathBuilder::new();
        match self.ground.clone() {
            None => push_world_segment(
                cam,
                &mut line,
                &Point3::new(trunk.x, trunk.y, 0.0),
                &Point3::new(goal.x, goal.y, 0.0),
            ),
            Some(grid) => {
                let mut points = std::mem::take(&mut self.line_pts);
                draped(
                    &grid,
                    [trunk.x, trunk.y],
                    [goal.x, goal.y],
                    0.1,
                    &mut points,
                );
                push_world_polyline(cam, &mut line, &points);
                self.line_pts = points;
            }
        }
        if let (Some(path), Some(dash)) = (line.finish(), StrokeDash::new(vec![9.0, 7.0], 0.0)) {
            let stroke = Stroke {
                width: 2.0,
                line_cap: LineCap::Round,
                dash: Some(dash),
                ..Stroke::default()
            };
            stroke_solid(&mut self.pixmap, &path, GOAL.alpha(0.75), &stroke);
        }

        let mut ring = PathBuilder::new();
        self.hull.clear();
        push_circle_points(
            [goal.x, goal.y],
            GOAL_RING_M * self.scale,
            48,
            &mut self.hull,
        );
        self.push_ground_polygon(cam, &mut ring);
        if let Some(path) = ring.finish() {
            fill_solid(&mut self.pixmap, &path, GOAL.alpha(0.22));
            let stroke = Stroke {
                width: 2.0,
                ..Stroke::default()
            };
            stroke_solid(&mut self.pixmap, &path, GOAL.scale(0.8).alpha(0.9), &stroke);
        }
    }

    /// Projects the robot's shapes and the goal's pole and ball into `self.prims`.
    fn collect_prims(&mut self, cam: &Camera, contacts: &[bool], goal: Option<&Point3<f64>>) {
        self.prims.clear();
        let trunk_contact = contacts[self.model.trunk_tracked_index()];
        let light = light_direction(cam);
        for i in 0..self.parts.len() {
            let part = self.parts[i];
            let link = &self.model.links()[part.link];
            let c = &link.collisions[part.collision];
            let pose = self.poses[part.link] * c.origin;
            let colour = match part.role {
                Role::Trunk if trunk_contact => TRUNK_CONTACT,
                Role::Trunk => TRUNK,
                Role::Foot(f) if contacts[f] => FOOT_CONTACT,
                Role::Foot(_) => FOOT_AIR,
                Role::Limb(depth) => LIMBS[depth.clamp(1, LIMBS.len()) - 1],
            };
            let prim = match c.shape {
                Shape::Box { half_extents: e } => box_prim(cam, &pose, &e, colour, &light),
                Shape::Sphere { radius } => {
                    let min_px = if matches!(part.role, Role::Foot(_)) {
                        MIN_FOOT_PX
                    } else {
                        0.0
                    };
                    sphere_prim(
                        cam,
                        &Point3::from(pose.translation.vector),
                        radius,
                        colour,
                        min_px,
                    )
                }
                Shape::Capsule {
                    radius,
                    half_length,
                }
                | Shape::Cylinder {
                    radius,
                    half_length,
                } => capsule_prim(
                    cam,
                    &(pose * Point3::new(0.0, 0.0, -half_length)),
                    &(pose * Point3::new(0.0, 0.0, half_length)),
                    radius,
                    colour,
                ),
                // A shape kind this renderer does not know is not drawn.
                _ => None,
            };
            self.prims.extend(prim);
        }
        if let Some(g) = goal {
            let foot = self
                .ground
                .as_ref()
                .map_or(0.0, |grid| grid.height_at(g.x, g.y));
            if g.z > foot {
                self.prims.extend(capsule_prim(
                    cam,
                    &Point3::new(g.x, g.y, foot),
                    g,
                    GOAL_POLE_M,
                    POLE,
                ));
            }
            self.prims
                .extend(sphere_prim(cam, g, GOAL_BALL_M * self.scale, GOAL, 3.0));
        }
        // Far first; an unstable sort allocates nothing and is deterministic for equal input.
        self.prims
            .sort_unstable_by(|a, b| b.depth.total_cmp(&a.depth));
    }

    fn draw_prims(&mut self) {
        for prim in &self.prims {
            match prim.kind {
                PrimKind::Faces {
                    corners,
                    colours,
                    count,
                } => {
                    for (quad, colour) in corners.iter().zip(colours).take(count) {
                        let mut pb = PathBuilder::new();
                        pb.move_to(quad[0][0], quad[0][1]);
                        for p in &quad[1..] {
                            pb.line_to(p[0], p[1]);
                        }
                        pb.close();
                        if let Some(path) = pb.finish() {
                            fill_and_outline(
                                &mut self.pixmap,
                                &path,
                                Shader::SolidColor(colour.opaque()),
                                colour,
                                1.0,
                            );
                        }
                    }
                }
                PrimKind::Capsule {
                    a,
                    ra,
                    b,
                    rb,
                    colour,
                } => {
                    if let Some(path) = capsule_path(a, ra, b, rb) {
                        let shader = capsule_shader(a, ra, b, rb, colour);
                        fill_and_outline(&mut self.pixmap, &path, shader, colour, 0.8);
                    }
                }
                PrimKind::Sphere { c, r, colour } => {
                    if let Some(path) = PathBuilder::from_circle(c[0], c[1], r) {
                        let shader = RadialGradient::new(
                            Point::from_xy(c[0] - 0.35 * r, c[1] - 0.4 * r),
                            0.0,
                            Point::from_xy(c[0], c[1]),
                            r,
                            vec![
                                GradientStop::new(0.0, colour.tint(0.55).opaque()),
                                GradientStop::new(0.55, colour.opaque()),
                                GradientStop::new(1.0, colour.scale(0.6).opaque()),
                            ],
                            SpreadMode::Pad,
                            Transform::identity(),
                        )
                        .unwrap_or(Shader::SolidColor(colour.opaque()));
                        fill_and_outline(&mut self.pixmap, &path, shader, colour, 0.8);
                    }
                }
            }
        }
    }

    /// The text panel in the top-left corner: time, distance to the goal and return, or under
    /// the velocity task time, return and the task's three rows (`hud.rs`); then the feet.
    fn draw_overlay(&mut self, overlay: &Overlay, contacts: &[bool], hud: Option<&VelocityHud>) {
        let pad = 8.0;
        let margin = 8.0;
        let goal_rows = [
            ("time", overlay.time_s, " s"),
            ("to goal", overlay.distance_to_goal_m, " m"),
            ("return", overlay.episode_return, ""),
        ];
        let velocity_rows = [goal_rows[0], goal_rows[2]];
        let plain: &[(&str, f64, &str)] = if hud.is_some() {
            &velocity_rows
        } else {
            &goal_rows
        };
        let hud_labels: &[&str] = if hud.is_some() { &hud::ROW_LABELS } else { &[] };
        let label_w = plain
            .iter()
            .map(|r| r.0)
            .chain(hud_labels.iter().copied())
            .map(|l| self.text.width(l, TEXT_PX))
            .fold(0.0, f32::max);
        // Values are right-aligned in a column as wide as a wide value, so that the panel does
        // not change size from frame to frame (DejaVu's digits all have the same width).
        let mut value_w = self.bold.width("-0000.00 m", TEXT_PX);
        if hud.is_some() {
            value_w = value_w.max(self.velocity_value_width());
        }
        let feet_w = self.foot_names.len() as f32 * 44.0;
        let inner_w = (label_w + 14.0 + value_w).max(feet_w);
        let n_rows = plain.len() + hud_labels.len();
        let rows = n_rows as f32 + if self.foot_names.is_empty() { 0.0 } else { 1.0 };
        let panel_w = inner_w + 2.0 * pad;
        let panel_h = rows * LINE_PX + 2.0 * pad - 2.0;
        // The text has a fixed pixel size, so in a small frame (an 84 × 84 rgb_array for
        // pixel-based learning) the panel would hide the robot: it is left out when it would
        // take more than OVERLAY_MAX_SHARE of the width or of the height.
        let (w, h) = (self.config.width as f32, self.config.height as f32);
        if margin + panel_w > OVERLAY_MAX_SHARE[0] * w
            || margin + panel_h > OVERLAY_MAX_SHARE[1] * h
        {
            return;
        }
        if let Some(path) = rounded_rect(margin, margin, panel_w, panel_h, 6.0) {
            fill_solid(&mut self.pixmap, &path, PANEL.alpha(0.62));
        }
        let label_paint = paint(Shader::SolidColor(TEXT_LABEL.opaque()));
        let value_paint = paint(Shader::SolidColor(TEXT_VALUE.opaque()));
        let x0 = margin + pad;
        let right = margin + pad + inner_w;
        let baseline_of = |row: usize| margin + pad + TEXT_PX - 1.0 + row as f32 * LINE_PX;
        for (row, &(label, value, unit)) in plain.iter().enumerate() {
            let baseline = baseline_of(row);
            self.text
                .draw(&mut self.pixmap, label, TEXT_PX, x0, baseline, &label_paint);
            self.line.clear();
            // Writing to a String cannot fail.
            let _ = write!(self.line, "{:.2}{unit}", shown(value));
            let w = self.bold.width(&self.line, TEXT_PX);
            self.bold.draw(
                &mut self.pixmap,
                &self.line,
                TEXT_PX,
                right - w,
                baseline,
                &value_paint,
            );
        }
        if let Some(hud) = hud {
            self.draw_velocity_rows(x0, right, baseline_of(plain.len()), hud, &label_paint);
        }
        // One dot per foot, orange when in contact, with the foot's name from the profile.
        let baseline = baseline_of(n_rows);
        self.draw_feet(x0, baseline, contacts, &label_paint);
    }

    /// The overlay's last row from `x0` on `baseline`: a dot per foot, filled when the foot
    /// touched the ground (`contacts`), and its name.
    fn draw_feet(&mut self, x0: f32, baseline: f32, contacts: &[bool], label_paint: &Paint) {
        let mut x = x0;
        for (f, name) in self.foot_names.iter().enumerate() {
            let (cx, cy, r) = (x + 5.0, baseline - 4.5, 4.5);
            if let Some(dot) = PathBuilder::from_circle(cx, cy, r) {
                if contacts[f] {
                    fill_solid(&mut self.pixmap, &dot, FOOT_CONTACT.opaque());
                } else {
                    stroke_solid(
                        &mut self.pixmap,
                        &dot,
                        TEXT_LABEL.opaque(),
                        &Stroke {
                            width: 1.2,
                            ..Stroke::default()
                        },
                    );
                }
            }
            self.text.draw(
                &mut self.pixmap,
                name,
                TEXT_PX - 1.0,
                x + 13.0,
                baseline,
                label_paint,
            );
            x += 44.0;
        }
    }

    /// Appends the ground polygon in `self.hull` (world x, y on the ground, counter-clockwise)
    /// to `pb`, clipped to the near plane and projected. On a height field each corner sits
    /// just above the surface.
    fn push_ground_polygon(&mut self, cam: &Camera, pb: &mut PathBuilder) {
        self.cam_pts.clear();
        let ground = self.ground.as_deref();
        self.cam_pts.extend(self.hull.iter().map(|p| {
            let z = ground.map_or(0.0, |g| g.height_at(p[0], p[1]) + LIFT_M);
            cam.to_camera(&Point3::new(p[0], p[1], z))
        }));
        clip_polygon_near(&self.cam_pts, &mut self.clipped);
        push_projected(cam, &self.clipped, pb);
    }

    /// A world polygon clipped to the near plane and projected, as a closed path.
    fn world_polygon_path(&mut self, cam: &Camera, polygon: &[Point3<f64>]) -> Option<Path> {
        self.cam_pts.clear();
        self.cam_pts
            .extend(polygon.iter().map(|p| cam.to_camera(p)));
        clip_polygon_near(&self.cam_pts, &mut self.clipped);
        let mut pb = PathBuilder::new();
        push_projected(cam, &self.clipped, &mut pb);
        pb.finish()
    }
}

/// A value as the overlay prints it: a small negative value would print as "-0.00"; what shows
/// is zero.
fn shown(value: f64) -> f64 {
    if value.abs() < 0.005 { 0.0 } else { value }
}

/// Gives every collision shape of the model its role: trunk, a foot (the tracked feet's
/// shapes) or a limb at some kinematic depth below the trunk.
fn classify_parts(model: &RobotModel) -> Vec<Part> {
    let tracked = model.tracked();
    let trunk_index = model.trunk_tracked_index();
    let mut parts = Vec::new();
    for (li, link) in model.links().iter().enumerate() {
        let mut depth = 0;
        let mut at = link.parent;
        while let Some(p) = at {
            depth += 1;
            at = model.links()[p].parent;
        }
        for ci in 0..link.collisions.len() {
            let holder = tracked
                .iter()
                .position(|t| t.link == li && t.shapes.contains(&ci));
            let role = match holder {
                Some(t) if t == trunk_index => Role::Trunk,
                Some(t) => Role::Foot(t),
                None if depth == 0 => Role::Trunk,
                None => Role::Limb(depth),
            };
            parts.push(Part {
                link: li,
                collision: ci,
                role,
            });
        }
    }
    parts
}

fn paint(shader: Shader<'static>) -> Paint<'static> {
    Paint {
        shader,
        anti_alias: true,
        ..Paint::default()
    }
}

/// Fills `path` with `shader`, cut to the rasteriser's safe range first ([`clip`]).
fn fill_with(pixmap: &mut Pixmap, path: &Path, shader: Shader<'static>) {
    if let Some(path) = clip::for_fill(path, pixmap.width(), pixmap.height()) {
        pixmap.fill_path(
            &path,
            &paint(shader),
            FillRule::Winding,
            Transform::identity(),
            None,
        );
    }
}

/// Fills `path` with one colour.
fn fill_solid(pixmap: &mut Pixmap, path: &Path, colour: Color) {
    fill_with(pixmap, path, Shader::SolidColor(colour));
}

/// Strokes `path` with one colour, cut to the rasteriser's safe range first ([`clip`]).
fn stroke_solid(pixmap: &mut Pixmap, path: &Path, colour: Color, stroke: &Stroke) {
    if let Some(path) = clip::for_stroke(path, pixmap.width(), pixmap.height()) {
        pixmap.stroke_path(
            &path,
            &paint(Shader::SolidColor(colour)),
            stroke,
            Transform::identity(),
            None,
        );
    }
}

/// Fills `path` with `shader` and outlines it in a darker shade of `colour`.
fn fill_and_outline(
    pixmap: &mut Pixmap,
    path: &Path,
    shader: Shader<'static>,
    colour: Rgb,
    width: f32,
) {
    fill_with(pixmap, path, shader);
    let stroke = Stroke {
        width,
        line_join: LineJoin::Round,
        ..Stroke::default()
    };
    stroke_solid(pixmap, path, colour.scale(0.45).alpha(0.9), &stroke);
}

/// The light, coming from above, from the left of the image and from the camera's side.
fn light_direction(cam: &Camera) -> Vector3<f64> {
    (Vector3::z() * 1.0 - cam.right() * 0.45 - cam.forward() * 0.35).normalize()
}

/// Corner `k` of a box (bit 0: +x, bit 1: +y, bit 2: +z) in its own frame.
fn box_corner(e: &Vector3<f64>, k: usize) -> Point3<f64> {
    let s = |bit: usize| if k & bit != 0 { 1.0 } else { -1.0 };
    Point3::new(s(1) * e.x, s(2) * e.y, s(4) * e.z)
}

fn to_f32(p: [f64; 2]) -> [f32; 2] {
    [p[0] as f32, p[1] as f32]
}

/// A box's visible faces, shaded by `light`; `None` if any corner is behind the near plane.
fn box_prim(
    cam: &Camera,
    pose: &Isometry3<f64>,
    e: &Vector3<f64>,
    colour: Rgb,
    light: &Vector3<f64>,
) -> Option<Prim> {
    let mut screen = [[0.0f32; 2]; 8];
    let mut world = [Point3::origin(); 8];
    for k in 0..8 {
        world[k] = pose * box_corner(e, k);
        screen[k] = to_f32(cam.project(&world[k])?);
    }
    let mut corners = [[[0.0f32; 2]; 4]; 3];
    let mut colours = [colour; 3];
    let mut count = 0;
    for (idx, n) in BOX_FACES {
        let normal = pose.rotation * Vector3::new(n[0], n[1], n[2]);
        let centre = idx
            .iter()
            .fold(Vector3::zeros(), |acc, &k| acc + world[k].coords)
            / 4.0;
        if normal.dot(&(cam.eye().coords - centre)) <= 0.0 || count == 3 {
            continue;
        }
        for (slot, &k) in corners[count].iter_mut().zip(idx.iter()) {
            *slot = screen[k];
        }
        let lit = 0.55 + 0.45 * normal.dot(light).max(0.0) as f32;
        colours[count] = colour.scale(lit * 1.1);
        count += 1;
    }
    Some(Prim {
        depth: (pose.translation.vector - cam.eye().coords).norm(),
        kind: PrimKind::Faces {
            corners,
            colours,
            count,
        },
    })
}

/// A capsule between world points `a` and `b`; `None` if an end is behind the near plane.
fn capsule_prim(
    cam: &Camera,
    a: &Point3<f64>,
    b: &Point3<f64>,
    radius: f64,
    colour: Rgb,
) -> Option<Prim> {
    let (ca, cb) = (cam.to_camera(a), cam.to_camera(b));
    let (pa, pb) = (cam.project_camera(&ca)?, cam.project_camera(&cb)?);
    let mid = Point3::from((a.coords + b.coords) / 2.0);
    Some(Prim {
        depth: (mid - cam.eye()).norm(),
        kind: PrimKind::Capsule {
            a: to_f32(pa),
            ra: (cam.focal_px() * radius / ca.z) as f32,
            b: to_f32(pb),
            rb: (cam.focal_px() * radius / cb.z) as f32,
            colour,
        },
    })
}

/// A sphere at world point `c`, at least `min_px` pixels in radius; `None` behind the camera.
fn sphere_prim(
    cam: &Camera,
    c: &Point3<f64>,
    radius: f64,
    colour: Rgb,
    min_px: f32,
) -> Option<Prim> {
    let cc = cam.to_camera(c);
    let p = cam.project_camera(&cc)?;
    Some(Prim {
        depth: (c - cam.eye()).norm(),
        kind: PrimKind::Sphere {
            c: to_f32(p),
            r: ((cam.focal_px() * radius / cc.z) as f32).max(min_px),
            colour,
        },
    })
}

/// The outline of the hull of two circles (a capsule seen in perspective): the outer tangents
/// and the far arcs of each end circle.
fn capsule_path(a: [f32; 2], ra: f32, b: [f32; 2], rb: f32) -> Option<Path> {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = (dx * dx + dy * dy).sqrt();
    if len <= (ra - rb).abs() + 1e-3 {
        // One end circle contains the other (the capsule points at the camera).
        let (c, r) = if ra >= rb { (a, ra) } else { (b, rb) };
        return PathBuilder::from_circle(c[0], c[1], r.max(0.5));
    }
    // The outer tangents touch each circle where the radius makes angle acos(s) with the axis,
    // s = (ra − rb) / len.
    let axis = dy.atan2(dx);
    let half = ((ra - rb) / len).clamp(-1.0, 1.0).acos();
    let mut pb = PathBuilder::new();
    let arc = |pb: &mut PathBuilder, c: [f32; 2], r: f32, from: f32, sweep: f32, first: bool| {
        let n = ((r * sweep.abs() / 2.0).ceil() as usize).clamp(4, 48);
        for i in 0..=n {
            let t = from + sweep * i as f32 / n as f32;
            let (x, y) = (c[0] + r * t.cos(), c[1] + r * t.sin());
            if first && i == 0 {
                pb.move_to(x, y);
            } else {
                pb.line_to(x, y);
            }
        }
    };
    // Around b's far side, from one tangent point to the other, then around a's far side.
    arc(&mut pb, b, rb, axis + half, -2.0 * half, true);
    let back = std::f32::consts::PI - half;
    arc(&mut pb, a, ra, axis - half, -2.0 * back, false);
    pb.close();
    pb.finish()
}

/// A gradient across a capsule: lit on the side facing up in the image, dark on the other.
fn capsule_shader(a: [f32; 2], ra: f32, b: [f32; 2], rb: f32, colour: Rgb) -> Shader<'static> {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = (dx * dx + dy * dy).sqrt().max(1e-3);
    // The unit normal to the axis that points up in the image (y down), or left when the axis
    // is vertical.
    let (mut nx, mut ny) = (-dy / len, dx / len);
    if ny > 0.0 || (ny == 0.0 && nx > 0.0) {
        nx = -nx;
        ny = -ny;
    }
    let r = ra.max(rb).max(0.5);
    let m = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
    LinearGradient::new(
        Point::from_xy(m[0] + nx * r, m[1] + ny * r),
        Point::from_xy(m[0] - nx * r, m[1] - ny * r),
        vec![
            GradientStop::new(0.0, colour.tint(0.35).opaque()),
            GradientStop::new(0.4, colour.opaque()),
            GradientStop::new(1.0, colour.scale(0.55).opaque()),
        ],
        SpreadMode::Pad,
        Transform::identity(),
    )
    .unwrap_or(Shader::SolidColor(colour.opaque()))
}

/// Appends a clipped, projected polygon (camera coordinates) as a closed sub-path.
fn push_projected(cam: &Camera, polygon: &[Vector3<f64>], pb: &mut PathBuilder) {
    if polygon.len() < 3 {
        return;
    }
    for (i, c) in polygon.iter().enumerate() {
        // Clipped points are at or beyond the near plane, so they project.
        let Some(p) = cam.project_camera(&Vector3::new(c.x, c.y, c.z.max(NEAR_PLANE_M))) else {
            continue;
        };
        let (x, y) = (p[0] as f32, p[1] as f32);
        if i == 0 {
            pb.move_to(x, y);
        } else {
            pb.line_to(x, y);
        }
    }
    pb.close();
}

/// Appends a world polyline, projected as one contour (so that a dash pattern runs along it)
/// while its points are in front of the near plane, each of its segments clipped otherwise.
fn push_world_polyline(cam: &Camera, pb: &mut PathBuilder, points: &[Point3<f64>]) {
    let mut open = false;
    for pair in points.windows(2) {
        let (a, b) = (cam.to_camera(&pair[0]), cam.to_camera(&pair[1]));
        match (cam.project_camera(&a), cam.project_camera(&b)) {
            (Some(pa), Some(pbb)) if clip_segment_near(a, b) == Some((a, b)) => {
                if !open {
                    pb.move_to(pa[0] as f32, pa[1] as f32);
                    open = true;
                }
                pb.line_to(pbb[0] as f32, pbb[1] as f32);
            }
            _ => {
                open = false;
                push_world_segment(cam, pb, &pair[0], &pair[1]);
            }
        }
    }
}

/// Appends a world segment clipped to the near plane and projected.
fn push_world_segment(cam: &Camera, pb: &mut PathBuilder, a: &Point3<f64>, b: &Point3<f64>) {
    if let Some((ca, cb)) = clip_segment_near(cam.to_camera(a), cam.to_camera(b))
        && let (Some(pa), Some(pbb)) = (cam.project_camera(&ca), cam.project_camera(&cb))
    {
        pb.move_to(pa[0] as f32, pa[1] as f32);
        pb.line_to(pbb[0] as f32, pbb[1] as f32);
    }
}

/// The ground point straight ahead of the camera at `distance` (m, horizontal) from it.
fn ground_point_ahead(cam: &Camera, distance: f64) -> Point3<f64> {
    let f = cam.forward();
    let ahead = Vector3::new(f.x, f.y, 0.0).normalize();
    let e = cam.eye();
    Point3::new(e.x + ahead.x * distance, e.y + ahead.y * distance, 0.0)
}

/// A rectangle with rounded corners.
fn rounded_rect(x: f32, y: f32, w: f32, h: f32, r: f32) -> Option<Path> {
    let mut pb = PathBuilder::new();
    pb.move_to(x + r, y);
    pb.line_to(x + w - r, y);
    pb.quad_to(x + w, y, x + w, y + r);
    pb.line_to(x + w, y + h - r);
    pb.quad_to(x + w, y + h, x + w - r, y + h);
    pb.line_to(x + r, y + h);
    pb.quad_to(x, y + h, x, y + h - r);
    pb.line_to(x, y + r);
    pb.quad_to(x, y, x + r, y);
    pb.close();
    pb.finish()
}
