#!/usr/bin/python3
"""`shpb report DIR`: figures and a one-page HTML report from any shpb output folder.

The entry point `shpb report` runs (src/app/report.cpp). The package shpb_report beside this file
does the work (its __init__ lists the modules); `shpb` finds both under share/shpb/ — beside bin/
once installed, in the build tree after a build.
"""
import os
import signal
import sys


def stop_with_parent() -> None:
    """shpb killed outright (SIGKILL) cannot pass a signal on: Linux sends SIGTERM to this script
    when its parent dies (prctl PR_SET_PDEATHSIG), so that it stops rather than put a report in
    place after shpb is gone. Asked first, before the long imports; a parent gone already (shpb
    names itself in SHPB_PARENT_PID) ends the script at once."""
    try:
        import ctypes
        ctypes.CDLL(None).prctl(1, int(signal.SIGTERM))  # 1: PR_SET_PDEATHSIG
    except (OSError, AttributeError):  # not Linux: the report is then finished
        return
    if os.environ.get("SHPB_PARENT_PID", str(os.getppid())) != str(os.getppid()):
        sys.exit(130)


stop_with_parent()
sys.dont_write_bytecode = True  # never write __pycache__ into an installed share/shpb/
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from shpb_report.main import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main(sys.argv))
