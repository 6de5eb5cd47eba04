#pragma once
// Running another program (the report's Python script) and finding what shpb installs beside its
// executable.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace shpb {

// Runs `argv` (argv[0] looked up on PATH) and returns its exit status, 128 + N if it died from
// signal N (as a shell says), or -1 if it could not be started. With `quiet`, its stdout and
// stderr go to /dev/null; with `errors`, its stdout does and its stderr is read into *errors.
// SIGINT or SIGTERM arriving meanwhile is passed on to it (interrupted() then tells the caller).
int run_program(const std::vector<std::string>& argv, bool quiet, std::string* errors = nullptr);

// A file installed under share/shpb/, found from the binary that runs this code alone, so an
// installed shpb works without the source tree: PREFIX/bin/shpb → PREFIX/share/shpb/NAME;
// build/shpb → build/share/shpb/NAME (CMake copies it there); the Python module
// (build/python/shpb/_shpb*.so, PREFIX/lib/pythonX.Y/dist-packages/shpb/_shpb*.so) → the nearest
// share/shpb/NAME above its folder.
std::optional<std::filesystem::path> find_installed(const std::string& name);

// A Python that runs `check` (e.g. "import matplotlib, numpy"). Debian's python3-matplotlib
// belongs to /usr/bin/python3, which may not be the first python3 on PATH (README.md (Layout)):
// it is tried first.
std::optional<std::string> find_python(const std::string& check);

}  // namespace shpb
