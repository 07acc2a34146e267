//! An element's attributes after its default class is applied, read as numbers and frames:
//! every number finite and within [`MAX_ABS`], every attribute either read, known and left to
//! the project's own settings (with a note), or refused by name.

use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, Unit, UnitQuaternion, Vector3};

use super::elem::{Elem, MjcfReadError};

/// The largest magnitude of any number read: far beyond any robot's figure in SI units, far
/// below where `f32` would overflow; the model's own bounds then check each quantity.
pub(crate) const MAX_ABS: f64 = 1e9;

/// The `<compiler>` settings that change how numbers read.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Compiler {
    /// Angles in degrees (MuJoCo's default) rather than radians.
    pub(crate) degrees: bool,
    /// The Euler sequence: three of `xyzXYZ` (lower case: axes that move with the frame).
    pub(crate) eulerseq: [u8; 3],
    /// `autolimits`: a joint with a range is limited unless it says otherwise.
    pub(crate) autolimits: bool,
}

impl Default for Compiler {
    fn default() -> Self {
        Self {
            degrees: true,
            eulerseq: *b"xyz",
            autolimits: true,
        }
    }
}

/// An element's attributes, its class defaults first, its own written ones after.
pub(crate) struct Attrs<'a> {
    pub(crate) elem: &'a Elem,
    list: Vec<(String, String)>,
}

impl<'a> Attrs<'a> {
    /// The attributes of `elem` over `defaults` (both in file order; the element's win).
    pub(crate) fn new(elem: &'a Elem, defaults: &[(String, String)]) -> Self {
        let mut list: Vec<(String, String)> = defaults.to_vec();
        for (k, v) in &elem.attrs {
            if k == "class" {
                continue;
            }
            match list.iter_mut().find(|(lk, _)| lk == k) {
                Some(slot) => slot.1.clone_from(v),
                None => list.push((k.clone(), v.clone())),
            }
        }
        Self { elem, list }
    }

