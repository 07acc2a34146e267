/* The C shim of hyq-mujoco: see hyq_mujoco.h for the contract. */
#define _GNU_SOURCE
#include "hyq_mujoco.h"

#include <dlfcn.h>
#include <math.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <mujoco/mujoco.h>

#if mjVERSION_HEADER != 4000000
#error "hyq-mujoco is written against MuJoCo 4.0.0's headers"
#endif

/* ---------------------------------------------------------------------------------------------
 * The library, opened at run time. Each entry is a pointer with the exact type of the MuJoCo
 * function of the same name, taken from the headers. */

#define HYQ_MJ_FUNCTIONS(X) \
  X(mj_version)             \
  X(mj_versionString)       \
  X(mj_defaultVFS)          \
  X(mj_addBufferVFS)        \
  X(mj_deleteVFS)           \
  X(mj_loadXML)             \
  X(mj_makeData)            \
  X(mj_deleteData)          \
  X(mj_deleteModel)         \
  X(mj_resetData)           \
  X(mj_step1)               \
  X(mj_step2)               \
  X(mj_setConst)            \
  X(mju_eig3)               \
  X(mj_name2id)

static struct {
#define HYQ_MJ_FIELD(name) __typeof__(&name) name;
  HYQ_MJ_FUNCTIONS(HYQ_MJ_FIELD)
#undef HYQ_MJ_FIELD
  int version;
} api;

static void copy_message(char* dst, int len, const char* src) {
  if (dst && len > 0) {
    snprintf(dst, (size_t)len, "%s", src ? src : "");
  }
}

/* ---------------------------------------------------------------------------------------------
 * MuJoCo's errors do not return to their caller (by default they print, write MUJOCO_LOG.TXT
 * and exit the process). Every call into MuJoCo below runs under a jump buffer; the error
 * handler copies the message and jumps back to it, and the call fails with the message. The
 * buffer is per thread, so worlds on different threads do not interfere. Warnings are recorded
 * (per thread) instead of printed; steps read MuJoCo's warning counters to act on them. */

static _Thread_local jmp_buf* error_jump;
static _Thread_local char error_text[1024];
static _Thread_local char warning_text[1024];
static void (*previous_error_handler)(const char*);

static void on_error(const char* msg) {
  copy_message(error_text, (int)sizeof error_text, msg);
  if (error_jump) {
    longjmp(*error_jump, 1);
  }
  /* An error raised outside this shim's calls (another user of the same library in this
   * process): hand it to the handler that was there before, or stop, as MuJoCo would. */
  if (previous_error_handler) {
    previous_error_handler(msg);
  }
  fprintf(stderr, "MuJoCo error outside hyq-mujoco: %s\n", msg);
  abort();
}

static void on_warning(const char* msg) {
  copy_message(warning_text, (int)sizeof warning_text, msg);
}

/* Runs `body` with MuJoCo errors turned into a jump to `on_failure` (a statement). */
#define GUARDED(body, on_failure)       \
  do {                                  \
    jmp_buf env_;                       \
    jmp_buf* volatile saved_ = error_jump; \
    error_jump = &env_;                 \
    if (setjmp(env_) == 0) {            \
      body;                             \
      error_jump = saved_;              \
    } else {                            \
      error_jump = saved_;              \
      on_failure;                       \
    }                                   \
  } while (0)

int hyq_mj_header_version(void) { return mjVERSION_HEADER; }

int hyq_mj_library_version(void) { return api.version; }

