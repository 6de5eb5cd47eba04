"""python3 -m shpb_report DIR (the same as tools/report.py DIR)."""
import sys

from .main import main

sys.exit(main(sys.argv))