    pub(crate) fn get(&self, name: &str) -> Option<&str> {
        self.list
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    pub(crate) fn error(&self, message: impl std::fmt::Display) -> MjcfReadError {
        self.elem.error(message)
    }

    /// Refuses any attribute outside `read` and `ignored`; returns the ignored ones written
    /// (for the caller's note).
    pub(crate) fn check_known(
        &self,
        read: &[&str],
        ignored: &[&str],
    ) -> Result<Vec<String>, MjcfReadError> {
        let mut skipped = Vec::new();
        for (k, _) in &self.list {
            if read.contains(&k.as_str()) {
                continue;
            }
            if ignored.contains(&k.as_str()) {
                skipped.push(k.clone());
                continue;
            }
            return Err(self.error(format!(
                "attribute `{}` is not understood here, so the robot cannot be read faithfully",
                hyq_physics::printable(k)
            )));
        }
        Ok(skipped)
    }

    /// The numbers of attribute `name` (`None` if not written); each finite and at most
    /// [`MAX_ABS`] in magnitude; `count` of them when given.
    pub(crate) fn nums(
        &self,
        name: &str,
        count: Option<usize>,
    ) -> Result<Option<Vec<f64>>, MjcfReadError> {
        let Some(text) = self.get(name) else {
            return Ok(None);
        };
        let mut out = Vec::new();
        for word in text.split_whitespace() {
            let v: f64 = word.parse().map_err(|_| {
                self.error(format!(
                    "attribute `{name}`: {:?} is not a number",
                    hyq_physics::printable(word)
                ))
            })?;
            if !v.is_finite() || v.abs() > MAX_ABS {
                return Err(self.error(format!(
                    "attribute `{name}`: {word} is not a finite number of magnitude at most {MAX_ABS:e}"
                )));
            }
            out.push(v);
            if out.len() > 4096 {
                return Err(self.error(format!("attribute `{name}`: too many numbers")));
            }
        }
        if let Some(n) = count
            && out.len() != n
        {
            return Err(self.error(format!(
                "attribute `{name}`: {} numbers, expected {n}",
                out.len()
            )));
        }
        Ok(Some(out))
    }

    /// One number, or `default` if not written.
    pub(crate) fn num(&self, name: &str, default: f64) -> Result<f64, MjcfReadError> {
        Ok(self.nums(name, Some(1))?.map_or(default, |v| v[0]))
    }

    /// A vector of three, or `default`.
    pub(crate) fn vec3(
        &self,
        name: &str,
        default: Vector3<f64>,
    ) -> Result<Vector3<f64>, MjcfReadError> {
        Ok(self
            .nums(name, Some(3))?
            .map_or(default, |v| Vector3::new(v[0], v[1], v[2])))
    }

    /// An integer attribute (contype, conaffinity), or `default`.
    pub(crate) fn int(&self, name: &str, default: i64) -> Result<i64, MjcfReadError> {
        match self.get(name) {
            None => Ok(default),
            Some(t) => t.trim().parse().map_err(|_| {
                self.error(format!(
                    "attribute `{name}`: {:?} is not an integer",
                    hyq_physics::printable(t)
                ))
            }),
        }
    }

    /// A `true`/`false`/`auto` attribute.
    pub(crate) fn tristate(&self, name: &str) -> Result<Option<bool>, MjcfReadError> {
        match self.get(name) {
            None | Some("auto") => Ok(None),
            Some("true") => Ok(Some(true)),
            Some("false") => Ok(Some(false)),
            Some(other) => Err(self.error(format!(
                "attribute `{name}`: {:?} is not true, false or auto",
                hyq_physics::printable(other)
            ))),
        }
    }

    /// The frame given by `pos` and at most one orientation attribute (`quat`, `axisangle`,
    /// `euler`, `xyaxes`, `zaxis`).
    pub(crate) fn frame(&self, compiler: &Compiler) -> Result<Isometry3<f64>, MjcfReadError> {
        let pos = self.vec3("pos", Vector3::zeros())?;
        let rot = self.orientation(compiler)?;
        Ok(Isometry3::from_parts(Translation3::from(pos), rot))
    }

    fn orientation(&self, compiler: &Compiler) -> Result<UnitQuaternion<f64>, MjcfReadError> {
        let forms = ["quat", "axisangle", "euler", "xyaxes", "zaxis"];
        let written: Vec<&str> = forms
            .iter()
            .copied()
            .filter(|f| self.get(f).is_some())
            .collect();
        if written.len() > 1 {
            return Err(self.error(format!(
                "more than one orientation ({}): MuJoCo takes one",
                written.join(", ")
            )));
        }
        let angle = |a: f64| if compiler.degrees { a.to_radians() } else { a };
        let Some(&form) = written.first() else {
            return Ok(UnitQuaternion::identity());
        };
        let bad = |what: &str| self.error(format!("attribute `{form}`: {what}"));
        match form {
            "quat" => {
                let q = self.nums("quat", Some(4))?.unwrap_or_default();
                let q = nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]);
                if q.norm() < 1e-9 {
                    return Err(bad("a zero quaternion is no rotation"));
                }
                Ok(UnitQuaternion::from_quaternion(q))
            }
            "axisangle" => {
                let v = self.nums("axisangle", Some(4))?.unwrap_or_default();
                let axis = unit(Vector3::new(v[0], v[1], v[2])).ok_or_else(|| bad("zero axis"))?;
                Ok(UnitQuaternion::from_axis_angle(&axis, angle(v[3])))
            }
            "euler" => {
                let v = self.nums("euler", Some(3))?.unwrap_or_default();
                Ok(euler(
                    &compiler.eulerseq,
                    [angle(v[0]), angle(v[1]), angle(v[2])],
                ))
            }
            "xyaxes" => {
                let v = self.nums("xyaxes", Some(6))?.unwrap_or_default();
                xyaxes(&v).ok_or_else(|| bad("the x and y axes must be non-zero and not parallel"))
            }
            _ => {
                let v = self.vec3("zaxis", Vector3::z())?;
                zaxis(v).ok_or_else(|| bad("zero axis"))
            }
        }
    }
}

/// `v` normalised, or `None` if it is (nearly) zero.
pub(crate) fn unit(v: Vector3<f64>) -> Option<Unit<Vector3<f64>>> {
    Unit::try_new(v, 1e-9)
}

/// MuJoCo's Euler rotation: for each of the three axes in turn, a rotation about it composed
/// on the right (lower case, axes moving with the frame) or on the left (upper case, fixed).
pub(crate) fn euler(seq: &[u8; 3], angles: [f64; 3]) -> UnitQuaternion<f64> {
    let mut q = UnitQuaternion::identity();
    for (&c, a) in seq.iter().zip(angles) {
        let axis = match c.to_ascii_lowercase() {
            b'x' => Vector3::x_axis(),
            b'y' => Vector3::y_axis(),
            _ => Vector3::z_axis(),
        };
        let r = UnitQuaternion::from_axis_angle(&axis, a);
        q = if c.is_ascii_lowercase() { q * r } else { r * q };
    }
    q
}

