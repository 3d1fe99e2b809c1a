# One image for every Skydeck process: `skydeck core` and `skydeck run NODE` (either world).
# docker-compose.yml runs one container of it per process, the drone workshop; with
# docker-compose.robot.yml beside it, the robot world; see README "Run with Docker".
#
# Stages:
#   web-vendor  npm ci of web_ui/vendor (Swagger UI for the core's /docs, three.js for the
#               dashboard's 3D view); only the files served leave
#   build       a venv at /opt/skydeck: runtime dependencies from requirements-runtime.lock
#               (hash-checked), then the project itself as a wheel (no editable install)
#               and the Swagger UI and three.js files inside the installed web_ui package
#   final       python slim + that venv, a non-root user; no node, npm, pip, setuptools or compilers
#               (the base image's own pip, setuptools and wheel are removed too)
#
# Layer order: lock files first, sources last, so a code change rebuilds only the last layers.

ARG PYTHON_IMAGE=python:3.11-slim-bookworm
ARG NODE_IMAGE=node:20-bookworm-slim

# -- web-vendor: browser assets from the npm lock ----------------------------------------------
FROM ${NODE_IMAGE} AS web-vendor
WORKDIR /vendor
COPY web_ui/vendor/package.json web_ui/vendor/package-lock.json ./
RUN npm ci --omit=dev --ignore-scripts --no-audit --no-fund

# -- build: the venv ----------------------------------------------------------------------------
FROM ${PYTHON_IMAGE} AS build
ENV PIP_DISABLE_PIP_VERSION_CHECK=1 \
    PIP_NO_CACHE_DIR=1 \
    PYTHONDONTWRITEBYTECODE=1
# pybullet publishes x86_64 wheels only: elsewhere (arm64) it is compiled here, in this stage.
RUN if [ "$(dpkg --print-architecture)" != "amd64" ]; then \
        apt-get update \
        && apt-get install -y --no-install-recommends g++ \
        && rm -rf /var/lib/apt/lists/*; \
    fi
RUN python -m venv /opt/skydeck
# requirements-runtime.lock: requirements.lock's pins and hashes for pyproject.toml's runtime
# dependencies plus numpy, which pybullet's wheel imports (tests/test_containers.py checks both).
COPY requirements-runtime.lock /tmp/requirements-runtime.lock
RUN /opt/skydeck/bin/pip install --require-hashes --no-deps -r /tmp/requirements-runtime.lock
# SKYDECK_EXTRAS=ros2 (compose's ros2 profile: the image skydeck:ros2) adds the ROS 2 bridge's
# extra: rclpy, Fast DDS and rosidl from requirements-ros2.lock, and the interface packages no
# wheel ships, built here with cmake and g++ (which stay in this stage).
ARG SKYDECK_EXTRAS=""
COPY requirements-ros2.lock /tmp/requirements-ros2.lock
RUN if [ "$SKYDECK_EXTRAS" = "ros2" ]; then \
        apt-get update \
        && apt-get install -y --no-install-recommends cmake g++ make \
        && rm -rf /var/lib/apt/lists/* \
        && /opt/skydeck/bin/pip install --require-hashes --no-deps -r /tmp/requirements-ros2.lock; \
    fi
WORKDIR /src
COPY pyproject.toml README.md ./
COPY shared_models ./shared_models
COPY sim_server ./sim_server
COPY web_ui ./web_ui
COPY services ./services
# Dependencies are already in place (--no-deps); pip builds the wheel in a throwaway build env.
RUN /opt/skydeck/bin/pip install --no-deps .
RUN if [ "$SKYDECK_EXTRAS" = "ros2" ]; then /opt/skydeck/bin/python -m services.protocols.ros2.interface_build; fi
# The core serves Swagger UI and three.js from web_ui/vendor/node_modules next to the installed
# web_ui package (services/core/app.py); the package's folder is asked, not assumed. Of three.js
# only what the dashboard imports: the ES module build and the orbit controls.
COPY --from=web-vendor /vendor/node_modules/swagger-ui-dist /tmp/swagger-ui-dist
COPY --from=web-vendor /vendor/node_modules/three/LICENSE /vendor/node_modules/three/package.json /tmp/three/
COPY --from=web-vendor /vendor/node_modules/three/build /tmp/three/build
COPY --from=web-vendor /vendor/node_modules/three/examples/jsm/controls /tmp/three/examples/jsm/controls
RUN web_ui="$(/opt/skydeck/bin/python -I -c 'import pathlib, web_ui; print(pathlib.Path(web_ui.__file__).parent)')" \
    && mkdir -p "$web_ui/vendor/node_modules" \
    && mv /tmp/swagger-ui-dist "$web_ui/vendor/node_modules/swagger-ui-dist" \
    && mv /tmp/three "$web_ui/vendor/node_modules/three" \
    && /opt/skydeck/bin/python -m pip uninstall --yes setuptools pip
# Fail the build, not the first `docker compose up`, if a process cannot even import: the core
# (with its rosbridge and Foxglove endpoints), both worlds and every node `skydeck run` knows.
RUN cd / && /opt/skydeck/bin/python -I -c "import importlib, services.core.app, services.core.protocols.servers, sim_server.robot.node; from services.builtin_nodes import BUILTIN_NODES; [importlib.import_module(module) for module in BUILTIN_NODES.values()]" \
    && /opt/skydeck/bin/skydeck run --help >/dev/null

# -- final: the runtime image -------------------------------------------------------------------
FROM ${PYTHON_IMAGE}
ENV PATH=/opt/skydeck/bin:$PATH \
    PYTHONUNBUFFERED=1 \
    PYTHONDONTWRITEBYTECODE=1 \
    SKYDECK_HOST=0.0.0.0 \
    SKYDECK_STATE_DIR=/var/lib/skydeck
# The base image's own Python ships the packaging tools; the processes never install anything.
RUN /usr/local/bin/python -m pip uninstall --yes --quiet pip setuptools wheel \
    && useradd --system --uid 10001 --user-group --create-home --home-dir /home/skydeck skydeck \
    && mkdir -p /var/lib/skydeck \
    && chown skydeck:skydeck /var/lib/skydeck
COPY --from=build /opt/skydeck /opt/skydeck
USER skydeck
WORKDIR /home/skydeck
# The core, the nodes, and the core's rosbridge and Foxglove endpoints.
EXPOSE 8000 8001 8002 8003 8004 9090 8765
CMD ["skydeck", "core", "--host", "0.0.0.0"]
