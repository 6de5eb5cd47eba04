#pragma once
// `shpb process` in two halves (analysis/process_scene.hpp, analysis/process_outputs.hpp), for
// callers that keep the result in memory (the Python module); run_process() is the two in
// sequence.
#include "analysis/process_outputs.hpp"
#include "analysis/process_scene.hpp"
