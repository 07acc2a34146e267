//! The `<worldbody>`: one robot (a root body with a free joint), its bodies, hinge joints,
//! inertials and primitive collision geoms, turned into a URDF description. Each body becomes
//! a link whose frame is its joint's frame (the body frame moved to the joint's `pos`); a body
//! without a joint is fixed to its parent (the model lumps it).

use std::collections::HashMap;

use nalgebra::{Isometry3, Matrix3, Translation3, UnitQuaternion, Vector3};

use super::attrs::{Attrs, Compiler, unit, zaxis};
use super::defaults::{Defaults, MAIN};
use super::elem::{Elem, MjcfReadError};

/// Geom attributes that only MuJoCo's contact solver, rendering or mass-from-shape uses: the
/// project's engines have their own contact settings, and masses come from `<inertial>`.
const GEOM_IGNORED: &[&str] = &[
    "condim",
    "solimp",
    "solref",
    "solmix",
    "friction",
    "priority",
    "margin",
    "gap",
    "rgba",
    "material",
    "group",
    "density",
    "mass",
    "shellinertia",
    "fluidshape",
    "fluidcoef",
    "user",
    "hfield",
];

/// Joint attributes left to the project's own settings (limit softness, solver tuning).
const JOINT_IGNORED: &[&str] = &[
    "solreflimit",
    "solimplimit",
    "solreffriction",
    "solimpfriction",
    "margin",
    "group",
    "user",
    "springref",
    "actuatorgravcomp",
    "actuatorfrclimited",
];

/// Elements inside a body that carry no physics of the robot.
const BODY_SKIPPED: &[&str] = &["site", "camera", "light"];

/// What the walk builds.
pub(crate) struct Walk<'a> {
    pub(crate) defaults: &'a Defaults,
    pub(crate) compiler: Compiler,
    pub(crate) robot: urdf_rs::Robot,
    pub(crate) joints: Vec<String>,
    /// The range (rad) of each limited hinge, for actuators' `inheritrange`.
    pub(crate) ranges: HashMap<String, [f64; 2]>,
    /// `actuatorfrcrange` by joint, the effort limit when no actuator gives one.
    pub(crate) joint_force: HashMap<String, [f64; 2]>,
    pub(crate) armature: HashMap<String, f64>,
    pub(crate) notes: Vec<String>,
    skipped_visual: usize,
    skipped_other: usize,
}

impl<'a> Walk<'a> {
    pub(crate) fn new(defaults: &'a Defaults, compiler: Compiler, name: &str) -> Self {
        Self {
            defaults,
            compiler,
            robot: urdf_rs::Robot {
                name: name.to_owned(),
                version: None,
                links: Vec::new(),
                joints: Vec::new(),
                materials: Vec::new(),
            },
            joints: Vec::new(),
            ranges: HashMap::new(),
            joint_force: HashMap::new(),
            armature: HashMap::new(),
            notes: Vec::new(),
            skipped_visual: 0,
            skipped_other: 0,
        }
    }

    /// Reads the `<worldbody>`s: exactly one robot body; world geoms (a floor) are skipped.
    /// Returns the root body's name.
    pub(crate) fn worldbody(&mut self, worlds: &[&Elem]) -> Result<String, MjcfReadError> {
        let mut root: Option<&Elem> = None;
        for w in worlds {
            if let Some((k, _)) = w.attrs.first() {
                return Err(w.error(format!("attribute `{k}` is not understood")));
            }
            for child in &w.children {
                match child.tag.as_str() {
                    "body" => {
                        if let Some(first) = root {
                            return Err(child.error(format!(
                                "a second body in the world (the first is at line {}): one \
                                 robot is read, and the world holds nothing else",
                                first.line
                            )));
                        }
                        root = Some(child);
                    }
                    "geom" => self.notes.push(format!(
                        "{}: a world geom (the floor or scenery) is skipped: the project \
                         makes its own ground",
                        child.at()
                    )),
                    t if BODY_SKIPPED.contains(&t) => self.skipped_other += 1,
                    _ => return Err(child.error("is not read in the <worldbody>")),
                }
            }
        }
        let root = root.ok_or_else(|| {
            MjcfReadError("the MJCF file has no robot: no <body> in its <worldbody>".to_owned())
        })?;
        let name = self.body(root, None, MAIN, &Isometry3::identity())?;
        if self.skipped_visual > 0 {
            self.notes.push(format!(
                "{} visual-only geoms (contype and conaffinity 0, or meshes that do not collide) \
                 skipped; mesh files are not read",
                self.skipped_visual
            ));
        }
        if self.skipped_other > 0 {
            self.notes.push(format!(
                "{} sites, cameras and lights skipped (no physics)",
                self.skipped_other
            ));
        }
        Ok(name)
    }

