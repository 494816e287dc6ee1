"""The whole page: a header with the tab bar "One support" | "Orientation (polar)" |
"Regime map" | "Load" | "Equations" (buttons, so it works from the keyboard; the paper's
figure numbers in their tooltip and the figures' titles), the controls on the left,
notices and the headline (the result in one sentence) above the visible tab.

The figures fill the window (``layout``): a 1280 x 720 laptop shows a whole tab without
scrolling, a 1920 x 1080 projector the same tab larger; projector mode enlarges text,
lines, slider handles and buttons. On a phone the controls fold above the plots, one
plot per row. The URL follows the state (written with the result a change brings; the page
makes a history entry once it has settled, so dragging a slider does not flood the
history) and Back/Forward restore the state of the entry (``browser.PageBehaviour``).
"""
from __future__ import annotations

import io
from typing import Callable

import panel as pn
import param

from ..export import sweep_csv, trajectory_csv
from ..jobs import solver_ready
from ..results import SessionResults
from ..state import URL_KEYS, ExplorerState
from ..texts import HELP
from ..defaults import TABS
from .access import PageAccess
from .array import ArrayView
from .arrays import LoadView, RegimeMapView
from .browser import PageBehaviour
from .export import ResultDownload, svg_button
from .offline_download import offline_button
from .code import CodeView
from .at_once import answer_at_once
from .controls import Controls
from .design import DesignView
from .equations import EquationsView
from .layout import (BODY_CSS, BUTTON_CSS, HEADER_CSS, ROOT_CSS, ROOT_PROJECTOR, ROOT_SCREEN,
                     SHRINK_CSS, SIDE_ROW_CSS, SIDEBAR_CSS)
from .polar import PolarView
from .readouts import HeadlineView, ReadoutsView
from .support import SupportView
from .widgets import caption, look

PREPARING = ("**Preparing the solver** (first start after installing: compiling, about "
             "10-20 s). The plots fill in when it is ready.")

#: The tab bar: what each tab shows, and the paper's figures it draws (tooltip).
TAB_TITLES = ("One support", "Array", "Orientation (polar)", "Regime map", "Load", "Equations",
              "Design")
TAB_FIGURES = ("Figs. 3, 7, Eq. 12", "Figs. 2a, 4", "Fig. 11", "Fig. 5", "Fig. 6", "Eqs. 3-13",
               "Eq. 5 in physical units, Figs. 5a, 11a")
URL_DELAY_MS = 400
#: Tabs whose figures fill the window (their views stretch both ways).
FILL_TABS = ("polar", "map", "load", "design")
PROJECTOR_STYLES, SCREEN_STYLES = ROOT_PROJECTOR, ROOT_SCREEN
#: Width of the controls (px) on a screen and in projector mode, and folded away.
SIDEBAR_WIDTH = {False: 290, True: 340}
FOLDED_WIDTH = 150
#: CSS class of the page's root: a client that opened a page waits for a model with it
#: (the dashboard is sent once the browser has the page, ``app.opening``).
DASHBOARD_CLASS = "dashboard"


#: The results each tab shows (``SessionResults.show``): only those are computed.
TAB_RESULTS = {"support": ("support", "uniform"), "array": ("support", "array"),
               "polar": ("support", "polar"),
               "map": ("support", "regime_map"), "load": ("support", "uniform", "load", "load_regimes"),
               "equations": ("support",),
               "design": ("support", "design_point", "design_array", "design_polar")}


