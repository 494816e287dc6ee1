/* The generic solvers of the arrays, in JavaScript for the offline explorer: ports of
 * model/arrays/quadrature.py (adaptive Gauss-Kronrod (7, 15) quadrature of vector integrands)
 * and model/arrays/beta.py (the self-consistent load factor beta = L0/<tau_out>(beta): the
 * bracketed Illinois method of ``solve_beta`` and the safeguarded secant method of
 * ``solve_beta_secant``). No physics here: arrays.js applies them to the kernel's contacts.
 *
 * Every loop has a budget and says when it ran out: the quadrature stops at
 * ``maxIntervals`` intervals or ``maxRounds`` rounds (``converged`` false), the bracket
 * after ``maxIter`` steps and the secant after ``maxEvals`` evaluations (``converged``
 * false, ``message`` saying so). Where Python's secant hands over to scipy's Brent method
 * on [BETA_MIN, 1], this port hands over to the Illinois bracket on the same interval:
 * both bracketed, both to the same xtol.
 *
 * Works as a browser script (``MicropillarSolvers``), in a Web Worker and in Node.
 */
(function (root, factory) {
  "use strict";
  var api = factory();
  if (typeof module === "object" && module.exports) module.exports = api;
  else root.MicropillarSolvers = api;
}(typeof self !== "undefined" ? self : this, function () {
  "use strict";

  // ---------------------------------------------------------------- quadrature
  // Kronrod nodes on [-1, 1] (non-negative half) and weights; Gauss weights at the odd nodes.
  var XGK = [0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0];
  var WGK = [0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714];
  var WG = [0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327];
  // The 15 nodes in increasing order and their Kronrod and Gauss weights.
  var NODES = [], W_K = [], W_G = [];
  (function () {
    var i;
    for (i = 0; i < 7; i++) { NODES.push(-XGK[i]); W_K.push(WGK[i]); }
    for (i = 7; i >= 0; i--) { NODES.push(XGK[i]); W_K.push(WGK[i]); }
    for (i = 0; i < 15; i++) W_G.push(0.0);
    [1, 3, 5, 7, 9, 11, 13].forEach(function (j, k) { W_G[j] = WG[k < 4 ? k : 6 - k]; });
  }());

  function linspace(a, b, n) {
    var out = [];
    for (var i = 0; i < n; i++) out.push(a + (b - a) * i / (n - 1));
    out[n - 1] = b;
    return out;
  }

  /** The 15 Kronrod nodes of every interval of the partition ``edges``. */
  function nodes(edges) {
    var x = [];
    for (var i = 0; i + 1 < edges.length; i++) {
      var mid = 0.5 * (edges[i] + edges[i + 1]), half = 0.5 * (edges[i + 1] - edges[i]);
      for (var j = 0; j < 15; j++) x.push(mid + half * NODES[j]);
    }
    return x;
  }

  /** Kronrod mean over [0, span] of one component from its values at ``nodes(edges)``. */
  function kronrodMean(edges, values, span) {
    var total = 0.0;
    for (var i = 0; i + 1 < edges.length; i++) {
      var s = 0.0;
      for (var j = 0; j < 15; j++) s += W_K[j] * values[15 * i + j];
      total += 0.5 * (edges[i + 1] - edges[i]) * s;
    }
    return total / span;
  }

  /**
   * integrate(f, a, b, tol, control, edges, maxIntervals, maxRounds): the vector function
   * f(x: number[]) -> rows (one array of q numbers per x) over [a, b]. ``tol[k]`` bounds
   * the error estimate |K15 - G7| of component ``control[k]``; intervals whose error
   * density is above the tolerance density are bisected (the roughest first within the
   * budget) until the estimates meet it or the budget runs out (``converged`` false).
   */
  function integrate(f, a, b, tol, control, edges, maxIntervals, maxRounds) {
    maxIntervals = maxIntervals || 512;
    maxRounds = maxRounds || 30;
    edges = edges || linspace(a, b, 5);
    var intervals = [], cache = new Map(), rounds = 0, q = 0, i, j, c;
    for (i = 0; i + 1 < edges.length; i++) intervals.push([edges[i], edges[i + 1]]);
    function key(iv) { return iv[0] + "," + iv[1]; }
    var kron, err, converged;
    for (;;) {
      rounds += 1;
      var fresh = intervals.filter(function (iv) { return !cache.has(key(iv)); });
      if (fresh.length) {
        var x = [];
        fresh.forEach(function (iv) { x.push.apply(x, nodes(iv)); });
        var vals = f(x);
        fresh.forEach(function (iv, k) {
          var v = vals.slice(15 * k, 15 * (k + 1)), half = 0.5 * (iv[1] - iv[0]);
          q = v[0].length;
          var kr = [], er = [];
          for (c = 0; c < q; c++) {
            var sk = 0.0, sg = 0.0;
            for (j = 0; j < 15; j++) { sk += W_K[j] * v[j][c]; sg += W_G[j] * v[j][c]; }
            kr.push(half * sk);
            er.push(Math.abs(half * sk - half * sg));
          }
          cache.set(key(iv), {kron: kr, err: er, values: v});
        });
      }
      kron = new Array(q).fill(0.0);
      err = new Array(q).fill(0.0);
      intervals.forEach(function (iv) {
        var e = cache.get(key(iv));
        for (var m = 0; m < q; m++) { kron[m] += e.kron[m]; err[m] += e.err[m]; }
      });
      converged = control.every(function (comp, k) { return err[comp] <= tol[k]; });
      if (converged || rounds >= maxRounds || intervals.length >= maxIntervals) break;
      // Bisect intervals whose error density exceeds the tolerance density.
      var share = intervals.map(function (iv) {
        var e = cache.get(key(iv)).err, w = iv[1] - iv[0];
        return Math.max.apply(null, control.map(function (comp, k) {
          return e[comp] / (tol[k] * w / (b - a));
        }));
      });
      var top = Math.max.apply(null, share);
      var split = share.map(function (s) { return s > 1.0; });
      if (!split.some(Boolean)) split = share.map(function (s) { return s >= top; });
      var budget = maxIntervals - intervals.length;
      if (split.filter(Boolean).length > budget) {
        var order = share.map(function (s, k) { return k; })
          .sort(function (p, r) { return share[r] - share[p] || p - r; });
        split = share.map(function () { return false; });
        order.slice(0, budget).forEach(function (k) { split[k] = true; });
      }
      var refined = [];
      intervals.forEach(function (iv, k) {
        var mid = 0.5 * (iv[0] + iv[1]);
        if (split[k]) refined.push([iv[0], mid], [mid, iv[1]]);
        else refined.push(iv);
      });
      intervals = refined;
    }
    var values = [];
    intervals.forEach(function (iv) { values.push.apply(values, cache.get(key(iv)).values); });
    var outEdges = [intervals[0][0]].concat(intervals.map(function (iv) { return iv[1]; }));
    return {integral: kron, error: err, edges: outEdges, nodes: nodes(outEdges),
            values: values, converged: converged, rounds: rounds};
  }

  // ---------------------------------------------------------------- the load factor beta
  var BETA_MIN = 1e-3;  // model.arrays.beta.BETA_MIN

  function clip(b) { return Math.min(1.0, Math.max(BETA_MIN, b)); }

  /**
   * solveBetaBracket(meanTau, L0, xtol, maxIter): beta = L0/meanTau(beta) for one problem,
   * the Illinois method on a bracket in [BETA_MIN, 1] (model.arrays.beta.solve_beta, one row).
   * Returns {beta, residual, iterations, evaluations, converged, capped, jump, message}.
   */
  function solveBetaBracket(meanTau, L0, xtol, maxIter) {
    xtol = xtol || 1e-8;
    maxIter = maxIter || 100;
    var hi = 1.0, tauHi = meanTau(hi), gHi = hi - L0 / tauHi;
    // Where tau_out grows with the load, the root is above L0/tau(1): a tighter lower end.
    var lo = clip(L0 / tauHi), gLo = lo - L0 / meanTau(lo);
    if (!(gLo < 0)) { lo = BETA_MIN; gLo = BETA_MIN - L0 / meanTau(lo); }
    var evaluations = 3, capped = gHi < 0, active = !capped && gLo < 0;
    var x = hi, gx = gHi, side = 0, it = 0;
    while (active && it < maxIter) {
      it += 1;
      var trial = (lo * gHi - hi * gLo) / (gHi - gLo);
      if (!isFinite(trial) || trial <= lo || trial >= hi) trial = 0.5 * (lo + hi);
      var gt = trial - L0 / meanTau(trial);
      evaluations += 1;
      var upper = gt >= 0, lower = gt < 0;
      // Illinois: halve the function value at an end that was kept twice in a row.
      if (upper && side === 1) gLo *= 0.5;
      if (lower && side === -1) gHi *= 0.5;
      if (upper) { hi = trial; gHi = gt; }
      if (lower) { lo = trial; gLo = gt; }
      side = upper ? 1 : lower ? -1 : side;
      x = trial; gx = gt;
      active = hi - lo > xtol * hi && gt !== 0;
    }
    var converged = capped || hi - lo <= xtol * hi || gx === 0;
    if (capped) { x = 1.0; gx = gHi; }
    var jump = !capped && Math.abs(gx) > 1e3 * xtol;
    return {beta: x, residual: gx, iterations: it, evaluations: evaluations,
            converged: converged, capped: capped, jump: jump,
            message: converged ? "ok" : (active ? "the load factor beta ran out of its budget of " +
                                         maxIter + " bracketing steps" : "no sign change of G in [" +
                                         BETA_MIN + ", 1]")};
  }

  /**
   * solveBetaSecant(meanTau, L0, o): beta = L0/meanTau(beta) by a safeguarded secant
   * method from o.guess with o.slope (model.arrays.beta.solve_beta_secant: same steps, same
   * stopping rules; o.xtol, o.maxEvals = 30, o.gtol, o.known = [beta, G]). The returned
   * beta is the last point evaluated. Out of budget, the bracket finishes.
   */
  function solveBetaSecant(meanTau, L0, o) {
    var xtol = o.xtol === undefined ? 1e-8 : o.xtol, maxEvals = o.maxEvals || 30;
    var gtol = o.gtol || 0.0, known = o.known || null, slope = o.slope;
    var calls = 0;
    function G(b) { calls += 1; return b - L0 / meanTau(b); }
    function done(b, g, it, conv, capped, sl) {
      return {beta: b, residual: g, iterations: it, evaluations: calls, converged: conv,
              capped: capped, slope: sl === undefined || sl === null ? NaN : sl};
    }
    var b0, g0, b1, s;
    if (o.guess === undefined || o.guess === null) {
      b0 = 1.0; g0 = G(1.0);
      if (g0 < 0) return done(1.0, g0, 0, true, true);  // contacts shorter than L0 at beta = 1
      b1 = clip(1.0 - g0);  // L0/tau(1), the fixed-point iterate
    } else {
      b0 = clip(o.guess); g0 = G(b0);
      if (b0 === 1.0 && g0 < 0) return done(1.0, g0, 0, true, true);
      if (Math.abs(g0) <= gtol || g0 === 0) return done(b0, g0, 0, true, false, slope);
      s = slope !== undefined && slope !== null && isFinite(slope) && slope > 0 ? slope : 1.0;
      if (known && known[0] !== b0) {
        var through = (g0 - known[1]) / (b0 - known[0]);
        if (isFinite(through) && through > 0) s = through;
      }
      b1 = clip(b0 - g0 / s);
    }
    var lo = null, hi = null, gLo = 0.0, gHi = 0.0, side = 0, it = 0;
    function enclose(b, g) {  // the bracket G(lo) < 0 <= G(hi)
      if (g < 0 && (lo === null || b > lo)) { lo = b; gLo = g; }
      else if (g >= 0 && (hi === null || b < hi)) { hi = b; gHi = g; }
    }
    enclose(b0, g0);
    if (known) enclose(known[0], known[1]);
    while (calls < maxEvals) {
      if (b1 === b0) {
        b1 = clip(g0 > 0 ? b0 * (1 - 1e-3) : b0 * (1 + 1e-3));
        if (b1 === b0) break;  // pinned at an end of [BETA_MIN, 1]
      }
      var g1 = G(b1);
      it += 1;
      enclose(b1, g1);
      if (b1 === 1.0 && g1 < 0) return done(1.0, g1, it, true, true);
      var sl = (g1 - g0) / (b1 - b0);
      if (g1 === 0 || Math.abs(g1) <= gtol || (sl > 0 && Math.abs(g1 / sl) <= xtol * b1) ||
          Math.abs(b1 - b0) <= 0.1 * xtol * b1) return done(b1, g1, it, true, false, sl);
      if (lo !== null && hi !== null && hi - lo <= xtol * hi) return done(b1, g1, it, true, false, sl);
      var b2 = sl !== 0 && isFinite(sl) ? b1 - g1 / sl : NaN;
      if (lo !== null && hi !== null) {
        if (!(lo < b2 && b2 < hi)) {
          // Illinois on the bracket: halve the value at an end kept twice.
          if (g1 < 0) { if (side === -1) gHi *= 0.5; side = -1; }
          else { if (side === 1) gLo *= 0.5; side = 1; }
          b2 = (lo * gHi - hi * gLo) / (gHi - gLo);
          if (!(lo < b2 && b2 < hi)) b2 = 0.5 * (lo + hi);
        }
      } else if (!isFinite(b2) || sl <= 0) {
        b2 = clip(g1 < 0 ? b1 * 2.0 : b1 * 0.5);  // look for a sign change
      } else {
        b2 = clip(Math.min(4 * b1, Math.max(0.25 * b1, b2)));  // at most a factor 4 away
      }
      b0 = b1; g0 = g1; b1 = b2;
    }
    var cold = solveBetaBracket(meanTau, L0, xtol);
    return {beta: cold.beta, residual: cold.residual, iterations: it + cold.iterations,
            evaluations: calls + cold.evaluations, converged: cold.converged,
            capped: cold.capped, slope: NaN, message: cold.message};
  }

  return {
    integrate: integrate, nodes: nodes, kronrodMean: kronrodMean, linspace: linspace,
    solveBetaBracket: solveBetaBracket, solveBetaSecant: solveBetaSecant,
    BETA_MIN: BETA_MIN, NODES: NODES, W_K: W_K, W_G: W_G
  };
}));
