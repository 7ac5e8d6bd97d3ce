#!/usr/bin/python3
r"""Several picture scripts of vis/ in one Python process, so matplotlib and VTK are imported
(and an X server started by xvfb-run) once for all of an example's pictures, not once per
picture:

  batch.py charts.py --csv a.csv --x t --y e --out e.png ::: render_particles.py s.pvd --out f.png

Jobs are separated by ':::'; each job is a script of vis/ with a main(argv) and its arguments.
Every job runs even if an earlier one failed; the exit status is 0 only if all of them
succeeded, and each failure is one line on stderr naming the job.
"""
import importlib
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


def main(argv=None):
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    todo = list(jobs(sys.argv[1:] if argv is None else argv))
    if not todo:
        print("batch.py: no jobs (usage: batch.py SCRIPT ARGS... [::: SCRIPT ARGS...]...)", file=sys.stderr)
        return 2
    failed = sum(not run(j) for j in todo)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
