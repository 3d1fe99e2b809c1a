# Skydeck: `make up` runs the whole system, `make test` sets up and runs the tests.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
ROS2_STAMP := $(VENV)/.installed-ros2

.PHONY: install install-ros2 install-vision bytecode up robot test test-deps lint bench clean

# The last line says how a new terminal finds `skydeck` (tests/services/launch/test_next_steps.py).
install: $(STAMP) bytecode
	@echo "skydeck is installed in $(VENV)/bin; in each new terminal, first: source $(abspath $(VENV))/bin/activate"

# Reinstall only when the lock or the project metadata change, so `make install` is idempotent.
$(STAMP): requirements.lock pyproject.toml web_ui/vendor/package-lock.json tests/clients/package-lock.json
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --require-hashes --no-deps -r requirements.lock
	$(BIN)/python -m pip install --quiet --no-deps --no-build-isolation -e .
	cd web_ui/vendor && npm ci --silent --no-audit --no-fund
	cd tests/clients && npm ci --silent --no-audit --no-fund
	touch $(STAMP)

# The project's own modules as bytecode, written here: where PYTHONDONTWRITEBYTECODE is set (CI,
# containers, sandboxes) every process would compile them again at each start, 0.1-0.2 s of CPU
# each (docs/performance.md). Only changed files are compiled again.
bytecode: $(STAMP)
	@$(BIN)/python -m compileall -q -j 0 services shared_models sim_server

# The ROS 2 bridge's extra (heavy: rclpy, Fast DDS, rosidl): its lock, then the interface
# packages no wheel ships, built with rosidl into the venv (again only when Skydeck's
# definitions change). `make install` stays light without it.
install-ros2: $(ROS2_STAMP)

$(ROS2_STAMP): $(STAMP) requirements-ros2.lock $(wildcard shared_models/*.py) services/protocols/ros2/interface_build.py
	$(BIN)/python -m pip install --quiet --require-hashes --no-deps -r requirements-ros2.lock
	$(BIN)/python -m services.protocols.ros2.interface_build
	touch $(ROS2_STAMP)

# The vision extra (cv_bridge over OpenCV), apart from the default install as DESIGN.md asks;
# requirements-vision.lock is pyproject.toml's `vision` extra pinned to requirements.lock.
install-vision: $(VENV)/.vision-installed

$(VENV)/.vision-installed: $(STAMP) requirements-vision.lock
	$(BIN)/python -m pip install --quiet --require-hashes --no-deps -r requirements-vision.lock
	touch $@

# The drone workshop, the drone landed and the AI waiting for /ai/start (the dashboard's Start
# mission button); `make up MISSION=true` starts the AI's mission at once.
MISSION ?= false
up: $(STAMP) bytecode
	$(BIN)/skydeck launch start_mission:=$(MISSION)

# The robot world (the second seed's Neato class): the core and the simulator's room.
robot: $(STAMP) bytecode
	$(BIN)/skydeck launch robot

# System packages the tests drive for real: Debian's Chromium (browser tests), the
# docker-compose tool (validates the compose files without an engine), zsh (completion),
# cmake and g++ (the ROS 2 interface build), iproute2 (the two-machine bridge test's netns), and
# Mesa's EGL and llvmpipe (libegl1, libgl1-mesa-dri: the camera's OpenGL renderer; without them
# the simulator falls back to PyBullet's, slower, and says so).
test-deps:
	@command -v chromium >/dev/null && command -v docker-compose >/dev/null && command -v zsh >/dev/null && \
		command -v cmake >/dev/null && command -v g++ >/dev/null && command -v ip >/dev/null && \
		ldconfig -p | grep -q 'libEGL.so.1 ' && ls /usr/lib/*/dri/swrast_dri.so >/dev/null 2>&1 || \
		{ apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium docker-compose zsh cmake g++ make iproute2 libegl1 libgl1-mesa-dri >/dev/null; }

test: $(STAMP) install-vision test-deps install-ros2
	docker-compose -f docker-compose.yml config --quiet
	docker-compose -f docker-compose.yml -f docker-compose.robot.yml config --quiet
	$(BIN)/python -m pytest -q

lint: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/mypy services shared_models sim_server benchmarks

bench: $(STAMP) bytecode
	$(BIN)/skydeck bench --out bench.json

clean:
	rm -rf $(VENV) .pytest_cache build *.egg-info
