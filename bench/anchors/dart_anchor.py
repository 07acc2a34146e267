#!/usr/bin/env python3
"""DART from Python (dartpy) on the environment's robot: how fast a Python loop around DART runs
the workload of `hyq bench` (see README.md in this directory for what each case does).

The model is ``hyq.urdf`` (``hyq model --format urdf --capsules cylinder``): DART's URDF loader
(urdfdom) knows no capsule, so the generator writes each capsule as a cylinder spanning it and
this script puts the capsule back (``--shape capsule``, the default, as the DART backend
simulates) or keeps the cylinder (``--shape cylinder``). The PD law is evaluated in Python
before every sub-step, as in the environment's shared actuator, and applied as joint forces.
"""

import time

import dartpy as dart
import numpy as np

import common

ANCHOR = "dart"
CASES = ["env_random", "stand"]
DETECTORS = {
    "bullet": lambda: dart.collision.BulletCollisionDetector(),
    "ode": lambda: dart.collision.OdeCollisionDetector(),
}
# The ground: a box whose top face is the plane z = 0 (DART's detectors have no infinite
# plane that all of them support); 40 m across, far more than a 10 s episode covers.
GROUND_SIZE = (40.0, 40.0, 1.0)


def rotation_vector(q_wxyz):
    """The rotation vector (axis times angle) of a unit quaternion, for DART's free joint."""
    w, v = q_wxyz[0], np.asarray(q_wxyz[1:])
    s = np.linalg.norm(v)
    if s < 1e-12:
        return 2.0 * v
    return 2.0 * np.arctan2(s, w) * v / s


class DartEnv:
    """The environment's step written in Python over dartpy."""

    def __init__(self, facts, detector, shape):
        self.facts = f = facts
        self.world = w = dart.simulation.World()
        w.setTimeStep(f.dt)
        w.setGravity(list(f.raw["gravity"]))
        loader = dart.utils.DartLoader()
        self.skel = sk = loader.parseSkeleton("file://" + f.path("hyq.urdf"))
        if sk is None:
            raise SystemExit("DART could not load %s" % f.path("hyq.urdf"))
        self.capsules = 0
        for name, link in f.links.items():
            nodes = sk.getBodyNode(name).getShapeNodes()
            if len(nodes) != len(link["collisions"]):
                raise SystemExit("hyq.urdf: link %s has %d shapes in DART, %d in the facts"
                                 % (name, len(nodes), len(link["collisions"])))
            for node, c in zip(nodes, link["collisions"]):
                node.getDynamicsAspect().setFrictionCoeff(f.raw["ground_friction"])
                if c["shape"] == "capsule" and shape == "capsule":
                    if node.getShape().getType() != "CylinderShape":
                        raise SystemExit("hyq.urdf: %s should be a cylinder" % c["name"])
                    node.setShape(dart.dynamics.CapsuleShape(c["radius"], 2.0 * c["half_length"]))
                    self.capsules += 1
        ground = dart.dynamics.Skeleton("ground")
        _, body = ground.createWeldJointAndBodyNodePair()
        node = body.createShapeNode(dart.dynamics.BoxShape(list(GROUND_SIZE)))
        node.createCollisionAspect()
        node.createDynamicsAspect().setFrictionCoeff(f.raw["ground_friction"])
        pose = dart.math.Isometry3()
        pose.set_translation([0.0, 0.0, -0.5 * GROUND_SIZE[2]])
        body.getParentJoint().setTransformFromParentBodyNode(pose)
        # The detector is chosen before the skeletons are added, so that it builds their
        # collision objects (the default detector would try first, and it has no capsule).
        w.getConstraintSolver().setCollisionDetector(DETECTORS[detector]())
        w.addSkeleton(sk)
        w.addSkeleton(ground)
        self.dofs = []
        for name in f.joint_names:
            joint = sk.getJoint(name)
            # Position limits enforced (DART's default is off); no velocity constraint: the
            # environment's speed limit is a rule of its actuator, not of the engine.
            joint.setLimitEnforcement(True)
            joint.setVelocityLowerLimit(0, -np.inf)
            joint.setVelocityUpperLimit(0, np.inf)
            self.dofs.append(joint.getIndexInSkeleton(0))
        self.dofs = np.array(self.dofs)
        self.trunk = sk.getBodyNode(f.trunk["link"])
        self.tracked_nodes = [
            [sk.getBodyNode(body["link"]).getShapeNode(k) for k in body["shapes"]]
            for body in f.tracked
        ]
        self.q0 = np.zeros(sk.getNumDofs())
        self.q0[0:3] = rotation_vector(f.spawn_quaternion)
        self.q0[3:6] = f.spawn_position
        self.q0[self.dofs] = f.spawn_q
        self.tau = np.zeros(sk.getNumDofs())
        self.touched = np.zeros(len(f.tracked), dtype=bool)
        self.obs = np.zeros(f.obs_size)
        self.prev_v = np.zeros(3)
        self.t = 0
        self.ended = common.Episodes()
        self.time_steps = False
        self.step_cpu = 0.0
        self.reset()

    def reset(self):
        sk = self.skel
        sk.setPositions(self.q0)
        sk.setVelocities(np.zeros(sk.getNumDofs()))
        self.world.getConstraintSolver().clearLastCollisionResult()
        self.prev_v[:] = 0.0
        self.t = 0

    def substep(self, target):
        """The PD law of the shared actuator (kp (q* - q) - kd q', clamped to the effort
        limit) then one physics step."""
        f, sk = self.facts, self.skel
        q = sk.getPositions()[self.dofs]
        qd = sk.getVelocities()[self.dofs]
        self.tau[self.dofs] = np.clip(f.kp * (target - q) - f.kd * qd, -f.effort, f.effort)
        sk.setForces(self.tau)
        if self.time_steps:
            c0 = time.process_time()
            self.world.step()
            self.step_cpu += time.process_time() - c0
        else:
            self.world.step()

    def note_contacts(self):
        result = self.world.getLastCollisionResult()
        for slot, nodes in enumerate(self.tracked_nodes):
            if not self.touched[slot]:
                for node in nodes:
                    if result.inCollision(node):
                        self.touched[slot] = True
                        break

    def step(self, target):
        """One env step: the sub-steps with the PD before each, noting every tracked shape
        that touches the ground in any of them; the observation; the spec's episode end
        (fall, joint limit, timeout) and reset."""
        f, sk = self.facts, self.skel
        self.touched[:] = False
        for _ in range(f.substeps):
            self.substep(target)
            self.note_contacts()
        o, n = self.obs, f.n
        positions = sk.getPositions()
        q = positions[self.dofs]
        o[0:n] = q
        o[n:2 * n] = sk.getVelocities()[self.dofs]
        k = 2 * n + len(f.tracked)
        o[2 * n:k] = self.touched
        pose = self.trunk.getWorldTransform()
        o[k:k + 4] = common.quaternion_wxyz(pose.rotation())
        v = self.trunk.getLinearVelocity()
        o[k + 4:k + 7] = (v - self.prev_v) / f.env_dt
        self.prev_v[:] = v
        o[k + 7:k + 10] = pose.translation()
        self.t += 1
        fell = self.touched[-1]
        limit = f.joint_limit_reached(q)
        timeout = self.t >= f.max_env_steps
        if fell or limit or timeout:
            self.ended.fell += int(fell)
            self.ended.joint_limit += int(limit)
            self.ended.timeout += int(timeout)
            self.reset()
        return o


