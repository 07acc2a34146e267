//! One MuJoCo world behind the C shim (`csrc/hyq_mujoco.c`): the crate's only `unsafe` code.
//!
//! The shim owns `mjModel` and `mjData`; this side holds an opaque pointer and passes plain
//! numbers in slices whose lengths are checked here, so every foreign call reads and writes
//! only memory of the sizes the shim was told at build. The library is opened once per
//! process, at the first world; models are compiled one at a time (MuJoCo's parser keeps
//! process-wide state).
#![allow(unsafe_code)]

use std::ffi::{CString, c_char, c_int};
use std::path::PathBuf;
use std::ptr::NonNull;
use std::sync::{Mutex, OnceLock};

use crate::error::MujocoError;

/// The MuJoCo version the shim is compiled against.
pub const MUJOCO_VERSION: &str = "4.0.0";

/// The library's file name in a MuJoCo directory's `lib/`.
const LIBRARY: &str = "libmujoco.so.4.0.0";

/// How users get the library.
const SETUP: &str = "cargo xtask setup mujoco";

/// Bytes for one error message from the shim.
const ERR_LEN: usize = 1024;

/// The shim's world (opaque).
#[repr(C)]
struct RawWorld {
    _private: [u8; 0],
}

/// `hyq_mj_layout` (see `csrc/hyq_mujoco.h`).
#[repr(C)]
struct RawLayout {
    num_joints: c_int,
    joint_names: *const *const c_char,
    num_bodies: c_int,
    body_names: *const *const c_char,
    num_tracked: c_int,
    num_tracked_geoms: c_int,
    tracked_geom_names: *const *const c_char,
    tracked_geom_owner: *const c_int,
    num_actuators: c_int,
    actuator_names: *const *const c_char,
}

const STEP_OK: c_int = 0;
const STEP_DIVERGED: c_int = 1;

unsafe extern "C" {
    fn hyq_mj_header_version() -> c_int;
    fn hyq_mj_open(path: *const c_char, err: *mut c_char, err_len: c_int) -> c_int;
    fn hyq_mj_library_version() -> c_int;
    fn hyq_mj_new(
        xml: *const c_char,
        layout: *const RawLayout,
        err: *mut c_char,
        err_len: c_int,
    ) -> *mut RawWorld;
    fn hyq_mj_free(w: *mut RawWorld);
    fn hyq_mj_set_state(
        w: *mut RawWorld,
        root_pose: *const f64,
        root_vel: *const f64,
        q: *const f64,
        qd: *const f64,
        err: *mut c_char,
        err_len: c_int,
    ) -> c_int;
    fn hyq_mj_set_joint_torques(w: *mut RawWorld, tau: *const f64);
    fn hyq_mj_set_controls(w: *mut RawWorld, ctrl: *const f64);
    fn hyq_mj_step(w: *mut RawWorld, contacts: *mut u8, err: *mut c_char, err_len: c_int) -> c_int;
    fn hyq_mj_joint_positions(w: *const RawWorld, out: *mut f64);
    fn hyq_mj_joint_velocities(w: *const RawWorld, out: *mut f64);
    fn hyq_mj_root_state(w: *const RawWorld, pose: *mut f64, vel: *mut f64);
    fn hyq_mj_body_pose(w: *const RawWorld, body: c_int, out: *mut f64);
    fn hyq_mj_total_mass(w: *const RawWorld) -> f64;
    fn hyq_mj_num_touching(w: *const RawWorld) -> c_int;
    fn hyq_mj_set_dynamics(
        w: *mut RawWorld,
        friction: f64,
        stiffness_scale: f64,
        damping_scale: f64,
        damping_ratio: f64,
        nominal: *const u8,
        bodies: *const f64,
        damping: *const f64,
        err: *mut c_char,
        err_len: c_int,
    ) -> c_int;
    fn hyq_mj_body_inertial(w: *const RawWorld, body: c_int, out: *mut f64);
    fn hyq_mj_add_root_velocity(
        w: *mut RawWorld,
        dv: *const f64,
        err: *mut c_char,
        err_len: c_int,
    ) -> c_int;
    fn hyq_mj_time(w: *const RawWorld) -> f64;
}

/// A buffer the shim writes one message into.
struct ErrBuf([c_char; ERR_LEN]);

impl ErrBuf {
    fn new() -> Self {
        Self([0; ERR_LEN])
    }

