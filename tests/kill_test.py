#!/usr/bin/env python3
"""A run killed with SIGKILL leaves readable output (called by ctest).

  kill_test.py dem   SLUICE SCENE WORKDIR
      Runs a DEM scene, kills it with SIGKILL three times at different moments
      while it writes its series, and checks each time that every .pvd index is
      valid XML naming files that exist and that every .csv row is whole.

  kill_test.py fluid SLUICE SCENE WORKDIR
      Runs a time-dependent fluid scene with checkpoints once uninterrupted, and
      once killed with SIGKILL after its second checkpoint and restarted from
      it into the same directory. The restarted fluid.csv must be the
      uninterrupted one: one header, the same times in the same order, the same
      values (to 1e-6 relative; solver iteration counts aside).

Exits non-zero, saying why, when a check fails.
"""
import os
import shutil
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET


def fail(why):
    print("FAILED: " + why)
    sys.exit(1)


def check_series(directory):
    """Every .pvd parses and names existing files; every .csv row is whole."""
    n_pvd = n_rows = 0
    for root, _, files in os.walk(directory):
        for name in files:
            path = os.path.join(root, name)
            if name.endswith(".pvd"):
                try:
                    tree = ET.parse(path)
                except ET.ParseError as e:
                    fail("%s is not valid XML: %s" % (path, e))
                for ds in tree.iter("DataSet"):
                    if not os.path.exists(os.path.join(root, ds.get("file"))):
                        fail("%s names %s, which does not exist" % (path, ds.get("file")))
                n_pvd += 1
            elif name.endswith(".csv"):
                text = open(path).read()
                if text and not text.endswith("\n"):
                    fail("%s ends in a half-written row" % path)
                rows = [r for r in text.splitlines() if not r.startswith("#")]
                for r in rows:
                    if r.count(",") != rows[0].count(","):
                        fail("%s has an incomplete row: '%s'" % (path, r))
                n_rows += len(rows)
    return n_pvd, n_rows


def wait_for(predicate, proc, seconds):
    end = time.time() + seconds
    while time.time() < end:
        if predicate():
            return True
        if proc.poll() is not None:
            return False
        time.sleep(0.01)
    return False


def csv_rows(path):
    if not os.path.exists(path):
        return 0
    return sum(1 for _ in open(path)) - 1


def dem(sluice, scene, work):
    for attempt, rows_before_kill in enumerate((3, 12, 25)):
        d = os.path.join(work, "kill-%d" % attempt)
        shutil.rmtree(d, ignore_errors=True)
        os.makedirs(d)
        shutil.copy(scene, d)
        proc = subprocess.Popen([sluice, os.path.basename(scene)], cwd=d,
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        csv = os.path.join(d, "output-kill", "particles.csv")
        if not wait_for(lambda: csv_rows(csv) >= rows_before_kill, proc, 120):
            fail("the scene ended or stalled before it was killed (rows: %d)" % csv_rows(csv))
        time.sleep(0.003 * attempt)
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        n_pvd, n_rows = check_series(d)
        if n_pvd == 0 or n_rows < rows_before_kill:
            fail("killed run %d left %d .pvd and %d .csv rows" % (attempt, n_pvd, n_rows))
        print("killed after %d rows: %d .pvd valid, %d whole .csv rows" %
              (rows_before_kill, n_pvd, n_rows))


def summary(out):
    return [l for l in out.splitlines() if l.startswith("final:")]


def read_csv(path):
    """The rows, without the solver's iteration counts: a restart rebuilds the
    preconditioner, so GMRES may take a few iterations more or fewer."""
    lines = open(path).read().splitlines()
    header = [l for l in lines if l.startswith("time,")]
    if len(header) != 1:
        fail("%s has %d header lines" % (path, len(header)))
    keep = [k for k, name in enumerate(header[0].split(",")) if not name.endswith("_iterations")]
    return [[float(l.split(",")[k]) for k in keep] for l in lines[1:]]


def fluid(sluice, scene, work):
    text = open(scene).read()
    # Uninterrupted.
    a = os.path.join(work, "uninterrupted")
    shutil.rmtree(a, ignore_errors=True)
    os.makedirs(a)
    shutil.copy(scene, a)
    ref = subprocess.run([sluice, os.path.basename(scene)], cwd=a, capture_output=True,
                         text=True)
    if ref.returncode != 0:
        fail("the uninterrupted run failed: " + ref.stderr)
    # Killed after the second checkpoint, then restarted from it.
    b = os.path.join(work, "killed")
    shutil.rmtree(b, ignore_errors=True)
    os.makedirs(b)
    shutil.copy(scene, b)
    out = os.path.join(b, "output-kill")
    proc = subprocess.Popen([sluice, os.path.basename(scene)], cwd=b,
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    state = os.path.join(out, "fluid-checkpoint.state")

    def second_checkpoint_and_more():
        if not os.path.exists(state):
            return False
        try:
            steps = int([l for l in open(state) if l.startswith("steps ")][0].split()[1])
        except (IndexError, ValueError):
            return False
        return steps >= 10 and csv_rows(os.path.join(out, "fluid.csv")) >= steps + 2
    if not wait_for(second_checkpoint_and_more, proc, 300):
        fail("the scene ended or stalled before its second checkpoint")
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    check_series(b)
    restart = text.replace("subsection fluid time",
                           "subsection fluid time\n  set restart from = output-kill/fluid-checkpoint",
                           1)
    open(os.path.join(b, "restart.prm"), "w").write(restart)
    res = subprocess.run([sluice, "restart.prm"], cwd=b, capture_output=True, text=True)
    if res.returncode != 0:
        fail("the restart failed: " + res.stderr)
    check_series(b)
    x = read_csv(os.path.join(a, "output-kill", "fluid.csv"))
    y = read_csv(os.path.join(out, "fluid.csv"))
    if [r[0] for r in x] != [r[0] for r in y]:
        fail("the restarted series has times %s, the uninterrupted one %s" %
             ([r[0] for r in y], [r[0] for r in x]))
    for rx, ry in zip(x, y):
        for u, v in zip(rx, ry):
            if abs(u - v) > 1e-6 * max(abs(u), abs(v), 1e-30):
                fail("row at t = %g differs: %s against %s" % (rx[0], ry, rx))
    print("killed after the checkpoint at step 10 and restarted: fluid.csv has %d rows, "
          "one header, equal to the uninterrupted run's" % len(y))
    print("uninterrupted: " + " ".join(summary(ref.stdout)))
    print("restarted:     " + " ".join(summary(res.stdout)))


if __name__ == "__main__":
    if len(sys.argv) != 5 or sys.argv[1] not in ("dem", "fluid"):
        fail(__doc__)
    mode, sluice, scene, work = sys.argv[1:]
    os.makedirs(work, exist_ok=True)
    (dem if mode == "dem" else fluid)(sluice, os.path.abspath(scene), work)
