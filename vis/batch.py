#!/usr/bin/python3
r"""Several picture scripts of vis/ in one Python process, so matplotlib and VTK are imported
(and an X server started by xvfb-run) once for all of an example's pictures, not once per
picture:

  batch.py charts.py --csv a.csv --x t --y e --out e.png ::: render_particles.py s.pvd --out f.png

Jobs are separated by ':::'; each job is a script of vis/ with a main(argv) and its arguments.
Every job runs even if an earlier one failed; the exit status is 0 only if all of them
succeeded, and each failure is one line on stderr naming the job.

The jobs are spread over the cores this process may use (`--processes N` before the first job
to say how many; 1: one after the other): matplotlib (and VTK, when a job renders particles)
is imported once, then the process forks, and each worker takes the next job as it finishes
one. The pictures are the same either way; only their order of completion changes.
"""
import contextlib
import importlib
import io
import multiprocessing
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool
import os
import sys

SEPARATOR = ":::"


def jobs(argv):
    job = []
    for a in argv:
        if a == SEPARATOR:
            if job:
                yield job
            job = []
        else:
            job.append(a)
    if job:
        yield job


def run(job):
    script, args = job[0], job[1:]
    name, ext = os.path.splitext(os.path.basename(script))
    if ext != ".py" or os.path.dirname(script):
        print(f"batch.py: '{script}': expected a script name of vis/, e.g. charts.py", file=sys.stderr)
        return False
    saved_argv0, sys.argv[0] = sys.argv[0], script  # the script's own name in its messages
    try:
        importlib.import_module(name).main(args)
        return True
    except SystemExit as e:  # a script's own error exit (it printed why)
        if e.code in (0, None):
            return True
        print(f"batch.py: {script} exited with status {e.code}", file=sys.stderr)
    except Exception as e:  # noqa: BLE001 -- one broken picture must not stop the others
        print(f"batch.py: {script}: {type(e).__name__}: {e}", file=sys.stderr)
    finally:
        sys.argv[0] = saved_argv0
    return False


def processes_option(argv):
    """(processes, the rest of argv): --processes N if first, else the usable cores."""
    if len(argv) >= 2 and argv[0] == "--processes":
        return max(1, int(argv[1])), argv[2:]
    return len(os.sched_getaffinity(0)), argv


def preload(todo):
    """Imports the heavy modules the jobs share before the workers fork (each imports them once)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot  # noqa: F401
    if any(os.path.basename(j[0]) == "render_particles.py" for j in todo):
        import vtk  # noqa: F401


def run_captured(job):
    """run(job) in a worker: (its result, what it printed on stdout, on stderr), for the parent to
    print whole, so that the lines of jobs finishing together never interleave."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        ok = run(job)
    return ok, out.getvalue(), err.getvalue()


def run_all(todo, processes):
    """One result (True: the job succeeded) per job, in order."""
    processes = min(processes, len(todo))
    if processes <= 1:
        return [run(j) for j in todo]
    preload(todo)
    sys.stdout.flush()
    sys.stderr.flush()
    results = []
    # (a worker that dies, e.g. a crash inside VTK, fails its job and the ones left: no hang)
    with ProcessPoolExecutor(processes, mp_context=multiprocessing.get_context("fork")) as pool:
        for job, future in [(j, pool.submit(run_captured, j)) for j in todo]:
            try:
                ok, out, err = future.result()
                sys.stdout.write(out)
                sys.stdout.flush()
                sys.stderr.write(err)
                sys.stderr.flush()
                results.append(ok)
            except BrokenProcessPool:
                print(f"batch.py: {job[0]}: its worker process died", file=sys.stderr)
                results.append(False)
    return results


def main(argv=None):
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    try:
        processes, argv = processes_option(sys.argv[1:] if argv is None else argv)
    except ValueError:
        print("batch.py: --processes needs a whole number", file=sys.stderr)
        return 2
    todo = list(jobs(argv))
    if not todo:
        print("batch.py: no jobs (usage: batch.py [--processes N] SCRIPT ARGS... [::: SCRIPT ARGS...]...)",
              file=sys.stderr)
        return 2
    failed = sum(not ok for ok in run_all(todo, processes))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