    /// One body and the bodies inside it. `parent` is the parent link's name (`None` for the
    /// root) and `in_parent` maps this body's MJCF parent frame into that link's frame.
    fn body(
        &mut self,
        b: &Elem,
        parent: Option<&str>,
        inherited: &str,
        in_parent: &Isometry3<f64>,
    ) -> Result<String, MjcfReadError> {
        let a = Attrs::new(b, &[]);
        let (name, class) = self.body_header(b, &a, inherited)?;
        let body_frame = in_parent * a.frame(&self.compiler)?;
        let joint = self.body_joint(b, class, parent.is_none())?;
        // The link frame is the joint frame: the body frame moved to the joint's position.
        let shift = Isometry3::from_parts(
            Translation3::from(joint.as_ref().map_or(Vector3::zeros(), |j| j.pos)),
            UnitQuaternion::identity(),
        );
        let to_link = shift.inverse();
        let link = self.link(b, &name, class, &to_link)?;
        self.robot.links.push(link);
        if let Some(parent) = parent {
            self.push_joint(&name, parent, &(body_frame * shift), joint)?;
        }
        for child in b.children.iter().filter(|c| c.tag == "body") {
            self.body(child, Some(&name), class, &to_link)?;
        }
        Ok(name)
    }

    /// A body's name and the class its children take; refuses what a body cannot be here.
    fn body_header<'b>(
        &self,
        b: &'b Elem,
        a: &Attrs<'_>,
        inherited: &'b str,
    ) -> Result<(String, &'b str), MjcfReadError> {
        a.check_known(
            &[
                "name",
                "pos",
                "quat",
                "axisangle",
                "euler",
                "xyaxes",
                "zaxis",
                "childclass",
                "mocap",
                "gravcomp",
            ],
            &["user"],
        )?;
        if b.get("class").is_some() {
            return Err(b.error("a body takes `childclass`, not `class`"));
        }
        for (key, ok) in [("mocap", "false"), ("gravcomp", "0")] {
            if b.get(key).is_some_and(|v| v.trim() != ok) {
                return Err(a.error(format!("attribute `{key}` cannot be represented")));
            }
        }
        let name = b
            .get("name")
            .ok_or_else(|| b.error("a body needs a name here (links are named by it)"))?
            .to_owned();
        if self.robot.links.iter().any(|l| l.name == name) {
            return Err(b.error(format!("a second body named {name:?}")));
        }
        let class = match b.get("childclass") {
            Some(c) => {
                self.defaults.check_class(b, c)?;
                c
            }
            None => inherited,
        };
        Ok((name, class))
    }

    /// The link of a body: its inertial and colliding geoms in the link frame (`to_link` maps
    /// the body frame into it).
    fn link(
        &mut self,
        b: &Elem,
        name: &str,
        class: &str,
        to_link: &Isometry3<f64>,
    ) -> Result<urdf_rs::Link, MjcfReadError> {
        let mut link = urdf_rs::Link {
            name: name.to_owned(),
            inertial: urdf_rs::Inertial::default(),
            visual: Vec::new(),
            collision: Vec::new(),
        };
        let mut has_inertial = false;
        for child in &b.children {
            match child.tag.as_str() {
                "inertial" => {
                    if has_inertial {
                        return Err(child.error("a second <inertial> in the body"));
                    }
                    has_inertial = true;
                    link.inertial = self.inertial(child, to_link)?;
                }
                "geom" => {
                    if let Some(c) = self.geom(child, class, to_link)? {
                        link.collision.push(c);
                    }
                }
                "joint" | "freejoint" | "body" => {}
                t if BODY_SKIPPED.contains(&t) => self.skipped_other += 1,
                _ => return Err(child.error("is not read inside a <body>")),
            }
        }
        if !has_inertial && !link.collision.is_empty() {
            return Err(b.error(
                "has collision geoms but no <inertial>: masses from geom shapes are not \
                 computed here, so give the body an <inertial>",
            ));
        }
        Ok(link)
    }

    /// The URDF joint attaching body `child` to link `parent` at `origin`: revolute for a hinge,
    /// fixed for none.
    fn push_joint(
        &mut self,
        child: &str,
        parent: &str,
        origin: &Isometry3<f64>,
        hinge: Option<Hinge>,
    ) -> Result<(), MjcfReadError> {
        let (roll, pitch, yaw) = origin.rotation.euler_angles();
        let t = origin.translation.vector;
        let mut joint = urdf_rs::Joint {
            name: format!("{child}_fixed"),
            joint_type: urdf_rs::JointType::Fixed,
            origin: urdf_rs::Pose {
                xyz: urdf_rs::Vec3([t.x, t.y, t.z]),
                rpy: urdf_rs::Vec3([roll, pitch, yaw]),
            },
            parent: urdf_rs::LinkName {
                link: parent.to_owned(),
            },
            child: urdf_rs::LinkName {
                link: child.to_owned(),
            },
            axis: urdf_rs::Axis::default(),
            limit: urdf_rs::JointLimit::default(),
            calibration: None,
            dynamics: None,
            mimic: None,
            safety_controller: None,
        };
        if let Some(h) = hinge {
            joint.name.clone_from(&h.name);
            joint.joint_type = if h.range.is_some() {
                urdf_rs::JointType::Revolute
            } else {
                urdf_rs::JointType::Continuous
            };
            joint.axis.xyz = urdf_rs::Vec3([h.axis.x, h.axis.y, h.axis.z]);
            if let Some([lo, hi]) = h.range {
                joint.limit.lower = lo;
                joint.limit.upper = hi;
                self.ranges.insert(h.name.clone(), [lo, hi]);
            }
            joint.dynamics = Some(urdf_rs::Dynamics {
                damping: h.damping,
                friction: h.frictionloss,
            });
            if h.armature != 0.0 {
                self.armature.insert(h.name.clone(), h.armature);
            }
            if let Some(f) = h.force {
                self.joint_force.insert(h.name.clone(), f);
            }
            if self.robot.joints.iter().any(|j| j.name == h.name) {
                return Err(MjcfReadError(format!("two joints named {:?}", h.name)));
            }
            self.joints.push(h.name);
        }
        self.robot.joints.push(joint);
        Ok(())
    }

    /// The body's joint: `None` (fixed to its parent) or one hinge; the root must have a free
    /// joint instead, and nothing else may.
    fn body_joint(
        &mut self,
        b: &Elem,
        class: &str,
        root: bool,
    ) -> Result<Option<Hinge>, MjcfReadError> {
        let joints: Vec<&Elem> = b
            .children
            .iter()
            .filter(|c| c.tag == "joint" || c.tag == "freejoint")
            .collect();
        if joints.len() > 1 {
            return Err(joints[1]
                .error("a second joint in the body: each body here moves by one hinge (or none)"));
        }
        let Some(&j) = joints.first() else {
            if root {
                return Err(b.error(
                    "the root body has no free joint: the trunk is free in this project, \
                     a robot fixed to the world cannot be represented",
                ));
            }
            return Ok(None);
        };
        let jclass = self.defaults.class_of(j, class)?;
        let a = Attrs::new(j, &self.defaults.template(jclass, &j.tag));
        let kind = if j.tag == "freejoint" {
            "free"
        } else {
            a.get("type").unwrap_or("hinge")
        };
        match (kind, root) {
            ("free", true) => {
                a.check_known(&["name", "type", "pos", "axis", "align"], JOINT_IGNORED)?;
                self.notes.push(format!(
                    "{}: the root body's pose in the world is not read: the profile's spawn \
                     height places the trunk",
                    b.at()
                ));
                Ok(None)
            }
            ("free", false) => Err(a.error("a free joint is only read on the root body")),
            (_, true) => Err(a.error("the root body's joint must be free")),
            ("hinge", false) => self.hinge(&a).map(Some),
            (other, false) => Err(a.error(format!(
                "joint type {:?} cannot be represented (hinge joints only)",
                hyq_physics::printable(other)
            ))),
        }
    }

    fn hinge(&mut self, a: &Attrs<'_>) -> Result<Hinge, MjcfReadError> {
        let ignored = a.check_known(
            &[
                "name",
                "type",
                "pos",
                "axis",
                "range",
                "limited",
                "damping",
                "armature",
                "frictionloss",
                "stiffness",
                "ref",
                "actuatorfrcrange",
            ],
            JOINT_IGNORED,
        )?;
        let name = a
            .get("name")
            .ok_or_else(|| a.error("a hinge needs a name here (the profile names joints)"))?
            .to_owned();
        for key in ["stiffness", "ref"] {
            if a.num(key, 0.0)? != 0.0 {
                return Err(a.error(format!(
                    "attribute `{key}` cannot be represented (must be 0)"
                )));
            }
        }
        let axis = unit(a.vec3("axis", Vector3::z())?).ok_or_else(|| a.error("zero axis"))?;
        let range = a.nums("range", Some(2))?.map(|r| {
            if self.compiler.degrees {
                [r[0].to_radians(), r[1].to_radians()]
            } else {
                [r[0], r[1]]
            }
        });
        let limited = a
            .tristate("limited")?
            .unwrap_or(self.compiler.autolimits && range.is_some());
        if limited && range.is_none() {
            return Err(a.error("limited, but no `range`"));
        }
        let force = a.nums("actuatorfrcrange", Some(2))?.map(|r| [r[0], r[1]]);
        if !ignored.is_empty() {
            self.notes.push(format!(
                "{}: {} left to the project's own settings",
                a.elem.at(),
                ignored.join(", ")
            ));
        }
        Ok(Hinge {
            name,
            pos: a.vec3("pos", Vector3::zeros())?,
            axis: axis.into_inner(),
            range: if limited { range } else { None },
            damping: a.num("damping", 0.0)?,
            frictionloss: a.num("frictionloss", 0.0)?,
            armature: a.num("armature", 0.0)?,
            force,
        })
    }

    /// An `<inertial>` in the link frame (`to_link` maps the body frame into it).
    fn inertial(
        &self,
        e: &Elem,
        to_link: &Isometry3<f64>,
    ) -> Result<urdf_rs::Inertial, MjcfReadError> {
        let a = Attrs::new(e, &[]);
        a.check_known(
            &[
                "pos",
                "quat",
                "axisangle",
                "euler",
                "xyaxes",
                "zaxis",
                "mass",
                "diaginertia",
                "fullinertia",
            ],
            &[],
        )?;
        let frame = to_link * a.frame(&self.compiler)?;
        let mass = a
            .nums("mass", Some(1))?
            .ok_or_else(|| a.error("no `mass`"))?[0];
        let local = match (
            a.nums("diaginertia", Some(3))?,
            a.nums("fullinertia", Some(6))?,
        ) {
            (Some(d), None) => Matrix3::from_diagonal(&Vector3::new(d[0], d[1], d[2])),
            (None, Some(f)) => Matrix3::new(f[0], f[3], f[4], f[3], f[1], f[5], f[4], f[5], f[2]),
            _ => return Err(a.error("exactly one of `diaginertia` and `fullinertia` is needed")),
        };
        let r = frame.rotation.to_rotation_matrix();
        let i = r.matrix() * local * r.matrix().transpose();
        let t = frame.translation.vector;
        Ok(urdf_rs::Inertial {
            origin: urdf_rs::Pose {
                xyz: urdf_rs::Vec3([t.x, t.y, t.z]),
                rpy: urdf_rs::Vec3([0.0; 3]),
            },
            mass: urdf_rs::Mass { value: mass },
            inertia: urdf_rs::Inertia {
                ixx: i[(0, 0)],
                ixy: i[(0, 1)],
                ixz: i[(0, 2)],
                iyy: i[(1, 1)],
                iyz: i[(1, 2)],
                izz: i[(2, 2)],
            },
        })
    }

    /// A colliding primitive geom as a URDF collision; `None` for a visual-only geom.
    fn geom(
        &mut self,
        e: &Elem,
        class: &str,
        to_link: &Isometry3<f64>,
    ) -> Result<Option<urdf_rs::Collision>, MjcfReadError> {
        let gclass = self.defaults.class_of(e, class)?;
        let a = Attrs::new(e, &self.defaults.template(gclass, "geom"));
        a.check_known(
            &[
                "name",
                "type",
                "size",
                "pos",
                "quat",
                "axisangle",
                "euler",
                "xyaxes",
                "zaxis",
                "fromto",
                "contype",
                "conaffinity",
                "mesh",
            ],
            GEOM_IGNORED,
        )?;
        let kind = a.get("type").unwrap_or("sphere");
        let (contype, conaffinity) = (a.int("contype", 1)?, a.int("conaffinity", 1)?);
        if contype == 0 && conaffinity == 0 {
            self.skipped_visual += 1;
            return Ok(None);
        }
        let (frame, geometry) = self.shape(&a, kind)?;
        Ok(Some(urdf_rs::Collision {
            name: a.get("name").map(str::to_owned),
            origin: {
                let f = to_link * frame;
                let (roll, pitch, yaw) = f.rotation.euler_angles();
                let t = f.translation.vector;
                urdf_rs::Pose {
                    xyz: urdf_rs::Vec3([t.x, t.y, t.z]),
                    rpy: urdf_rs::Vec3([roll, pitch, yaw]),
                }
            },
            geometry,
        }))
    }

    /// A primitive's frame (in the body frame) and URDF geometry, from `size`, or from
    /// `fromto` for capsules and cylinders.
    fn shape(
        &self,
        a: &Attrs<'_>,
        kind: &str,
    ) -> Result<(Isometry3<f64>, urdf_rs::Geometry), MjcfReadError> {
        let size = a.nums("size", None)?.unwrap_or_default();
        let need = |n: usize| -> Result<&[f64], MjcfReadError> {
            if size.len() < n {
                return Err(a.error(format!(
                    "a {kind} geom needs {n} `size` numbers, {} given",
                    size.len()
                )));
            }
            if let Some(bad) = size[..n].iter().find(|s| **s <= 0.0) {
                return Err(a.error(format!("attribute `size`: {bad} is not positive")));
            }
            Ok(&size[..n])
        };
        let fromto = a.nums("fromto", Some(6))?;
        match kind {
            "sphere" | "box" if fromto.is_some() => {
                Err(a.error(format!("`fromto` on a {kind} geom is not read")))
            }
            "sphere" => Ok((
                a.frame(&self.compiler)?,
                urdf_rs::Geometry::Sphere {
                    radius: need(1)?[0],
                },
            )),
            "box" => {
                let s = need(3)?;
                let size = urdf_rs::Vec3([2.0 * s[0], 2.0 * s[1], 2.0 * s[2]]);
                Ok((a.frame(&self.compiler)?, urdf_rs::Geometry::Box { size }))
            }
            "capsule" | "cylinder" => {
                let (frame, radius, half) = match fromto {
                    Some(f) => {
                        let (p0, p1) = (
                            Vector3::new(f[0], f[1], f[2]),
                            Vector3::new(f[3], f[4], f[5]),
                        );
                        let rot = zaxis(p1 - p0)
                            .ok_or_else(|| a.error("`fromto`: the two ends coincide"))?;
                        let frame = Isometry3::from_parts(Translation3::from((p0 + p1) / 2.0), rot);
                        (frame, need(1)?[0], (p1 - p0).norm() / 2.0)
                    }
                    None => {
                        let s = need(2)?;
                        (a.frame(&self.compiler)?, s[0], s[1])
                    }
                };
                let length = 2.0 * half;
                let geometry = if kind == "capsule" {
                    urdf_rs::Geometry::Capsule { radius, length }
                } else {
                    urdf_rs::Geometry::Cylinder { radius, length }
                };
                Ok((frame, geometry))
            }
            "mesh" => Err(a.error(
                "a colliding mesh geom cannot be represented (primitive shapes only); give it \
                 contype=\"0\" conaffinity=\"0\" to keep it visual",
            )),
            other => Err(a.error(format!(
                "geom type {:?} cannot be represented (box, sphere, capsule, cylinder)",
                hyq_physics::printable(other)
            ))),
        }
    }
}

/// A hinge joint as read.
struct Hinge {
    name: String,
    pos: Vector3<f64>,
    axis: Vector3<f64>,
    range: Option<[f64; 2]>,
    damping: f64,
    frictionloss: f64,
    armature: f64,
    force: Option<[f64; 2]>,
}
