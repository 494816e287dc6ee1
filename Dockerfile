# The dashboard (`panel serve app`) in a container; see docs/deploying.md.
#
#   docker build -t micropillar-friction .
#   docker run --rm -p 5006:5006 micropillar-friction      # http://localhost:5006/app
#
# tests/test_docker.py reads this file: it lints it with hadolint, replays the install,
# the warm-up and the CMD outside Docker, and runs the HEALTHCHECK against that server.
FROM python:3.11.14-slim-bookworm

# NUMBA_CACHE_DIR: numba's compile cache, filled at build time by `python -m model warmup`.
# MICROPILLAR_CACHE_DIR: the model's on-disk result cache (model/runs/cache.py).
# BOKEH_RESOURCES=server: BokehJS and Panel's JS/CSS come from this server, never a CDN.
# BOKEH_ALLOW_WS_ORIGIN: comma-separated host[:port] list of pages allowed to open the
#   websocket, as the browser sees them (set it to the public host behind a proxy).
# PYTHONMALLOC=malloc, MALLOC_ARENA_MAX=2: glibc's allocator, in two arenas, for every
#   object: the server hands a class's memory back once it has left (1.06 x the start
#   instead of 1.19 x with CPython's own, whose 1 MB arenas stay while a single object in
#   them lives; same CPU per update; docs/performance.md, "Load").
ENV PYTHONUNBUFFERED=1 \
    PYTHONMALLOC=malloc \
    MALLOC_ARENA_MAX=2 \
    PYTHONDONTWRITEBYTECODE=1 \
    PIP_DISABLE_PIP_VERSION_CHECK=1 \
    NUMBA_CACHE_DIR=/var/cache/micropillar/numba \
    MICROPILLAR_CACHE_DIR=/var/cache/micropillar/results \
    BOKEH_RESOURCES=server \
    BOKEH_ALLOW_WS_ORIGIN=localhost:5006,127.0.0.1:5006

RUN groupadd --system --gid 10001 micropillar \
    && useradd --system --uid 10001 --gid micropillar --create-home \
        --home-dir /home/micropillar --shell /usr/sbin/nologin micropillar \
    && mkdir -p /var/cache/micropillar/numba /var/cache/micropillar/results \
    && chown -R micropillar:micropillar /var/cache/micropillar

# The package and its dependencies, from the project's own pyproject.toml, each at the
# exact version in constraints.txt: the versions the test suite ran against (regenerate
# the file with `python .ci/constraints.py` in the tested environment).
# Both packages are installed: the app's modules import ``app`` by name (app/__init__.py).
WORKDIR /tmp/build
COPY pyproject.toml README.md constraints.txt ./
COPY model ./model
COPY app ./app
RUN pip install --no-cache-dir --constraint constraints.txt . \
    && rm -rf /tmp/build

# Only the app folder sits in the working directory, so every process (including the
# warm-up below) imports `model` from site-packages: numba keys its cache by the path of
# the source files, and this way the cache filled at build time is the one used at run time.
WORKDIR /srv/micropillar
COPY app ./app

# Numeric, so a runtime that enforces a non-root user can verify it.
USER 10001:10001
# The compiled kernel, and the disk-cached uniform arrays of the Load tab's four regime
# curves (7 loads each, the points app/compute.py asks for): the first visitor waits for neither.
RUN python -m model warmup \
    && python -m model sweep load --n 7 --workers 2 --out /var/cache/micropillar/load-curves.csv

EXPOSE 5006

# app/healthcheck.py: Panel's /liveness?endpoint=/app must answer (the server is up and
# not stuck), then a real session of /app must receive the dashboard. The second step makes
# an app that raises unhealthy: Panel shows it as an error page, and its liveness says 200.
# The first check after a start also starts worker processes, hence the long timeout.
HEALTHCHECK --interval=30s --timeout=30s --start-period=120s --retries=3 \
    CMD ["python", "-m", "app.healthcheck", "http://127.0.0.1:5006/", "--timeout", "25"]

# One server process: the model already runs in three worker processes per server
# (app/jobs.py), and a second server process would double them (about 230 MB each).
# No --num-threads: the app's callbacks only hand work to those workers.
# Sessions whose browser has gone are dropped after 60 s (checked every 10 s).
CMD ["panel", "serve", "app", "--address", "0.0.0.0", "--port", "5006", "--num-procs", "1", "--liveness", "--check-unused-sessions", "10000", "--unused-session-lifetime", "60000"]
