# auszug: two set-up commands, `make run` and `make test`, both work on a fresh machine.
PY      ?= python3
VENV    := .venv
BIN     := $(VENV)/bin
STAMP   := $(VENV)/.installed
OUT     ?= out

NODE_STAMP := web/node_modules/.installed

.PHONY: run test install bench clean

$(STAMP): pyproject.toml
	$(PY) -m pip install --quiet --disable-pip-version-check uv || $(PY) -m pip install --quiet --user uv
	$(PY) -m uv venv --quiet --allow-existing --python $(PY) $(VENV)
	$(PY) -m uv pip install --quiet --python $(BIN)/python -e ".[dev]"
	touch $(STAMP)

install: $(STAMP)

# three.js for the glTF check (and the studio front end): from the npm registry, pinned by package-lock.json
$(NODE_STAMP): web/package.json web/package-lock.json
	cd web && npm ci --no-audit --no-fund
	touch $(NODE_STAMP)

## run: set up, then build and render the bundled teaching sheet and Basel drawings, and the
## tracery style gallery, into ./out
run: $(STAMP)
	$(BIN)/auszug demo -o $(OUT)
	$(BIN)/auszug tracery --gallery $(OUT)/tracery

## test: set up, then run every test
test: $(STAMP) $(NODE_STAMP)
	AUSZUG_REQUIRE_NODE=1 $(BIN)/python -m pytest -n 2 -q

## bench: every benchmark (tables for benchmarks/RESULTS.md)
bench: $(STAMP)
	$(BIN)/python benchmarks/bench_engine.py
	$(BIN)/python benchmarks/bench_meshing.py
	$(BIN)/python benchmarks/bench_tracery.py --markdown

clean:
	rm -rf $(VENV) $(OUT) .pytest_cache
