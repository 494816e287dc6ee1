"""Micropillar friction explorer: the Panel dashboard served by ``panel serve app``.

Data flows one way: the controls (``state.ExplorerState``, mirrored in the URL by
``urlstate``) -> one ``results.SessionResults`` per session, which owns every computation
(each result a ``slot.Slot``) and hands it to the server's worker processes (``jobs``: the work pool,
``lanes``: its workers and fair queues, ``result_cache``: shared results; ``worker``: the
functions they run; ``pages``: the page gate; ``opening``: a light page at once, the
dashboard once the browser has it, each update in one message; ``edge``: the server's
guards on Panel's internals, on the tested versions only) -> the views (``views``), renderers that
declare which results they draw (``param.depends``) with the figure functions of
``figures``. Also: ``reproduce`` (the paper's figures drawn), ``healthcheck`` (the
container health check), ``export`` (CSV) and ``texts``; ``main.py`` builds the page and
``app_hooks.py`` warms the kernel and the workers, rehearses the page and installs the
guards when the server starts; ``trace``: timestamps along an update for the benchmarks.

``app`` is an ordinary installed package (``pip install .`` or ``pip install -e .``
installs it beside ``model``): ``panel serve app`` runs ``app/main.py``, which imports
``app`` by name, so the server, its worker processes and the tests share one copy.
"""
