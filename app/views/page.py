"""The whole page: a header with the tab bar "Support" | "Polar (Fig. 11)" | "Regime map
(Fig. 5)" | "Load (Fig. 6)" | "Equations" (buttons, so it works from the keyboard), the
controls on the left, notices above the visible tab.

Sized for a 1280 x 720 screen without scrolling. The URL follows the state (debounced,
so dragging a slider does not flood the browser history); projector mode enlarges text
and lines everywhere.
"""
from __future__ import annotations

import io

import panel as pn
import param

from ..compute import polar_cached, polar_future
from ..export import sweep_csv, trajectory_csv
from ..state import URL_KEYS, ExplorerState
from ..texts import HELP
from ..urlstate import TABS
from .arrays import LoadView, RegimeMapView
from .controls import Controls
from .equations import EquationsView
from .polar import PolarView
from .readouts import ReadoutsView
from .support import SupportView
from .widgets import caption, look

TAB_TITLES = ("Support", "Polar (Fig. 11)", "Regime map (Fig. 5)", "Load (Fig. 6)", "Equations")
URL_DELAY_MS = 400
PROJECTOR_STYLES = {"--bokeh-font-size": "16px", "font-size": "16px", "color": "#000000"}
SCREEN_STYLES = {"--bokeh-font-size": "13px", "font-size": "13px", "color": "#18191D"}