class Dashboard(pn.viewable.Viewer):
    """The page of one session: controls -> ``SessionResults`` -> views.

    The page owns the state (``ExplorerState``) and the results (``SessionResults``); every
    view renders from them and none reads another view.
    """

    messages = param.List(default=[], doc="notices and errors shown at the top of the page")

    def __init__(self, state: ExplorerState | None = None, **params):
        super().__init__(**params)
        self.state = state = state or ExplorerState()
        self.results = results = SessionResults(state)
        self._url_generation = 0
        self._url_pending = False  # the state changed since the address was last written
        results.param.watch(self._url_with_result, "busy")
        views = dict(state=state, results=results)
        self.support = SupportView(**views)
        self.readouts = ReadoutsView(**views)
        self.headline = HeadlineView(**views)
        self.behaviour = PageBehaviour(search=state.to_search(), margin=0, width=0, height=0)
        self.behaviour.param.watch(self._on_history, "pops")
        self.behaviour.param.watch(self._on_narrow, "narrow")
        self.access = PageAccess(margin=0, width=0, height=0)
        # The other tabs are built when first shown: a quicker first page.
        self.array = self.polar = self.regime_map = self.load = self.equations = None
        self.design = None
        self._builders = {
            "array": ("array", lambda: ArrayView(**views)),
            "polar": ("polar", lambda: PolarView(**views)),
            "map": ("regime_map", lambda: RegimeMapView(**views)),
            "load": ("load", lambda: LoadView(**views)),
            "equations": ("equations", EquationsView),
            "design": ("design", lambda: DesignView(**views))}
        # On a phone a tab is never wider than the screen, whatever its desktop layout.
        # Views of figures that fill the window stretch both ways, and so do their holders
        # (said here, Panel does not override them with a warning at each page build).
        self._holders = {tab: pn.Column(
            sizing_mode="stretch_both" if tab in FILL_TABS else "stretch_width", margin=0,
            stylesheets=[SHRINK_CSS]) for tab in self._builders}
        self.downloads = [
            pn.widgets.FileDownload(callback=self._trajectory_csv, filename="trajectory.csv",
                                    label="Trajectory CSV", css_classes=["download-trajectory"],
                                    **look("light"), sizing_mode="stretch_width",
                                    margin=(2, 3), stylesheets=[BUTTON_CSS]),
            # Offered once the sweep is there ("computing…" until then, app.views.export).
            ResultDownload(lambda: self._polar_csv().getvalue(), "polar_sweep.csv", "polar",
                           results=results, name="polar", label="Polar sweep CSV")]
        self.help = pn.pane.Markdown(HELP, styles={"font-size": "0.85em", "color": "#555"},
                                     margin=(0, 10), visible=not state.projector)
        self.code = CodeView(**views)
        self.controls = Controls(state, extra=[
            pn.pane.Markdown("**Download** (CSV; the figures on screen as SVG)",
                             margin=(4, 10, 0, 10)),
            pn.Row(*self.downloads, sizing_mode="stretch_width"),
            svg_button("page-svg", label="Figures on screen (SVG)"),
            offline_button(state),
            pn.pane.Markdown("**Animation of the support** (for slides)",
                             margin=(4, 10, 0, 10)),
            self.support.export, self.code, self.help])
        self.alert = pn.pane.Alert("", alert_type="warning", visible=False,
                                   css_classes=["page-notice"], margin=(2, 10),
                                   sizing_mode="stretch_width",
                                   stylesheets=[":host(.alert) {padding: 4px 10px;}",
                                                "p {margin: 0;}"])
        # A first start after installing compiles the solver in the background: say so
        # until it is ready (the plots fill in then).
        self.preparing = pn.pane.Alert(PREPARING, alert_type="info", visible=not solver_ready(),
                                       css_classes=["page-preparing"], margin=(2, 10),
                                       sizing_mode="stretch_width",
                                       stylesheets=[":host(.alert) {padding: 4px 10px;}",
                                                    "p {margin: 0;}"])
        self._preparing_check = None
        if self.preparing.visible and pn.state.curdoc is not None \
                and pn.state.curdoc.session_context is not None:
            self._preparing_check = pn.state.add_periodic_callback(self._check_solver, 500)
        self.dismiss = pn.widgets.Button(**caption("Dismiss"), visible=False, width=80,
                                         css_classes=["notice-dismiss"], margin=(4, 4))
        self.dismiss.on_click(self._dismiss)
        self._support_row = pn.Row(self.support, self.readouts, css_classes=["support-tab"],
                                   sizing_mode="stretch_both", margin=0,
                                   stylesheets=[SIDE_ROW_CSS])
        self._complete = True  # see ``in_two_parts``
        self.tabs = pn.Tabs(
            (TAB_TITLES[0], self._support_row),
            *((title, self._holders[tab]) for title, tab in zip(TAB_TITLES[1:], TABS[1:])),
            active=TABS.index(state.tab), dynamic=False, css_classes=["main-tabs"],
            sizing_mode="stretch_both", margin=0,
            stylesheets=[".bk-header {display: none;}", SHRINK_CSS])
        # The tab bar: buttons, so the views are reachable with the keyboard (Tab, Space).
        self.tab_bar = pn.widgets.RadioButtonGroup.from_param(
            state.param.tab, options=dict(zip(TAB_TITLES, TABS)),
            description="; ".join(f"{t}: {f}" for t, f in zip(TAB_TITLES, TAB_FIGURES))
            + " of the paper (Sci. Rep. 11, 8093, 2021)",
            **look("primary", "outline"), css_classes=["tab-bar"],
            margin=(6, 10, 0, 10), stylesheets=[BUTTON_CSS])
        state.param.watch(self._on_state_tab, "tab")
        results.param.watch(self._collect, "errors")
        state.param.watch(self._collect, "notice")
        state.param.watch(self._on_projector, "projector")
        state.param.watch(self._schedule_url, list(URL_KEYS))
        # The files are named when asked for (``_trajectory_csv``, ``_polar_csv``): a name
        # written at every slider move would cost the page a message per move.
        self._name_downloads()
        self._set_active(state.tab)
        results.start()
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
        self.results.show(TAB_RESULTS[tab])

    def _build(self, tab: str) -> None:
        """Build the view of ``tab`` the first time it is shown."""
        if tab not in self._builders or getattr(self, self._builders[tab][0]) is not None:
            return
        attribute, build = self._builders[tab]
        view = build()
        setattr(self, attribute, view)
        self._holders[tab].objects = [view]

    @property
    def views(self) -> list:
        """The views built so far."""
        return [v for v in (self.support, self.readouts, self.array, self.polar, self.regime_map,
                            self.load, self.equations, self.design) if v is not None]

    # ------------------------------------------------------------------ notices
    def _collect(self, *_events) -> None:
        errors = self.results.error_messages
        self.messages = [m for m in [self.state.notice, *errors] if m]
        error = bool(errors)
        self.alert.alert_type = "danger" if error else "warning"
        self.alert.object = "  \n".join(self.messages)
        self.alert.visible = self.dismiss.visible = bool(self.messages)

    def _check_solver(self) -> None:
        if solver_ready():
            self.preparing.visible = False
            if self._preparing_check is not None:
                self._preparing_check.stop()
                self._preparing_check = None

    def _dismiss(self, _event) -> None:
        self.state.notice = ""
        self.results.clear_errors()

    # ------------------------------------------------------------------ URL, projector
    def _schedule_url(self, *_events) -> None:
        """The address follows the state: written with the next result the change brings
        (in its message: ``_url_with_result``), else ``URL_DELAY_MS`` later on its own.
        The page makes a history entry once the address has settled (``PageBehaviour``)."""
        doc = pn.state.curdoc
        if doc is None or doc.session_context is None:
            self.behaviour.search = self.state.to_search()
            return
        self._url_pending = True
        self._url_generation += 1
        generation = self._url_generation

        def write():
            if generation == self._url_generation:
                self._write_url()
        doc.add_timeout_callback(write, URL_DELAY_MS)

    def _write_url(self) -> None:
        self._url_pending = False
        self._url_generation += 1  # written: a write still scheduled has nothing to do
        self.behaviour.search = self.state.to_search()

    def _url_with_result(self, event) -> None:
        """A computation ended (its result is being applied, in one message): an address
        still to be written goes with it rather than in a message of its own."""
        if self._url_pending and set(event.old) - set(event.new):
            self._write_url()

    def _on_history(self, _event) -> None:
        """Back/Forward showed another address: show its state, and write that state
        canonically in place of the entry (never as a new one)."""
        popped = self.behaviour.popped
        self.behaviour.acked = self.behaviour.pops  # what follows answers this step
        self.behaviour.search = popped  # the address bar already shows it: nothing to push
        self.state.restore_query(popped)
        self._url_generation += 1  # the state's own (debounced) write is not needed
        self._url_pending = False
        canonical = self.state.to_search()
        self.behaviour.replace_search = canonical
        self.behaviour.search = canonical

    def _on_narrow(self, event) -> None:
        """A phone: the controls start folded above the plots."""
        if hasattr(self, "sidebar"):
            self.sidebar.collapsed = bool(event.new)

    def _on_projector(self, *_events) -> None:
        self._root_styles = PROJECTOR_STYLES if self.state.projector else SCREEN_STYLES
        self.help.visible = not self.state.projector
        if hasattr(self, "_root"):
            self._root.styles = self._root_styles
            if not self.state.projector:  # the controls fold only in projector mode
                self.sidebar.collapsed = False
            self._size_sidebar()

    def _size_sidebar(self, *_events) -> None:
        folded = self.sidebar.collapsed
        self.sidebar.width = FOLDED_WIDTH if folded else SIDEBAR_WIDTH[self.state.projector]

    # ------------------------------------------------------------------ downloads
    def _trajectory_csv(self):
        self._name_downloads()  # read by the button once this returns
        r = self.results  # with a pinned state A, A's trajectory beside B's
        return io.StringIO(trajectory_csv(r.support, pinned=r.support_A,
                                          comparing=r.comparing))

    def _polar_csv(self):
        """The polar sweep of the current springs and load (and of a pinned state A), from
        what is computed: never waits. If it is not computed yet, the sweep starts and the
        file says so."""
        self._name_downloads()  # read by the button once this returns
        r = self.results
        slots = [s for s in (r.slots["polar"], r.pinned_slot("polar")) if s is not None]
        for slot in slots:
            if not slot.current:
                slot.request()
        if not all(slot.current for slot in slots):
            return io.StringIO("# The polar sweep for these settings is being computed "
                               "(the Polar tab shows it): download again in a moment.\n")
        return io.StringIO(sweep_csv(r.polar, pinned=r.polar_A, comparing=r.comparing))

    def _name_downloads(self) -> None:
        """The downloads' file names, from the controls they are asked for at."""
        s = self.state
        tag = f"kr{s.k_r:.3g}_kt{s.k_theta:.3g}_FN{s.F_N:.3g}"
        self.downloads[0].filename = f"trajectory_{tag}_theta0_{s.theta0:g}.csv"
        self.downloads[1].download.filename = f"polar_{tag}.csv"

    def sent(self, doc) -> None:
        """The page's models are in ``doc`` and on their way: a slider moved in the
        browser reaches the state as its message arrives (``app.views.at_once``)."""
        answer_at_once(doc, self.controls.sliders)

    def in_two_parts(self) -> Callable[[], None] | None:
        """Leave the One-support tab's views and the root's CSS class (``DASHBOARD_CLASS``)
        out of the page until the function returned is called: a served page is sent in
        two messages (``app.opening``), each holding the event loop half as long.

        The support tab's views are ~410 of the page's ~530 models (its figures, their
        sources and the player); the rest (header, controls, the other tabs' holders) the
        other ~120. The root's class marks the page complete for whoever waits for it
        (``app.healthcheck``, the browser tests). Only for a page opened on that tab (None
        otherwise: one message): figures added to a hidden tab are never laid out, and
        BokehJS then fails on them ("inner_width is unset") as other views play."""
        if self.state.tab != TABS[0]:  # the One-support tab
            return None
        objects = list(self._support_row.objects)
        self._support_row.objects = []
        self._complete = False

        def rest() -> None:
            self._complete = True
            self._support_row.objects = objects
            if hasattr(self, "_root"):
                self._root.css_classes = [DASHBOARD_CLASS]
        return rest

    def __panel__(self):
        header = pn.Row(
            pn.pane.Markdown("### Micropillar friction explorer", margin=(0, 10), width=270,
                             disable_anchors=True, styles={"white-space": "nowrap"},
                             css_classes=["page-title"]),
            self.tab_bar, sizing_mode="stretch_width", min_height=46,
            css_classes=["page-header"], stylesheets=[HEADER_CSS])
        self.sidebar = pn.Card(
            self.controls, title="Controls", collapsed=False, collapsible=True,
            width=SIDEBAR_WIDTH[self.state.projector], css_classes=["sidebar"], margin=(0, 4),
            scroll=True, styles={"max-height": "calc(100vh - 50px)"},
            stylesheets=[SIDEBAR_CSS])
        self.sidebar.param.watch(self._size_sidebar, "collapsed")
        self.sidebar.collapsed = self.state.projector  # projected: the figures take the room
        main = pn.Column(self.preparing,
                         pn.Row(self.alert, self.dismiss, sizing_mode="stretch_width",
                                stylesheets=[SHRINK_CSS]),
                         self.headline, self.tabs, sizing_mode="stretch_both", margin=0,
                         css_classes=["main-area"], stylesheets=[SHRINK_CSS])
        # stretch_both down to the support's figures (which stretch both ways): said here,
        # Panel does not override the containers with a warning at each page build.
        self._root = pn.Column(header, pn.Row(self.sidebar, main, sizing_mode="stretch_both",
                                              css_classes=["page-body"],
                                              stylesheets=[BODY_CSS]),
                               self.behaviour, self.access, sizing_mode="stretch_both",
                               styles=self._root_styles,
                               css_classes=[DASHBOARD_CLASS] if self._complete else [],
                               stylesheets=[ROOT_CSS])
        return self._root
