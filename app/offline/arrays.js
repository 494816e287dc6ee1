/* Arrays of supports in JavaScript for the offline explorer: ports of model/arrays/fixed.py
 * (fixed-orientation arrays, Figs. 9-11, with the self-consistent load factor beta =
 * L0/tau_out(beta) of each orientation) and model/arrays/uniform.py (the uniform-orientation
 * array, Figs. 5, 6, 8: the average over theta0 as an adaptive Gauss-Kronrod quadrature
 * on [0, pi] by mirror symmetry, wrapped in the coarse-to-fine solve of beta =
 * L0/<tau_out>(beta)), on top of the kernel's ``simulate`` and solvers.js.
 *
 *   fixedArray(input, beta)           -> {contact, beta, beta_note, ...}
 *   orientationSweep(base, theta0s, beta) -> Fig. 11's columns over theta0 (each beta
 *       solved by the secant method from the neighbours' beta, extrapolated: 3-6 contacts
 *       per orientation instead of the bracket's 6-12, the same beta to BETA_XTOL)
 *   uniformArray(input, o)            -> the fields of model.arrays.uniform.UniformArrayResult
 *
 * ``beta`` is "self" (solved) or a number. Budgets: every contact has its step budget
 * (the kernel's ``max_steps``), every solver its own (solvers.js), and a uniform array at
 * most ``o.max_contacts`` contacts (default MAX_CONTACTS): past it the result says
 * "ran out of its budget" with success false. tests/test_offline_arrays.py holds these
 * to the Python model. Works as a browser script (``MicropillarArrays``), in a Web Worker
 * and in Node.
 */