/// The frame whose x axis is along the first three numbers and whose y axis is the next three
/// made orthogonal to it (MuJoCo's `xyaxes`).
fn xyaxes(v: &[f64]) -> Option<UnitQuaternion<f64>> {
    let x = unit(Vector3::new(v[0], v[1], v[2]))?;
    let y = Vector3::new(v[3], v[4], v[5]);
    let y = unit(y - x.into_inner() * x.dot(&y))?;
    let z = x.cross(&y);
    let m = Matrix3::from_columns(&[x.into_inner(), y.into_inner(), z]);
    Some(UnitQuaternion::from_rotation_matrix(
        &Rotation3::from_matrix_unchecked(m),
    ))
}

/// The smallest rotation taking z to `v` (MuJoCo's `zaxis`, also the frame of a `fromto`).
pub(crate) fn zaxis(v: Vector3<f64>) -> Option<UnitQuaternion<f64>> {
    let z = unit(v)?;
    Some(
        UnitQuaternion::rotation_between(&Vector3::z(), &z.into_inner()).unwrap_or_else(|| {
            // Opposite to z: half a turn about x.
            UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
        }),
    )
}

/// Reads `<compiler>`: angle units, Euler sequence, autolimits; refuses global coordinates.
pub(crate) fn compiler(elem: &Elem, into: &mut Compiler) -> Result<(), MjcfReadError> {
    let a = Attrs::new(elem, &[]);
    a.check_known(
        &["angle", "eulerseq", "autolimits", "coordinate"],
        &[
            "meshdir",
            "texturedir",
            "assetdir",
            "discardvisual",
            "inertiafromgeom",
            "strippath",
            "usethread",
            "boundmass",
            "boundinertia",
            "settotalmass",
            "balanceinertia",
            "fitaabb",
            "inertiagrouprange",
            "exactmeshinertia",
            "alignfree",
            "fusestatic",
            "saveinertial",
            "convexhull",
        ],
    )?;
    if let Some(v) = a.get("settotalmass")
        && v.trim() != "-1"
    {
        return Err(a.error("attribute `settotalmass` rescales the masses, which is not done here"));
    }
    match a.get("angle") {
        None => {}
        Some("degree") => into.degrees = true,
        Some("radian") => into.degrees = false,
        Some(o) => return Err(a.error(format!("attribute `angle`: {o:?} is not degree or radian"))),
    }
    if let Some(seq) = a.get("eulerseq") {
        let b = seq.as_bytes();
        let ok = b.len() == 3 && b.iter().all(|c| b"xyzXYZ".contains(c));
        if !ok {
            return Err(a.error(format!(
                "attribute `eulerseq`: {seq:?} is not three of xyzXYZ"
            )));
        }
        into.eulerseq = [b[0], b[1], b[2]];
    }
    if let Some(auto) = a.tristate("autolimits")? {
        into.autolimits = auto;
    }
    if a.get("coordinate").is_some_and(|c| c != "local") {
        return Err(a.error("attribute `coordinate`: only local coordinates are read"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn euler_sequences_compose_as_mujoco_does() {
        let (a, b, c) = (0.3, -0.7, 1.1);
        let rx = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), a);
        let ry = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), b);
        let rz = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), c);
        let intrinsic = euler(b"xyz", [a, b, c]);
        assert!(intrinsic.angle_to(&(rx * ry * rz)) < 1e-12);
        let extrinsic = euler(b"XYZ", [a, b, c]);
        assert!(extrinsic.angle_to(&(rz * ry * rx)) < 1e-12);
        // URDF's rpy is the fixed-axis XYZ sequence.
        let rpy = UnitQuaternion::from_euler_angles(a, b, c);
        assert!(extrinsic.angle_to(&rpy) < 1e-12);
    }

    #[test]
    fn zaxis_and_xyaxes_give_the_frames_they_name() {
        let v = Vector3::new(1.0, 2.0, -0.5);
        let q = zaxis(v).expect("non-zero");
        assert!((q * Vector3::z() - v.normalize()).norm() < 1e-12);
        let down = zaxis(-Vector3::z()).expect("non-zero");
        assert!((down * Vector3::z() + Vector3::z()).norm() < 1e-12);
        let r = xyaxes(&[0.0, 1.0, 0.0, -1.0, 0.0, 0.0]).expect("valid");
        assert!((r * Vector3::x() - Vector3::y()).norm() < 1e-12);
        assert!((r * Vector3::y() + Vector3::x()).norm() < 1e-12);
        assert!(xyaxes(&[1.0, 0.0, 0.0, 2.0, 0.0, 0.0]).is_none());
    }
}
