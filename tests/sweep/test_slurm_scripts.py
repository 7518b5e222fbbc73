#!/usr/bin/python3
"""The Slurm scripts of docs/scale-out.md, as the page gives them (`sbatch --test-only` needs a
Slurm controller, which the build machines do not have). For each ```bash block that starts with
#!/bin/bash:

- `bash -n` accepts it;
- every #SBATCH line comes before the first command (sbatch reads no directive after it), names an
  option from sbatch's manual (a list here) and gives it a value of that option's form;
- it runs: the job-array script once per task with the variables Slurm sets (SLURM_ARRAY_TASK_ID,
  SLURM_ARRAY_TASK_COUNT, SLURM_CPUS_PER_TASK, SLURM_SUBMIT_DIR) and then the page's merge command;
  the MPI script with an `srun` that stands for `mpirun -n $SLURM_NTASKS` (its own options dropped).
  On a small study.toml both give points.csv, results.csv and limits.csv identical to one process's.

Usage: test_slurm_scripts.py FOGRADAR SOURCE_DIR MPIEXEC|none"""
import os
import re
import stat
import subprocess
import sys
import tempfile

fogradar, source, mpiexec = os.path.abspath(sys.argv[1]), sys.argv[2], sys.argv[3]
failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAIL:", what)


count = r"[1-9][0-9]*"
# sbatch(1) options the scripts may use, with the form of their values.
forms = {
    "job-name": r"[A-Za-z0-9_.-]+",
    "nodes": count,
    "ntasks": count,
    "ntasks-per-node": count,
    "cpus-per-task": count,
    "time": r"([0-9]+-)?[0-9]{1,2}:[0-9]{2}:[0-9]{2}",
    "output": r"[A-Za-z0-9_.%/-]+",
    "array": r"[0-9]+-[0-9]+(%[0-9]+)?",
    "partition": r"[A-Za-z0-9_,-]+",
    "mem": r"[0-9]+[KMGT]?",
}

with open(os.path.join(source, "docs", "scale-out.md")) as f:
    page = f.read()
scripts = [b for b in re.findall(r"```bash\n(.*?)```", page, re.S) if b.startswith("#!/bin/bash\n")]
check(len(scripts) == 2, f"{len(scripts)} Slurm scripts on the page, expected 2")
merge_lines = [line for b in re.findall(r"```sh\n(.*?)```", page, re.S) for line in b.splitlines()
               if "--merge" in line]
check(len(merge_lines) == 1, f"merge command lines: {merge_lines}")

with tempfile.TemporaryDirectory() as work:
    bin_dir = os.path.join(work, "bin")
    os.makedirs(bin_dir)
    os.symlink(os.path.abspath(fogradar), os.path.join(bin_dir, "fogradar"))
    launcher = "" if mpiexec == "none" else \
        f"{mpiexec} --allow-run-as-root --oversubscribe --bind-to none"
    # srun: its options dropped, then mpirun -n $SLURM_NTASKS.
    with open(os.path.join(bin_dir, "srun"), "w") as f:
        f.write("#!/bin/bash\nwhile [[ $1 == --* ]]; do shift; done\n"
                f"exec {launcher} -n \"$SLURM_NTASKS\" \"$@\"\n")
    os.chmod(os.path.join(bin_dir, "srun"), stat.S_IRWXU)
    env = dict(os.environ, PATH=bin_dir + ":" + os.environ["PATH"])
    with open(os.path.join(work, "small.toml"), "w") as f:
        f.write("[radar]\nmeasurements_per_step = 8\n[lidar]\nscans_per_step = 4\n"
                "[camera]\nframes_per_step = 2\n")
    with open(os.path.join(work, "study.toml"), "w") as f:
        f.write("[sweep]\nbase = \"small.toml\"\n[[axis]]\nkey = \"fog.extinction_per_km\"\n"
                "values = [200.0, 500.0, 900.0, 1400.0, 2000.0]\n")
    reference = os.path.join(work, "reference")
    subprocess.run([fogradar, "sweep", "--sweep", "study.toml", "--out", reference], cwd=work,
                   check=True, capture_output=True)

    def same_tables(out, what):
        for name in ("points.csv", "results.csv", "limits.csv"):
            try:
                with open(os.path.join(reference, name), "rb") as a, \
                        open(os.path.join(out, name), "rb") as b:
                    check(a.read() == b.read(), f"{what}: {name} differs from one process's")
            except OSError as e:
                check(False, f"{what}: {e}")
        print(f"{what}: the tables of one process")

    for number, script in enumerate(scripts):
        lines = script.splitlines()
        path = os.path.join(work, f"script{number}.sbatch")
        with open(path, "w") as f:
            f.write(script)
        syntax = subprocess.run(["bash", "-n", path], capture_output=True, text=True)
        check(syntax.returncode == 0, f"script {number}: bash -n: {syntax.stderr}")
        first_command = next(i for i, line in enumerate(lines)
                             if line.strip() and not line.startswith("#"))
        options = {}
        for i, line in enumerate(lines):
            if not line.startswith("#SBATCH"):
                continue
            check(i < first_command, f"script {number}: '{line}' comes after the first command")
            match = re.fullmatch(r"#SBATCH --([a-z-]+)=(\S+)", line)
            check(match is not None, f"script {number}: '{line}' is not '#SBATCH --option=value'")
            if match:
                name, value = match.groups()
                check(name in forms, f"script {number}: --{name} is not an sbatch option listed")
                check(name not in forms or re.fullmatch(forms[name], value) is not None,
                      f"script {number}: --{name}={value} is not of its form")
                options[name] = value
        print(f"script {number}: bash -n passes; #SBATCH {sorted(options)} well formed")
        out = os.path.join(work, "study")
        base = dict(env, SLURM_SUBMIT_DIR=work, SLURM_CPUS_PER_TASK="1", SLURM_JOB_ID="1")
        if "array" in options:
            first, last = map(int, options["array"].split("%")[0].split("-"))
            check(last - first + 1 == 16, f"the array's range {options['array']}")
            tasks = 3
            for task in range(tasks):
                done = subprocess.run(["bash", path], cwd=work, capture_output=True, text=True,
                                      env=dict(base, SLURM_ARRAY_TASK_ID=str(task),
                                               SLURM_ARRAY_TASK_COUNT=str(tasks)))
                check(done.returncode == 0, f"array task {task}: {done.stderr}")
            merge = merge_lines[0].split("--wrap", 1)[1].strip().strip('"') if merge_lines else ""
            done = subprocess.run(merge, shell=True, cwd=work, capture_output=True, text=True,
                                  env=base)
            check(done.returncode == 0, f"'{merge}': {done.stderr}")
            same_tables(out, f"the job array's script as {tasks} tasks, then '{merge}'")
        elif mpiexec != "none":
            done = subprocess.run(["bash", path], cwd=work, capture_output=True, text=True,
                                  env=dict(base, SLURM_NTASKS="2"))
            check(done.returncode == 0, f"MPI script: {done.stderr}")
            same_tables(out, "the MPI script on 2 ranks")
        else:
            print("a build without MPI: the MPI script is only parsed")
        subprocess.run(["rm", "-rf", out])

if failures:
    print(f"{len(failures)} failure(s)")
    sys.exit(1)
print("all checks passed")
