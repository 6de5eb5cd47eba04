# Two commands (README): `make run` and `make test`. Both install missing Debian packages first.
BUILD      ?= build
JOBS       ?= $(shell nproc)
EXPERIMENT ?= experiments/classic-al6061
RESULTS    ?= results

.PHONY: run test build deps bench fuzz format clean

deps:
	@bash tools/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

run: build
	@bash tools/run-default.sh $(BUILD)/shpb $(EXPERIMENT) $(RESULTS)

test: build
	@bash tools/install-deps.sh chromium
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: deps
	@bash tools/bench.sh $(BUILD)

format:
	@clang-format -i $$(git ls-files 'src/*.cpp' 'src/*.hpp' 'tests/*.cpp' 'tests/*.hpp')

clean:
	@rm -rf $(BUILD)
