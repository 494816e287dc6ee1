"""Server hooks (``panel serve app`` runs ``on_server_loaded`` once, before any request).

* The compiled kernel is loaded and the worker processes started, so the first page is as
  quick as the next; on a first start after installing (nothing in numba's cache) that
  compile runs in the background while pages are served and say so.
* The dashboard is built once (``app.opening.rehearse``) when the solver is ready, so the
  first visitor's page holds the event loop no longer than the next one's.
* A client without room in the page gate (``app.pages``) is sent to the busy page before
  any session is made (Panel's ``authorize_callback``: ``app.opening.admit_or_busy``).
* The serving edge's guards (``app.edge``: security headers, queued writes) are installed
  on the tested stack; on another one the server says so in one line.
* Bokeh's expensive error diagnostics are off in the server (``quiet_diagnostics``).
* Panel's default design, its parameters worked out once per component type and page
  instead of at every property update (``app.steady_design``).
"""
import logging
import os

import panel as pn
from bokeh.settings import settings

from app.edge import install
from app.heap import page_built
from app.jobs import start_warm_up
from app.opening import admit_or_busy, rehearse
from app.steady_design import use_steady_design


log = logging.getLogger(__name__)

#: The environment variable of Bokeh's setting ``perform_error_diagnostics``.
DIAGNOSTICS_ENV = "BOKEH_PERFORM_ERROR_DIAGNOSTICS"


def quiet_diagnostics(environ=os.environ) -> bool:
    """Turn off Bokeh's "expensive error diagnostics" for this server, unless the
    environment sets ``BOKEH_PERFORM_ERROR_DIAGNOSTICS`` (a developer's choice wins).
    Returns whether it turned them off.

    With them on (Bokeh's default), every attribute a model lacks is answered with
    close-match suggestions (``difflib``) and every callback's signature is checked when it
    is attached. Panel reads an attribute each of its custom components lacks at every
    update (``docs/upstream/esm_update_attribute_miss.py``), so each text written in place
    paid for suggestions nobody reads; the page build checked every callback.
    ``benchmarks/bench_diagnostics.py`` measures both with the setting on and off.
    """
    if DIAGNOSTICS_ENV in environ:
        return False
    settings.perform_error_diagnostics.set_value(False)
    return True


def on_server_loaded(server_context):
    if quiet_diagnostics():
        log.info("Bokeh's error diagnostics off (set %s=true to keep them)", DIAGNOSTICS_ENV)
    pn.config.authorize_callback = admit_or_busy
    use_steady_design()
    install()
    if start_warm_up():  # the solver compiles in the background: no results to show yet
        return
    try:
        log.info("the dashboard rehearsed in %.2f s", rehearse())
        page_built()  # what start-up made lives as long as the server (app.heap)
    except Exception:  # the pages will say what fails; the server still serves them
        log.exception("the dashboard could not be rehearsed")
