/* The offline explorer's page: controls -> state (mirrored in the URL fragment,
 * fragment.js) -> the JavaScript kernel and arrays (arrays.js, in three Web Workers) ->
 * Bokeh's data sources, the headline and the uniform array's readout.
 *
 * window.explorer is the page's API (docs/offline.md):
 *   explorer.simulate({k_r, k_theta, F_N, theta0, beta, rtol, ...}) -> one contact, the
 *       quantities of `micropillar support --json` (synchronous, on the calling thread);
 *   explorer.state   -> the current state {k_r, k_theta, F_N, theta0_deg, beta_mode, beta, tab, ...};
 *   explorer.set({k_r: 0.5, ...}) -> change the state (as the sliders do) and redraw;
 *   explorer.preset("slider") -> a regime's springs;
 *   explorer.result  -> the last drawn result; explorer.drawn counts the redraws (texts
 *       included: they follow the support's figures after the paint, paint.js);
 *   explorer.rehearsed -> the support's figures rehearsed once the page was idle (support.js);
 *   explorer.keyToSupportMs -> for the last key presses that changed the state: ms from
 *       the key press to the first animation frame after the support's figures changed;
 *   explorer.ready   -> a Promise resolved at the first drawn plot;
 *   explorer.pending() -> true while the support's contact is computed or drawn;
 *   explorer.polar   -> the last orientation sweep (Fig. 11, drawn once its tab is shown;
 *       its ``key`` as the uniform array's), explorer.polarDrawn;
 *   explorer.uniform -> the last uniform array drawn (its ``key``: k_r,k_theta,F_N,beta),
 *       explorer.uniformDrawn.
 * Reads its configuration (ranges, defaults, regimes: from the Python model at pack time)
 * from the JSON element #mp-config and the kernel from #mp-kernel. Its Bokeh models are
 * found by models.js (the support's figures drawn by support.js), the polar and map tabs
 * added by tabs.js; its texts are readouts.js's, Fig. 11 polarview.js's, Fig. 5
 * mapview.js's.
 */
