/* One support dragged by the slab, integrated in JavaScript: a port of the explicit
 * path of the Python kernel (model/_kernel: rhs.py, dopri5.py, driver.py, event.py,
 * batch.py) for the offline explorer (docs/offline.md).
 *
 * Same equations (Eqs. 3-6 of the paper, docs/model.md "One support"), same state
 * (motion, six quadratures, tau), same Sundman time regularisation near the pivot,
 * same Dormand-Prince 5(4) pair with its PI step-size control and its error norm over
 * the motion and tau, same exit condition (Eq. 9: first crossing of s(tau) = L0,
 * located on the 4th-order dense output and the step retaken to it), same derived
 * quantities (Eqs. 8, 12, 13). The Python kernel switches to DOP853 at rtol <= 1e-6 and
 * to Rodas4 where stiffness is detected; this port is the 5(4) pair alone, which is
 * what Python's ``method="explicit"`` uses at rtol > 1e-6 (tests/test_offline_kernel.py
 * checks it takes the very same steps there, and agrees with Python's default solver
 * at rtol 1e-8 on a grid of states).
 *
 * This file puts one contact together: its inputs (kernel_inputs.js), the system
 * (kernel_rhs.js), the integrator (kernel_dopri5.js), then the recorded histories and the
 * results. Works as a browser script (defines ``MicropillarKernel``, after those three),
 * in a Web Worker and in Node (``require``). No network, no allocation inside a step.
 */
