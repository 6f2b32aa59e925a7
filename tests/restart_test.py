#!/usr/bin/env python3
"""Checkpoint and restart of DEM scenes (called by ctest).

  restart_test.py equivalence SLUICE SCENE WORKDIR NP_FIRST NP_SECOND TOLERANCE
      Runs the scene to its end time T on NP_FIRST ranks; then to T/2 (the
      scene writes a checkpoint there) and continues from that checkpoint to T
      on NP_SECOND ranks, in the same output directory. The 'final:' line and
      every row of every .csv (series and particle dumps) must equal the
      uninterrupted run's: character for character when TOLERANCE is 0, else
      each number within TOLERANCE (relative). Every .pvd index must list the
      same snapshots.

  restart_test.py kill SLUICE SCENE WORKDIR [END_TIME]
      Kills the scene (run to END_TIME if given) with SIGKILL after its second
      checkpoint, checks that its series are readable, restarts from 'latest'
      and requires the uninterrupted run's final line and .csv rows exactly.

  restart_test.py bad SLUICE SCENE WORKDIR
      Writes a checkpoint, then restarts from a damaged or wrong one: a cut
      particles.bin, a cut rank file, a cut mesh file, a state without its end,
      a missing directory, a scene with another friction or particle count;
      for a cfd-dem scene also a cut fluid mesh, cut self-induced histories and
      another fluid viscosity. Each must stop with exit code 2, a message
      naming the file or the mismatch, and leave the output directory exactly
      as it was.

Exits non-zero, saying why, when a check fails.
"""
import os
import re
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from kill_test import check_series, fail, wait_for  # noqa: E402


def command(sluice, np, prm):
    if np <= 1:
        return [sluice, prm]
    return ["mpirun", "-np", str(np), "--oversubscribe", sluice, prm]


def run(sluice, np, prm, cwd, expect=0):
    res = subprocess.run(command(sluice, np, prm), cwd=cwd, capture_output=True, text=True)
    if res.returncode != expect:
        fail("'%s' in %s exited %d, expected %d:\n%s%s" %
             (" ".join(command(sluice, np, prm)), cwd, res.returncode, expect, res.stdout,
              res.stderr))
    return res


def final_line(out):
    lines = [l for l in out.splitlines() if l.startswith("final:")]
    if len(lines) != 1:
        fail("expected one 'final:' line, got %s" % lines)
    return lines[0]


def set_entry(text, name, value):
    """Sets 'set name = value' in the scene text (the first such entry)."""
    pattern = re.compile(r"^(\s*set\s+%s\s*=).*$" % re.escape(name), re.M)
    if not pattern.search(text):
        fail("the scene has no entry '%s'" % name)
    return pattern.sub(lambda m: m.group(1) + " " + value, text, count=1)


def add_restart(text, target):
    return text.replace("subsection checkpoint",
                        "subsection checkpoint\n  set restart from = %s" % target, 1)


def numbers(line):
    return [float(x) for x in re.findall(r"[-+]?\d*\.?\d+(?:[eE][-+]?\d+)?", line)]


def same(a, b, tolerance, what):
    if tolerance == 0.:
        if a != b:
            fail("%s differs:\n  restarted:     %s\n  uninterrupted: %s" % (what, b, a))
        return
    x, y = numbers(a), numbers(b)
    if len(x) != len(y):
        fail("%s has another shape:\n  %s\n  %s" % (what, b, a))
    for u, v in zip(x, y):
        if abs(u - v) > tolerance * max(abs(u), abs(v), 1e-300):
            fail("%s differs beyond %g:\n  restarted:     %s\n  uninterrupted: %s" %
                 (what, tolerance, b, a))


def output_dir(cwd):
    return os.path.join(cwd, "output")


