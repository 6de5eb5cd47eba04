"""Executes a notebook with nbclient (Debian python3-nbclient, python3-ipykernel) from its own
folder (where it finds the experiments; it writes only to temporary folders): every cell must run
without an error. The notebook file is not modified, and the temporary folders it makes (the tour
keeps its results in one, for its reader to look at) are made inside one this run removes: a test
run leaves nothing in the temporary folder."""
import os
import pathlib
import sys
import tempfile

import nbformat
from nbclient import NotebookClient

os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # the kernel's debugger notes
notebook = pathlib.Path(sys.argv[1]).resolve()
nb = nbformat.read(notebook, as_version=4)
# A cell that takes a minute has gone wrong (the whole tour runs in seconds).
cell_timeout_s = 120
with tempfile.TemporaryDirectory(prefix="shpb-notebook-") as scratch:
    os.environ["TMPDIR"] = scratch  # the kernel's tempfile folders, inherited by its process
    NotebookClient(nb, timeout=cell_timeout_s, kernel_name="python3",
                   resources={"metadata": {"path": str(notebook.parent)}}).execute()
print(f"executed {notebook.name}: {len(nb.cells)} cells")
