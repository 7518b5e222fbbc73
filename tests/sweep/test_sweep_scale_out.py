#!/usr/bin/python3
"""`fogradar sweep` beyond one process (docs/scale-out.md). The reference is the sweep run in one
process without MPI: points.csv, results.csv and limits.csv must be the same bytes for

- `mpirun -n 1`, `-n 2` and `-n 4` (one thread each; the ranks take the points from rank 0's queue
  in whatever order they finish);
- `--shard 0/3`, `1/3`, `2/3` run as separate processes into one directory, then `--merge`; then
  with a value added to an axis, the shards rerun and merged (and on MPI resumed): only the new
  points computed, the tables a single process's;
- a job whose worker rank is killed (SIGKILL) once a point is committed, then resumed on MPI
  (against the single process's run of the same, slower points).

Bad input under mpirun is refused once (one "fogradar:" line), with exit 2 and nothing written;
`--merge` of an incomplete sweep names the missing points; a build without MPI refuses a process
an MPI launcher started. MPIEXEC "none": a build without MPI (the shards, the merge and that refusal
are tested).

Usage: test_sweep_scale_out.py FOGRADAR MPIEXEC|none"""
import os
import signal
import subprocess
import sys
import tempfile
import time

fogradar, mpiexec = sys.argv[1], sys.argv[2]
launcher = [] if mpiexec == "none" else [mpiexec, "--allow-run-as-root", "--oversubscribe"]
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


def run(command, expect=0, env=None):
    done = subprocess.run(command, capture_output=True, text=True, env=env)
    check(done.returncode == expect,
          f"{' '.join(command)}: exit {done.returncode} (expected {expect}), {done.stderr.strip()}")
    return done


def same_tables(reference, other, what):
    for name in ("points.csv", "results.csv", "limits.csv"):
        with open(os.path.join(reference, name), "rb") as a, \
                open(os.path.join(other, name), "rb") as b:
            check(a.read() == b.read(), f"{what}: {name} differs from the single process's")
    print(f"{what}: points.csv, results.csv, limits.csv identical")


