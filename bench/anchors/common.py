"""What the MuJoCo and DART anchors share: the robot facts, the timing, the random actions and
the JSON lines they print.

The facts (``hyq.json``) and the models (``hyq.xml``, ``hyq.urdf``) are written by
``hyq model`` from the robot the environment simulates; ``cargo xtask bench-vs-anchors``
writes them into ``target/anchor-models/`` before every run.
"""

import argparse
import json
import os
import time

import numpy as np

REPOSITORY = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DEFAULT_MODELS = os.path.join(REPOSITORY, "target", "anchor-models")
FACTS_SCHEMA = 1


class Facts:
    """The robot and workload facts of ``hyq model --format json``, as numpy arrays."""

    def __init__(self, models_dir):
        path = os.path.join(models_dir, "hyq.json")
        if not os.path.exists(path):
            raise SystemExit(
                "no robot facts at %s: write the models first "
                "(`cargo xtask bench-vs-anchors` does, or `hyq model --format json --out %s`)"
                % (path, path))
        with open(path) as f:
            raw = json.load(f)
        if raw.get("schema_version") != FACTS_SCHEMA:
            raise SystemExit("%s: schema_version %r, these scripts read %d"
                             % (path, raw.get("schema_version"), FACTS_SCHEMA))
        self.raw = raw
        self.models_dir = models_dir
        self.dt = float(raw["dt"])
        self.substeps = int(raw["substeps"])
        self.env_dt = self.dt * self.substeps
        self.max_env_steps = int(raw["max_env_steps"])
        self.joint_margin = float(raw["joint_limit_margin"])
        joints = raw["joints"]
        self.joint_names = [j["urdf_name"] for j in joints]
        self.lower = np.array([j["lower"] for j in joints])
        self.upper = np.array([j["upper"] for j in joints])
        self.effort = np.array([j["effort"] for j in joints])
        self.kp = np.array([j["kp"] for j in joints])
        self.kd = np.array([j["kd"] for j in joints])
        self.standing = np.array([j["standing"] for j in joints])
        self.trunk = raw["trunk"]
        self.feet = raw["feet"]
        self.links = {link["name"]: link for link in raw["links"]}
        spawn = raw["spawn"]
        self.spawn_position = np.array(spawn["position"])
        self.spawn_quaternion = np.array(spawn["quaternion_wxyz"])
        self.spawn_q = np.array(spawn["q"])
        # The tracked bodies in observation order: the feet, then the trunk (rows 24-28).
        self.tracked = list(self.feet) + [self.trunk]
        self.n = len(joints)
        self.obs_size = 2 * self.n + len(self.feet) + 11

    def path(self, name):
        return os.path.join(self.models_dir, name)

    def joint_limit_reached(self, q):
        """Spec 6.2 as the project reads it: a joint within the margin of either limit."""
        return bool(np.any((q <= self.lower + self.joint_margin)
                           | (q >= self.upper - self.joint_margin)))

    def random_targets(self, rng, steps):
        """Joint targets drawn uniformly within the limits, one row per env step (the same
        distribution as `hyq bench`'s normalized actions)."""
        return rng.uniform(self.lower, self.upper, size=(steps, self.n))


class Episodes:
    """How the episodes of a timed run ended."""

    def __init__(self):
        self.fell = 0
        self.joint_limit = 0
        self.timeout = 0

    def as_dict(self):
        return {"fell": self.fell, "joint_limit": self.joint_limit, "timeout": self.timeout}


def timed(body):
    """Runs ``body()`` and returns (its result, wall seconds, process CPU seconds)."""
    w0, c0 = time.perf_counter(), time.process_time()
    result = body()
    return result, time.perf_counter() - w0, time.process_time() - c0


def median(values):
    v = sorted(values)
    n = len(v)
    return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])


def emit(anchor, version, case, steps, runs, **extra):
    """Prints one JSON line for a timed case; ``runs`` is a list of (wall_s, cpu_s) of
    ``steps`` env steps each. The rates are env steps per second, medians over the runs."""
    wall = [steps / w for w, _ in runs]
    cpu = [steps / c for _, c in runs]
    line = {
        "schema_version": 1,
        "anchor": anchor,
        "version": version,
        "case": case,
        "env_steps": steps,
        "runs": len(runs),
        "env_steps_per_s": round(median(wall), 1),
        "env_steps_per_s_cpu": round(median(cpu), 1),
        "env_steps_per_s_runs": [round(x, 1) for x in wall],
        "env_steps_per_s_cpu_runs": [round(x, 1) for x in cpu],
    }
    line.update(extra)
    print(json.dumps(line), flush=True)


def emit_info(anchor, version, case, **fields):
    """Prints one JSON line that is not a rate (a check of what the model does)."""
    line = {"schema_version": 1, "anchor": anchor, "version": version, "case": case}
    line.update(fields)
    print(json.dumps(line), flush=True)


def arguments(description, cases, default_cases):
    """The command line every anchor script takes."""
    p = argparse.ArgumentParser(description=description)
    p.add_argument("--models", default=DEFAULT_MODELS,
                   help="directory holding hyq.json, hyq.xml and hyq.urdf (default: %(default)s)")
    p.add_argument("--cases", default=",".join(default_cases),
                   help="comma-separated, of: %s (default: %%(default)s)" % ", ".join(cases))
    p.add_argument("--env-steps", type=int, default=3000,
                   help="env steps per timed run (default: %(default)s)")
    p.add_argument("--runs", type=int, default=1,
                   help="timed runs per case; rates are their median (default: %(default)s)")
    p.add_argument("--seed", type=int, default=0,
                   help="seed of the random joint targets (default: %(default)s)")
    return p


def parse_cases(p, args, cases):
    chosen = [c for c in args.cases.split(",") if c]
    unknown = [c for c in chosen if c not in cases]
    if unknown:
        p.error("unknown case %s (cases: %s)" % (", ".join(unknown), ", ".join(cases)))
    if args.env_steps < 1 or args.runs < 1:
        p.error("--env-steps and --runs must be at least 1")
    return chosen


def quaternion_wxyz(r):
    """The unit quaternion (w, x, y, z) of a 3x3 rotation matrix (Shepperd's method)."""
    trace = r[0, 0] + r[1, 1] + r[2, 2]
    if trace > 0.0:
        s = 2.0 * np.sqrt(trace + 1.0)
        return np.array([0.25 * s, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s,
                         (r[1, 0] - r[0, 1]) / s])
    i = int(np.argmax([r[0, 0], r[1, 1], r[2, 2]]))
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2.0 * np.sqrt(1.0 + r[i, i] - r[j, j] - r[k, k])
    q = np.empty(4)
    q[0] = (r[k, j] - r[j, k]) / s
    q[1 + i] = 0.25 * s
    q[1 + j] = (r[j, i] + r[i, j]) / s
    q[1 + k] = (r[k, i] + r[i, k]) / s
    return q