def compare_runs(a, b, out_a, out_b, tolerance):
    """The final line and the statistics' summary lines (wear, breakage,
    stream, and on as many ranks energy: across rank counts its pairs at a rank
    boundary use the ghosts' half-step velocities, doc/geometry.md), every .csv
    (series and particle dumps) row by row, and the times every .pvd lists."""
    same(final_line(out_a), final_line(out_b), tolerance, "the final line")
    kinds = ("wear", "breakage", "stream", "field", "check", "result") + \
        (("energy",) if tolerance == 0. else ())
    # (a result line ends in its own run's wall time)
    summary = lambda out: [re.sub(r" wall_s=\S+", "", l) for l in out.splitlines()
                           if l.split(":")[0] in kinds]
    if len(summary(out_a)) != len(summary(out_b)):
        fail("the runs print different summary lines:\n%s\n%s" % (summary(out_a), summary(out_b)))
    for la, lb in zip(summary(out_a), summary(out_b)):
        same(la, lb, tolerance, "a summary line")
    names = sorted(f for f in os.listdir(output_dir(a)) if f.endswith((".csv", ".pvd")))
    names_b = sorted(f for f in os.listdir(output_dir(b)) if f.endswith((".csv", ".pvd")))
    if names != names_b:
        fail("the restarted run wrote %s, the uninterrupted %s" % (names_b, names))
    rows, snapshots = 0, 0
    for name in names:
        text_a = open(os.path.join(output_dir(a), name)).read()
        text_b = open(os.path.join(output_dir(b), name)).read()
        if name.endswith(".pvd"):
            times_a = re.findall(r'timestep="([^"]*)"', text_a)
            times_b = re.findall(r'timestep="([^"]*)"', text_b)
            if times_a != times_b:
                fail("the restarted %s lists times %s, the uninterrupted %s" %
                     (name, times_b, times_a))
            snapshots += len(times_a)
            continue
        rows_a, rows_b = text_a.splitlines(), text_b.splitlines()
        if len(rows_a) != len(rows_b):
            fail("the restarted %s has %d lines, the uninterrupted %d" %
                 (name, len(rows_b), len(rows_a)))
        for ra, rb in zip(rows_a, rows_b):
            same(ra, rb, tolerance, "a row of " + name)
        rows += len(rows_a) - 1
    return rows, snapshots


MESH_FILES = []


def read_scene(scene):
    """The scene's text, with the mesh and particle files it names (relative to the scene,
    as sluice finds them) noted for fresh() to copy and named by their base
    names."""
    def local(match):
        MESH_FILES.append(os.path.join(os.path.dirname(scene), match.group(2)))
        return match.group(1) + os.path.basename(match.group(2))
    return re.sub(r"^(\s*set\s+file\s*=\s*)(\S+\.(?:msh|stl|vtu|csv))\s*$", local,
                  open(scene).read(), flags=re.M)


def fresh(work, name, scene_text, prm="scene.prm"):
    """A new directory with the scene and the mesh files it names."""
    d = os.path.join(work, name)
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    open(os.path.join(d, prm), "w").write(scene_text)
    for f in MESH_FILES:
        shutil.copy(f, d)
    return d


def end_time(text):
    return float(re.search(r"^\s*set\s+end time\s*=\s*(\S+)", text, re.M).group(1))


def equivalence(sluice, scene, work, np_first, np_second, tolerance):
    text = read_scene(scene)
    a = fresh(work, "uninterrupted", text)
    out_a = run(sluice, np_first, "scene.prm", a).stdout
    b = fresh(work, "restarted", set_entry(text, "end time", repr(end_time(text) / 2)))
    run(sluice, np_first, "scene.prm", b)
    open(os.path.join(b, "restart.prm"), "w").write(add_restart(text, "latest"))
    out_b = run(sluice, np_second, "restart.prm", b).stdout
    check_series(b)
    rows, snapshots = compare_runs(a, b, out_a, out_b, tolerance)
    print("%d rank(s) to T/2, checkpoint, %d rank(s) to T: final line and %d .csv rows %s, "
          "%d snapshots listed" % (np_first, np_second, rows,
                                   "identical" if tolerance == 0. else "within %g" % tolerance,
                                   snapshots))
    print("uninterrupted: " + final_line(out_a))
    print("restarted:     " + final_line(out_b))


def complete_checkpoints(directory):
    if not os.path.isdir(directory):
        return []
    return sorted(d for d in os.listdir(directory)
                  if re.fullmatch(r"particles-checkpoint-\d{10}", d) and
                  os.path.exists(os.path.join(directory, d, "state")))


