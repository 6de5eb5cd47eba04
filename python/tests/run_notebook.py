"""Executes a notebook with nbclient (Debian python3-nbclient, python3-ipykernel) from its own
folder (where it finds the experiments; it writes only to temporary folders): every cell must run
without an error. The notebook file is not modified."""
import os
import pathlib
import sys

import nbformat
from nbclient import NotebookClient

os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # the kernel's debugger notes
notebook = pathlib.Path(sys.argv[1]).resolve()
nb = nbformat.read(notebook, as_version=4)
# A cell that takes a minute has gone wrong (the whole tour runs in seconds).
cell_timeout_s = 120
NotebookClient(nb, timeout=cell_timeout_s, kernel_name="python3",
               resources={"metadata": {"path": str(notebook.parent)}}).execute()
print(f"executed {notebook.name}: {len(nb.cells)} cells")
