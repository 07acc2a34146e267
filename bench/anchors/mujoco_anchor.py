#!/usr/bin/env python3
"""MuJoCo from Python on the environment's robot: how fast a Python loop around MuJoCo runs the
workload of `hyq bench` (see README.md in this directory for what each case does).

The model is ``hyq.xml`` (``hyq model --format mjcf``): the robot every backend simulates, with
one position servo per joint, so MuJoCo itself applies kp (q* - q) - kd q' clamped to the
effort limit inside every physics step.
"""

import mujoco
import numpy as np

import common

ANCHOR = "mujoco"
CASES = ["env_random", "c_loop", "stand"]


class MujocoEnv:
    """The environment's step written in Python over MuJoCo's bindings."""

    def __init__(self, facts):
        self.facts = f = facts
        self.m = m = mujoco.MjModel.from_xml_path(f.path("hyq.xml"))
        self.d = mujoco.MjData(m)
        if m.nu != f.n or m.nkey < 1:
            raise SystemExit("hyq.xml: expected %d actuators and a spawn keyframe, found %d and %d"
                             % (f.n, m.nu, m.nkey))
        joints = [m.joint(name) for name in f.joint_names]
        self.qpos_at = np.array([j.qposadr[0] for j in joints])
        self.qvel_at = np.array([j.dofadr[0] for j in joints])
        # The servos are in action order (the generator writes them so); check it.
        for i, j in enumerate(joints):
            if m.actuator_trnid[i, 0] != j.id:
                raise SystemExit("hyq.xml: actuator %d does not drive joint %s" % (i, f.joint_names[i]))
        # Geom id -> observation slot: 0..F-1 the feet, F the trunk, F+1 nothing tracked.
        slots = len(f.tracked)
        self.slot_of = np.full(m.ngeom, slots, dtype=np.intp)
        for slot, body in enumerate(f.tracked):
            b = m.body(body["link"])
            for k in body["shapes"]:
                self.slot_of[m.body_geomadr[b.id] + k] = slot
        self.trunk_slot = slots - 1
        self.touched = np.zeros(slots + 1, dtype=bool)
        self.obs = np.zeros(f.obs_size)
        self.prev_v = np.zeros(3)
        self.t = 0
        self.ended = common.Episodes()
        self.reset()

    def reset(self):
        m, d = self.m, self.d
        mujoco.mj_resetDataKeyframe(m, d, 0)
        d.ctrl[:] = self.facts.standing
        mujoco.mj_forward(m, d)
        self.prev_v[:] = 0.0
        self.t = 0

    def step(self, target):
        """One env step: set the targets, run the sub-steps noting every tracked shape that
        touches the ground in any of them, assemble the observation, end the episode by the
        spec's rules (fall, joint limit, timeout) and reset."""
        f, m, d, touched = self.facts, self.m, self.d, self.touched
        d.ctrl[:] = target
        touched[:] = False
        for _ in range(f.substeps):
            mujoco.mj_step(m, d)
            if d.ncon:
                touched[self.slot_of[d.contact.geom]] = True
        o, n = self.obs, f.n
        q = d.qpos[self.qpos_at]
        o[0:n] = q
        o[n:2 * n] = d.qvel[self.qvel_at]
        k = 2 * n + len(f.feet) + 1
        o[2 * n:k] = touched[:-1]
        o[k:k + 4] = d.qpos[3:7]
        v = d.qvel[0:3]
        o[k + 4:k + 7] = (v - self.prev_v) / f.env_dt
        self.prev_v[:] = v
        o[k + 7:k + 10] = d.qpos[0:3]
        self.t += 1
        fell = touched[self.trunk_slot]
        limit = f.joint_limit_reached(q)
        timeout = self.t >= f.max_env_steps
        if fell or limit or timeout:
            self.ended.fell += int(fell)
            self.ended.joint_limit += int(limit)
            self.ended.timeout += int(timeout)
            self.reset()
        return o

    def c_loop_step(self, target):
        """The same targets with MuJoCo's own loop of sub-steps (one call), no observation,
        the fall checked once at the end: the floor of what any binding can cost."""
        m, d = self.m, self.d
        d.ctrl[:] = target
        mujoco.mj_step(m, d, nstep=self.facts.substeps)
        self.t += 1
        fell = d.ncon and bool((self.slot_of[d.contact.geom] == self.trunk_slot).any())
        if fell or self.t >= self.facts.max_env_steps:
            self.ended.fell += int(bool(fell))
            self.ended.timeout += int(not fell)
            self.reset()


def run_steps(env, targets, step):
    env.reset()
    env.ended = common.Episodes()
    for a in targets:
        step(a)


def stand(env, seconds=10.0):
    """Holds the standing pose from the spawn state: where the trunk settles."""
    f, m, d = env.facts, env.m, env.d
    env.reset()
    heights = {}
    trunk_touched = False
    steps = int(round(seconds / f.dt))
    for i in range(1, steps + 1):
        mujoco.mj_step(m, d)
        if d.ncon:
            trunk_touched |= bool((env.slot_of[d.contact.geom] == env.trunk_slot).any())
        if i in (500, 1000, steps):
            heights["%g" % (i * f.dt)] = round(float(d.qpos[2]), 5)
    feet = set(int(s) for s in env.slot_of[d.contact.geom].ravel()) if d.ncon else set()
    q = d.qpos[env.qpos_at]
    return {
        "trunk_z_m": heights,
        "trunk_touched": trunk_touched,
        "feet_touching": sum(1 for s in range(len(f.feet)) if s in feet),
        "max_joint_sag_rad": round(float(np.abs(q - f.standing).max()), 4),
        "contacts": int(d.ncon),
        "deepest_contact_m": round(float(d.contact.dist.min()), 5) if d.ncon else None,
    }


def main():
    p = common.arguments(__doc__.splitlines()[0], CASES, ["env_random", "c_loop"])
    args = p.parse_args()
    cases = common.parse_cases(p, args, CASES)
    facts = common.Facts(args.models)
    env = MujocoEnv(facts)
    rng = np.random.default_rng(args.seed)
    targets = [facts.random_targets(rng, args.env_steps) for _ in range(args.runs)]
    version = mujoco.__version__
    for case in cases:
        if case == "stand":
            common.emit_info(ANCHOR, version, case, **stand(env))
            continue
        step = env.step if case == "env_random" else env.c_loop_step
        runs, ended = [], []
        for t in targets:
            _, wall, cpu = common.timed(lambda: run_steps(env, t, step))
            runs.append((wall, cpu))
            ended.append(env.ended.as_dict())
        common.emit(ANCHOR, version, case, args.env_steps, runs, episodes_ended=ended)


if __name__ == "__main__":
    main()