def run_steps(env, targets):
    env.reset()
    env.ended = common.Episodes()
    for a in targets:
        env.step(a)


def stand(env, seconds=10.0):
    """Holds the standing pose from the spawn state: where the trunk settles."""
    f = env.facts
    env.reset()
    heights = {}
    trunk_touched = False
    steps = int(round(seconds / f.dt))
    for i in range(1, steps + 1):
        env.touched[:] = False
        env.substep(f.standing)
        env.note_contacts()
        trunk_touched |= bool(env.touched[-1])
        if i in (500, 1000, steps):
            heights["%g" % (i * f.dt)] = round(float(env.trunk.getWorldTransform().translation()[2]), 5)
    q = env.skel.getPositions()[env.dofs]
    return {
        "trunk_z_m": heights,
        "trunk_touched": trunk_touched,
        "feet_touching": int(env.touched[:-1].sum()),
        "max_joint_sag_rad": round(float(np.abs(q - f.standing).max()), 4),
    }


def main():
    p = common.arguments(__doc__.splitlines()[0], CASES, ["env_random"])
    p.add_argument("--detector", choices=sorted(DETECTORS), default="bullet",
                   help="collision detector (default: %(default)s, the DART backend's)")
    p.add_argument("--shape", choices=["capsule", "cylinder"], default="capsule",
                   help="leg shapes (default: %(default)s, as the model has them)")
    p.add_argument("--step-only", action="store_true",
                   help="also time world.step() alone, in a second pass over the same targets")
    args = p.parse_args()
    cases = common.parse_cases(p, args, CASES)
    facts = common.Facts(args.models)
    env = DartEnv(facts, args.detector, args.shape)
    rng = np.random.default_rng(args.seed)
    targets = [facts.random_targets(rng, args.env_steps) for _ in range(args.runs)]
    version = "dartpy " + getattr(dart, "__version__", "?")
    anchor = "%s-%s-%s" % (ANCHOR, args.detector, args.shape)
    for case in cases:
        if case == "stand":
            common.emit_info(anchor, version, case, **stand(env))
            continue
        runs, ended, step_only = [], [], []
        for t in targets:
            env.time_steps = False
            _, wall, cpu = common.timed(lambda: run_steps(env, t))
            runs.append((wall, cpu))
            ended.append(env.ended.as_dict())
            if args.step_only:
                # The same targets again, timing only the engine's step: what a binding with
                # no cost at all would reach with this DART build.
                env.time_steps, env.step_cpu = True, 0.0
                run_steps(env, t)
                env.time_steps = False
                step_only.append(len(t) / env.step_cpu)
        extra = {"episodes_ended": ended, "detector": args.detector, "leg_shape": args.shape}
        if step_only:
            extra["step_only_env_steps_per_s_cpu"] = round(common.median(step_only), 1)
        common.emit(anchor, version, case, args.env_steps, runs, **extra)


if __name__ == "__main__":
    main()
