# Candela: `make demo` and `make test` do all set-up on a fresh Debian 12 machine.
BUILD ?= build
JOBS ?= $(shell nproc)
PYTHON := /usr/bin/python3.11
# Blender and the tests must not inherit another interpreter's environment (pyenv, virtualenv).
CLEAN_ENV := env -u PYTHONPATH -u PYTHONHOME -u VIRTUAL_ENV

DEB_PACKAGES := blender cmake g++ make libembree-dev pybind11-dev libopenexr-dev libtbb-dev python3-dev \
    python3-numpy libgtest-dev libbenchmark-dev nlohmann-json3-dev libcli11-dev python3-pytest python3-matplotlib

.PHONY: all deps build demo test bench microbench accuracy parity sampling-docs bdpt-strategies fuzz test-sanitize robustness-report install-addon clean test-native test-blender

all: build

# Installs the Debian packages that are missing (apt-get update + install, as root or through sudo).
deps:
	@missing=$$(for p in $(DEB_PACKAGES); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "Installing missing Debian packages:" $$missing; \
	  if [ "$$(id -u)" = 0 ]; then SUDO=; else SUDO=sudo; fi; \
	  $$SUDO apt-get update && $$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends $$missing; \
	fi

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=$(PYTHON)

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	$(CLEAN_ENV) bin/candela-blender -b --factory-startup -noaudio --python-exit-code 1 --python examples/demo.py -- --out out

test: build
	cd $(BUILD) && $(CLEAN_ENV) ctest --output-on-failure -j 2

test-native: build
	cd $(BUILD) && ctest --output-on-failure -L native -j 2

test-blender: build
	cd $(BUILD) && $(CLEAN_ENV) ctest --output-on-failure -L blender

bench: build
	$(CLEAN_ENV) $(PYTHON) bench/bench.py --build $(BUILD)

# Error-vs-time report: docs/accuracy.md, docs/accuracy/*.png and measurements.csv (about 10 minutes idle, < 30 loaded).
accuracy: build
	$(CLEAN_ENV) $(PYTHON) bench/accuracy.py --build $(BUILD)

# Parity with Cycles 3.4 on scripted scenes at full size: build/parity/ and docs/parity.md (about 30 minutes;
# then the per-node suite, docs/parity_nodes.md, about 5 minutes;
# `make test` runs a quick mode).
parity: build
	$(CLEAN_ENV) $(PYTHON) tests/parity/parity.py --build $(BUILD) --docs docs
	$(CLEAN_ENV) $(PYTHON) tests/parity/parity.py --nodes --size 96 --build $(BUILD) --docs docs

# docs/sampling.md and docs/sampling/*.png: one picture, error and time per sampling technique (~15 minutes;
# the scenes' references are cached in build/sampling/cache).
bdpt-strategies: build
	$(CLEAN_ENV) bin/candela-blender -b --factory-startup -noaudio --python-exit-code 1 --python examples/bdpt_strategies_picture.py

sampling-docs: build
	$(CLEAN_ENV) $(PYTHON) examples/sampling_gallery.py --build $(BUILD)

# 20,000 random scenes under every integrator (make test runs 1,000).
fuzz: build
	CANDELA_FUZZ_COUNT=20000 $(BUILD)/bin/candela_robustness_tests --gtest_filter='Fuzz.*'

# The C++ suites and a short render under AddressSanitizer + UndefinedBehaviorSanitizer (own build directory).
test-sanitize: build
	cmake -S . -B $(BUILD)-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCANDELA_SANITIZE=ON \
	    -DCANDELA_ENABLE_PYTHON=OFF -DCANDELA_ENABLE_BENCH=OFF
	cmake --build $(BUILD)-sanitize -j $(JOBS) --target candela_tests candela_robustness_tests candela
	$(BUILD)-sanitize/bin/candela_tests
	CANDELA_FUZZ_COUNT=200 $(BUILD)-sanitize/bin/candela_robustness_tests
	$(CLEAN_ENV) $(PYTHON) tests/robustness/write_dump.py --build $(BUILD) $(BUILD)-sanitize/dump
	$(BUILD)-sanitize/bin/candela $(BUILD)-sanitize/dump -o $(BUILD)-sanitize/render.exr --samples 4

# docs/robustness.md from a fresh run of the robustness cases.
robustness-report: build
	$(CLEAN_ENV) $(PYTHON) tests/robustness/report.py --build $(BUILD)

microbench: build
	$(BUILD)/bin/candela_microbench

# Installs the built add-on (with its native module) into the user's Blender 3.4 add-on folder.
install-addon: build
	@dest="$${BLENDER_USER_SCRIPTS:-$$HOME/.config/blender/3.4/scripts}/addons/candela"; \
	rm -rf "$$dest" && mkdir -p "$$(dirname "$$dest")" && cp -r $(BUILD)/scripts/addons/candela "$$dest" && \
	echo "Installed to $$dest; enable 'Render: Candela' in Edit > Preferences > Add-ons (or run blender --addons candela)"

clean:
	rm -rf $(BUILD) out
