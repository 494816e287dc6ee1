"""Micropillar friction explorer: ``panel serve app`` serves this page at ``/app``.

Builds the page of one browser session from the URL's state; everything else lives in
the package (see ``app/__init__.py``).
"""
import panel as pn

from .views import Dashboard

pn.extension("mathjax", notifications=False)
Dashboard.from_session().servable(title="Micropillar friction explorer")