with tempfile.TemporaryDirectory() as work:
    def write(name, text):
        path = os.path.join(work, name)
        with open(path, "w") as f:
            f.write(text)
        return path

    # Points of unequal cost (the camera's frames and the lidar's scans vary with the axis), so the
    # queue's order differs from the points' order.
    write("small.toml", "[radar]\nmeasurements_per_step = 12\n[lidar]\nscans_per_step = 6\n"
          "[camera]\nframes_per_step = 3\n")
    sweep_file = write("sweep.toml", "[sweep]\nbase = \"small.toml\"\n[[axis]]\n"
                       "key = \"fog.extinction_per_km\"\n"
                       "values = [150.0, 300.0, 600.0, 900.0, 1200.0, 1500.0, 2000.0, 2500.0]\n"
                       "[[axis]]\nkey = \"camera.frames_per_step\"\nvalues = [2, 4]\n")
    points = 16
    reference = os.path.join(work, "serial")
    run([fogradar, "sweep", "--sweep", sweep_file, "--out", reference, "--threads", "1"])

    # Shards of a job array, then the merge.
    sharded = os.path.join(work, "sharded")
    early = run([fogradar, "sweep", "--merge", sharded], expect=2)
    check("--merge" in early.stderr, f"merge of nothing: {early.stderr!r}")
    for i in range(3):
        done = run([fogradar, "sweep", "--sweep", sweep_file, "--out", sharded, "--shard", f"{i}/3",
                    "--threads", "1"])
        check(f"shard {i}/3:" in done.stdout, f"shard {i}: {done.stdout!r}")
        if i == 1:
            missing = run([fogradar, "sweep", "--merge", sharded], expect=2)
            check("of 16 points are not" in missing.stderr and missing.stderr.count("\n") == 1,
                  f"merge of two shards of three: {missing.stderr!r}")
            print("merge before the last shard:", missing.stderr.strip())
    check(not os.path.exists(os.path.join(sharded, "results.csv")), "a shard wrote the tables")
    run([fogradar, "sweep", "--merge", sharded])
    same_tables(reference, sharded, "--shard 0/3, 1/3, 2/3 and --merge")
    for bad in ("3/3", "1", "-1/2", "a/b", "0/0"):
        done = run([fogradar, "sweep", "--sweep", sweep_file, "--out", sharded, "--shard", bad],
                   expect=2)
        check(done.stderr.startswith(f"fogradar: --shard = '{bad}': must be i/N"),
              f"--shard {bad}: {done.stderr!r}")
    done = run([fogradar, "sweep", "--merge", sharded, "--out", sharded], expect=2)
    check("--merge" in done.stderr, f"--merge with --out: {done.stderr!r}")

    # A value added to an axis: the shards rerun into the same directory compute only the two new
    # points (each point is committed by its resolved scenario, wherever it sits in the grid), and
    # the merge equals a single process's run of the extended sweep.
    with open(sweep_file) as f:
        extended_file = write("extended.toml", f.read().replace("[150.0, ", "[150.0, 450.0, "))
    extended = os.path.join(work, "extended")
    run([fogradar, "sweep", "--sweep", extended_file, "--out", extended, "--threads", "1"])
    computed = 0
    for i in range(3):
        done = run([fogradar, "sweep", "--sweep", extended_file, "--out", sharded, "--shard",
                    f"{i}/3", "--threads", "1"])
        computed += sum(int(line.split(" point")[0].split()[-1])
                        for line in done.stdout.splitlines() if " computed, " in line)
    check(computed == 2, f"shards of the sweep with a value added computed {computed} points, not 2")
    run([fogradar, "sweep", "--merge", sharded])
    same_tables(extended, sharded, "a value added, --shard 0/3, 1/3, 2/3 and --merge")

    if not launcher:
        env = dict(os.environ, OMPI_COMM_WORLD_RANK="0", OMPI_COMM_WORLD_SIZE="2")
        done = run([fogradar, "sweep", "--sweep", sweep_file, "--out", os.path.join(work, "no")],
                   expect=2, env=env)
        check("built without MPI" in done.stderr and not os.path.exists(os.path.join(work, "no")),
              f"a launched process in a build without MPI: {done.stderr!r}")
    else:
        for ranks in (1, 2, 4):
            out = os.path.join(work, f"n{ranks}")
            done = run(launcher + ["-n", str(ranks), fogradar, "sweep", "--sweep", sweep_file,
                                   "--out", out, "--threads", "1"])
            check(f"on {ranks} MPI rank" in done.stdout and done.stdout.count("sweep: ") == 1,
                  f"-n {ranks} output: {done.stdout!r}")
            same_tables(reference, out, f"mpirun -n {ranks}")
        # A value added to an axis, resumed on 2 ranks: only the 2 new points are computed.
        out = os.path.join(work, "n2")
        done = run(launcher + ["-n", "2", fogradar, "sweep", "--sweep", extended_file, "--out",
                               out, "--threads", "1", "--resume"])
        check("2 points computed, 16 committed before" in done.stdout,
              f"a value added, --resume on 2 ranks: {done.stdout!r}")
        same_tables(extended, out, "a value added, --resume on 2 ranks")

        # A worker killed once a point is committed: the job ends (the launcher takes about a
        # second to stop rank 0, so these points are slower); --resume on MPI finishes it.
        write("slow.toml", "[radar]\nmeasurements_per_step = 60\n[lidar]\nscans_per_step = 6\n"
              "[camera]\nframes_per_step = 3\n")
        with open(sweep_file) as f:
            slow_file = write("slow_sweep.toml", f.read().replace("small.toml", "slow.toml"))
        slow = os.path.join(work, "slow")
        run([fogradar, "sweep", "--sweep", slow_file, "--out", slow, "--threads", "1"])
        killed = os.path.join(work, "killed")
        job = subprocess.Popen(launcher + ["-n", "2", fogradar, "sweep", "--sweep", slow_file,
                                           "--out", killed, "--threads", "1"],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        state = os.path.join(killed, ".sweep")

        def rank_one():
            for pid in os.listdir("/proc"):
                try:
                    with open(f"/proc/{pid}/environ", "rb") as f:
                        environ = f.read().split(b"\0")
                    with open(f"/proc/{pid}/cmdline", "rb") as f:
                        command = f.read()
                except OSError:
                    continue
                # This job's rank 1 alone: another test (or user) may run a sweep beside it.
                if b"OMPI_COMM_WORLD_RANK=1" in environ and killed.encode() in command:
                    return int(pid)
            return None

        victim, killed_at = None, None
        deadline = time.monotonic() + 60
        while killed_at is None and time.monotonic() < deadline and job.poll() is None:
            victim = victim or rank_one()
            if victim and os.path.isdir(state) and \
                    any(n.endswith(".json") for n in os.listdir(state)):
                os.kill(victim, signal.SIGKILL)
                killed_at = time.monotonic()
            time.sleep(0.002)
        status = job.wait()
        at_kill = len([n for n in os.listdir(state) if n.endswith(".json")])
        check(killed_at is not None and status != 0 and at_kill < points,
              f"the killed job: rank 1 {victim}, exit {status}, {at_kill} of {points} committed")
        print(f"rank 1 killed: mpirun exit {status}, {at_kill} of {points} points committed")
        done = run(launcher + ["-n", "2", fogradar, "sweep", "--sweep", slow_file, "--out",
                               killed, "--threads", "1", "--resume"])
        print("resumed:", [line for line in done.stdout.splitlines() if "computed" in line])
        same_tables(slow, killed, "rank 1 killed, then --resume on 2 ranks")

        # Bad input: said once, by rank 0; every rank exits with 2; nothing written.
        bad = write("bad.toml",
                    "[[axis]]\nkey = \"fog.extinction_per_km\"\nvalues = [900.0, -5.0]\n")
        nowhere = os.path.join(work, "nowhere")
        for command in (["sweep", "--sweep", bad, "--out", nowhere],
                        ["sweep", "--sweep", sweep_file, "--out", nowhere, "--threads", "x"],
                        ["sweep", "--sweep", sweep_file, "--out", nowhere, "--shard", "0/2"]):
            done = run(launcher + ["-n", "3", fogradar] + command, expect=2)
            said = [line for line in done.stderr.splitlines() if line.startswith("fogradar:")]
            check(len(said) == 1, f"mpirun -n 3 {command[1:]}: said {said}")
            print(f"mpirun -n 3 fogradar {' '.join(command[3:])}: {said}")
        check(not os.path.exists(nowhere), "a refused sweep wrote its directory")

if failures:
    print(f"{len(failures)} failure(s)")
    sys.exit(1)
print("all checks passed")
