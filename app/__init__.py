"""Micropillar friction explorer: the Panel dashboard served by ``panel serve app``.

Modules: ``state`` (the controls, a ``param.Parameterized``), ``urlstate`` (the state in
the URL), ``compute``, ``worker`` and ``jobs`` (model calls in worker processes, caches,
newest-wins background jobs), ``figures`` (one function per figure), ``reproduce``
(the paper's figures drawn), ``healthcheck`` (the container health check), ``views``
(``pn.viewable.Viewer`` classes), ``export`` (CSV) and ``texts``; ``main.py`` builds the
page and ``app_hooks.py`` warms the kernel and the workers when the server starts.
"""