(function (root, factory) {
  "use strict";
  var node = typeof module === "object" && module.exports;
  var api = factory(node ? require("./kernel.js") : root.MicropillarKernel,
                    node ? require("./solvers.js") : root.MicropillarSolvers);
  if (node) module.exports = api;
  else root.MicropillarArrays = api;
}(typeof self !== "undefined" ? self : this, function (K, S) {
  "use strict";

  var BETA_XTOL = 1e-8;       // model.arrays.fixed.orientation_sweep's beta_xtol
  var BETA_GTOL = 0.1;        // model.arrays.uniform.BETA_GTOL
  var MAX_CONTACTS = 100000;  // a uniform array's budget of contacts
  // Integrand components per orientation (model.arrays.uniform.QUANTITIES); then the diagnostics
  // pivot, relative residual, failed.
  var QUANTITIES = ["F_x", "F_y", "t_out", "W", "D_x", "D_y", "U_el", "K", "dtheta_rms", "dr_rms"];
  var FROM = {F_x: "F_mean_x", F_y: "F_mean_y"};
  var FX = 0, T = 2, NQ = QUANTITIES.length;

  function assign(target) {
    for (var i = 1; i < arguments.length; i++) {
      var src = arguments[i];
      for (var k in src) if (Object.prototype.hasOwnProperty.call(src, k)) target[k] = src[k];
    }
    return target;
  }
  function L0of(input) { return input.L0 === undefined ? K.DEFAULTS.L0 : input.L0; }

  /** The load factor of a fixed array at input.theta0: solved (beta "self") or given. */
  function fixedBeta(input, beta) {
    if (beta !== "self") return {beta: beta, note: "", iterations: 0, converged: true};
    var base = assign({}, input, {samples: 0});
    var sol = S.solveBetaBracket(function (b) {
      return K.simulate(assign({}, base, {beta: b})).t_out;
    }, L0of(input), BETA_XTOL);
    return {beta: sol.beta, residual: sol.residual, iterations: sol.iterations,
            converged: sol.converged,
            note: sol.capped ? "capped at 1" : sol.jump ? "no root: tau_out jumps" :
              sol.converged ? "" : sol.message};
  }

  /** A fixed-orientation array at input.theta0: its contact at its load factor. */
  function fixedArray(input, beta) {
    var b = fixedBeta(input, beta === undefined ? "self" : beta);
    var contact = K.simulate(assign({}, input, {beta: b.beta}));
    return {contact: contact, beta: b.beta, beta_note: b.note, beta_iterations: b.iterations,
            success: contact.success && b.note !== "no root: tau_out jumps" &&
              b.note.indexOf("budget") < 0};
  }

  /** Fixed arrays over theta0s (Fig. 11): per orientation F_mean_x, F_mean_y, D_x, D_y,
   * t_out, beta, success; ``contacts``: how many contacts were integrated. */
  function orientationSweep(base, theta0s, beta) {
    var keys = ["F_mean_x", "F_mean_y", "D_x", "D_y", "t_out"];
    var out = {theta0: theta0s.slice(), beta: [], beta_note: [], success: [], contacts: 0};
    keys.forEach(function (k) { out[k] = []; });
    var solved = [];  // the last orientations' solved beta and slope of G
    theta0s.forEach(function (t) {
      var input = assign({}, base, {theta0: t, samples: 0});
      var a = beta === "self" ? warmArray(input, predicted(solved)) : fixedArray(input, beta);
      if (a.slope !== undefined) solved = isFinite(a.slope) && !a.beta_note ? solved.concat([a]).slice(-3) : [];
      keys.forEach(function (k) { out[k].push(a.contact[k]); });
      out.contacts += a.contacts === undefined ? 1 : a.contacts;
      out.beta.push(a.beta);
      out.beta_note.push(a.beta_note);
      out.success.push(a.success);
    });
    return out;
  }

  /** The next orientation's beta, extrapolated from the last three solved (a parabola
   * through them on the equally spaced theta0 grid), the last two (a line) or the last one;
   * the secant's first slope likewise from the last two slopes of G (the last one where
   * that line is not positive). Only the starting point: the root is solved to BETA_XTOL. */
  function predicted(solved) {
    if (!solved.length) return null;
    var n = solved.length, last = solved[n - 1], guess;
    if (n < 2) return last;
    if (n < 3) guess = 2 * last.beta - solved[0].beta;
    else guess = 3 * last.beta - 3 * solved[1].beta + solved[0].beta;
    var slope = 2 * last.slope - solved[n - 2].slope;
    return {beta: Math.min(1.0, Math.max(S.BETA_MIN, guess)), slope: slope > 0 ? slope : last.slope};
  }

  /** A fixed array whose self-consistent beta starts from a neighbouring orientation's
   * (``previous``: {beta, slope}; null: from beta = 1): the safeguarded secant method,
   * to the same tolerance and with the same notes as ``fixedBeta``'s bracket. The contact
   * at the solved beta is the one the solver integrated last, not integrated again. */
  function warmArray(input, previous) {
    var contacts = new Map();
    function meanTau(b) {
      var c = K.simulate(assign({}, input, {beta: b}));
      contacts.set(b, c);
      return c.t_out;
    }
    var integrated = 0;
    var sol = S.solveBetaSecant(meanTau, L0of(input), {
      xtol: BETA_XTOL, guess: previous ? previous.beta : null,
      slope: previous ? previous.slope : null});
    var jump = !sol.capped && Math.abs(sol.residual) > 1e3 * BETA_XTOL;
    var note = sol.capped ? "capped at 1" : jump ? "no root: tau_out jumps" :
      sol.converged ? "" : sol.message;
    var contact = contacts.get(sol.beta);
    if (contact === undefined) { contact = K.simulate(assign({}, input, {beta: sol.beta})); integrated = 1; }
    return {contact: contact, beta: sol.beta, beta_note: note, slope: sol.slope,
            contacts: sol.evaluations + integrated,
            beta_iterations: sol.iterations,
            success: contact.success && !jump && !(note && note.indexOf("budget") >= 0)};
  }

  function Budget(limit) { this.limit = limit; }

  /** The orientation integrand: each member's quantities at a load factor, each
   * (beta, theta0) integrated once; failed members take their nearest neighbour's. */
  function members(base, counter, limit) {
    var rows = new Map();
    return function (theta0s, beta) {
      var out = theta0s.map(function (t) {
        var key = beta + "|" + t, row = rows.get(key);
        if (!row) {
          if (counter.trajectories >= limit) throw new Budget(limit);
          var c = K.simulate(assign({}, base, {theta0: t, beta: beta}));
          counter.trajectories += 1;
          counter.n_rhs += c.stats.n_rhs;
          row = QUANTITIES.map(function (q) { return c.success ? c[FROM[q] || q] : NaN; });
          row.push(c.pivot_approach ? 1 : 0, Math.abs(c.energy_residual / c.W),
                   c.success ? 0 : 1);
          rows.set(key, row);
        }
        return row.slice();
      });
      return repair(out);
    };
  }

  function repair(rows) {  // model.arrays.uniform._repair: failed rows take the nearest good one's
    var good = [];
    rows.forEach(function (r, i) { if (!isNaN(r[0])) good.push(i); });
    if (!good.length || good.length === rows.length) return rows;
    rows.forEach(function (r, i) {
      if (!isNaN(r[0])) return;
      var best = good[0];
      good.forEach(function (g) { if (Math.abs(g - i) < Math.abs(best - i)) best = g; });
      for (var q = 0; q < NQ; q++) r[q] = rows[best][q];
    });
    return rows;
  }

  /**
   * uniformArray({k_r, k_theta, F_N, ...}, {beta: "self" | number, tol: 1e-3, rtol,
   * max_intervals: 256, max_contacts}): the uniform-orientation array, as
   * model.arrays.uniform.uniform_array computes it without a guess (beta on one 15-node
   * interval first, then the quadrature at that beta, then Newton and secant steps on
   * the refined partition until |G| <= BETA_GTOL tol beta^2).
   */
  function uniformArray(input, o) {
    o = o || {};
    var started = Date.now();
    var tol = o.tol === undefined ? 1e-3 : o.tol;
    if (!(tol >= 1e-8 && tol <= 0.5)) throw new RangeError("tol=" + tol + " is not in [1e-08, 0.5]");
    var self = o.beta === undefined || o.beta === "self";
    var rtol = o.rtol === undefined ? Math.min(1e-5, Math.max(1e-10, tol / 100)) : o.rtol;
    var maxIntervals = o.max_intervals || 256, limit = o.max_contacts || MAX_CONTACTS;
    var base = assign({}, input, {rtol: rtol, samples: 0, beta: self ? 1.0 : o.beta});
    delete base.theta0;
    K.simulate(assign({}, base, {theta0: 0.0}));  // a bad input throws here, as in Python
    var span = Math.PI, L0 = L0of(input), m0 = K.mu0(assign({}, K.DEFAULTS, input));
    var counter = {trajectories: 0, n_rhs: 0};
    var f = members(base, counter, limit);
    var targets = [tol * m0 * span, tol * L0 * span], control = [FX, T];
    var beta = base.beta, betaIter = 0, betaRes = 0.0, slope = null, fineSlope = null;
    var quad, last;
    try {
      if (self) {  // coarse: beta on one interval of 15 nodes, to xtol = tol
        var edges1 = [0.0, span];
        var sol = S.solveBetaSecant(function (b) {
          return S.kronrodMean(edges1, f(S.nodes(edges1), b).map(function (r) { return r[T]; }), span);
        }, L0, {xtol: tol});
        betaIter += sol.iterations;
        beta = sol.beta;
        if (isFinite(sol.slope)) slope = sol.slope;
      }
      fineSlope = fineSlope || slope;
      var integrand = function (b) { return function (x) { return f(x, b); }; };
      quad = S.integrate(integrand(beta), 0.0, span, targets, control,
                         S.linspace(0.0, span, 5), maxIntervals);
      last = {beta: beta, quad: quad};
      var meanTau = function (b) {  // <tau_out> at b, refining on from the last partition
        last.beta = b;
        last.quad = S.integrate(integrand(b), 0.0, span, targets, control, last.quad.edges,
                                maxIntervals);
        return last.quad.integral[T] / span;
      };
      for (var round = 0; self && round < 6; round++) {
        betaRes = beta - L0 * span / quad.integral[T];
        var gtol = BETA_GTOL * tol * beta * beta;
        if (Math.abs(betaRes) <= gtol) break;
        var s = fineSlope && fineSlope > 0 ? fineSlope : 1.0;
        var fine = S.solveBetaSecant(meanTau, L0, {xtol: gtol / beta, guess: beta - betaRes / s,
                                                   slope: s, gtol: gtol, known: [beta, betaRes]});
        betaIter += fine.iterations;
        beta = fine.beta;
        if (last.beta !== beta) meanTau(beta);
        quad = last.quad;
        if (isFinite(fine.slope) && fine.slope > 0) fineSlope = fine.slope;
      }
    } catch (error) {
      if (!(error instanceof Budget)) throw error;
      return {success: false, status: "budget", beta: beta,
              message: "the uniform array ran out of its budget of " + limit +
                " contacts (max_contacts) before its tolerance was met",
              stats: counter, seconds: (Date.now() - started) / 1000};
    }
    var res = result(base, beta, quad, span, m0, counter, rtol);
    var finalRes = beta - L0 * span / quad.integral[T];
    if (self && Math.abs(finalRes) > BETA_GTOL * tol * beta * beta) {
      res.message += "; the self-consistent beta is not within its tolerance after 6 rounds";
    }
    res.beta_iterations = betaIter;
    res.beta_residual = betaRes;
    res.seconds = (Date.now() - started) / 1000;
    return res;
  }

  function result(base, beta, quad, span, m0, counter, rtol) {
    var mean = {}, err = {};
    QUANTITIES.forEach(function (q, i) {
      mean[q] = quad.integral[i] / span;
      err[q] = quad.error[i] / span;
    });
    var fN = beta * (base.F_N === undefined ? 1.0 : base.F_N), L0 = L0of(base);
    function ratio(a, b) {
      var v = mean[a] / mean[b];
      return [v, Math.abs(v) * (err[a] / Math.abs(mean[a]) + err[b] / Math.abs(mean[b]))];
    }
    var DyDx = ratio("D_y", "D_x"), split = {}, splitErr = {};
    ["D_x", "D_y", "U_el", "K"].forEach(function (k) {
      var r = ratio(k, "W");
      split[k] = r[0];
      splitErr["work_split." + k] = r[1];
    });
    var duration = mean.W / (fN * mean.t_out) / m0;
    var nFailed = 0, nPivot = 0, nInaccurate = 0, worst = 0, failedTheta0 = [];
    quad.values.forEach(function (row, i) {
      if (row[NQ] > 0) nPivot += 1;
      if (row[NQ + 1] > K.ACCURACY_FACTOR * rtol) nInaccurate += 1;
      if (row[NQ + 1] > worst) worst = row[NQ + 1];
      if (row[NQ + 2] > 0) { nFailed += 1; failedTheta0.push(quad.nodes[i]); }
    });
    var message = quad.converged ? "ok" : "quadrature tolerance not met within max_intervals";
    if (nFailed) message += "; " + nFailed + " of " + quad.nodes.length + " members did not " +
      "finish their contact and took the values of their nearest neighbour in theta0";
    if (nInaccurate) message += "; " + nInaccurate + " members miss the energy balance by more " +
      "than " + K.formatG(K.ACCURACY_FACTOR) + " rtol (largest " + worst.toExponential(1) + " of W)";
    if (nPivot) message += "; " + nPivot + " members were driven into the region of their pivot";
    return {
      FTx_over_mu0FN: mean.F_x / m0, FTx_over_mu0FN_duration: duration, FTy_over_mu0FN: 0.0,
      Dy_over_Dx: DyDx[0], Nc_over_Nc0: mean.t_out / L0, beta: beta, work_split: split,
      dtheta_rms: mean.dtheta_rms, dr_rms: mean.dr_rms,
      quadrature_error: assign({
        FTx_over_mu0FN: err.F_x / m0,
        FTx_over_mu0FN_duration: duration * (err.W / Math.abs(mean.W) + err.t_out / mean.t_out),
        FTy_over_mu0FN: 0.0, Dy_over_Dx: DyDx[1], Nc_over_Nc0: err.t_out / L0}, splitErr),
      integration_error: worst, n_members: quad.nodes.length, n_failed: nFailed,
      n_pivot: nPivot, failed_theta0: failedTheta0,
      success: quad.converged && nFailed === 0, status: quad.converged ? "ok" : "budget",
      message: message,
      stats: {trajectories: counter.trajectories, n_rhs: counter.n_rhs,
              intervals: quad.edges.length - 1, rounds: quad.rounds, rtol: rtol}
    };
  }

  /** The page's jobs (its Web Workers run this): "contact", the support at theta0 as its
   * fixed array's contact (beta solved or given, like app.worker.compute_support; with
   * ``previous`` {beta, slope} solved from there), with its array's ``beta_note`` and
   * ``beta_slope``; "sweep", Fig. 11's orientations; "uniform", the array. */
  function job(kind, o) {
    if (kind === "contact") {
      // o.previous ({beta, slope}: the last contact's at the same springs and load): the
      // secant starts there (warmArray) instead of bracketing from scratch.
      var a;
      if (o.beta === "self" && o.previous) {  // the secant's contacts unsampled, as fixedBeta's
        a = warmArray(assign({}, o.input, {samples: 0}), o.previous);
        var contact = K.simulate(assign({}, o.input, {beta: a.beta}));
        a.success = a.success && contact.success;
        a.contact = contact;
      } else {
        a = fixedArray(o.input, o.beta);
      }
      return assign(a.contact, {beta_note: a.beta_note, array_success: a.success,
                                beta_slope: a.slope});
    }
    if (kind === "sweep") return orientationSweep(o.base, o.theta0, o.beta);
    if (kind === "uniform") return uniformArray(o.input, {beta: o.beta, tol: o.tol});
    throw new RangeError(kind + " is not a job (contact, sweep, uniform)");
  }

  return {fixedArray: fixedArray, orientationSweep: orientationSweep,
          uniformArray: uniformArray, job: job, MAX_CONTACTS: MAX_CONTACTS};
}));