int hyq_mj_open(const char* library_path, char* err, int err_len) {
  void* lib = dlopen(library_path, RTLD_NOW | RTLD_LOCAL);
  if (!lib) {
    copy_message(err, err_len, dlerror());
    return -1;
  }
#define HYQ_MJ_RESOLVE(name)                                                    \
  api.name = (__typeof__(&name))dlsym(lib, #name);                              \
  if (!api.name) {                                                              \
    snprintf(err, (size_t)err_len, "%s has no function %s", library_path, #name); \
    return -1;                                                                  \
  }
  /* The version first: another version may lack some of the functions below. */
  HYQ_MJ_RESOLVE(mj_version)
  HYQ_MJ_RESOLVE(mj_versionString)
  int version = api.mj_version();
  if (version != mjVERSION_HEADER) {
    snprintf(err, (size_t)err_len,
             "%s is MuJoCo %d.%d.%d (%s), hyq-mujoco is built against MuJoCo %d.%d.%d",
             library_path, version / 1000000, version / 1000 % 1000, version % 1000,
             api.mj_versionString(), mjVERSION_HEADER / 1000000,
             mjVERSION_HEADER / 1000 % 1000, mjVERSION_HEADER % 1000);
    return -1;
  }
  HYQ_MJ_FUNCTIONS(HYQ_MJ_RESOLVE)
#undef HYQ_MJ_RESOLVE
  void (**user_error)(const char*) = (void (**)(const char*))dlsym(lib, "mju_user_error");
  void (**user_warning)(const char*) = (void (**)(const char*))dlsym(lib, "mju_user_warning");
  if (!user_error || !user_warning) {
    snprintf(err, (size_t)err_len, "%s has no mju_user_error or mju_user_warning",
             library_path);
    return -1;
  }
  previous_error_handler = *user_error;
  *user_error = on_error;
  *user_warning = on_warning;
  api.version = version;
  /* The library stays open for the life of the process. */
  return 0;
}

/* ---------------------------------------------------------------------------------------------
 * One world. */

struct hyq_mj {
  mjModel* m;
  mjData* d;
  int num_joints;
  int num_bodies;
  int num_tracked;
  int num_actuators;
  int root_qpos;  /* address of the free joint in qpos */
  int root_dof;   /* ... and in qvel */
  int* qpos_of;   /* qpos address of each joint (profile order) */
  int* dof_of;    /* qvel address of each joint */
  int* body_of;   /* body id of each layout body */
  int* actuator_of;
  int* tracked_of_geom; /* tracked index of each geom id, or -1 */
  /* The compiled mass properties of each layout body and the frame flags that depend on them,
   * restored when a body's dynamics are the model's own again; `modified` marks the bodies
   * whose values differ from the compiled ones. */
  double* mass0;
  double* ipos0;
  double* iquat0;
  double* inertia0;
  mjtByte* body_sameframe0;
  mjtByte* geom_sameframe0;
  uint8_t* modified;
  /* The compiled contact solref of every geom (2 per geom), which the drawn contact factors
   * scale. */
  double* geom_solref0;
};

static void free_world(hyq_mj* w) {
  if (!w) {
    return;
  }
  if (w->d) {
    api.mj_deleteData(w->d);
  }
  if (w->m) {
    api.mj_deleteModel(w->m);
  }
  free(w->qpos_of);
  free(w->dof_of);
  free(w->body_of);
  free(w->actuator_of);
  free(w->tracked_of_geom);
  free(w->mass0);
  free(w->ipos0);
  free(w->iquat0);
  free(w->inertia0);
  free(w->body_sameframe0);
  free(w->geom_sameframe0);
  free(w->modified);
  free(w->geom_solref0);
  free(w);
}

/* Looks `name` up; on failure writes which element is missing and returns -1. */
static int lookup(const mjModel* m, int type, const char* kind, const char* name, char* err,
                  int err_len) {
  int id = api.mj_name2id(m, type, name);
  if (id < 0) {
    snprintf(err, (size_t)err_len, "the compiled model has no %s named \"%s\"", kind, name);
  }
  return id;
}

/* Copies the compiled mass properties of the layout's bodies and the frame flags (see
 * struct hyq_mj). */
static int save_compiled_masses(hyq_mj* w, char* err, int err_len) {
  const mjModel* m = w->m;
  size_t nb = (size_t)w->num_bodies;
  w->mass0 = calloc(nb + 1, sizeof(double));
  w->ipos0 = calloc(3 * nb + 1, sizeof(double));
  w->iquat0 = calloc(4 * nb + 1, sizeof(double));
  w->inertia0 = calloc(3 * nb + 1, sizeof(double));
  w->body_sameframe0 = calloc(nb + 1, 1);
  w->geom_sameframe0 = calloc((size_t)m->ngeom + 1, 1);
  w->modified = calloc(nb + 1, 1);
  w->geom_solref0 = calloc(mjNREF * (size_t)m->ngeom + 1, sizeof(double));
  if (!w->mass0 || !w->ipos0 || !w->iquat0 || !w->inertia0 || !w->body_sameframe0 ||
      !w->geom_sameframe0 || !w->modified || !w->geom_solref0) {
    copy_message(err, err_len, "out of memory");
    return -1;
  }
  for (int b = 0; b < w->num_bodies; b++) {
    int id = w->body_of[b];
    w->mass0[b] = m->body_mass[id];
    memcpy(w->ipos0 + 3 * b, m->body_ipos + 3 * id, 3 * sizeof(double));
    memcpy(w->iquat0 + 4 * b, m->body_iquat + 4 * id, 4 * sizeof(double));
    memcpy(w->inertia0 + 3 * b, m->body_inertia + 3 * id, 3 * sizeof(double));
    w->body_sameframe0[b] = m->body_sameframe[id];
  }
  memcpy(w->geom_sameframe0, m->geom_sameframe, (size_t)m->ngeom);
  memcpy(w->geom_solref0, m->geom_solref, mjNREF * (size_t)m->ngeom * sizeof(double));
  return 0;
}

static int resolve_layout(hyq_mj* w, const hyq_mj_layout* layout, char* err, int err_len) {
  const mjModel* m = w->m;
  w->num_joints = layout->num_joints;
  w->num_bodies = layout->num_bodies;
  w->num_tracked = layout->num_tracked;
  w->num_actuators = layout->num_actuators;
  w->qpos_of = calloc((size_t)layout->num_joints + 1, sizeof(int));
  w->dof_of = calloc((size_t)layout->num_joints + 1, sizeof(int));
  w->body_of = calloc((size_t)layout->num_bodies + 1, sizeof(int));
  w->actuator_of = calloc((size_t)layout->num_actuators + 1, sizeof(int));
  w->tracked_of_geom = calloc((size_t)m->ngeom + 1, sizeof(int));
  if (!w->qpos_of || !w->dof_of || !w->body_of || !w->actuator_of || !w->tracked_of_geom) {
    copy_message(err, err_len, "out of memory");
    return -1;
  }
  if (layout->num_bodies < 1) {
    copy_message(err, err_len, "the layout names no body");
    return -1;
  }
  for (int j = 0; j < layout->num_joints; j++) {
    int id = lookup(m, mjOBJ_JOINT, "joint", layout->joint_names[j], err, err_len);
    if (id < 0) {
      return -1;
    }
    if (m->jnt_type[id] != mjJNT_HINGE) {
      snprintf(err, (size_t)err_len, "joint \"%s\" is not a hinge", layout->joint_names[j]);
      return -1;
    }
    w->qpos_of[j] = m->jnt_qposadr[id];
    w->dof_of[j] = m->jnt_dofadr[id];
  }
  for (int b = 0; b < layout->num_bodies; b++) {
    int id = lookup(m, mjOBJ_BODY, "body", layout->body_names[b], err, err_len);
    if (id < 0) {
      return -1;
    }
    w->body_of[b] = id;
  }
  int root = w->body_of[0];
  if (m->body_jntnum[root] != 1 || m->jnt_type[m->body_jntadr[root]] != mjJNT_FREE) {
    snprintf(err, (size_t)err_len, "body \"%s\" has no free joint", layout->body_names[0]);
    return -1;
  }
  w->root_qpos = m->jnt_qposadr[m->body_jntadr[root]];
  w->root_dof = m->jnt_dofadr[m->body_jntadr[root]];
  if (m->nq != 7 + layout->num_joints || m->nv != 6 + layout->num_joints) {
    snprintf(err, (size_t)err_len,
             "the compiled model has %d position and %d velocity coordinates, the layout %d "
             "joints besides the free one",
             (int)m->nq, (int)m->nv, layout->num_joints);
    return -1;
  }
  for (int a = 0; a < layout->num_actuators; a++) {
    int id = lookup(m, mjOBJ_ACTUATOR, "actuator", layout->actuator_names[a], err, err_len);
    if (id < 0) {
      return -1;
    }
    w->actuator_of[a] = id;
  }
  for (int g = 0; g < (int)m->ngeom; g++) {
    w->tracked_of_geom[g] = -1;
  }
  if (save_compiled_masses(w, err, err_len) != 0) {
    return -1;
  }
  for (int k = 0; k < layout->num_tracked_geoms; k++) {
    int id = lookup(m, mjOBJ_GEOM, "geom", layout->tracked_geom_names[k], err, err_len);
    if (id < 0) {
      return -1;
    }
    int owner = layout->tracked_geom_owner[k];
    if (owner < 0 || owner >= layout->num_tracked) {
      snprintf(err, (size_t)err_len, "geom \"%s\" reports to tracked body %d of %d",
               layout->tracked_geom_names[k], owner, layout->num_tracked);
      return -1;
    }
    w->tracked_of_geom[id] = owner;
  }
  return 0;
}

/* Compiling touches MuJoCo's process-wide parser state ("the last loaded XML"), so models are
 * compiled one at a time; the Rust side holds a lock around this call. */
hyq_mj* hyq_mj_new(const char* xml, const hyq_mj_layout* layout, char* err, int err_len) {
  if (!api.version) {
    copy_message(err, err_len, "the MuJoCo library is not open");
    return NULL;
  }
  hyq_mj* volatile w = calloc(1, sizeof(hyq_mj));
  if (!w) {
    copy_message(err, err_len, "out of memory");
    return NULL;
  }
  volatile int ok = 0;
  GUARDED(
      {
        mjVFS vfs;
        api.mj_defaultVFS(&vfs);
        const char* file = "hyq.xml";
        if (api.mj_addBufferVFS(&vfs, file, xml, (int)strlen(xml)) != 0) {
          copy_message(err, err_len, "cannot hand the MJCF text to MuJoCo's virtual files");
        } else {
          char message[1024] = "";
          w->m = api.mj_loadXML(file, &vfs, message, (int)sizeof message);
          if (!w->m) {
            snprintf(err, (size_t)err_len, "MuJoCo refused the model: %s", message);
          } else {
            w->d = api.mj_makeData(w->m);
            if (!w->d) {
              copy_message(err, err_len, "MuJoCo could not allocate the model's data");
            } else if (resolve_layout(w, layout, err, err_len) == 0) {
              ok = 1;
            }
          }
        }
        api.mj_deleteVFS(&vfs);
      },
      { snprintf(err, (size_t)err_len, "MuJoCo error while building the world: %s", error_text); });
  if (!ok) {
    GUARDED(free_world(w), {});
    return NULL;
  }
  return w;
}

void hyq_mj_free(hyq_mj* w) { GUARDED(free_world(w), {}); }

/* The layout's joints and the free joint, from plain arrays. */
static void write_state(hyq_mj* w, const double root_pose[7], const double root_vel[6],
                        const double* q, const double* qd) {
  mjData* d = w->d;
  memcpy(d->qpos + w->root_qpos, root_pose, 7 * sizeof(double));
  memcpy(d->qvel + w->root_dof, root_vel, 6 * sizeof(double));
  for (int j = 0; j < w->num_joints; j++) {
    d->qpos[w->qpos_of[j]] = q[j];
    d->qvel[w->dof_of[j]] = qd[j];
  }
}

int hyq_mj_set_state(hyq_mj* w, const double root_pose[7], const double root_vel[6],
                     const double* q, const double* qd, char* err, int err_len) {
  volatile int status = 0;
  GUARDED(
      {
        /* mj_resetData clears everything a step could carry over: time, warm start
         * (qacc_warmstart), applied forces, controls, contacts, warnings. mj_step1 then
         * computes what the next mj_step2 needs (kinematics, contacts, velocities): the same
         * calls a world makes before its first step, so a reset world and a fresh one take
         * bitwise the same steps. */
        api.mj_resetData(w->m, w->d);
        write_state(w, root_pose, root_vel, q, qd);
        api.mj_step1(w->m, w->d);
      },
      {
        snprintf(err, (size_t)err_len, "MuJoCo error while setting the state: %s", error_text);
        status = -1;
      });
  return status;
}

void hyq_mj_set_joint_torques(hyq_mj* w, const double* tau) {
  for (int j = 0; j < w->num_joints; j++) {
    w->d->qfrc_applied[w->dof_of[j]] = tau[j];
  }
}

void hyq_mj_set_controls(hyq_mj* w, const double* ctrl) {
  for (int a = 0; a < w->num_actuators; a++) {
    w->d->ctrl[w->actuator_of[a]] = ctrl[a];
  }
}

/* Sets the flag of every tracked body with a geom in MuJoCo's current contact list. */
static void mark_contacts(const hyq_mj* w, uint8_t* contacts) {
  const mjData* d = w->d;
  for (int c = 0; c < d->ncon; c++) {
    for (int side = 0; side < 2; side++) {
      int g = d->contact[c].geom[side];
      if (g >= 0) {
        int t = w->tracked_of_geom[g];
        if (t >= 0) {
          contacts[t] = 1;
        }
      }
    }
  }
}

/* Names the first non-finite or huge (beyond mjMAXVAL, MuJoCo's own bound) coordinate. */
static int check_state(const hyq_mj* w, char* err, int err_len) {
  const mjModel* m = w->m;
  const mjData* d = w->d;
  for (int i = 0; i < (int)m->nq; i++) {
    if (!isfinite(d->qpos[i]) || fabs(d->qpos[i]) > mjMAXVAL) {
      snprintf(err, (size_t)err_len, "position coordinate %d (%g)", i, d->qpos[i]);
      return -1;
    }
  }
  for (int i = 0; i < (int)m->nv; i++) {
    if (!isfinite(d->qvel[i]) || fabs(d->qvel[i]) > mjMAXVAL) {
      snprintf(err, (size_t)err_len, "velocity coordinate %d (%g)", i, d->qvel[i]);
      return -1;
    }
  }
  return 0;
}

/* The warnings that mean the step cannot be trusted, with what they mean here. */
static int check_warnings(const mjData* d, char* err, int err_len) {
  static const struct {
    int id;
    int diverged;
    const char* what;
  } watched[] = {
      {mjWARN_BADQACC, 1, "MuJoCo found a non-finite or huge joint acceleration"},
      {mjWARN_BADQVEL, 1, "MuJoCo found a non-finite or huge velocity"},
      {mjWARN_BADQPOS, 1, "MuJoCo found a non-finite or huge position"},
      {mjWARN_CONTACTFULL, 0, "MuJoCo's contact buffer is full: contacts were dropped"},
      {mjWARN_CNSTRFULL, 0, "MuJoCo's constraint buffer is full: constraints were dropped"},
      {mjWARN_BADCTRL, 0, "MuJoCo found a non-finite or huge control"},
  };
  for (size_t k = 0; k < sizeof watched / sizeof watched[0]; k++) {
    if (d->warning[watched[k].id].number > 0) {
      snprintf(err, (size_t)err_len, "%s (%s)", watched[k].what, warning_text);
      return watched[k].diverged ? HYQ_MJ_DIVERGED : HYQ_MJ_FAILED;
    }
  }
  return HYQ_MJ_OK;
}

int hyq_mj_step(hyq_mj* w, uint8_t* contacts, char* err, int err_len) {
  mjData* d = w->d;
  for (int i = 0; i < mjNWARNING; i++) {
    d->warning[i].number = 0;
  }
  warning_text[0] = '\0';
  memset(contacts, 0, (size_t)w->num_tracked);
  /* The contacts the solver is about to use: detected at the start of this step. */
  mark_contacts(w, contacts);
  volatile int status = HYQ_MJ_OK;
  /* mj_step2 then mj_step1: the second half of one MuJoCo step (forces, constraints,
   * integration) from what the previous mj_step1 (or hyq_mj_set_state) computed, then the
   * first half of the next one (kinematics and collision at the new positions). Together they
   * are MuJoCo's mj_step, shifted so that body poses and contacts are those of the state the
   * step ends in. */
  GUARDED(
      {
        api.mj_step2(w->m, d);
        int s = check_warnings(d, err, err_len);
        if (s == HYQ_MJ_OK && check_state(w, err, err_len) != 0) {
          s = HYQ_MJ_DIVERGED;
        }
        if (s == HYQ_MJ_OK) {
          api.mj_step1(w->m, d);
          s = check_warnings(d, err, err_len);
        }
        status = s;
      },
      {
        snprintf(err, (size_t)err_len, "MuJoCo error during a step: %s", error_text);
        status = HYQ_MJ_FAILED;
      });
  /* Torques act for one step only. */
  for (int j = 0; j < w->num_joints; j++) {
    d->qfrc_applied[w->dof_of[j]] = 0;
  }
  if (status == HYQ_MJ_OK) {
    mark_contacts(w, contacts);
  } else {
    memset(contacts, 0, (size_t)w->num_tracked);
  }
  return status;
}

void hyq_mj_joint_positions(const hyq_mj* w, double* out) {
  for (int j = 0; j < w->num_joints; j++) {
    out[j] = w->d->qpos[w->qpos_of[j]];
  }
}

void hyq_mj_joint_velocities(const hyq_mj* w, double* out) {
  for (int j = 0; j < w->num_joints; j++) {
    out[j] = w->d->qvel[w->dof_of[j]];
  }
}

void hyq_mj_root_state(const hyq_mj* w, double pose[7], double vel[6]) {
  memcpy(pose, w->d->qpos + w->root_qpos, 7 * sizeof(double));
  memcpy(vel, w->d->qvel + w->root_dof, 6 * sizeof(double));
}

void hyq_mj_body_pose(const hyq_mj* w, int body, double out[7]) {
  int id = w->body_of[body];
  memcpy(out, w->d->xpos + 3 * id, 3 * sizeof(double));
  memcpy(out + 3, w->d->xquat + 4 * id, 4 * sizeof(double));
}

double hyq_mj_total_mass(const hyq_mj* w) {
  double total = 0;
  for (int b = 0; b < w->num_bodies; b++) {
    total += w->m->body_mass[w->body_of[b]];
  }
  return total;
}

int hyq_mj_num_touching(const hyq_mj* w) {
  int n = 0;
  for (int c = 0; c < w->d->ncon; c++) {
    if (w->d->contact[c].dist <= 0) {
      n++;
    }
  }
  return n;
}

double hyq_mj_time(const hyq_mj* w) { return w->d->time; }

/* ---------------------------------------------------------------------------------------------
 * Per-episode dynamics and pushes. */

/* Body b's compiled mass properties back, with the frame flags that went with them. */
static void restore_body(hyq_mj* w, int b) {
  mjModel* m = w->m;
  int id = w->body_of[b];
  m->body_mass[id] = w->mass0[b];
  memcpy(m->body_ipos + 3 * id, w->ipos0 + 3 * b, 3 * sizeof(double));
  memcpy(m->body_iquat + 4 * id, w->iquat0 + 4 * b, 4 * sizeof(double));
  memcpy(m->body_inertia + 3 * id, w->inertia0 + 3 * b, 3 * sizeof(double));
  m->body_sameframe[id] = w->body_sameframe0[b];
  for (int g = m->body_geomadr[id]; g < m->body_geomadr[id] + m->body_geomnum[id]; g++) {
    m->geom_sameframe[g] = w->geom_sameframe0[g];
  }
}

/* Body b's mass properties from mass, centre of mass and full tensor (ixx iyy izz ixy ixz iyz),
 * principal axes by MuJoCo's own mju_eig3, as its compiler takes a fullinertia. The inertial
 * frame no longer coincides with the body frame or any geom's, so those shortcuts are off. */
static int write_body(hyq_mj* w, int b, const double v[10], char* err, int err_len) {
  mjModel* m = w->m;
  int id = w->body_of[b];
  if (m->body_simple[id]) {
    snprintf(err, (size_t)err_len,
             "body %d is one MuJoCo treats as simple (diagonal mass matrix): its mass "
             "properties cannot be changed in place", b);
    return -1;
  }
  mjtNum full[9] = {v[4], v[7], v[8], v[7], v[5], v[9], v[8], v[9], v[6]};
  mjtNum eigval[3], eigvec[9], quat[4];
  api.mju_eig3(eigval, eigvec, quat, full);
  if (!(eigval[2] > 0)) {
    snprintf(err, (size_t)err_len, "body %d: inertia tensor is not positive definite", b);
    return -1;
  }
  m->body_mass[id] = v[0];
  memcpy(m->body_ipos + 3 * id, v + 1, 3 * sizeof(double));
  memcpy(m->body_iquat + 4 * id, quat, 4 * sizeof(double));
  memcpy(m->body_inertia + 3 * id, eigval, 3 * sizeof(double));
  m->body_sameframe[id] = mjSAMEFRAME_NONE;
  for (int g = m->body_geomadr[id]; g < m->body_geomadr[id] + m->body_geomnum[id]; g++) {
    if (m->geom_sameframe[g] == mjSAMEFRAME_INERTIA ||
        m->geom_sameframe[g] == mjSAMEFRAME_INERTIAROT) {
      m->geom_sameframe[g] = mjSAMEFRAME_NONE;
    }
  }
  return 0;
}

/* Every geom's contact solref for a stiffness factor `s` and a damping factor `c` on its
 * compiled one, and, when `zeta` > 0 (a drawn restitution), the damping that gives the spring
 * the damping ratio `zeta` at its new stiffness, times `c`. MuJoCo's reference acceleration is
 * -b v - k r. In the positive form (timeconst tc, dampratio z) b = 2 / (dmax tc) and
 * k = d / (dmax² tc² z²), a spring of frequency 1 / (tc z) and damping ratio z at d = dmax,
 * where MuJoCo raises a tc below two steps to two steps (its refsafe) and so uses
 * tc0' = max(tc0, 2 dt): tc0' / c and z0 c / √s scale b by c and k by s, and
 * tc0' z0 / (√s c zeta), c zeta keep k at s k0 with the damping ratio c zeta. A tc the draw
 * takes below two steps would be raised by MuJoCo with z kept, softening the spring by the
 * square of the raise; it is raised here with tc z kept instead, so the stiffness is the drawn
 * one and the damping the most MuJoCo allows. In the negative form (-k, -b) the two are scaled
 * directly, and the damping for zeta is 2 zeta √(k / dmax) (b = damping / dmax,
 * k = stiffness / dmax²). Factors of 1 and no zeta write the compiled values back bit for
 * bit. */
static void scale_contact(hyq_mj* w, double s, double c, double zeta) {
  mjModel* m = w->m;
  int nominal = s == 1.0 && c == 1.0 && zeta <= 0.0;
  double tmin = (m->opt.disableflags & mjDSBL_REFSAFE) ? 0.0 : 2.0 * m->opt.timestep;
  for (int g = 0; g < (int)m->ngeom; g++) {
    const double* r0 = w->geom_solref0 + mjNREF * g;
    double* r = m->geom_solref + mjNREF * g;
    double dmax = m->geom_solimp[mjNIMP * g + 1];
    if (nominal) {
      r[0] = r0[0];
      r[1] = r0[1];
    } else if (r0[0] < 0.0) {
      r[0] = r0[0] * s;
      r[1] = zeta > 0.0 ? -2.0 * c * zeta * sqrt(-r[0] / dmax) : r0[1] * c;
    } else {
      double tc0 = fmax(r0[0], tmin);
      double tc = zeta > 0.0 ? tc0 * r0[1] / (sqrt(s) * c * zeta) : tc0 / c;
      double z = zeta > 0.0 ? c * zeta : r0[1] * c / sqrt(s);
      if (tc < tmin) {
        z *= tc / tmin;
        tc = tmin;
      }
      r[0] = tc;
      r[1] = z;
    }
  }
}

int hyq_mj_set_dynamics(hyq_mj* w, double friction, double stiffness_scale,
                        double damping_scale, double damping_ratio, const uint8_t* nominal,
                        const double* bodies, const double* damping, char* err, int err_len) {
  mjModel* m = w->m;
  for (int g = 0; g < (int)m->ngeom; g++) {
    m->geom_friction[3 * g] = friction;
  }
  scale_contact(w, stiffness_scale, damping_scale, damping_ratio);
  for (int j = 0; j < w->num_joints; j++) {
    m->dof_damping[w->dof_of[j]] = damping[j];
  }
  int masses_changed = 0;
  for (int b = 0; b < w->num_bodies; b++) {
    if (nominal[b]) {
      if (w->modified[b]) {
        restore_body(w, b);
        w->modified[b] = 0;
        masses_changed = 1;
      }
    } else {
      if (write_body(w, b, bodies + 10 * b, err, err_len) != 0) {
        return -1;
      }
      w->modified[b] = 1;
      masses_changed = 1;
    }
  }
  if (!masses_changed) {
    return 0;
  }
  volatile int status = 0;
  /* The constants MuJoCo derives from masses (subtree masses, the inverse weights that scale
   * constraint softness, the mean inertia that scales the solver's tolerance) as its compiler
   * sets them. It computes them at qpos0 in the data, whose state the caller then replaces. */
  GUARDED(api.mj_setConst(m, w->d), {
    snprintf(err, (size_t)err_len, "MuJoCo error while setting the masses: %s", error_text);
    status = -1;
  });
  return status;
}

void hyq_mj_body_inertial(const hyq_mj* w, int body, double out[10]) {
  const mjModel* m = w->m;
  int id = w->body_of[body];
  const double* q = m->body_iquat + 4 * id;
  const double* d = m->body_inertia + 3 * id;
  /* R = rotation of the unit quaternion (w, x, y, z); I = R diag(d) R^T. */
  double r[9] = {
      1 - 2 * (q[2] * q[2] + q[3] * q[3]), 2 * (q[1] * q[2] - q[0] * q[3]),
      2 * (q[1] * q[3] + q[0] * q[2]),     2 * (q[1] * q[2] + q[0] * q[3]),
      1 - 2 * (q[1] * q[1] + q[3] * q[3]), 2 * (q[2] * q[3] - q[0] * q[1]),
      2 * (q[1] * q[3] - q[0] * q[2]),     2 * (q[2] * q[3] + q[0] * q[1]),
      1 - 2 * (q[1] * q[1] + q[2] * q[2])};
  double full[9];
  for (int i = 0; i < 3; i++) {
    for (int k = 0; k < 3; k++) {
      full[3 * i + k] = r[3 * i] * d[0] * r[3 * k] + r[3 * i + 1] * d[1] * r[3 * k + 1] +
                        r[3 * i + 2] * d[2] * r[3 * k + 2];
    }
  }
  out[0] = m->body_mass[id];
  memcpy(out + 1, m->body_ipos + 3 * id, 3 * sizeof(double));
  out[4] = full[0];
  out[5] = full[4];
  out[6] = full[8];
  out[7] = full[1];
  out[8] = full[2];
  out[9] = full[5];
}

int hyq_mj_add_root_velocity(hyq_mj* w, const double dv[3], char* err, int err_len) {
  volatile int status = 0;
  GUARDED(
      {
        for (int k = 0; k < 3; k++) {
          w->d->qvel[w->root_dof + k] += dv[k];
        }
        /* The velocity-dependent terms the next mj_step2 uses (bias and passive forces) were
         * computed by the last mj_step1 from the old velocity: compute them again. Positions,
         * contacts and the warm start are unchanged. */
        api.mj_step1(w->m, w->d);
      },
      {
        snprintf(err, (size_t)err_len, "MuJoCo error while pushing the trunk: %s", error_text);
        status = -1;
      });
  return status;
}