    fn ptr(&mut self) -> *mut c_char {
        self.0.as_mut_ptr()
    }

    fn len() -> c_int {
        ERR_LEN as c_int
    }

    /// The message on one line (MuJoCo's messages span several: their lines are joined
    /// with "; ").
    fn text(&self) -> String {
        // The shim always NUL-terminates within the buffer (and it starts zeroed).
        let bytes: Vec<u8> = self
            .0
            .iter()
            .take_while(|&&c| c != 0)
            .map(|&c| c as u8)
            .collect();
        String::from_utf8_lossy(&bytes)
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty())
            .collect::<Vec<_>>()
            .join("; ")
    }
}

/// Where the library is loaded from: `$MUJOCO_DIR/lib/libmujoco.so.4.0.0` when `MUJOCO_DIR` is
/// set while the program runs, else the library the crate was built against.
pub fn library_path() -> PathBuf {
    match std::env::var_os("MUJOCO_DIR") {
        Some(dir) if !dir.is_empty() => PathBuf::from(dir).join("lib").join(LIBRARY),
        _ => PathBuf::from(env!("HYQ_MUJOCO_LIBRARY")),
    }
}

/// Opens the library once per process; later calls return the first outcome.
pub fn open_library() -> Result<(), MujocoError> {
    static OPENED: OnceLock<Result<(), String>> = OnceLock::new();
    OPENED
        .get_or_init(|| {
            let path = library_path();
            let c_path = CString::new(path.as_os_str().as_encoded_bytes())
                .map_err(|_| format!("the library path {} holds a NUL byte", path.display()))?;
            let mut err = ErrBuf::new();
            // SAFETY: both pointers are valid for the call; the shim writes at most
            // `ErrBuf::len()` bytes into `err`. `OnceLock` runs this once per process.
            let status = unsafe { hyq_mj_open(c_path.as_ptr(), err.ptr(), ErrBuf::len()) };
            if status == 0 {
                Ok(())
            } else {
                Err(format!(
                    "cannot load MuJoCo {MUJOCO_VERSION}: {}; run `{SETUP}` (or set MUJOCO_DIR \
                     to a MuJoCo {MUJOCO_VERSION} directory)",
                    err.text()
                ))
            }
        })
        .clone()
        .map_err(MujocoError::Library)
}

/// `mjVERSION_HEADER` of the headers the shim was compiled against.
pub fn header_version() -> i32 {
    // SAFETY: a pure function of the shim.
    unsafe { hyq_mj_header_version() }
}

/// `mj_version()` of the loaded library, once [`open_library`] succeeded (else 0).
pub fn library_version() -> i32 {
    // SAFETY: reads a value the shim set while opening the library.
    unsafe { hyq_mj_library_version() }
}

/// The names a world looks up in its compiled model (see `hyq_mj_layout`).
#[derive(Debug, Clone, Default)]
pub struct Layout {
    /// Hinge joints, profile order.
    pub joints: Vec<String>,
    /// Bodies, model order; the first has the free joint.
    pub bodies: Vec<String>,
    /// Number of tracked bodies.
    pub num_tracked: usize,
    /// Geoms reporting contacts, each with the tracked body it reports to.
    pub tracked_geoms: Vec<(String, usize)>,
    /// Actuators, profile order (empty when the model has none).
    pub actuators: Vec<String>,
}

/// Why a step failed.
#[derive(Debug, Clone, PartialEq)]
pub enum StepError {
    /// The state became non-finite or huge; names what.
    Diverged(String),
    /// MuJoCo raised an error, or a warning that makes the step wrong (e.g. a full contact
    /// buffer).
    Failed(String),
}

/// One compiled model with its data.
pub struct World {
    raw: NonNull<RawWorld>,
    num_joints: usize,
    num_bodies: usize,
    num_tracked: usize,
    num_actuators: usize,
}

// SAFETY: a world's model and data are used by one thread at a time (`&mut self` for every
// call that writes, and `World` is not `Sync`); MuJoCo keeps no per-thread state for them, and
// the shim's error handling is per thread.
unsafe impl Send for World {}

impl std::fmt::Debug for World {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("World")
            .field("num_joints", &self.num_joints)
            .field("num_bodies", &self.num_bodies)
            .field("num_tracked", &self.num_tracked)
            .finish_non_exhaustive()
    }
}