class Dashboard(pn.viewable.Viewer):
    """Every view of one session, wired to one ``ExplorerState``."""

    messages = param.List(default=[], doc="notices and errors shown at the top of the page")

    def __init__(self, state: ExplorerState | None = None, **params):
        super().__init__(**params)
        self.state = state = state or ExplorerState()
        self._url_generation = 0
        self.support = SupportView(state)
        self.readouts = ReadoutsView(state, self.support)
        # The other tabs are built when first shown: a quicker first page.
        self.polar = self.regime_map = self.load = self.equations = None
        self._builders = {
            "polar": ("polar", lambda: PolarView(state, self.support)),
            "map": ("regime_map", lambda: RegimeMapView(state)),
            "load": ("load", lambda: LoadView(state, self.readouts)),
            "equations": ("equations", EquationsView)}
        self._holders = {tab: pn.Column(sizing_mode="stretch_width", margin=0)
                         for tab in self._builders}
        self.downloads = [
            pn.widgets.FileDownload(callback=self._trajectory_csv, filename="trajectory.csv",
                                    label="Trajectory CSV", css_classes=["download-trajectory"],
                                    **look("light"), sizing_mode="stretch_width",
                                    margin=(2, 3)),
            pn.widgets.FileDownload(callback=self._polar_csv, filename="polar_sweep.csv",
                                    label="Polar sweep CSV", css_classes=["download-polar"],
                                    **look("light"), sizing_mode="stretch_width",
                                    margin=(2, 3))]
        self.help = pn.pane.Markdown(HELP, styles={"font-size": "0.85em", "color": "#555"},
                                     margin=(0, 10), visible=not state.projector)
        self.controls = Controls(state, extra=[
            pn.pane.Markdown("**Download** (CSV)", margin=(4, 10, 0, 10)),
            pn.Row(*self.downloads, sizing_mode="stretch_width"),
            self.help])
        self.alert = pn.pane.Alert("", alert_type="warning", visible=False,
                                   css_classes=["page-notice"], margin=(2, 10),
                                   sizing_mode="stretch_width",
                                   stylesheets=[":host(.alert) {padding: 4px 10px;}",
                                                "p {margin: 0;}"])
        self.dismiss = pn.widgets.Button(**caption("Dismiss"), visible=False, width=80,
                                         css_classes=["notice-dismiss"], margin=(4, 4))
        self.dismiss.on_click(self._dismiss)
        self.tabs = pn.Tabs(
            (TAB_TITLES[0], pn.Row(self.support, self.readouts)),
            *((title, self._holders[tab]) for title, tab in zip(TAB_TITLES[1:], TABS[1:])),
            active=TABS.index(state.tab), dynamic=False, css_classes=["main-tabs"],
            sizing_mode="stretch_width", margin=0,
            stylesheets=[".bk-header {display: none;}"])
        # The tab bar: buttons, so the views are reachable with the keyboard (Tab, Space).
        self.tab_bar = pn.widgets.RadioButtonGroup.from_param(
            state.param.tab, options=dict(zip(TAB_TITLES, TABS)), description=None,
            **look("primary", "outline"), css_classes=["tab-bar"],
            margin=(8, 10, 0, 10))
        state.param.watch(self._on_state_tab, "tab")
        for view in (self.support, self.readouts):
            view.param.watch(self._collect, "error")
        state.param.watch(self._collect, "notice")
        state.param.watch(self._on_projector, "projector")
        state.param.watch(self._schedule_url, list(URL_KEYS))
        state.param.watch(self._name_downloads, ["k_r", "k_theta", "F_N", "theta0"])
        self._name_downloads()
        self._set_active(state.tab)
        self._collect()
        self._on_projector()

    @classmethod
    def from_session(cls) -> "Dashboard":
        """A dashboard whose state is read from the page URL (bad values: defaults + notice)."""
        state = ExplorerState()
        args = pn.state.session_args if pn.state.curdoc is not None else {}
        notices = state.load_query(args or {})
        page = cls(state)
        if notices:  # show the corrected state in the address bar once the page is up
            pn.state.onload(page._schedule_url)
        return page

    # ------------------------------------------------------------------ tabs
    def _on_state_tab(self, event) -> None:
        self.tabs.active = TABS.index(event.new)
        self._set_active(event.new)

    def _set_active(self, tab: str) -> None:
        self._build(tab)
        self.readouts.active = tab in ("support", "load")
        for view, name in ((self.polar, "polar"), (self.load, "load")):
            if view is not None:
                view.active = tab == name

    def _build(self, tab: str) -> None:
        """Build the view of ``tab`` the first time it is shown."""
        if tab not in self._builders or getattr(self, self._builders[tab][0]) is not None:
            return
        attribute, build = self._builders[tab]
        view = build()
        setattr(self, attribute, view)
        if "error" in view.param:
            view.param.watch(self._collect, "error")
        self._holders[tab].objects = [view]

    @property
    def views(self) -> list:
        """The views built so far."""
        return [v for v in (self.support, self.readouts, self.polar, self.regime_map,
                            self.load, self.equations) if v is not None]

    # ------------------------------------------------------------------ notices
    def _collect(self, *_events) -> None:
        errors = [v.error for v in self.views if "error" in v.param and v.error]
        self.messages = [m for m in [self.state.notice, *errors] if m]
        error = bool(errors)
        self.alert.alert_type = "danger" if error else "warning"
        self.alert.object = "  \n".join(self.messages)
        self.alert.visible = self.dismiss.visible = bool(self.messages)

    def _dismiss(self, _event) -> None:
        self.state.notice = ""
        for view in self.views:
            if "error" in view.param:
                view.error = ""

    # ------------------------------------------------------------------ URL, projector
    def _schedule_url(self, *_events) -> None:
        doc, location = pn.state.curdoc, pn.state.location
        if doc is None or location is None or doc.session_context is None:
            return
        self._url_generation += 1
        generation = self._url_generation

        def write():
            if generation == self._url_generation:
                location.search = self.state.to_search()
        doc.add_timeout_callback(write, URL_DELAY_MS)

    def _on_projector(self, *_events) -> None:
        self._root_styles = PROJECTOR_STYLES if self.state.projector else SCREEN_STYLES
        self.help.visible = not self.state.projector
        if hasattr(self, "_root"):
            self._root.styles = self._root_styles

    # ------------------------------------------------------------------ downloads
    def _trajectory_csv(self):
        return io.StringIO(trajectory_csv(self.support.data))

    def _polar_csv(self):
        """The polar sweep of the current springs and load; started here if the Polar tab
        has not computed it, and waited for briefly."""
        s = self.state
        sweep = polar_cached(s.params, s.array_beta, s.rtol)
        if sweep is None:
            try:
                sweep = polar_future(s.params, s.array_beta, s.rtol).result(timeout=3)
            except TimeoutError:
                return io.StringIO("# the polar sweep is still being computed: "
                                   "download again in a moment\n")
            except Exception as exc:
                return io.StringIO(f"# the polar sweep failed: {exc}\n")
        return io.StringIO(sweep_csv(sweep))

    def _name_downloads(self, *_events) -> None:
        s = self.state
        tag = f"kr{s.k_r:.3g}_kt{s.k_theta:.3g}_FN{s.F_N:.3g}"
        self.downloads[0].filename = f"trajectory_{tag}_theta0_{s.theta0:g}.csv"
        self.downloads[1].filename = f"polar_{tag}.csv"

    def __panel__(self):
        header = pn.Row(
            pn.pane.Markdown("### Micropillar friction explorer", margin=(0, 10), width=270,
                             disable_anchors=True, styles={"white-space": "nowrap"}),
            self.tab_bar, sizing_mode="stretch_width", height=46,
            css_classes=["page-header"])
        sidebar = pn.Column(self.controls, width=290, css_classes=["sidebar"], margin=0,
                            scroll=True, styles={"max-height": "calc(100vh - 50px)"})
        main = pn.Column(pn.Row(self.alert, self.dismiss, sizing_mode="stretch_width"),
                         self.tabs, sizing_mode="stretch_width", margin=0)
        self._root = pn.Column(header, pn.Row(sidebar, main, sizing_mode="stretch_width"),
                               sizing_mode="stretch_width", styles=self._root_styles,
                               css_classes=["dashboard"])
        return self._root
