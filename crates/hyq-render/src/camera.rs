//! A pinhole camera orbiting a target point: world (z up) to pixel coordinates.
//!
//! The camera sits at `distance_m` from its target (by default scaled to the robot's size), `elevation_deg` above the ground plane
//! through the target and at `azimuth_deg` around the vertical (0° on +x, 90° on +y), and
//! looks at the target with the world's z axis up. A point p maps to the camera frame
//! (x right, y up, z along the view direction) and then to pixels:
//!
//! u = w/2 + f · x_c / z_c,   v = h/2 − f · y_c / z_c,   f = (h/2) / tan(fov_y / 2),
//!
//! so the target is always at the image centre. Points closer than [`NEAR_PLANE_M`] in front of
//! the camera (or behind it) do not project.

use hyq_physics::na::{Point3, Vector3};

use crate::error::RenderError;

/// The distance (m) in front of the camera below which geometry is clipped away.
pub const NEAR_PLANE_M: f64 = 0.05;

/// The camera distance (m) that frames HyQ, a robot standing [`REFERENCE_HEIGHT_M`] tall.
pub const REFERENCE_DISTANCE_M: f64 = 3.2;

/// The standing height (m) of the robot the drawing sizes were chosen on (HyQ's trunk frame,
/// standing): a renderer scales its camera distance and markers by the robot's standing height
/// over this.
pub const REFERENCE_HEIGHT_M: f64 = 0.5895;

/// Where the camera sits relative to its target, and how wide it sees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraConfig {
    /// Distance from the target (m) (default: unset: [`REFERENCE_DISTANCE_M`] scaled by the
    /// robot's standing height over [`REFERENCE_HEIGHT_M`], so every robot fills the frame as
    /// HyQ does at 3.2 m; a [`Camera`] built from an unset distance uses 3.2 m).
    pub distance_m: Option<f64>,
    /// Angle above the horizontal plane through the target, exclusive of 0° and 90° (default:
    /// 22°).
    pub elevation_deg: f64,
    /// Angle around the vertical axis, from +x towards +y, of the camera's position seen from
    /// the target (default: −140°: behind the robot and to its right, so that a goal a few
    /// metres ahead along +x, where goals usually lie, is in view beside the robot).
    pub azimuth_deg: f64,
    /// Vertical field of view (default: 45°).
    pub fov_y_deg: f64,
}

impl Default for CameraConfig {
    fn default() -> Self {
        Self {
            distance_m: None,
            elevation_deg: 22.0,
            azimuth_deg: -140.0,
            fov_y_deg: 45.0,
        }
    }
}

impl CameraConfig {
    /// Checks every setting; the error names the first one out of range.
    pub fn validate(&self) -> Result<(), RenderError> {
        let check = |field: &'static str, value: f64, ok: bool, reason: &'static str| {
            if value.is_finite() && ok {
                Ok(())
            } else {
                Err(RenderError::InvalidConfig {
                    field,
                    value,
                    reason,
                })
            }
        };
        if let Some(d) = self.distance_m {
            check(
                "camera.distance_m",
                d,
                d > NEAR_PLANE_M,
                "must be finite and above the near plane (0.05 m)",
            )?;
        }
        check(
            "camera.elevation_deg",
            self.elevation_deg,
            self.elevation_deg > 0.0 && self.elevation_deg < 90.0,
            "must be above 0° and below 90° (the camera looks down at the target)",
        )?;
        check(
            "camera.azimuth_deg",
            self.azimuth_deg,
            true,
            "must be finite",
        )?;
        check(
            "camera.fov_y_deg",
            self.fov_y_deg,
            self.fov_y_deg >= 1.0 && self.fov_y_deg <= 150.0,
            "must be between 1° and 150°",
        )
    }
}

/// A camera placed for one frame: its position, axes and focal length in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    eye: Point3<f64>,
    right: Vector3<f64>,
    up: Vector3<f64>,
    forward: Vector3<f64>,
    focal_px: f64,
    centre: [f64; 2],
}

impl Camera {
    /// The camera of `config` looking at `target`, for an image of `width × height` pixels.
    ///
    /// `config` is assumed valid ([`CameraConfig::validate`]); the renderer checks it once.
    pub fn looking_at(config: &CameraConfig, target: Point3<f64>, width: u32, height: u32) -> Self {
        let (el, az) = (
            config.elevation_deg.to_radians(),
            config.azimuth_deg.to_radians(),
        );
        let offset = Vector3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin());
        let eye = target + offset * config.distance_m.unwrap_or(REFERENCE_DISTANCE_M);
        let forward = -offset;
        // The elevation is strictly between 0° and 90°, so the view direction is never
        // vertical and the cross product with z is never zero.
        let right = forward.cross(&Vector3::z()).normalize();
        let up = right.cross(&forward);
        let focal_px = f64::from(height) / 2.0 / (config.fov_y_deg.to_radians() / 2.0).tan();
        Self {
            eye,
            right,
            up,
            forward,
            focal_px,
            centre: [f64::from(width) / 2.0, f64::from(height) / 2.0],
        }
    }

    /// The camera's position (world, m).
    pub fn eye(&self) -> Point3<f64> {
        self.eye
    }

    /// The unit view direction (world).
    pub fn forward(&self) -> Vector3<f64> {
        self.forward
    }

    /// The unit vector pointing right in the image (world).
    pub fn right(&self) -> Vector3<f64> {
        self.right
    }

    /// The unit vector pointing up in the image (world).
    pub fn up(&self) -> Vector3<f64> {
        self.up
    }

    /// The focal length in pixels: a length of 1 m at 1 m depth spans this many pixels.
    pub fn focal_px(&self) -> f64 {
        self.focal_px
    }

    /// A world point in the camera frame: (right, up, depth along the view direction), m.
    pub fn to_camera(&self, p: &Point3<f64>) -> Vector3<f64> {
        let d = p - self.eye;
        Vector3::new(d.dot(&self.right), d.dot(&self.up), d.dot(&self.forward))
    }

    /// Pixel coordinates (x right, y down, origin at the top-left corner of the image) of a
    /// point in the camera frame, or `None` if it lies closer than [`NEAR_PLANE_M`].
    pub fn project_camera(&self, c: &Vector3<f64>) -> Option<[f64; 2]> {
        (c.z >= NEAR_PLANE_M).then(|| {
            [
                self.centre[0] + self.focal_px * c.x / c.z,
                self.centre[1] - self.focal_px * c.y / c.z,
            ]
        })
    }

    /// Pixel coordinates of a world point, or `None` if it lies closer than [`NEAR_PLANE_M`] in
    /// front of the camera (or behind it).
    pub fn project(&self, p: &Point3<f64>) -> Option<[f64; 2]> {
        self.project_camera(&self.to_camera(p))
    }

    /// The depth (m, along the view direction) of a world point.
    pub fn depth(&self, p: &Point3<f64>) -> f64 {
        (p - self.eye).dot(&self.forward)
    }

    /// The image row of the horizon (where the ground plane meets the sky at infinity).
    pub fn horizon_y(&self) -> f64 {
        // A horizontal direction straight ahead; its image is the vanishing point on the
        // horizon. The camera looks down, so that direction is in front of it.
        let ahead = Vector3::new(self.forward.x, self.forward.y, 0.0).normalize();
        self.centre[1] - self.focal_px * ahead.dot(&self.up) / ahead.dot(&self.forward)
    }
}
