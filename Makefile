# Two commands (README): `make run` and `make test`. Both install missing Debian packages first.
BUILD      ?= build
JOBS       ?= $(shell nproc)
EXPERIMENT ?= experiments/classic-al6061
RESULTS    ?= results
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60
# One build folder for everything: optimised; `make test` adds the sanitized twin to it, where
# warnings are errors (CMakeLists.txt).
CONFIGURE = cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

.PHONY: run test check build deps bench fuzz docs format format-check clean

deps:
	@bash tools/install-deps.sh

# The executable (and the report script beside it).
build: deps
	@$(CONFIGURE) >/dev/null
	@cmake --build $(BUILD) -j $(JOBS) --target shpb

run: build
	@bash tools/run-default.sh $(BUILD)/shpb $(EXPERIMENT) $(RESULTS)

# Formatting first, then the suite twice in one CTest run: the optimised build, and the same test
# objects against the library built under AddressSanitizer + UBSan (tests named "sanitized: ...",
# all but those tagged [release-only]).
test: format-check
	@bash tools/install-deps.sh chromium parallel slurm-wlm munge
	@$(CONFIGURE) -DSHPB_SANITIZED_TWIN=ON >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The optimised suite alone (what a developer runs while working).
check: deps
	@bash tools/install-deps.sh chromium parallel slurm-wlm munge
	@$(CONFIGURE) -DSHPB_SANITIZED_TWIN=OFF >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

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
# fails when either is stale, or when a page shows a command with an option it does not have).
docs: build
	@python3 tools/doc_outputs.py --update $(BUILD)/shpb experiments/*/README.md docs/*.md README.md

bench: deps
	@bash tools/bench.sh $(BUILD)

FORMATTED = $$(git ls-files 'src/*.cpp' 'src/*.hpp' 'tests/*.cpp' 'tests/*.hpp' 'tools/*.cpp' 'python/*.cpp' 'python/*.hpp')
format:
	@clang-format -i $(FORMATTED)

# clang-format clean (the repository's .clang-format), checked by `make test`.
format-check:
	@command -v clang-format >/dev/null || bash tools/install-deps.sh clang-format
	@clang-format --dry-run -Werror $(FORMATTED)

clean:
	@rm -rf $(BUILD) $(FUZZ_BUILD)
