#pragma once
// Interruption of a run: by a signal, or asked for by a host (the Python module).

namespace shpb {

// Interruption (SIGINT, SIGTERM): installed once, before main (main.cpp), and unblocked; long
// loops poll interrupted() and throw shpb::Interrupted so that OutputFolder's destructor cleans
// up. A second signal ends the process at once.
void install_interrupt_handlers();
bool interrupted();
// Throws Interrupted if a signal arrived: the one-line poll of a loop.
void throw_if_interrupted();
// For a host with its own signal handling (the Python module: Ctrl-C in a notebook): ask the
// running work to stop as a signal would, and forget the request once that work has stopped.
void request_interrupt();
void clear_interrupt();

}  // namespace shpb
