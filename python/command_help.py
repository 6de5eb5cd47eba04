"""Writes _command_help.py: `shpb <command> --help` of the executable, for the docstrings of
the Python functions (one source for both)."""
import subprocess
import sys

exe, out = sys.argv[1], sys.argv[2]
commands = ["simulate", "process", "compare", "fit", "study", "dispersion"]
# "Usage: <path of the built executable> simulate": the command as a user types it (an installed
# file names no build folder).
helps = {c: subprocess.run([exe, c, "--help"], capture_output=True, text=True, check=True)
         .stdout.replace(exe, "shpb") for c in commands}
with open(out, "w", encoding="utf-8") as f:
    f.write('"""`shpb <command> --help`, generated at build time from the executable."""\n')
    f.write(f"HELP = {helps!r}\n")
