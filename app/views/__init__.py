"""The dashboard's views (``pn.viewable.Viewer`` subclasses), each reading one
``ExplorerState`` and drawing with the figure functions of ``app.figures``."""
from .array import ArrayView
from .arrays import LoadView, RegimeMapView
from .controls import Controls
from .design import DesignView
from .page import Dashboard
from .polar import PolarView
from .readouts import ReadoutsView
from .support import SupportView

__all__ = ["Dashboard", "ArrayView", "Controls", "SupportView", "ReadoutsView", "PolarView",
           "RegimeMapView", "LoadView", "DesignView"]
