# Two commands (README): `make run` and `make test`. Both install missing Debian packages first.
BUILD      ?= build
JOBS       ?= $(shell nproc)
EXPERIMENT ?= experiments/classic-al6061
RESULTS    ?= results
ASAN_BUILD ?= build-asan
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60
# Sanitizer reports fail the test that triggers them; leaks included.
SANITIZER_ENV = ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1 \
                UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

.PHONY: run test check build asan deps bench fuzz docs format format-check clean

deps:
	@bash tools/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

run: build
	@bash tools/run-default.sh $(BUILD)/shpb $(EXPERIMENT) $(RESULTS)

# The suite twice: the Release build, then the same tests under AddressSanitizer + UBSan
# (warnings are errors there). Formatting is checked first.
test: format-check check
	@$(MAKE) --no-print-directory asan
	@cd $(ASAN_BUILD) && $(SANITIZER_ENV) ctest --output-on-failure -j $(JOBS)

# The Release suite alone (what a developer runs while working; about a minute on 2 cores).
check: build
	@bash tools/install-deps.sh chromium parallel slurm-wlm munge
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# ASan + UBSan build of the executable and the tests (-O1: fast enough to run the whole suite).
asan: deps
	@cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
	       -DSHPB_SANITIZE=ON -DSHPB_WERROR=ON -DSHPB_BENCHMARKS=OFF >/dev/null
	@cmake --build $(ASAN_BUILD) -j $(JOBS) --target shpb shpb_tests

# libFuzzer targets of tests/fuzz (clang), each run FUZZ_SECONDS; not part of `make test`.
# FUZZ_TARGETS="fuzz_units fuzz_scene" runs a subset.
fuzz:
	@bash tools/install-deps.sh clang
	@cmake -S . -B $(FUZZ_BUILD) -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
	       -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" -DSHPB_FUZZ=ON >/dev/null
	@cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzz_targets
	@bash tests/fuzz/run_fuzzers.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_TARGETS)

# The printed output shown in the experiment READMEs and docs/commands.md, run again and rewritten,
# and the column tables of docs/outputs.md from src/core/output_schema.json (ctest docs.outputs
# fails when either is stale).
docs: build
	@python3 tools/doc_outputs.py --update $(BUILD)/shpb experiments/*/README.md docs/commands.md \
	  docs/outputs.md

bench: deps
	@bash tools/bench.sh $(BUILD)

FORMATTED = $$(git ls-files 'src/*.cpp' 'src/*.hpp' 'tests/*.cpp' 'tests/*.hpp' 'tools/*.cpp' 'python/*.cpp')
format:
	@clang-format -i $(FORMATTED)

# clang-format clean (the repository's .clang-format), checked by `make test`.
format-check:
	@command -v clang-format >/dev/null || bash tools/install-deps.sh clang-format
	@clang-format --dry-run -Werror $(FORMATTED)

clean:
	@rm -rf $(BUILD) $(ASAN_BUILD) $(FUZZ_BUILD)
