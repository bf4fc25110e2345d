# syntax=docker/dockerfile:1
# The urdflint validation service (HTTP API + web page on port 8000).
#   docker build -t urdflint .
#   docker run --rm -p 8000:8000 urdflint
# Dependencies come from requirements.lock (exact versions, regenerated with
# scripts/lock_image_requirements.py); keep PYTHON on the minor version it was locked on.
ARG PYTHON=3.11

FROM python:${PYTHON}-slim-bookworm AS base
# OpenMP and quadmath runtimes that the pin/cmeel wheels link against; slim images lack them.
# Debian versions are not pinned: bookworm point releases replace them (hence DL3008).
# hadolint ignore=DL3008
RUN apt-get update \
 && apt-get install -y --no-install-recommends libgomp1 libquadmath0 \
 && rm -rf /var/lib/apt/lists/*

FROM base AS build
ENV PIP_NO_CACHE_DIR=1 \
    PIP_DISABLE_PIP_VERSION_CHECK=1 \
    PIP_ROOT_USER_ACTION=ignore
# Locked dependencies first: this heavy layer (Pinocchio, SciPy, ...) stays cached across
# code changes. --no-deps + pip check: the lock must be complete, nothing is resolved here.
# The venv's pip is the one the lock was made with (the bundled one predates some metadata).
RUN python -m venv /opt/venv \
 && /opt/venv/bin/pip install --no-cache-dir pip==26.3
COPY requirements.lock /tmp/requirements.lock
RUN /opt/venv/bin/pip install --no-cache-dir --no-deps -r /tmp/requirements.lock \
 && /opt/venv/bin/pip check

# The project, built as a wheel with a pinned build backend (no build isolation, no download
# of an unpinned setuptools), then installed without dependencies. Then the slimming
# (cmeel headers ~200 MB, static archives) and a smoke test of the installed venv
# (python -I: never the source tree in /src).
WORKDIR /src
COPY pyproject.toml README.md ./
COPY urdflint ./urdflint
COPY rules ./rules
COPY server ./server
COPY fixtures ./fixtures
RUN pip install --no-cache-dir setuptools==84.2.1 \
 && pip wheel --no-cache-dir --no-deps --no-build-isolation --wheel-dir /tmp/dist . \
 && /opt/venv/bin/pip install --no-cache-dir --no-deps /tmp/dist/urdflint-*.whl \
 && /opt/venv/bin/pip check \
 && rm -rf /opt/venv/lib/python*/site-packages/cmeel.prefix/include \
 && find /opt/venv -name '*.a' -delete \
 && /opt/venv/bin/python -I -c "import pinocchio, trimesh, urdflint.server.app; \
assert pinocchio.buildModelFromUrdf('fixtures/models/example_arm.urdf').nq == 2" \
 && /opt/venv/bin/urdflint check --format json fixtures/models/example_arm.urdf > /dev/null

FROM base AS runtime
LABEL org.opencontainers.image.title="urdflint" \
      org.opencontainers.image.description="Linter and validation service for robot descriptions (URDF and xacro)" \
      org.opencontainers.image.licenses="Apache-2.0"
# Service limits (server/limits.py; override with docker run -e NAME=value). JOBS is set
# because the CPU count a container sees ignores its CPU quota: match it to --cpus. The
# workers' analysis cache is in /tmp (the user has no home); mount a volume there to keep it.
ENV PATH=/opt/venv/bin:$PATH \
    PYTHONDONTWRITEBYTECODE=1 \
    PYTHONUNBUFFERED=1 \
    TMPDIR=/tmp \
    URDFLINT_MAX_URDF_BYTES=5M \
    URDFLINT_MAX_ZIP_BYTES=100M \
    URDFLINT_TIMEOUT=60 \
    URDFLINT_JOBS=2 \
    URDFLINT_QUEUE=16 \
    URDFLINT_CACHE_DIR=/tmp/urdflint-cache \
    URDFLINT_CACHE_MAX_SIZE=512M
RUN groupadd --system --gid 10001 urdflint \
 && useradd --system --uid 10001 --gid 10001 --no-create-home --home-dir /nonexistent \
      --shell /usr/sbin/nologin urdflint
COPY --from=build /opt/venv /opt/venv
USER 10001:10001
EXPOSE 8000
# Liveness only (no curl in slim images); Kubernetes ignores HEALTHCHECK: probe /healthz and /readyz.
HEALTHCHECK --interval=30s --timeout=5s --start-period=20s --retries=3 \
  CMD ["python", "-c", "import sys, urllib.request; sys.exit(0 if urllib.request.urlopen('http://127.0.0.1:8000/healthz', timeout=4).status == 200 else 1)"]
CMD ["urdflint", "serve", "--host", "0.0.0.0", "--port", "8000"]
