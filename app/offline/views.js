/* The offline explorer's drawing: the data of the dashboard's figures (app/figures) from a
 * result of the JavaScript kernel, ported function by function so the page fills the very
 * sources the dashboard's figures have (docs/offline.md):
 *
 *   sceneData       <- app.figures.scene.scene_data      (path, pivot, rest, notes)
 *   viewBox         <- app.figures.scene.view_box
 *   supportFrames   <- app.figures.live_energy.support_frames_data
 *   energyFrames    <- app.figures.live_energy.energy_frames / energy_live_range
 *   forceData, forceXRange, forceYRange <- app.figures.histories
 *   polarData, polarNow, extentData     <- app.figures.polar (Fig. 11)
 *   changeWords, headlineText           <- app.views.readouts (the headline sentence)
 *   uniformMarkdown                     <- app.views.readouts.uniform_markdown
 *
 * tests/test_offline_views.py runs each in Node against its Python original. Works as a
 * browser script (``MicropillarViews``) and in Node (``require``); needs the kernel.
 */
(function (root, factory) {
  "use strict";
  var kernel = (typeof module === "object" && module.exports) ? require("./kernel.js")
    : root.MicropillarKernel;
  var api = factory(kernel);
  if (typeof module === "object" && module.exports) module.exports = api;
  else root.MicropillarViews = api;
}(typeof self !== "undefined" ? self : this, function (K) {
  "use strict";
  var fmtG = K.formatG;

  function linspace(a, b, n) {
    var out = new Array(n);
    for (var i = 0; i < n; i++) out[i] = n === 1 ? a : a + (b - a) * i / (n - 1);
    if (n > 1) out[n - 1] = b;
    return out;
  }
  function maxOf(a) { var m = -Infinity; for (var i = 0; i < a.length; i++) if (a[i] > m) m = a[i]; return m; }
  function minOf(a) { var m = Infinity; for (var i = 0; i < a.length; i++) if (a[i] < m) m = a[i]; return m; }
  /** numpy.interp on an increasing grid xp. */
  function interp(x, xp, fp) {
    var out = new Array(x.length), j = 0, n = xp.length;
    for (var i = 0; i < x.length; i++) {
      var t = x[i];
      if (t <= xp[0]) { out[i] = fp[0]; continue; }
      if (t >= xp[n - 1]) { out[i] = fp[n - 1]; continue; }
      while (j < n - 2 && xp[j + 1] <= t) j++;
      while (j > 0 && xp[j] > t) j--;
      var w = (t - xp[j]) / (xp[j + 1] - xp[j]);
      out[i] = fp[j] + w * (fp[j + 1] - fp[j]);
    }
    return out;
  }

  // ------------------------------------------------------------ the scene
  function extent(s) {
    var m = 1.0;
    for (var i = 0; i < s.x.length; i++) m = Math.max(m, Math.hypot(s.x[i], s.y[i]));
    return m;
  }

  /** [x0, x1, y0, y1, to_scale]: the region shown (scene.view_box). */
  function viewBox(s, C) {
    var xs = [-1, 1], ys = [-1, 1];
    if (s && s.tau.length) { xs.push(minOf(s.x), maxOf(s.x)); ys.push(minOf(s.y), maxOf(s.y)); }
    var x0 = minOf(xs), x1 = maxOf(xs), y0 = minOf(ys), y1 = maxOf(ys);
    var w = x1 - x0, h = y1 - y0;
    var toScale = Math.max(w, h) <= C.max_aspect * Math.min(w, h);
    if (toScale) {
      var side = Math.max(w, h), cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
      x0 = cx - side / 2; x1 = cx + side / 2; y0 = cy - side / 2; y1 = cy + side / 2;
    }
    var px = 0.12 * (x1 - x0), py = 0.12 * (y1 - y0);
    return [x0 - px, x1 + px, y0 - py, y1 + py, toScale];
  }

  function notes(s, toScale, C) {
    var out = toScale ? [] : ["axes not to scale"];
    if (s && s.r.length) {
      var rMax = maxOf(s.r);
      if (rMax > C.stretch_warning) out.push("stretched to " + fmtG(rMax, 3) + " r₀: beyond a real pillar");
    }
    return out.join("; ");
  }

  /** The sources fixed for one trajectory (scene.scene_data). */
  function sceneData(s, theta0, C) {
    var c = Math.cos(theta0), sn = Math.sin(theta0), ext = extent(s);
    var phi = linspace(0, 2 * Math.PI, 121), reach = 1.25 * Math.pow(ext, 0.25);
    var n = s.tau.length, tauOut = Math.max(s.tau[n - 1], 1e-300);
    var orbit = {x0: [], y0: [], x1: [], y1: [], t: []};
    for (var i = 0; i + 1 < n; i++) {
      orbit.x0.push(s.x[i]); orbit.y0.push(s.y[i]); orbit.x1.push(s.x[i + 1]);
      orbit.y1.push(s.y[i + 1]); orbit.t.push(s.tau[i] / tauOut);
    }
    return {
      scene_points: {x: [0, c], y: [0, sn], what: ["pivot", "rest position"], marker: ["square", "circle"]},
      scene_rest_line: {x: [0, c * reach], y: [0, sn * reach]},
      scene_circle: {x: phi.map(Math.cos), y: phi.map(Math.sin)},
      scene_notes: {x: [0], y: [0], text: [notes(s, viewBox(s, C)[4], C)]},
      orbit: orbit
    };
  }

  /** The player's frames and the trajectory's constants (live_energy.support_frames_data). */
  function supportFrames(s, p, C) {
    var n = C.n_frames, tau = linspace(0, s.tau[s.tau.length - 1], n), out = {tau: tau};
    ["x", "y", "theta", "v_x", "v_y", "F_x", "F_y", "F_abs"].forEach(function (k) {
      out[k] = interp(tau, s.tau, s[k]);
    });
    out.v_R = out.v_x.map(function (vx, i) { return Math.hypot(vx - 1, out.v_y[i]); });
    out.mu = out.v_R.map(function (v) { return K.mu(v, p); });
    var ext = extent(s), box = viewBox(s, C);
    return {
      support_frames: out,
      support_frame_params: {
        theta0: [p.theta0], L0: [p.L0], x_start: [s.x[0]], amp: [0.05 * Math.sqrt(ext)],
        rho0: [0.3 * Math.pow(ext, 0.25)], tau_out: [s.tau[s.tau.length - 1]],
        vx0: [box[0]], vx1: [box[1]], vy0: [box[2]], vy1: [box[3]]}
    };
  }

  var ENERGY_KEYS = ["W", "D_x", "D_y", "U_el", "K"];

  /** tau and the energy histories on the player's frames, and the bars' y range. */
  function energyFrames(s, C) {
    var tau = linspace(0, s.tau[s.tau.length - 1], C.n_frames), out = {tau: tau};
    ENERGY_KEYS.forEach(function (k) { out[k] = interp(tau, s.tau, s[k]); });
    var lo = 0, hiW = -Infinity, hiSum = -Infinity;
    ENERGY_KEYS.forEach(function (k) { lo = Math.min(lo, minOf(out[k])); });
    for (var i = 0; i < tau.length; i++) {
      hiW = Math.max(hiW, out.W[i]);
      hiSum = Math.max(hiSum, out.D_x[i] + out.D_y[i] + out.U_el[i] + out.K[i]);
    }
    var hi = Math.max(hiW, hiSum, 1e-12);
    return {frames: out, range: [lo - 0.05 * hi, 1.1 * hi]};
  }

  // ------------------------------------------------------------ Fig. 7
  function forceData(s) {
    return {forces: {tau: Array.from(s.tau), F_x: Array.from(s.F_x), F_y: Array.from(s.F_y),
                     F_abs: Array.from(s.F_abs)}};
  }
  function forceXRange(s) {
    var t = s.tau.length ? s.tau[s.tau.length - 1] : 10;
    return [-0.02 * t, 1.02 * t];
  }
  function forceYRange(s, m0) {
    var lo = Math.min(0, minOf(s.F_x), minOf(s.F_y)), hi = Math.max(maxOf(s.F_abs), m0);
    var pad = 0.06 * ((hi - lo) || 1);
    return [lo - pad, hi + pad];
  }

  // ------------------------------------------------------------ Fig. 11
  var SPOKES_DEG = [];
  for (var d = 0; d < 360; d += 30) SPOKES_DEG.push(d);

  function fullCircle(theta0, values, parity) {
    var sign = parity === "even" ? 1 : -1, n = theta0.length;
    var theta = theta0.slice(), vals = values.slice();
    for (var i = n - 1; i >= 0; i--) { theta.push(2 * Math.PI - theta0[i]); vals.push(sign * values[i]); }
    if (theta.length) { theta.push(theta[0] + 2 * Math.PI); vals.push(vals[0]); }
    return [theta, vals];
  }

  function nice(x) {
    var power = Math.pow(10, Math.floor(Math.log10(x)));
    var ms = [1, 2, 2.5, 5, 10];
    for (var i = 0; i < ms.length; i++) if (ms[i] * power >= x * (1 - 1e-12)) return ms[i] * power;
    return 10 * power;
  }

  function radialAxis(values, parity) {
    var v = values.filter(isFinite);
    var top = v.length ? Math.max.apply(null, v.map(Math.abs)) : 1;
    top = top > 0 ? top : 1;
    var odd = parity === "odd" || (v.length > 0 && minOf(v) < 0);
    var lo = odd ? 2 : 3, hi = odd ? 3 : 6, best = null;
    for (var k = lo; k <= hi; k++) {
      var step = nice(top / k), n = Math.max(1, Math.ceil(top / step - 1e-9));
      if (lo <= n && n <= hi && (best === null || n * step < best[0] * best[1] - 1e-12)) best = [n, step];
    }
    if (best === null) best = [hi, nice(top / hi)];
    var rings = [], j;
    if (odd) { for (j = -best[0]; j <= best[0]; j++) rings.push(j * best[1]); return [-best[0] * best[1], best[0] * best[1], rings]; }
    for (j = 1; j <= best[0]; j++) rings.push(j * best[1]);
    return [0, best[0] * best[1], rings];
  }

  // The ring labels' layout (polar.labelled_rings and its constants).
  var ANGLE_LABEL_R = 1.1, EXTENT_R = 1.34, RING_LABEL_DEG = 15;
  var LABEL_FRAME_PX = 250, LABEL_FONT_PX = 18, LABEL_GAP_PX = 2, WIDE_EM = 0.84;
  var CHAR_EM = {".": 0.32, "-": 0.37, "e": 0.62, "°": 0.5};
  for (var ch = 0; ch < 10; ch++) CHAR_EM[String(ch)] = 0.64;

  function labelBox(x, y, text) {
    var em = 0;
    for (var k = 0; k < text.length; k++) em += text[k] in CHAR_EM ? CHAR_EM[text[k]] : WIDE_EM;
    var hw = em * LABEL_FONT_PX / 2 + LABEL_GAP_PX, hh = LABEL_FONT_PX / 2 + LABEL_GAP_PX;
    return [x - hw, y - hh, x + hw, y + hh];
  }

  function overlap(a, b) { return a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]; }

  /** The indices of the labelled rings (polar.labelled_rings). */
  function labelledRings(axis) {
    var rLo = axis[0], rings = axis[2], n = rings.length, i, j, k;
    var px = LABEL_FRAME_PX / (2 * EXTENT_R * (axis[1] - rLo));
    var la = RING_LABEL_DEG * Math.PI / 180, c = Math.cos(la), sn = Math.sin(la);
    var a = ANGLE_LABEL_R * (axis[1] - rLo) * px;
    var angles = SPOKES_DEG.map(function (d) {
      return labelBox(a * Math.cos(d * Math.PI / 180), a * Math.sin(d * Math.PI / 180), d + "°");
    });
    var first = rLo < 0 && rings.indexOf(0) >= 0 ? rings.indexOf(0) : n - 1;
    for (var step = 1; step <= n; step++) {
      var chosen = [], boxes = [], clash = false;
      for (i = 0; i < n; i++) if ((((first - i) % step) + step) % step === 0) chosen.push(i);
      for (j = 0; j < chosen.length && !clash; j++) {
        var r = (rings[chosen[j]] - rLo) * px, b = labelBox(r * c, r * sn, fmtG(rings[chosen[j]]));
        for (k = 0; k < boxes.length && !clash; k++) clash = overlap(b, boxes[k]);
        for (k = 0; k < angles.length && !clash; k++) clash = overlap(b, angles[k]);
        boxes.push(b);
      }
      if (!clash) return chosen;
    }
    return [first];
  }

  function gridData(key, axis) {
    var rLo = axis[0], R = axis[1] - axis[0], rings = axis[2];
    var phi = linspace(0, 2 * Math.PI, 121), ringR = rings.map(function (v) { return v - rLo; });
    var spokes = SPOKES_DEG.map(function (a) { return a * Math.PI / 180; });
    var la = RING_LABEL_DEG * Math.PI / 180, labelled = labelledRings(axis);
    var out = {};
    out["polar_" + key + "_rings"] = {
      xs: ringR.map(function (r) { return phi.map(function (p) { return r * Math.cos(p); }); }),
      ys: ringR.map(function (r) { return phi.map(function (p) { return r * Math.sin(p); }); }),
      value: rings.slice(), width: rings.map(function (v) { return v === 0 && rLo < 0 ? 2 : 1; })};
    out["polar_" + key + "_spokes"] = {
      xs: spokes.map(function (a) { return [0, R * Math.cos(a)]; }),
      ys: spokes.map(function (a) { return [0, R * Math.sin(a)]; })};
    out["polar_" + key + "_ring_labels"] = {
      x: labelled.map(function (i) { return ringR[i] * Math.cos(la); }),
      y: labelled.map(function (i) { return ringR[i] * Math.sin(la); }),
      text: labelled.map(function (i) { return fmtG(rings[i]); })};
    out["polar_" + key + "_angle_labels"] = {
      x: spokes.map(function (a) { return ANGLE_LABEL_R * R * Math.cos(a); }),
      y: spokes.map(function (a) { return ANGLE_LABEL_R * R * Math.sin(a); }),
      text: SPOKES_DEG.map(function (a) { return a + "°"; })};
    return out;
  }

  function extentData(key, axis) {
    var E = EXTENT_R * (axis[1] - axis[0]), out = {};
    out["polar_" + key + "_extent"] = {x: [-E, E], y: [-E, E]};
    return out;
  }

  /** [sources, axis] of one polar diagram from a half sweep (polar.polar_data). */
  function polarData(key, parity, theta0, values) {
    var fc = fullCircle(theta0, values, parity), theta = fc[0], vals = fc[1];
    var axis = radialAxis(vals, parity), rLo = axis[0];
    var r = vals.map(function (v) { return Math.max(v - rLo, 0); });  // NaN stays NaN
    var curve = {x: r.map(function (q, i) { return isNaN(vals[i]) ? NaN : q * Math.cos(theta[i]); }),
                 y: r.map(function (q, i) { return isNaN(vals[i]) ? NaN : q * Math.sin(theta[i]); }),
                 theta0_deg: theta.map(function (t) { return ((t * 180 / Math.PI) % 360 + 360) % 360; }),
                 value: vals};
    var out = {};
    out["polar_" + key] = curve;
    if (parity === "odd") {
      [["pos", function (v) { return v >= 0; }], ["neg", function (v) { return v <= 0; }]].forEach(function (sg) {
        var keep = vals.map(sg[1]), n = keep.length;
        var near = keep.map(function (k, i) { return k || keep[(i - 1 + n) % n] || keep[(i + 1) % n]; });
        out["polar_" + key + "_" + sg[0]] = {
          x: curve.x.map(function (v, i) { return near[i] ? v : NaN; }),
          y: curve.y.map(function (v, i) { return near[i] ? v : NaN; }),
          theta0_deg: curve.theta0_deg, value: vals};
      });
    }
    Object.assign(out, gridData(key, axis), extentData(key, axis));
    return [out, axis];
  }

  /** The current theta0 (radians) as a spoke and its value as a marker (polar.polar_now). */
  function polarNow(key, theta0, value, axis) {
    var R = axis[1] - axis[0], c = Math.cos(theta0), s = Math.sin(theta0), out = {};
    var marker = {x: [], y: [], value: []};
    if (value !== null && value !== undefined && isFinite(value)) {
      var r = Math.max(value - axis[0], 0);
      marker = {x: [r * c], y: [r * s], value: [value]};
    }
    out["polar_" + key + "_now"] = marker;
    out["polar_" + key + "_spoke"] = {x: [0, R * c], y: [0, R * s]};
    return out;
  }

  // ------------------------------------------------------------ the headline
  /** F_T,x/(mu0 F_N) in words (readouts.change_words). */
  function changeWords(ratio) {
    if (ratio === null || ratio === undefined || !isFinite(ratio)) return "not available";
    var percent = 100 * (1 - ratio);
    if (Math.abs(percent) < 0.05) return "the same as on a rigid surface";
    return Math.abs(percent).toFixed(1) + " % " + (percent > 0 ? "below" : "above") + " a rigid surface";
  }

  /** The page's one-line result (readouts.headline_text); feltWords: app.texts.FELT_WORDS. */
  function headlineText(fixed, theta0Deg, uniform, uniformNote, feltWords) {
    var first = fixed !== null && fixed !== undefined
      ? "Friction is " + changeWords(fixed) + " (every support at θ₀ = " + fmtG(theta0Deg) + "°)"
      : "Friction: being computed";
    if (uniform === null || uniform === undefined)
      return first + "; what the slab feels with supports of all orientations: " +
        (uniformNote || "being computed") + ".";
    return first + "; with supports of all orientations the slab feels " + changeWords(uniform) +
      " (" + feltWords + ").";
  }

  function fmtReadout(x, digits) {  // app.views.readouts._fmt
    return x === null || x === undefined || !isFinite(x) ? "–" : fmtG(x, digits || 4);
  }

  /** The uniform array's readout table (Markdown), as the dashboard writes it: both averages
   * of its friction, the slab's (``felt``) first, the one named ``average`` in bold.
   * ``names``: app.texts.AVERAGE_NAMES (in its order), ``columns``: AVERAGE_COLUMNS. */
  function uniformMarkdown(row, average, note, names, columns, felt) {
    if (row === null || row === undefined)
      return "| Uniform array | value |\n|:--|--:|\n| F_T,x/(μ₀F_N) | " + (note || "…") + " |";
    var order = [felt].concat(Object.keys(names).filter(function (a) { return a !== felt; }));
    var rows = order.map(function (a) {
      var v = fmtReadout(row[columns[a]]);
      return ["friction F_T,x/(μ₀F_N), " + names[a], a === average ? "**" + v + "**" : v];
    });
    rows.push(["dissipated across / along, D_y/D_x", fmtReadout(row.Dy_over_Dx)],
              ["contacts, N_c/N_c0", fmtReadout(row.Nc_over_Nc0)],
              ["quadrature error", fmtReadout(row.quadrature_error_FTx, 2)]);
    var body = rows.map(function (r) { return "| " + r[0] + " | " + r[1] + " |"; }).join("\n");
    var ok = row.success === undefined ? true : row.success;
    var warn = ok ? "" : "\n\n⚠ not every member finished its contact (" + (row.n_failed || 0) + " failed)";
    return "| Uniform array (all θ₀) | value |\n|:--|--:|\n" + body + warn;
  }

  return {
    uniformMarkdown: uniformMarkdown,
    viewBox: viewBox, sceneData: sceneData, supportFrames: supportFrames,
    energyFrames: energyFrames, forceData: forceData, forceXRange: forceXRange,
    forceYRange: forceYRange, polarData: polarData, polarNow: polarNow,
    extentData: extentData, radialAxis: radialAxis, labelledRings: labelledRings,
    changeWords: changeWords,
    headlineText: headlineText, interp: interp, linspace: linspace
  };
}));