(function (root, factory) {
  "use strict";
  var node = typeof module === "object" && module.exports;
  var api = factory(node ? require("./kernel_inputs.js") : root.MicropillarKernelInputs,
                    node ? require("./kernel_rhs.js") : root.MicropillarKernelRhs,
                    node ? require("./kernel_dopri5.js") : root.MicropillarKernelDopri5);
  if (node) module.exports = api;
  else root.MicropillarKernel = api;
}(typeof self !== "undefined" ? self : this, function (I, S, D) {
  "use strict";
  var DEFAULTS = I.DEFAULTS, fmtG = I.formatG, inputs = I.inputs;
  var X = S.X, Y = S.Y, VX = S.VX, VY = S.VY, THETA = S.THETA, W = S.W, I_Y = S.I_Y,
      D_X = S.D_X, D_Y = S.D_Y, S_TH = S.S_TH, S_R = S.S_R, TAU = S.TAU;
  var SERIES_BELOW = S.SERIES_BELOW, seriesCoefficients = S.seriesCoefficients, mu = S.mu,
      elastic = S.elastic;
  var integrate = D.integrate;
  var OK = D.OK, STEP_BUDGET = D.STEP_BUDGET, TIME_BUDGET = D.TIME_BUDGET;

  // Status texts (model.contact.results.Status), by the integrator's status codes.
  var STATUS_TEXT = [
    ["contact ended: the slab slid L0 over the support (Eq. 9)", ""],
    ["step budget exhausted before the contact ended", "raise max_steps or loosen rtol"],
    ["time budget tau_max reached before the contact ended", "raise tau_max"],
    ["step size underflow", "try method='implicit' or a looser rtol"],
    ["non-finite state", "try method='implicit' or a looser rtol"]
  ];
  var ACCURACY_FACTOR = 3.0;            // model.contact.results.ACCURACY_FACTOR
  var PIVOT_RADIUS_OVER_LAMBDA = 0.2;   // model.arrays.contacts

  // Recorded nodes (record.py): at most MAX_NODES, then every other one.
  var MAX_NODES = 1 << 15;

  // ---------------------------------------------------------------- recording
  function Recorder() {
    this.rows = [];   // [tau, x, y, vx, vy, theta, W, D_x, D_y, then their d/dtau]
    this.stride = 1;
  }
  var REC = [X, Y, VX, VY, THETA, W, D_X, D_Y];
  Recorder.prototype.add = function (cand, force, y, f) {
    if (cand % this.stride !== 0 && !force) return;
    if (this.rows.length >= MAX_NODES) {
      var half = Math.floor((this.rows.length + 1) / 2);
      for (var i = 1; i < half; i++) this.rows[i] = this.rows[2 * i];
      this.rows.length = half;
      this.stride *= 2;
      if (cand % this.stride !== 0 && !force) return;
    }
    var row = new Float64Array(1 + 2 * REC.length);
    row[0] = y[TAU];
    for (var k = 0; k < REC.length; k++) {
      row[1 + k] = y[REC[k]];
      row[1 + REC.length + k] = f[REC[k]] / f[TAU];
    }
    this.rows.push(row);
  };

  // ---------------------------------------------------------------- results
  function message(status, t, rMin, approach, pivotRadius, opts) {
    var text = STATUS_TEXT[status][0];
    if (status === OK) text += " at tau_out = " + fmtG(t);
    else if (status === STEP_BUDGET) text += " (max_steps = " + opts.max_steps + ", tau = " + fmtG(t) + ")";
    else if (status === TIME_BUDGET) text += " (tau_max = " + fmtG(opts.tau_max) + ")";
    else text += " at tau = " + fmtG(t);
    if (STATUS_TEXT[status][1]) text += "; " + STATUS_TEXT[status][1];
    if (approach) {
      text += "; the mass was driven into the region of its pivot (r_min = " +
              fmtG(rMin, 3) + " < " + fmtG(pivotRadius, 3) + ")";
    }
    return text;
  }

  /** Uniform samples of the histories: cubic Hermite through the recorded nodes
   * (model.contact.support ``_series_from_nodes``, ``_series``). */
  function series(p, rows, samples) {
    var kept = [], top = -Infinity;
    for (var i = 0; i < rows.length; i++) {
      if (i === 0 || rows[i][0] > top) kept.push(rows[i]);
      top = Math.max(top, rows[i][0]);
    }
    if (kept.length < 2 || samples < 1) return null;
    var nr = REC.length, tEnd = kept[kept.length - 1][0];
    var names = ["x", "y", "v_x", "v_y", "theta", "W", "D_x", "D_y"];
    var out = {tau: new Float64Array(samples)};
    var columns = names.map(function (n) { return (out[n] = new Float64Array(samples)); });
    var seg = 0;
    for (var s = 0; s < samples; s++) {
      var tau = samples === 1 ? 0.0 : s * (tEnd / (samples - 1));
      if (s === samples - 1) tau = tEnd;
      while (seg < kept.length - 2 && tau > kept[seg + 1][0]) seg++;
      var a = kept[seg], b = kept[seg + 1], dt = b[0] - a[0], th = (tau - a[0]) / dt;
      out.tau[s] = tau;
      // The cubic Hermite of kernel_dopri5.js (``hermite``) on the rows' values and slopes
      // in place: the same arithmetic, no views allocated per sample.
      var h00 = (1 + 2 * th) * (1 - th) * (1 - th), h10 = th * (1 - th) * (1 - th),
          h01 = th * th * (3 - 2 * th), h11 = th * th * (th - 1);
      for (var k = 0; k < nr; k++) {
        columns[k][s] = h00 * a[1 + k] + h10 * dt * a[1 + nr + k] + h01 * b[1 + k] +
                        h11 * dt * b[1 + nr + k];
      }
    }
    var n = samples, r = new Float64Array(n), Fx = new Float64Array(n), Fy = new Float64Array(n),
        Fa = new Float64Array(n), U = new Float64Array(n), Kin = new Float64Array(n);
    var c = seriesCoefficients(p.A, p.B);
    for (var m = 0; m < n; m++) {
      var vrx = out.v_x[m] - 1.0, vy = out.v_y[m], sp = Math.hypot(vrx, vy), z = p.zeta * sp, mo;
      if (z < SERIES_BELOW) {
        var z2 = z * z;
        mo = p.mu_s * p.zeta * (c[0] + z2 * (c[1] + z2 * (c[2] + z2 * c[3])));
      } else {
        mo = mu(sp, p) / sp;
      }
      Fx[m] = -mo * vrx; Fy[m] = -mo * vy; Fa[m] = Math.hypot(Fx[m], Fy[m]);
      r[m] = Math.hypot(out.x[m], out.y[m]);
      U[m] = elastic(p, r[m], out.theta[m]);
      Kin[m] = 0.5 * (out.v_x[m] * out.v_x[m] + vy * vy);
    }
    out.r = r; out.F_x = Fx; out.F_y = Fy; out.F_abs = Fa; out.U_el = U; out.K = Kin;
    return out;
  }

  /**
   * simulate({k_r, k_theta, F_N, theta0, beta, rtol, ...}): one contact, as
   * ``micropillar support --json`` reports it (the same names and meaning; docs/offline.md).
   */
  function simulate(o) {
    var io = inputs(o), p = io.params, opts = io.options;
    var rec = opts.samples > 0 ? new Recorder() : null;
    var run = integrate(p, opts, rec);
    var y = run.y, t = y[TAU], fN = p.F_N * p.beta;
    var r = Math.sqrt(y[X] * y[X] + y[Y] * y[Y]);
    var U = elastic(p, r, y[THETA]);
    var Kin = 0.5 * (y[VX] * y[VX] + y[VY] * y[VY]);
    var inv = t > 0.0 ? 1.0 / t : NaN;
    var rMin = Math.min(run.rMin, r), rMax = Math.max(run.rMax, r);
    var pivotRadius = PIVOT_RADIUS_OVER_LAMBDA * p.lam;
    var approach = rMin < pivotRadius;
    var residual = y[W] - (y[D_X] + y[D_Y] + U + Kin);
    var success = run.status === OK;
    var accurate = Math.abs(residual) / Math.max(Math.abs(y[W]), 1e-300) <=
                   ACCURACY_FACTOR * Math.max(opts.rtol, 1e-9);
    var msg = message(run.status, t, rMin, approach, pivotRadius, opts);
    if (success && !accurate) {
      msg += "; warning: the energy balance misses by " +
             (Math.abs(residual) / Math.max(Math.abs(y[W]), 1e-300)).toExponential(1).replace(/e([+-])(\d)$/, "e$10$2") +
             " of W, more than " + fmtG(ACCURACY_FACTOR) + " rtol: the result is inaccurate; tighten rtol";
    }
    var result = {
      t_out: t,
      state_out: [y[X], y[Y], y[VX], y[VY], y[THETA]],
      F_mean_x: y[W] * inv / fN,
      F_mean_y: y[I_Y] * inv / fN,
      W: y[W], D_x: y[D_X], D_y: y[D_Y], U_el: U, K: Kin,
      energy_residual: residual,
      dtheta_rms: Math.sqrt(Math.max(y[S_TH], 0.0) * inv),
      dr_rms: Math.sqrt(Math.max(y[S_R], 0.0) * inv),
      r_min: rMin, r_max: rMax, pivot_approach: approach, accurate: accurate,
      success: success, status: run.status, message: msg,
      stats: {n_steps: run.stats.n_steps, n_rejected: run.stats.n_rejected,
              n_rhs: run.stats.n_rhs, method: "explicit (Dormand-Prince 5(4), JavaScript)"},
      params: {k_r: p.k_r, k_theta: p.k_theta, F_N: p.F_N, theta0: p.theta0, beta: p.beta,
               mu_s: p.mu_s, A: p.A, B: p.B, zeta: p.zeta, lam: p.lam, L0: p.L0}
    };
    if (rec) result.series = series(p, rec.rows, opts.samples);
    return result;
  }


  return {
    simulate: simulate,
    mu: mu,
    mu0: function (p) { return mu(1.0, p || DEFAULTS); },
    restPosition: S.restPosition,
    DEFAULTS: DEFAULTS,
    RANGES: I.RANGES,
    STATUS_TEXT: STATUS_TEXT,
    ACCURACY_FACTOR: ACCURACY_FACTOR,
    formatG: fmtG
  };
}));
