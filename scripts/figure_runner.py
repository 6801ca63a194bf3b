#!/usr/bin/env python3
"""Runs one figure script of scripts/ for railcontact (app/output/figures.cpp):

    figure_runner.py SCRIPT DIRECTORY

and tells the caller in its exit code and its last output line why a figure was not drawn, without
a traceback for the user to read:

    0  the figures are written
    3  matplotlib cannot be imported      last line: "matplotlib-missing<TAB>reason"
    4  a figure file cannot be written    last line: "write-failed<TAB>file<TAB>reason" (strerror)
    5  the script failed otherwise        last line: "script-failed<TAB>ExceptionType: message"

A write error is an OSError raised while a figure is saved (Figure.savefig: a full disk, a quota, a
read-only file system), named by the file being saved, or one of WRITE_ERRORS raised elsewhere in
the script (named by its file, or the directory)."""
import errno
import os
import runpy
import sys

# The errors of a write that failed for want of room or permission (not a bug of the script).
WRITE_ERRORS = {errno.ENOSPC, errno.EDQUOT, errno.EROFS, errno.EFBIG, errno.EIO, errno.EACCES, errno.EPERM}


def report(code, *fields):
    sys.stdout.flush()
    print("\t".join(str(f).replace("\t", " ").replace("\n", " ") for f in fields), file=sys.stderr)
    sys.stderr.flush()
    sys.exit(code)


class FigureWriteError(Exception):
    def __init__(self, path, reason):
        super().__init__(path, reason)
        self.path = path
        self.reason = reason


def main():
    if len(sys.argv) != 3:
        report(5, "script-failed", "usage: figure_runner.py SCRIPT DIRECTORY")
    script, directory = sys.argv[1], sys.argv[2]
    try:
        import matplotlib
        from matplotlib.figure import Figure
    except ImportError as e:
        report(3, "matplotlib-missing", e)

    save = Figure.savefig

    def savefig(self, fname, *args, **kwargs):
        try:
            return save(self, fname, *args, **kwargs)
        except OSError as e:
            reason = e.strerror or str(e)
            raise FigureWriteError(os.fspath(fname) if isinstance(fname, (str, os.PathLike)) else str(fname),
                                   reason) from None

    Figure.savefig = savefig
    matplotlib.use("Agg")
    sys.argv = [script, directory]
    try:
        runpy.run_path(script, run_name="__main__")
    except FigureWriteError as e:
        report(4, "write-failed", e.path, e.reason)
    except OSError as e:
        if e.errno not in WRITE_ERRORS:
            report(5, "script-failed", f"{type(e).__name__}: {e}")
        report(4, "write-failed", e.filename or directory, e.strerror or str(e))
    except SystemExit as e:
        if e.code not in (None, 0):
            report(5, "script-failed", f"exit status {e.code}")
    except Exception as e:  # noqa: BLE001 -- one line for the caller instead of a traceback
        report(5, "script-failed", f"{type(e).__name__}: {e}")


if __name__ == "__main__":
    main()