(function () {
  "use strict";
  var CONFIG = JSON.parse(document.getElementById("mp-config").textContent);
  var KERNEL = window.MicropillarKernel;
  var CONTROLS = CONFIG.controls;
  var MAX_STEPS = 1000000, HERE_STEPS = 2000;  // a contact this short: shortContact

  // ------------------------------------------------------------ state and fragment
  var FRAGMENT = window.MicropillarFragment;
  var KEYS = FRAGMENT.KEYS;
  function parseFragment(hash) { return FRAGMENT.parse(hash, CONFIG); }
  function fragment(s) { return FRAGMENT.write(s, CONFIG); }
  function inRange(key, x) { return FRAGMENT.inRange(CONFIG, key, x); }
  var state = FRAGMENT.defaults(CONFIG);

  // ------------------------------------------------------------ Bokeh models
  var doc = null, models = null, figures = null, polar = null, texts = null, laterTabs = null;
  function model(name) { return models.model(name); }
  function source(name) { return models.source(name); }
  function figure(name) { return models.figure(name); }
  function setData(map) { models.setData(map); }
  // Texts and the other views follow the support's figures after the paint (paint.js);
  // held while a newer contact is being computed.
  var PAINT = window.MicropillarPaint, later = new PAINT.Later(function () {
    return !!(contactChannel.inFlight || contactChannel.pending);
  }), keyClock = new PAINT.KeyClock(window);
  /** A Div's new text, written after the paint (the newest text for a Div wins). */
  function setText(name, text) { later.put(name, function () { model(name).text = text; }); }
  function esc(text) { return texts.esc(text); }
  var syncing = false;  // true while the page itself moves the controls
  function syncControls() {
    syncing = true;
    try {
      KEYS.forEach(function (k) {
        var c = CONTROLS[k], slider = model("slider-" + k);
        var v = c.log ? Math.log10(state[k]) : state[k];
        if (Math.abs(slider.value - v) > 1e-12) slider.value = v;
      });
      var tab = Math.max(0, CONFIG.offline_tabs.indexOf(state.tab));
      showTab(tab);
      if (model("tabs").active !== tab) model("tabs").active = tab;
      if (model("projector").active !== state.projector) model("projector").active = state.projector;
      if (model("beta-mode").value !== state.beta_mode) model("beta-mode").value = state.beta_mode;
    } finally { syncing = false; }
    applyProjector();
  }
  /** The polar and map tabs' models are added to the document when the tab is first
   * shown (tabs.js), then drawn in the current state. */
  function showTab(index) {
    if (!laterTabs.show(index)) return;
    models.added(CONFIG.projector);
    ({polar: polar, map: map})[CONFIG.offline_tabs[index]].show();
  }
  function showNotice(notices) {
    setText("notice", notices.length ? "<b>Link:</b> " + notices.map(esc).join("; ") : "");
  }

  // ------------------------------------------------------------ computing
  // Three job queues, each with its own Web Worker (jobs.js): the support's fixed array
  // (the Support tab, the headline), the orientation sweep (Fig. 11) and the uniform array
  // (the headline's average over all orientations), so neither array delays the support.
  var Channel = window.MicropillarJobs.Channel;
  var statusTimer = null;  // "computing…" only for a contact that takes a while
  var contactChannel = new Channel("contact", drawWhenReady, function (on) {
    clearTimeout(statusTimer);
    if (on) statusTimer = setTimeout(function () { if (doc) model("status").text = "computing…"; }, 200);
  });
  // The first contact (first.js), requested as the page's scripts run; drawn into the
  // document before its views are built.
  var first = null;
  function drawWhenReady(r, ms, input) {
    if (doc) drawSupport(r, ms, input);
    else if (first) first.keep(r, ms, input);
  }
  var sweepChannel = new Channel("sweep", drawPolar, function (on) {
    if (on) polar.status("computing the 72 orientations in the page…");
  });

  var uniformChannel = new Channel("uniform", drawUniform, function (on) {
    if (on) setText("uniform-readout", "<i>uniform array: computing in the page…</i>");
  });

  function arrayBeta(s) { return s.beta_mode === "fixed" ? s.beta : "self"; }
  function contactInput(s) {
    // The last contact's beta and slope start the solver when only theta0 changed
    // (arrays.js, "contact" with ``previous``: the same root to its tolerance, 1e-8).
    var r = explorer.result, previous = null;
    if (r && !r.beta_note && r.array_success && r.params.k_r === s.k_r &&
        r.params.k_theta === s.k_theta && r.params.F_N === s.F_N)
      previous = {beta: r.params.beta, slope: isFinite(r.beta_slope) ? r.beta_slope : null};
    return {beta: arrayBeta(s), previous: previous,
            input: {k_r: s.k_r, k_theta: s.k_theta, F_N: s.F_N, theta0: s.theta0_deg * Math.PI / 180,
                    rtol: 1e-6, samples: CONFIG.support_samples, max_steps: MAX_STEPS}};
  }
  function sweepInput(s) {
    return {theta0: CONFIG.polar_theta0, beta: arrayBeta(s),
            base: {k_r: s.k_r, k_theta: s.k_theta, F_N: s.F_N, rtol: 1e-6, max_steps: MAX_STEPS}};
  }
  function uniformInput(s) {  // app.worker.compute_uniform: tol UNIFORM_TOL
    return {beta: arrayBeta(s), tol: CONFIG.uniform_tol,
            input: {k_r: s.k_r, k_theta: s.k_theta, F_N: s.F_N}};
  }
  function arraysKey(s) { return [s.k_r, s.k_theta, s.F_N, arrayBeta(s)].join(","); }

  // ------------------------------------------------------------ drawing: the support
  var readyResolve;
  var explorer = {
    ready: new Promise(function (resolve) { readyResolve = resolve; }),
    drawn: 0, rehearsed: 0, result: null, polar: null, polarDrawn: 0, uniform: null,
    uniformDrawn: 0, keyToSupportMs: keyClock.times
  };
  function drawSupport(r, ms) {
    if (r.error) {
      later.put("headline", function () {
        model("headline").text = "";
        model("headline-number").text = "";
      });
      setText("status", "<b>Not computed:</b> " + esc(r.error));
      later.put("drawn", countDrawn);
      return;
    }
    var frames = figures.draw(r);
    keyClock.drawn();
    explorer.result = r;
    // After the paint: the texts (each lays its root out again) and the polar marker.
    var i = Math.min(model("support_player_frame").value, CONFIG.n_frames - 1);
    var readout = "frame " + (i + 1) + " / " + CONFIG.n_frames + " · τ = " +
      frames.support_frames.tau[i].toFixed(2);
    later.put("support_player_readout", function () {  // a live node: redraws only itself
      model("support_player_readout").html = readout;
    });
    later.put("headline", writeHeadline);
    setText("status", "one contact: τ_out = " + r.t_out.toPrecision(4) + " r₀/V₀, " +
      r.stats.n_steps + " steps, computed in " + ms + " ms in the browser" +
      (r.success ? "" : " — <b>" + esc(r.message) + "</b>"));
    later.put("polar-now", markPolar);
    later.put("drawn", countDrawn);
  }

  /** explorer.drawn and data-drawn count a contact's drawing, texts included. */
  function countDrawn() {
    explorer.drawn += 1;
    document.documentElement.setAttribute("data-drawn", String(explorer.drawn));
    if (explorer.drawn === 1) { readyResolve(explorer.result); autoplay(); }
    setTimeout(requestArrays, 0);  // their workers started once this frame is shown
  }

  /** The headline for the current contact and, once computed for this state, the
   * uniform array's average the slab feels. */
  function writeHeadline() {
    var r = explorer.result, u = explorer.uniform, felt = null, note = "";
    if (!r) return;
    if (u && u.key === arraysKey(state)) {
      if (u.error || u.status === "budget") note = CONFIG.uniform_failed_note;
      else felt = u[CONFIG.average_columns[CONFIG.felt_average]];
    }
    texts.headline(r, felt, note);
  }

  // ------------------------------------------------------------ drawing: the uniform array
  function drawUniform(u, ms, input) {
    var key = [input.input.k_r, input.input.k_theta, input.input.F_N, input.beta].join(",");
    explorer.uniform = Object.assign({}, u, {key: key});
    setText("uniform-readout", texts.uniform(u, ms));
    later.put("headline", writeHeadline);
    later.put("uniform-drawn", function () {
      explorer.uniformDrawn += 1;
      if (explorer.uniformDrawn === 1) setTimeout(warmUp, 0);
      document.documentElement.setAttribute("data-uniform", String(explorer.uniformDrawn));
    });
  }

  function warmUp() {  // the kernel compiled on the page (shortContact), the figures rehearsed
    var input = contactInput(state), r = shortContact(input) && contactChannel.warmHere(input, 4);
    var now = explorer.result;  // the contact one degree on, drawn and undrawn (support.js)
    var next = Object.assign({}, state, {theta0_deg: (state.theta0_deg + 1) % 360});
    var other = r && !r.error && contactChannel.warmHere(contactInput(next), 1);
    if (!other || other.error) return;
    figures.rehearse(other, now, function () {
      return explorer.result === now && !contactChannel.inFlight && !contactChannel.pending;
    }, function (n) { explorer.rehearsed = n; });
  }
  function reducedMotion() {
    return !!(window.matchMedia && window.matchMedia("(prefers-reduced-motion: reduce)").matches);
  }
  function autoplay() {  // play=1 in the link, unless the reader asked for reduced motion
    if (!state.play) return;
    if (reducedMotion()) {
      model("support_player_readout").html += " · autoplay off (reduced motion)";
      return;
    }
    model("support_player_play").active = true;
  }

  // ------------------------------------------------------------ drawing: Fig. 11
  function drawPolar(sweep, ms, input) {
    if (!polar.draw(sweep, ms)) return;
    explorer.polar = Object.assign({}, sweep, {key: [input.base.k_r, input.base.k_theta,
                                                     input.base.F_N, input.beta].join(",")});
    markPolar();
    later.put("polar-drawn", function () {
      explorer.polarDrawn += 1;
      document.documentElement.setAttribute("data-polar", String(explorer.polarDrawn));
    });
  }
  function markPolar() {  // the current theta0 and its values (this contact's)
    if (explorer.result && explorer.polar) polar.mark(explorer.result);
  }

  // ------------------------------------------------------------ drawing: Fig. 5
  var map = null;  // mapview.js, once the document is there
  function drawMap() { map.draw(); }

  // ------------------------------------------------------------ projector mode
  function applyProjector() { models.look(CONFIG.projector, state.projector); }

  // ------------------------------------------------------------ the API
  var lastArrays = null, arraysDue = false;
  function compute() {
    keyClock.take();  // the key press (if any) whose redraw is timed
    var input = contactInput(state), early = first ? first.take(input) : undefined;
    first = null;
    if (early === undefined) contactChannel[shortContact(input) ? "runHere" : "request"](input);
    else if (early) drawSupport.apply(null, early);  // else drawn when it comes
    if (arraysKey(state) !== lastArrays) {
      lastArrays = arraysKey(state);
      arraysDue = true;  // requested once the support is drawn (countDrawn)
    }
    later.put("map", drawMap);
  }
  /** A theta0 step from a short contact (a few contacts from the last beta, 1-5 ms). */
  function shortContact(input) {  // computed on the page's thread, drawn in the key's frame
    return !!input.previous && explorer.result.stats.n_steps <= HERE_STEPS;
  }
  /** The orientation sweep and the uniform array for the current state, after the
   * support's contact is drawn: on a small machine their workers would slow it down. */
  function requestArrays() {
    if (!arraysDue) return;
    arraysDue = false;
    sweepChannel.request(sweepInput(state));
    uniformChannel.request(uniformInput(state));
  }

  function setState(partial, fromControl) {
    var changed = false;
    Object.keys(partial).forEach(function (k) {
      var v = partial[k];
      if (k === "tab") {
        if (CONFIG.offline_tabs.indexOf(v) < 0)
          throw new RangeError("tab=" + v + " is not a tab of the offline explorer (one of " + CONFIG.offline_tabs.join(", ") + ")");
        state.tab = v;
        return;
      }
      if (k === "projector") { state.projector = !!v; return; }
      if (k === "beta_mode") {
        if (CONFIG.beta_mode.choices.indexOf(v) < 0)
          throw new RangeError("beta_mode=" + v + " is not " + CONFIG.beta_mode.expected);
        if (state.beta_mode !== v) { state.beta_mode = v; changed = true; }
        return;
      }
      if (KEYS.indexOf(k) < 0) throw new RangeError(k + " is not a setting; known: " + KEYS.concat(["tab", "projector", "beta_mode"]).join(", "));
      if (!inRange(k, v)) throw new RangeError(k + "=" + v + " is not " + CONTROLS[k].expected);
      if (state[k] !== v) { state[k] = v; changed = true; }
    });
    var link = fragment(state);
    later.put("link", function () { history.replaceState(null, "", link); });
    if (!fromControl) syncControls();
    if (changed) compute();
  }

  explorer.simulate = function (o) { return KERNEL.simulate(o); };
  /** True while the support's contact is being computed or drawn (texts included). */
  explorer.pending = function () {
    return !!(contactChannel.inFlight || contactChannel.pending) || later.waiting();
  };
  Object.defineProperty(explorer, "state", {
    get: function () { return Object.assign({}, state); }, enumerable: true
  });
  explorer.set = function (partial) { setState(partial, false); };
  explorer.preset = function (name) {
    var regime = CONFIG.regimes[name];
    if (!regime) throw new RangeError(name + " is not a regime; one of " + Object.keys(CONFIG.regimes).join(", "));
    setState({k_r: regime.k_r, k_theta: regime.k_theta}, false);
  };
  function clampRound(key, v) {
    var c = CONTROLS[key];
    return Math.min(c.hi, Math.max(c.lo, Number(v.toPrecision(c.log ? 3 : 6))));
  }
  explorer._slider = function (key, value) {  // the sliders' CustomJS callbacks
    if (syncing || !doc) return;
    var c = CONTROLS[key], partial = {};
    partial[key] = Math.min(c.hi, Math.max(c.lo, Number((c.log ? Math.pow(10, value) : value).toPrecision(6))));
    setState(partial, true);
  };
  explorer._tab = function (index) {
    if (!doc) return;
    showTab(index);
    if (syncing) return;
    setState({tab: CONFIG.offline_tabs[index]}, true);
  };
  explorer._projector = function (on) {
    if (syncing || !doc) return;
    setState({projector: on}, true);
    applyProjector();
  };
  explorer._betaMode = function (mode) {
    if (syncing || !doc) return;
    setState({beta_mode: mode}, true);
  };
  explorer._mapQuantity = function (q) { if (map) map.quantity(q); };
  explorer._mapTap = function (x, y) { if (map) map.tap(x, y); };  // a click on the map
  explorer._polarTap = function (x, y) {  // a click on a polar diagram: its angle is theta0
    if (!doc || (x === 0 && y === 0)) return;
    var deg = Math.round((Math.atan2(y, x) * 180 / Math.PI + 360) % 360);
    setState({theta0_deg: deg >= 360 ? 0 : deg}, false);
  };
  explorer.parseFragment = parseFragment;
  /** A figure's description for screen readers (``nameFigures``, app/figures/access_js.py). */
  window.describeFigure = function (name) { return doc ? texts.describe(name) : null; };
  window.explorer = explorer;

  // The state the file was packed with (the dashboard's download button): used when the
  // link has no fragment of its own.
  var INITIAL = document.getElementById("mp-initial");
  INITIAL = INITIAL ? JSON.parse(INITIAL.textContent) : "";
  function linkFragment() { return location.hash && location.hash !== "#" ? location.hash : INITIAL; }
  function applyFragment() {
    var parsed = parseFragment(linkFragment());
    state = parsed.state;
    showNotice(parsed.notices);
    syncControls();
    history.replaceState(null, "", fragment(state));
    compute();
  }

  function start(built) {
    doc = built;
    models = window.MicropillarModels(doc);
    figures = window.MicropillarSupportFigures(CONFIG, models);
    laterTabs = window.MicropillarLaterTabs(doc, model("tabs"), CONFIG.offline_tabs);
    texts = window.MicropillarReadouts(CONFIG, {model: model, state: function () { return state; }});
    polar = window.MicropillarPolarView(CONFIG, {setData: setData, setText: setText, esc: esc});
    map = window.MicropillarMapView(CONFIG, {
      source: source, model: model, figure: figure, clampRound: clampRound,
      state: function () { return state; },
      set: function (partial) { setState(partial, false); }
    });
    applyFragment();
    later.runBut(["drawn"]);  // the texts in place before the views are built and laid out
    window.addEventListener("hashchange", applyFragment);
    window.addEventListener("keydown", function (e) { map.keys(e); }, true);
  }

  try {  // before the document is built
    first = new window.MicropillarFirst(contactChannel, contactInput(parseFragment(linkFragment()).state));
  } catch (error) {
    first = null;  // requested by applyFragment, once the document is there
  }
  // The document is built after the page's scripts ran; its views wait for the first
  // contact (open.js, first.js), so that their first paint shows it.
  window.MicropillarOpen(function (built) {
    return (first ? first.ready() : Promise.resolve()).then(function () { start(built); });
  });
}());