fn c_strings(names: &[String], what: &str) -> Result<Vec<CString>, MujocoError> {
    names
        .iter()
        .map(|n| {
            CString::new(n.as_str())
                .map_err(|_| MujocoError::Model(format!("{what} name {n:?} holds a NUL byte")))
        })
        .collect()
}

fn c_int_of(n: usize, what: &str) -> Result<c_int, MujocoError> {
    c_int::try_from(n).map_err(|_| MujocoError::Model(format!("too many {what}: {n}")))
}

impl World {
    /// Compiles `xml` and looks up the layout's elements in it. A model MuJoCo refuses is an
    /// error with MuJoCo's own message.
    pub fn new(xml: &str, layout: &Layout) -> Result<Self, MujocoError> {
        open_library()?;
        let xml = CString::new(xml)
            .map_err(|_| MujocoError::Model("the MJCF text holds a NUL byte".into()))?;
        let joints = c_strings(&layout.joints, "joint")?;
        let bodies = c_strings(&layout.bodies, "body")?;
        let geoms = c_strings(
            &layout
                .tracked_geoms
                .iter()
                .map(|(n, _)| n.clone())
                .collect::<Vec<_>>(),
            "geom",
        )?;
        let owners = layout
            .tracked_geoms
            .iter()
            .map(|&(_, t)| c_int_of(t, "tracked bodies"))
            .collect::<Result<Vec<_>, _>>()?;
        let actuators = c_strings(&layout.actuators, "actuator")?;
        let ptrs = |v: &[CString]| v.iter().map(|s| s.as_ptr()).collect::<Vec<_>>();
        let (joint_ptrs, body_ptrs, geom_ptrs, actuator_ptrs) =
            (ptrs(&joints), ptrs(&bodies), ptrs(&geoms), ptrs(&actuators));
        let raw_layout = RawLayout {
            num_joints: c_int_of(joints.len(), "joints")?,
            joint_names: joint_ptrs.as_ptr(),
            num_bodies: c_int_of(bodies.len(), "bodies")?,
            body_names: body_ptrs.as_ptr(),
            num_tracked: c_int_of(layout.num_tracked, "tracked bodies")?,
            num_tracked_geoms: c_int_of(geoms.len(), "geoms")?,
            tracked_geom_names: geom_ptrs.as_ptr(),
            tracked_geom_owner: owners.as_ptr(),
            num_actuators: c_int_of(actuators.len(), "actuators")?,
            actuator_names: actuator_ptrs.as_ptr(),
        };
        // MuJoCo's XML parser keeps process-wide state: one compilation at a time.
        static COMPILING: Mutex<()> = Mutex::new(());
        let guard = COMPILING
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        let mut err = ErrBuf::new();
        // SAFETY: every pointer in `raw_layout` points into vectors alive for the call, with the
        // counts given beside them; `xml` is NUL-terminated; `err` holds `ErrBuf::len()` bytes.
        let raw = unsafe { hyq_mj_new(xml.as_ptr(), &raw_layout, err.ptr(), ErrBuf::len()) };
        drop(guard);
        let raw = NonNull::new(raw).ok_or_else(|| MujocoError::Model(err.text()))?;
        Ok(Self {
            raw,
            num_joints: joints.len(),
            num_bodies: bodies.len(),
            num_tracked: layout.num_tracked,
            num_actuators: actuators.len(),
        })
    }

    /// Resets the data and sets the state (MuJoCo's free-joint convention for the root: pose
    /// x, y, z, qw, qx, qy, qz; velocity of the frame origin in world axes, angular velocity in
    /// body axes).
    pub fn set_state(
        &mut self,
        root_pose: &[f64; 7],
        root_vel: &[f64; 6],
        q: &[f64],
        qd: &[f64],
    ) -> Result<(), MujocoError> {
        assert_eq!(q.len(), self.num_joints, "set_state: one angle per joint");
        assert_eq!(qd.len(), self.num_joints, "set_state: one speed per joint");
        let mut err = ErrBuf::new();
        // SAFETY: the arrays hold 7, 6 and `num_joints` values, as the shim reads.
        let status = unsafe {
            hyq_mj_set_state(
                self.raw.as_ptr(),
                root_pose.as_ptr(),
                root_vel.as_ptr(),
                q.as_ptr(),
                qd.as_ptr(),
                err.ptr(),
                ErrBuf::len(),
            )
        };
        if status == 0 {
            Ok(())
        } else {
            Err(MujocoError::Engine(err.text()))
        }
    }

