/* The offline explorer's page: controls -> state (mirrored in the URL fragment) -> the
 * JavaScript kernel (in a Web Worker) -> Bokeh's data sources and the headline.
 *
 * window.explorer is the page's API (docs/offline.md):
 *   explorer.simulate({k_r, k_theta, F_N, theta0, beta, rtol, ...}) -> one contact, the
 *       quantities of `micropillar support --json` (synchronous, on the calling thread);
 *   explorer.state   -> the current state {k_r, k_theta, F_N, theta0_deg, tab};
 *   explorer.set({k_r: 0.5, ...}) -> change the state (as the sliders do) and redraw;
 *   explorer.preset("slider") -> a regime's springs;
 *   explorer.result  -> the last drawn result; explorer.drawn counts the redraws;
 *   explorer.ready   -> a Promise resolved at the first drawn plot.
 * Reads its configuration (ranges, defaults, regimes: from the Python model at pack time)
 * from the JSON element #mp-config and the kernel from #mp-kernel.
 */
(function () {
  "use strict";
  var CONFIG = JSON.parse(document.getElementById("mp-config").textContent);
  var KERNEL = window.MicropillarKernel;
  var CONTROLS = CONFIG.controls;
  var KEYS = ["k_r", "k_theta", "F_N", "theta0_deg"];
  var MAX_STEPS = 1000000;
  var RESTART_AFTER_MS = 300;   // a newer request stops a computation older than this

  // ------------------------------------------------------------ state and fragment
  function defaults() {
    var s = {tab: "support"};
    KEYS.forEach(function (k) { s[k] = CONTROLS[k].default; });
    return s;
  }
  var state = defaults();

  function inRange(key, x) {
    var c = CONTROLS[key];
    return isFinite(x) && x >= c.lo && (c.hi_open ? x < c.hi : x <= c.hi);
  }

  /** The state a fragment asks for, and a notice for every value it could not use. */
  function parseFragment(hash) {
    var s = defaults(), notices = [];
    var text = (hash || "").replace(/^#/, "");
    if (!text) return {state: s, notices: notices};
    var pairs = text.split("&"), given = {};
    pairs.forEach(function (pair) {
      if (!pair) return;
      var i = pair.indexOf("="), key, value;
      try {
        key = decodeURIComponent(i < 0 ? pair : pair.slice(0, i));
        value = i < 0 ? "" : decodeURIComponent(pair.slice(i + 1).replace(/\+/g, " "));
      } catch (error) {
        notices.push("could not read “" + pair.slice(0, 40) + "” in the link: ignored");
        return;
      }
      given[key] = value;
    });
    if (given.regime !== undefined) {
      var regime = CONFIG.regimes[given.regime];
      if (regime) { s.k_r = regime.k_r; s.k_theta = regime.k_theta; }
      else notices.push("regime=" + given.regime.slice(0, 40) + " is not a regime (one of " +
                        Object.keys(CONFIG.regimes).join(", ") + "): kept the default springs");
    }
    Object.keys(given).forEach(function (key) {
      var value = given[key];
      if (key === "regime") return;
      if (KEYS.indexOf(key) >= 0) {
        var x = value.trim() === "" || value.length > 100 ? NaN : Number(value);
        if (inRange(key, x)) s[key] = x;
        else notices.push(key + "=" + value.slice(0, 40) + " is not " + CONTROLS[key].expected +
                          ": using the default " + CONTROLS[key].default);
      } else if (key === "tab") {
        if (CONFIG.tabs.indexOf(value) < 0) {
          notices.push("tab=" + value.slice(0, 40) + " is not a tab (one of " + CONFIG.tabs.join(", ") +
                       "): showing the support");
        } else if (CONFIG.offline_tabs.indexOf(value) < 0) {
          s.tab = value;
          notices.push("the " + value + " tab is not in the offline explorer yet: showing the support");
        } else s.tab = value;
      } else {
        notices.push(key.slice(0, 40) + " is not a setting of the offline explorer: ignored");
      }
    });
    return {state: s, notices: notices};
  }

  function fragment(s) {
    var parts = KEYS.map(function (k) { return k + "=" + Number(s[k].toPrecision(6)); });
    if (s.tab && s.tab !== "support") parts.push("tab=" + s.tab);
    return "#" + parts.join("&");
  }

  // ------------------------------------------------------------ Bokeh models
  var doc = null;
  function model(name) { return doc.get_model_by_name(name); }
  function esc(text) {
    return String(text).replace(/[&<>"]/g, function (c) {
      return {"&": "&amp;", "<": "&lt;", ">": "&gt;", "\"": "&quot;"}[c];
    });
  }
  var syncing = false;  // true while the page itself moves the sliders
  function syncSliders() {
    syncing = true;
    try {
      KEYS.forEach(function (k) {
        var c = CONTROLS[k], slider = model("slider-" + k);
        var v = c.log ? Math.log10(state[k]) : state[k];
        if (Math.abs(slider.value - v) > 1e-12) slider.value = v;
      });
    } finally { syncing = false; }
  }
  function showNotice(notices) {
    model("notice").text = notices.length
      ? "<b>Link:</b> " + notices.map(esc).join("; ") : "";
  }

  // ------------------------------------------------------------ computing
  var worker = null, inFlight = null, pending = null, nextId = 1;

  function input(s) {
    return {k_r: s.k_r, k_theta: s.k_theta, F_N: s.F_N, theta0: s.theta0_deg * Math.PI / 180,
            rtol: 1e-6, samples: CONFIG.orbit_samples, max_steps: MAX_STEPS};
  }

  function startWorker() {
    try {
      var source = document.getElementById("mp-kernel").textContent +
        "\nself.onmessage = function (e) {\n" +
        "  var t0 = Date.now(), r;\n" +
        "  try { r = MicropillarKernel.simulate(e.data.input); }\n" +
        "  catch (error) { r = {error: error.message}; }\n" +
        "  self.postMessage({id: e.data.id, result: r, ms: Date.now() - t0});\n};\n";
      var url = URL.createObjectURL(new Blob([source], {type: "text/javascript"}));
      var w = new Worker(url);
      URL.revokeObjectURL(url);
      w.onmessage = function (e) { finished(e.data.id, e.data.result, e.data.ms); };
      w.onerror = function () { worker = null; };
      return w;
    } catch (error) {
      return null;  // no workers (an old browser): compute on the page, one job at a time
    }
  }

  function request() {
    var job = {id: nextId++, input: input(state), started: Date.now()};
    if (inFlight) {
      pending = job;
      if (worker && Date.now() - inFlight.started > RESTART_AFTER_MS) {
        worker.terminate();  // a long contact the user has moved on from
        worker = startWorker();
        inFlight = null;
        send(pending);
        pending = null;
      }
      return;
    }
    send(job);
  }

  function send(job) {
    inFlight = job;
    model("status").text = "computing…";
    if (worker) { worker.postMessage({id: job.id, input: job.input}); return; }
    setTimeout(function () {
      var t0 = Date.now(), r;
      try { r = KERNEL.simulate(job.input); } catch (error) { r = {error: error.message}; }
      finished(job.id, r, Date.now() - t0);
    }, 0);
  }

  function finished(id, result, ms) {
    if (!inFlight || inFlight.id !== id) return;  // an abandoned job
    inFlight = null;
    if (pending) { var next = pending; pending = null; send(next); return; }
    draw(result, ms);
  }

  // ------------------------------------------------------------ drawing
  var readyResolve;
  var explorer = {
    ready: new Promise(function (resolve) { readyResolve = resolve; }),
    drawn: 0, result: null
  };

  function pct(x) { return (100 * x).toFixed(1); }

  function draw(r, ms) {
    if (r.error) {
      model("headline").text = "";
      model("status").text = "<b>Not computed:</b> " + esc(r.error);
      return;
    }
    var ser = r.series;
    var x = ser ? Array.from(ser.x) : [], y = ser ? Array.from(ser.y) : [];
    model("orbit-source").data = {x: x, y: y};
    var rest = KERNEL.restPosition(state.theta0_deg * Math.PI / 180);
    model("spring-source").data = {x: [0, rest[0]], y: [0, rest[1]]};
    model("ends-source").data = {x: [rest[0], r.state_out[0]], y: [rest[1], r.state_out[1]],
                                 label: ["rest", "exit"]};
    var ratio = r.F_mean_x / CONFIG.mu0;
    var change = ratio < 1 ? pct(1 - ratio) + " % less friction than a rigid contact"
                           : pct(ratio - 1) + " % more friction than a rigid contact";
    var head = "F<sub>T,x</sub>/(μ<sub>0</sub>F<sub>N</sub>) = <b>" + ratio.toFixed(3) + "</b>" +
      "<br><span style='font-size:0.8em'>An array whose supports all rest at θ₀ = " +
      Number(state.theta0_deg.toFixed(1)) + "° (Eq. 10): " + change +
      "; D<sub>y</sub>/D<sub>x</sub> = " + (r.D_y / r.D_x).toFixed(3) + ".</span>";
    if (!r.success) head = "<span style='color:#b00020'>" + esc(r.message) + "</span><br>" + head;
    model("headline").text = head;
    model("status").text = "one contact: τ_out = " + r.t_out.toPrecision(4) + " r₀/V₀, " +
      r.stats.n_steps + " steps, computed in " + ms + " ms in the browser" +
      (r.success ? "" : " — <b>" + esc(r.message) + "</b>");
    explorer.result = r;
    explorer.drawn += 1;
    document.documentElement.setAttribute("data-drawn", String(explorer.drawn));
    if (explorer.drawn === 1) readyResolve(r);
  }

  // ------------------------------------------------------------ the API
  function setState(partial, fromSlider) {
    var changed = false;
    Object.keys(partial).forEach(function (k) {
      if (KEYS.indexOf(k) < 0 && k !== "tab") throw new RangeError(k + " is not a setting; known: " + KEYS.join(", "));
      var v = partial[k];
      if (k === "tab") { state.tab = String(v); return; }
      if (!inRange(k, v)) {
        throw new RangeError(k + "=" + v + " is not " + CONTROLS[k].expected);
      }
      if (state[k] !== v) { state[k] = v; changed = true; }
    });
    history.replaceState(null, "", fragment(state));
    if (!fromSlider) syncSliders();
    if (changed || fromSlider) request();
  }

  explorer.simulate = function (o) { return KERNEL.simulate(o); };
  Object.defineProperty(explorer, "state", {
    get: function () { return Object.assign({}, state); }, enumerable: true
  });
  explorer.set = function (partial) { setState(partial, false); };
  explorer.preset = function (name) {
    var regime = CONFIG.regimes[name];
    if (!regime) throw new RangeError(name + " is not a regime; one of " + Object.keys(CONFIG.regimes).join(", "));
    setState({k_r: regime.k_r, k_theta: regime.k_theta}, false);
  };
  explorer._slider = function (key, value) {  // the sliders' CustomJS callbacks
    if (syncing || !doc) return;
    var c = CONTROLS[key];
    var v = c.log ? Math.pow(10, value) : value;
    v = Math.min(c.hi, Math.max(c.lo, Number(v.toPrecision(6))));
    var partial = {};
    partial[key] = v;
    setState(partial, true);
  };
  explorer.parseFragment = parseFragment;
  window.explorer = explorer;

  function applyFragment() {
    var parsed = parseFragment(location.hash);
    state = parsed.state;
    showNotice(parsed.notices);
    syncSliders();
    history.replaceState(null, "", fragment(state));
    request();
  }

  function start() {
    doc = window.Bokeh.documents[0];
    worker = startWorker();
    applyFragment();
    window.addEventListener("hashchange", applyFragment);
  }

  (function waitForBokeh() {  // the document is built after the page's scripts ran
    var B = window.Bokeh;
    if (B && B.documents && B.documents.length && B.documents[0].get_model_by_name("orbit-source")) start();
    else setTimeout(waitForBokeh, 5);
  })();
}());
