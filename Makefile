# The two commands a user needs:
#   make demo   install what is missing, build, run the whole pipeline on a built-in shape
#   make test   the same set-up and build, then every test through ctest
# `make` alone builds; the CLI is build/neuv.
#   make install PREFIX=DIR   build, then install the library, header, CLI,
#                             pkg-config file and CMake package under DIR
#   make python               build, then install the Python package (python/)
#                             into the venv .venv (VENV=DIR), Debian's Python

BUILD ?= build
JOBS  ?= $(shell nproc 2>/dev/null || echo 2)
PREFIX ?= /usr/local
PYTHON ?= /usr/bin/python3
VENV   ?= .venv

.PHONY: all build setup demo test bench install python sanitize clean

all: build

setup:
	@bash scripts/setup.sh

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

build: $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

demo: setup
	@$(MAKE) --no-print-directory build
	$(BUILD)/neuv demo -o demo-out

test: setup
	@$(MAKE) --no-print-directory build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: setup build
	cmake --build $(BUILD) --target benches -j $(JOBS)

install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

# Debian's Python (not whatever python3 comes first on PATH), a venv that sees
# Debian's NumPy, pip without network; libneuv.so is copied into the package.
python: setup
	@$(MAKE) --no-print-directory build
	bash python/install.sh $(VENV) $(BUILD)/libneuv.so $(PYTHON)

# The unit tests again, built with AddressSanitizer and UBSan.
sanitize: setup
	cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Debug -DNEUV_SANITIZE=ON
	cmake --build build-sanitize -j $(JOBS)
	cd build-sanitize && ASAN_OPTIONS=detect_leaks=1 ctest --output-on-failure -j $(JOBS) -L unit

clean:
	rm -rf $(BUILD) build-sanitize