    /// Joint torques for the next step only.
    pub fn set_joint_torques(&mut self, tau: &[f64]) {
        assert_eq!(tau.len(), self.num_joints, "one torque per joint");
        // SAFETY: `tau` holds `num_joints` values.
        unsafe { hyq_mj_set_joint_torques(self.raw.as_ptr(), tau.as_ptr()) }
    }

    /// Actuator controls, one per actuator of the layout.
    pub fn set_controls(&mut self, ctrl: &[f64]) {
        assert_eq!(ctrl.len(), self.num_actuators, "one control per actuator");
        // SAFETY: `ctrl` holds `num_actuators` values.
        unsafe { hyq_mj_set_controls(self.raw.as_ptr(), ctrl.as_ptr()) }
    }

    /// One time step; `contacts[t]` becomes 1 when tracked body `t` touched the ground.
    /// Allocates nothing unless it fails.
    pub fn step(&mut self, contacts: &mut [u8]) -> Result<(), StepError> {
        assert_eq!(
            contacts.len(),
            self.num_tracked,
            "one flag per tracked body"
        );
        let mut err = ErrBuf::new();
        // SAFETY: `contacts` holds `num_tracked` bytes; `err` holds `ErrBuf::len()` bytes.
        let status = unsafe {
            hyq_mj_step(
                self.raw.as_ptr(),
                contacts.as_mut_ptr(),
                err.ptr(),
                ErrBuf::len(),
            )
        };
        match status {
            STEP_OK => Ok(()),
            STEP_DIVERGED => Err(StepError::Diverged(err.text())),
            _ => Err(StepError::Failed(err.text())),
        }
    }

    /// Joint angles, profile order.
    pub fn joint_positions(&self, out: &mut [f64]) {
        assert_eq!(
            out.len(),
            self.num_joints,
            "joint_positions: one value per joint"
        );
        // SAFETY: `out` holds `num_joints` values.
        unsafe { hyq_mj_joint_positions(self.raw.as_ptr(), out.as_mut_ptr()) }
    }

    /// Joint speeds, profile order.
    pub fn joint_velocities(&self, out: &mut [f64]) {
        assert_eq!(
            out.len(),
            self.num_joints,
            "joint_velocities: one value per joint"
        );
        // SAFETY: `out` holds `num_joints` values.
        unsafe { hyq_mj_joint_velocities(self.raw.as_ptr(), out.as_mut_ptr()) }
    }

    /// The root's pose and velocity (MuJoCo's free-joint convention, see [`World::set_state`]).
    pub fn root_state(&self) -> ([f64; 7], [f64; 6]) {
        let (mut pose, mut vel) = ([0.0; 7], [0.0; 6]);
        // SAFETY: the arrays hold 7 and 6 values.
        unsafe { hyq_mj_root_state(self.raw.as_ptr(), pose.as_mut_ptr(), vel.as_mut_ptr()) };
        (pose, vel)
    }

    /// World pose of layout body `body`: x, y, z, qw, qx, qy, qz.
    pub fn body_pose(&self, body: usize) -> [f64; 7] {
        assert!(body < self.num_bodies, "body {body} of {}", self.num_bodies);
        let mut out = [0.0; 7];
        // SAFETY: `body` is in range (checked, so it fits a c_int); `out` holds 7 values.
        unsafe { hyq_mj_body_pose(self.raw.as_ptr(), body as c_int, out.as_mut_ptr()) };
        out
    }

    /// Total mass of the layout's bodies (kg).
    pub fn total_mass(&self) -> f64 {
        // SAFETY: reads the compiled model.
        unsafe { hyq_mj_total_mass(self.raw.as_ptr()) }
    }

