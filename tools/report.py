#!/usr/bin/python3
"""`shpb report DIR`: figures and a one-page HTML report from any shpb output folder.

The entry point `shpb report` runs (src/app/report.cpp). The package shpb_report beside this file
does the work (its __init__ lists the modules); `shpb` finds both under share/shpb/ — beside bin/
once installed, in the build tree after a build.
"""
import os
import sys

sys.dont_write_bytecode = True  # never write __pycache__ into an installed share/shpb/
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from shpb_report.main import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main(sys.argv))