def kill(sluice, scene, work, end=None):
    text = read_scene(scene)
    if end is not None:
        text = set_entry(text, "end time", end)
    a = fresh(work, "uninterrupted", text)
    out_a = run(sluice, 1, "scene.prm", a).stdout
    b = fresh(work, "killed", text)
    proc = subprocess.Popen([sluice, "scene.prm"], cwd=b, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    if not wait_for(lambda: len(complete_checkpoints(output_dir(b))) >= 2, proc, 300):
        fail("the scene ended or stalled before its second checkpoint")
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    check_series(b)
    kept = complete_checkpoints(output_dir(b))
    open(os.path.join(b, "restart.prm"), "w").write(add_restart(text, "latest"))
    out_b = run(sluice, 1, "restart.prm", b).stdout
    check_series(b)
    rows, snapshots = compare_runs(a, b, out_a, out_b, 0.)
    print("killed after checkpoint %s, restarted from it: final line and %d .csv rows "
          "identical, %d snapshots listed" % (kept[-1], rows, snapshots))


def listing(directory):
    """Every file under 'directory' with its size and modification time."""
    found = {}
    for root, _, files in os.walk(directory):
        for f in files:
            p = os.path.join(root, f)
            st = os.stat(p)
            found[os.path.relpath(p, directory)] = (st.st_size, st.st_mtime_ns)
    return found


def bad(sluice, scene, work):
    text = read_scene(scene)
    base = fresh(work, "written", text)
    run(sluice, 1, "scene.prm", base)
    checkpoint = complete_checkpoints(output_dir(base))[-1]

    def case(name, damage, scene_text, expected):
        d = os.path.join(work, "bad-" + name)
        shutil.rmtree(d, ignore_errors=True)
        shutil.copytree(base, d)
        target = os.path.join("output", checkpoint)
        damage(os.path.join(d, target))
        open(os.path.join(d, "restart.prm"), "w").write(add_restart(scene_text, target))
        before = listing(output_dir(d))
        res = run(sluice, 1, "restart.prm", d, expect=2)
        message = res.stderr.strip().splitlines()[-1] if res.stderr.strip() else ""
        if not re.search(expected, message):
            fail("case '%s': the message '%s' does not match '%s'" % (name, message, expected))
        if listing(output_dir(d)) != before:
            fail("case '%s': the failed restart changed the output directory" % name)
        print("%-22s exit 2: %s" % (name, message))

    def cut(relative, keep=0.5):
        def damage(path):
            p = os.path.join(path, relative)
            data = open(p, "rb").read()
            open(p, "wb").write(data[:int(len(data) * keep)])
        return damage

    def nothing(path):
        pass

    case("cut_particles", cut("particles.bin"), text, r"particles\.bin.*cut short")
    case("cut_rank_file", cut("rank-0.bin"), text, r"rank-0\.bin.*cut short")
    case("cut_mesh", cut("mesh_fixed.data"), text, r"mesh_fixed\.data.*cut short")
    case("cut_state", cut("state", 0.6), text, r"state.*cut short")
    case("missing", lambda path: shutil.rmtree(path), text, r"no such checkpoint directory")
    case("other_friction", nothing, set_entry(text, "friction", "0.3"),
         r"different scene.*contact/friction")
    if not re.search(r"^\s*set\s+physics\s*=\s*cfd-dem", text, re.M):
        case("other_particles", nothing, set_entry(text, "number of particles", "1000"),
             r"different scene.*particles inserted")
        return
    case("cut_fluid_mesh", cut("fluid.mesh_fixed.data"), text,
         r"fluid\.mesh_fixed\.data.*cut short")
    case("cut_self_induced", cut("self_induced.bin"), text, r"self_induced\.bin.*cut short")
    case("other_viscosity", nothing, set_entry(text, "viscosity", "1e-3"),
         r"different scene.*fluid = .*viscosity")


if __name__ == "__main__":
    modes = {"equivalence": [8], "kill": [5, 6], "bad": [5]}
    if len(sys.argv) < 2 or sys.argv[1] not in modes or len(sys.argv) not in modes[sys.argv[1]]:
        fail(__doc__)
    mode, sluice, scene, work = sys.argv[1:5]
    os.makedirs(work, exist_ok=True)
    scene = os.path.abspath(scene)
    if mode == "equivalence":
        equivalence(sluice, scene, work, int(sys.argv[5]), int(sys.argv[6]),
                    float(sys.argv[7]))
    elif mode == "kill":
        kill(sluice, scene, work, sys.argv[5] if len(sys.argv) > 5 else None)
    else:
        bad(sluice, scene, work)
