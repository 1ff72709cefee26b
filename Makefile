# MC Studio — two commands on a fresh machine:
#   make run    set everything up and start the studio at http://127.0.0.1:8000 with projects/demo
#   make test   set everything up (incl. Debian's chromium) and run the whole suite
# Other targets: lint, check-api (generated client current?), api-types (regenerate it), bench, clean.

PYTHON ?= python3
VENV   ?= .venv
PY     := $(VENV)/bin/python
PORT   ?= 8000
VISER_PORT ?= 8080
PROJECT ?= projects/demo
SUDO   := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
FRONTEND_SRC := $(shell find frontend/src frontend/index.html frontend/vite.config.ts frontend/tsconfig*.json \
                  frontend/package.json -type f 2>/dev/null)

.PHONY: run test setup lint check-api api-types chromium bench clean

run: setup
	$(PY) -m mcstudio serve --project $(PROJECT) --port $(PORT) --viser-port $(VISER_PORT)

test: setup chromium
	$(PY) -m ruff check backend tests benchmarks
	$(PY) -m mcstudio validate projects/*/ backend/mcstudio/project/templates/*/
	$(MAKE) --no-print-directory check-api
	$(PY) -m pytest

setup: $(VENV)/.stamp frontend/dist/index.html

# --- Python ---------------------------------------------------------------------------------------------------
$(VENV)/.stamp: pyproject.toml
	@$(PYTHON) -c 'import sys; sys.exit(0 if sys.version_info >= (3, 11) else "MC Studio needs Python >= 3.11 (found %s)" % sys.version.split()[0])'
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test]'
	@touch $@

# --- Frontend -------------------------------------------------------------------------------------------------
frontend/node_modules/.stamp: frontend/package.json frontend/package-lock.json
	# npm ci refuses a lock written against a registry without every platform package; install honours the lock
	cd frontend && npm install --no-audit --no-fund
	@touch $@

frontend/dist/index.html: frontend/node_modules/.stamp $(FRONTEND_SRC)
	cd frontend && npm run build

# The TypeScript client types are generated from the OpenAPI document; both are committed and must be current.
check-api: $(VENV)/.stamp frontend/node_modules/.stamp
	@mkdir -p build
	$(PY) -m mcstudio.api.openapi_export build/openapi.json
	@diff -u frontend/openapi.json build/openapi.json || \
	  (echo "frontend/openapi.json is stale: run 'make api-types' and commit"; exit 1)
	cd frontend && npx --no-install openapi-typescript ../build/openapi.json -o ../build/schema.d.ts >/dev/null
	@diff -u frontend/src/api/schema.d.ts build/schema.d.ts || \
	  (echo "frontend/src/api/schema.d.ts is stale: run 'make api-types' and commit"; exit 1)
	@echo "API schema and generated client types are current"

api-types: $(VENV)/.stamp frontend/node_modules/.stamp
	$(PY) -m mcstudio.api.openapi_export frontend/openapi.json
	cd frontend && npm run gen:api

# --- Browser for the end-to-end tests (Debian package; Playwright's own download does not work here) ---------
chromium:
	@command -v chromium >/dev/null 2>&1 || ( $(SUDO) apt-get update -qq && \
	  $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null )
	@chromium --version

lint: $(VENV)/.stamp
	$(PY) -m ruff check backend tests benchmarks

bench: $(VENV)/.stamp
	$(PY) -m pip install --quiet -e '.[bench]' || echo "pyplcopen not installed: the side-by-side row is skipped"
	$(PY) -m benchmarks all

clean:
	rm -rf $(VENV) build frontend/node_modules frontend/dist test-artifacts .pytest_cache .ruff_cache