    /// Sets the friction of every geom, every geom's contact solref for `contact`'s factors
    /// (stiffness, damping) of its compiled contact stiffness and damping and its damping ratio
    /// (`contact[2]` > 0: the contact's damping ratio at its new stiffness, before the damping
    /// factor; 0 keeps the compiled damping; factors of 1 and 0 restore the compiled solref bit
    /// for bit), each joint's damping and each layout body's mass
    /// properties: `nominal[b]` true restores body `b`'s compiled ones, else `bodies[b]` holds
    /// its mass, centre of mass (body frame) and tensor about it (ixx, iyy, izz, ixy, ixz,
    /// iyz). [`World::set_state`] must follow before a step.
    pub fn set_dynamics(
        &mut self,
        friction: f64,
        contact: [f64; 3],
        nominal: &[bool],
        bodies: &[[f64; 10]],
        damping: &[f64],
    ) -> Result<(), MujocoError> {
        assert_eq!(nominal.len(), self.num_bodies, "one flag per body");
        assert_eq!(bodies.len(), self.num_bodies, "one inertial per body");
        assert_eq!(damping.len(), self.num_joints, "one damping per joint");
        let flags: Vec<u8> = nominal.iter().map(|&n| u8::from(n)).collect();
        let flat: Vec<f64> = bodies.iter().flatten().copied().collect();
        let mut err = ErrBuf::new();
        // SAFETY: `flags` holds `num_bodies` bytes, `flat` 10 values per body, `damping` one
        // per joint, as the shim reads; `err` holds `ErrBuf::len()` bytes.
        let status = unsafe {
            hyq_mj_set_dynamics(
                self.raw.as_ptr(),
                friction,
                contact[0],
                contact[1],
                contact[2],
                flags.as_ptr(),
                flat.as_ptr(),
                damping.as_ptr(),
                err.ptr(),
                ErrBuf::len(),
            )
        };
        if status == 0 {
            Ok(())
        } else {
            Err(MujocoError::Engine(err.text()))
        }
    }

    /// Layout body `body`'s mass, centre of mass and tensor (as [`World::set_dynamics`] takes
    /// them) as the model holds them.
    pub fn body_inertial(&self, body: usize) -> [f64; 10] {
        assert!(body < self.num_bodies, "body {body} of {}", self.num_bodies);
        let mut out = [0.0; 10];
        // SAFETY: `body` is in range (checked, so it fits a c_int); `out` holds 10 values.
        unsafe { hyq_mj_body_inertial(self.raw.as_ptr(), body as c_int, out.as_mut_ptr()) };
        out
    }

    /// Adds `dv` (world frame) to the root's linear velocity now.
    pub fn add_root_velocity(&mut self, dv: &[f64; 3]) -> Result<(), MujocoError> {
        let mut err = ErrBuf::new();
        // SAFETY: `dv` holds 3 values; `err` holds `ErrBuf::len()` bytes.
        let status = unsafe {
            hyq_mj_add_root_velocity(self.raw.as_ptr(), dv.as_ptr(), err.ptr(), ErrBuf::len())
        };
        if status == 0 {
            Ok(())
        } else {
            Err(MujocoError::Engine(err.text()))
        }
    }

    /// Contacts in MuJoCo's current list that touch or penetrate.
    pub fn num_touching(&self) -> usize {
        // SAFETY: reads the data.
        let n = unsafe { hyq_mj_num_touching(self.raw.as_ptr()) };
        usize::try_from(n).unwrap_or(0)
    }

    /// Simulated time since the last state change (s).
    pub fn time(&self) -> f64 {
        // SAFETY: reads the data.
        unsafe { hyq_mj_time(self.raw.as_ptr()) }
    }
}

impl Drop for World {
    fn drop(&mut self) {
        // SAFETY: `raw` came from `hyq_mj_new` and is freed exactly once, here.
        unsafe { hyq_mj_free(self.raw.as_ptr()) }
    }
}

#[cfg(test)]
mod tests {
    //! The shim and the library agree on the version, and the library path follows
    //! `MUJOCO_DIR`.
    #![allow(clippy::unwrap_used)]

    use super::*;

    #[test]
    fn the_shim_and_the_loaded_library_are_the_same_version() {
        open_library().unwrap();
        assert_eq!(header_version(), 4_000_000);
        assert_eq!(library_version(), header_version());
    }

    #[test]
    fn a_model_mujoco_refuses_reports_mujocos_own_message() {
        for (xml, says) in [
            ("<mujoco><worldbody><bogus/></worldbody></mujoco>", "bogus"),
            (
                "<mujoco><worldbody><body><freejoint/>\
                 <inertial pos=\"0 0 0\" mass=\"-1\" diaginertia=\"1 1 1\"/>\
                 </body></worldbody></mujoco>",
                "mass",
            ),
            ("<mujoco><worldbody></mujoco>", "XML"),
        ] {
            let err = World::new(xml, &Layout::default()).unwrap_err().to_string();
            println!("{err}");
            assert!(err.starts_with("MuJoCo refused the model: "), "{err}");
            assert!(err.contains(says), "{err}");
            assert!(!err.contains('\n'), "one line: {err:?}");
        }
    }
}
