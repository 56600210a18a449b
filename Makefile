# auszug: two set-up commands, `make run` and `make test`, both work on a fresh machine.
PY      ?= python3
VENV    := .venv
BIN     := $(VENV)/bin
STAMP   := $(VENV)/.installed
OUT     ?= out

NODE_STAMP := web/node_modules/.installed

.PHONY: run test install web protocol bench clean

$(STAMP): pyproject.toml
	$(PY) -m pip install --quiet --disable-pip-version-check uv || $(PY) -m pip install --quiet --user uv
	$(PY) -m uv venv --quiet --allow-existing --python $(PY) $(VENV)
	$(PY) -m uv pip install --quiet --python $(BIN)/python -e ".[dev]"
	touch $(STAMP)

# the lifting's sparse LDL^T kernels (our C, loaded with ctypes; without them the lift uses QDLDL alone);
# Debian's gcc is installed if there is no C compiler
LDL_SO := src/auszug/lifting/ldl-kernels.so

$(LDL_SO): src/auszug/lifting/_ldl.c
	command -v $(CC) >/dev/null 2>&1 || $(SUDO) apt-get install -y gcc || ($(SUDO) apt-get update && $(SUDO) apt-get install -y gcc)
	$(CC) -O2 -shared -fPIC -o $@ $<

install: $(STAMP) $(LDL_SO)

# three.js for the glTF check (and the studio front end): from the npm registry, pinned by package-lock.json
$(NODE_STAMP): web/package.json web/package-lock.json
	cd web && npm ci --no-audit --no-fund
	touch $(NODE_STAMP)

# the studio front end: Vite builds web/ into the Python package (gitignored, shipped in the wheel)
WEB_BUILD := src/auszug/studio/static/index.html
WEB_SRC   := $(wildcard web/src/*.ts web/src/*.css) web/index.html web/tracery.html web/vite.config.ts web/tsconfig.json

$(WEB_BUILD): $(NODE_STAMP) $(WEB_SRC)
	cd web && npm run --silent build -- --logLevel warn

# Debian's chromium for the studio's end-to-end test (Playwright drives it; no browser downloads)
CHROMIUM := /usr/bin/chromium
SUDO     := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

$(CHROMIUM):
	$(SUDO) apt-get install -y chromium || ($(SUDO) apt-get update && $(SUDO) apt-get install -y chromium)

## web: build the studio front end into src/auszug/studio/static
web: $(WEB_BUILD)

## protocol: regenerate web/src/protocol.ts from src/auszug/studio/protocol.py
protocol: $(STAMP)
	$(BIN)/python -m auszug.studio.protocol > web/src/protocol.ts

## run: set up (the studio's front end too), then build and render the bundled teaching sheet and
## Basel drawings, and the tracery style gallery, into ./out
run: $(STAMP) $(LDL_SO) $(WEB_BUILD)
	$(BIN)/auszug demo -o $(OUT)
	$(BIN)/auszug tracery --gallery $(OUT)/tracery

## test: set up, then lint (ruff), type-check (mypy) and run every test
test: $(STAMP) $(LDL_SO) $(NODE_STAMP) $(WEB_BUILD) $(CHROMIUM)
	$(BIN)/ruff check src tests benchmarks
	$(BIN)/mypy src/auszug
	cd web && npm run --silent typecheck && npm test --silent
	AUSZUG_REQUIRE_NODE=1 $(BIN)/python -m pytest -n 2 -q

## bench: every benchmark (tables for benchmarks/RESULTS.md)
bench: $(STAMP) $(LDL_SO) $(WEB_BUILD) $(CHROMIUM)
	$(BIN)/python benchmarks/bench_engine.py
	$(BIN)/python benchmarks/bench_meshing.py
	$(BIN)/python benchmarks/bench_tracery.py --markdown
	$(BIN)/python benchmarks/bench_studio.py
	$(BIN)/python benchmarks/bench_studio_tracery.py

clean:
	rm -rf $(VENV) $(OUT) .pytest_cache $(LDL_SO)
