/* The C shim between hyq-mujoco's Rust code and MuJoCo 4.0's C API.
 *
 * Rust never sees mjModel or mjData: this file's functions take and return plain numbers in
 * arrays, and the shim, compiled against MuJoCo's own headers, does every access to MuJoCo's
 * structures. The library itself is opened at run time (hyq_mj_open), so binaries that contain
 * the backend start without MuJoCo and fail with a one-line error only when a MuJoCo world is
 * built.
 *
 * Conventions: status 0 is success; on failure the message is written to `err` (at most
 * `err_len` bytes, always NUL-terminated). Arrays are in the order of the layout given to
 * hyq_mj_new (joints in the robot profile's order, bodies in the robot model's order).
 * Root state is MuJoCo's free-joint convention: pose = position, quaternion (w, x, y, z) of the
 * root body frame; velocity = linear velocity of that frame's origin (world axes), angular
 * velocity (body axes). */
#ifndef HYQ_MUJOCO_H
#define HYQ_MUJOCO_H

#include <stdint.h>

/* Status of hyq_mj_step. */
enum {
  HYQ_MJ_OK = 0,
  HYQ_MJ_DIVERGED = 1, /* the state became non-finite or huge; `err` names what */
  HYQ_MJ_FAILED = 2,   /* MuJoCo raised an error or a warning that makes the step wrong */
};

typedef struct hyq_mj hyq_mj;

/* Names of the elements the shim looks up in the compiled model. */
typedef struct {
  int num_joints;                          /* hinge joints, profile order */
  const char* const* joint_names;
  int num_bodies;                          /* bodies, model order; body 0 has the free joint */
  const char* const* body_names;
  int num_tracked;                         /* tracked bodies (contact flags) */
  int num_tracked_geoms;                   /* geoms reporting to a tracked body */
  const char* const* tracked_geom_names;
  const int* tracked_geom_owner;           /* tracked index of each of those geoms */
  int num_actuators;                       /* 0, or one per joint in profile order */
  const char* const* actuator_names;
} hyq_mj_layout;

/* mjVERSION_HEADER of the headers this shim was compiled against. */
int hyq_mj_header_version(void);

/* Opens libmujoco at `library_path`, resolves the functions the shim calls, checks that its
 * mj_version() is the headers' version, and routes MuJoCo's error and warning messages to the
 * shim (MuJoCo's default error handler exits the process). Call once per process; the Rust
 * side makes sure of it. */
int hyq_mj_open(const char* library_path, char* err, int err_len);

/* mj_version() of the opened library (0 before hyq_mj_open succeeded). */
int hyq_mj_library_version(void);

/* Compiles an MJCF document and makes its data; NULL with MuJoCo's message on failure. */
hyq_mj* hyq_mj_new(const char* xml, const hyq_mj_layout* layout, char* err, int err_len);
void hyq_mj_free(hyq_mj* w);

/* Resets the data as freshly made (no warm start, contact, force or warning survives), puts
 * the robot into this state and computes everything a step needs from it. */
int hyq_mj_set_state(hyq_mj* w, const double root_pose[7], const double root_vel[6],
                     const double* q, const double* qd, char* err, int err_len);

/* Joint torques for the next step only (mjData.qfrc_applied). */
void hyq_mj_set_joint_torques(hyq_mj* w, const double* tau);

/* Actuator controls (mjData.ctrl), one per actuator; they stay until changed. */
void hyq_mj_set_controls(hyq_mj* w, const double* ctrl);

/* One time step. `contacts[t]` becomes 1 when a geom of tracked body t was in MuJoCo's contact
 * list at the start of the step (the contacts the solver used) or at its end, else 0. */
int hyq_mj_step(hyq_mj* w, uint8_t* contacts, char* err, int err_len);

void hyq_mj_joint_positions(const hyq_mj* w, double* out);
void hyq_mj_joint_velocities(const hyq_mj* w, double* out);
void hyq_mj_root_state(const hyq_mj* w, double pose[7], double vel[6]);
/* World pose of body `body` (layout order): position, quaternion (w, x, y, z). */
void hyq_mj_body_pose(const hyq_mj* w, int body, double out[7]);
/* Total mass of the layout's bodies (kg). */
double hyq_mj_total_mass(const hyq_mj* w);
/* Contacts in MuJoCo's current list whose shapes touch or penetrate (distance <= 0). */
int hyq_mj_num_touching(const hyq_mj* w);
/* Simulated time since the last hyq_mj_set_state (s). */
double hyq_mj_time(const hyq_mj* w);

/* Per-episode dynamics: the sliding friction of every geom (the ground's, whatever its shape,
 * and the robot's: MuJoCo takes the larger of a contact's two), every geom's contact solref
 * for factors of its compiled stiffness and damping and, when `damping_ratio` > 0, that damping
 * ratio in place of the compiled one (a drawn restitution; see hyq_mujoco.c), the damping of each joint
 * (profile order), and each layout body's mass properties: `nominal[b]` nonzero restores the
 * compiled ones, else `bodies` holds 10 values per body: mass, centre of mass (3, body frame),
 * inertia tensor about it (ixx, iyy, izz, ixy, ixz, iyz). Derived constants follow
 * (mj_setConst); hyq_mj_set_state must follow before a step. */
int hyq_mj_set_dynamics(hyq_mj* w, double friction, double stiffness_scale,
                        double damping_scale, double damping_ratio, const uint8_t* nominal,
                        const double* bodies, const double* damping, char* err, int err_len);

/* Layout body `body`'s mass properties as the model holds them, in the 10 values above. */
void hyq_mj_body_inertial(const hyq_mj* w, int body, double out[10]);

/* Adds dv (world frame) to the root's linear velocity now, keeping positions, contacts and the
 * warm start. */
int hyq_mj_add_root_velocity(hyq_mj* w, const double dv[3], char* err, int err_len);

#endif
